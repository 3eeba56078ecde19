// VkCommandPool and VkCommandBuffer: recording into an arena of plain command structs (commands.h).
#pragma once
#include <memory>
#include <new>
#include <vector>

#include "arena.h"
#include "commands.h"
#include "descriptor_pool.h"
#include "framebuffer.h"
#include "object.h"
#include "render_pass.h"

namespace tilevk::icd {

struct Device;
struct CommandBuffer;

struct CommandPool : NonDispatchableObject {
    using Handle = VkCommandPool;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_COMMAND_POOL;
    CommandPool() : NonDispatchableObject(kType) {}
    Device* device = nullptr;
    VkCommandPoolCreateFlags flags = 0;
    std::vector<CommandBuffer*> buffers;
};

// vkCmdBeginRendering: the one-subpass render pass and the framebuffer a VkRenderingInfo is translated into
// (dynamic_rendering.cpp), so that it runs as a vkCmdBeginRenderPass does.
struct RenderingInstance {
    RenderPass pass;
    Framebuffer framebuffer;
};

struct CommandBuffer : DispatchableObject {
    using Handle = VkCommandBuffer;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_COMMAND_BUFFER;
    CommandBuffer() : DispatchableObject(kType) {}

    enum class State : uint8_t { kInitial, kRecording, kExecutable };
    CommandPool* pool = nullptr;
    VkCommandBufferLevel level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    VkCommandBufferUsageFlags usage = 0;
    State state = State::kInitial;
    VkResult record_result = VK_SUCCESS;  // first allocation failure while recording, reported by vkEnd
    Arena arena;
    Cmd* first = nullptr;
    Cmd* last = nullptr;
    // The render passes of its vkCmdBeginRendering commands, kept until the next reset.
    std::vector<std::unique_ptr<RenderingInstance>> rendering;
    // The descriptor sets its vkCmdPushDescriptorSetKHR commands made (push_descriptor.cpp), kept until the next
    // reset: each push is a new set, bound as vkCmdBindDescriptorSets binds one.
    struct PushedSet {
        VkPipelineBindPoint bind_point;
        uint32_t set;
        std::unique_ptr<DescriptorSet> contents;
    };
    std::vector<PushedSet> pushed_sets;

    // Appends a zeroed command of type T, or returns nullptr (and remembers the failure) when out of memory.
    template <class T>
    T* append() {
        void* mem = arena.allocate(sizeof(T), alignof(T));
        if (mem == nullptr) {
            out_of_memory();
            return nullptr;
        }
        T* cmd = new (mem) T();  // value-initialised: every field zero, the header typed by CmdOf
        Cmd& header = cmd->header();
        if (last != nullptr)
            last->next = &header;
        else
            first = &header;
        last = &header;
        return cmd;
    }
    // Copies an array into the arena; nullptr for an empty array or on failure (then record_result is set).
    template <class T>
    const T* copy(const T* src, size_t count) {
        if (count == 0) return nullptr;
        const T* dst = arena.copy_array(src, count);
        if (dst == nullptr) out_of_memory();
        return dst;
    }
    void out_of_memory();
    // Back to the initial state. The arena keeps its blocks for the next recording unless `release_memory`
    // (VK_COMMAND_BUFFER_RESET_RELEASE_RESOURCES_BIT, VK_COMMAND_POOL_RESET_RELEASE_RESOURCES_BIT).
    void reset(bool release_memory = false);
};
TILEVK_ASSERT_DISPATCHABLE(CommandBuffer);

}  // namespace tilevk::icd
