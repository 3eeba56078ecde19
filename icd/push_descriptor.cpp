// vkCmdPushDescriptorSetKHR and vkCmdPushDescriptorSetWithTemplateKHR (VK_KHR_push_descriptor). Each push makes a
// descriptor set that the command buffer owns until its next reset, writes it as vkUpdateDescriptorSets (or the
// template) writes a pool's set, and records the bind vkCmdBindDescriptorSets would: execution cannot tell a pushed
// set from an allocated one. Descriptors a push leaves unwritten keep what the previous push to the same set number
// (same bind point, same layout) wrote, so an application may push a set's bindings in several commands.
#include <new>
#include <vector>

#include "command_buffer.h"
#include "descriptor_set_layout.h"
#include "descriptor_update_template.h"
#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {
namespace {

// The set `set` of `layout` for the next push, or nullptr (logged) when the layout has no such set or memory runs out.
DescriptorSet* new_pushed_set(CommandBuffer* cb, VkPipelineBindPoint bind_point, VkPipelineLayout layout, uint32_t set,
                              const char* command) {
    const PipelineLayout* pl = from_handle<PipelineLayout>(layout);
    if (pl == nullptr || set >= pl->set_layouts.size() || pl->set_layouts[set] == nullptr) {
        log_error("%s: set %u is not a set of the pipeline layout", command, set);
        return nullptr;
    }
    const std::shared_ptr<const SetLayout>& shared = pl->set_layouts[set];
    const DescriptorSet* previous = nullptr;
    for (auto it = cb->pushed_sets.rbegin(); it != cb->pushed_sets.rend(); ++it) {
        if (it->bind_point == bind_point && it->set == set) {
            previous = it->contents.get();
            break;
        }
    }
    try {
        auto contents = std::make_unique<DescriptorSet>();
        if (previous != nullptr && previous->layout == shared) {
            contents->layout = shared;
            contents->slots = previous->slots;
            contents->inline_data = previous->inline_data;
        } else {
            init_descriptor_set(*contents, shared);
        }
        DescriptorSet* raw = contents.get();
        cb->pushed_sets.push_back({bind_point, set, std::move(contents)});
        return raw;
    } catch (const std::bad_alloc&) {
        cb->out_of_memory();
        return nullptr;
    }
}

void bind_pushed_set(CommandBuffer* cb, VkPipelineBindPoint bind_point, uint32_t set, DescriptorSet* contents) {
    // An array of one set pointer in the arena, as vkCmdBindDescriptorSets records its sets.
    void* mem =
        cb->arena.allocate(sizeof(DescriptorSet*), alignof(DescriptorSet*));  // NOLINT(bugprone-sizeof-expression)
    auto** sets = static_cast<DescriptorSet**>(mem);
    if (sets == nullptr) {
        cb->out_of_memory();
        return;
    }
    sets[0] = contents;
    if (auto* c = cb->append<CmdBindDescriptorSets>()) {
        c->bind_point = bind_point;
        c->first_set = set;
        c->set_count = 1;
        c->sets = sets;
    }
}

}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_CmdPushDescriptorSetKHR(VkCommandBuffer commandBuffer,
                                                       VkPipelineBindPoint pipelineBindPoint, VkPipelineLayout layout,
                                                       uint32_t set, uint32_t descriptorWriteCount,
                                                       const VkWriteDescriptorSet* pDescriptorWrites) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    DescriptorSet* contents = new_pushed_set(cb, pipelineBindPoint, layout, set, "vkCmdPushDescriptorSetKHR");
    if (contents == nullptr) return;
    try {
        // The writes' dstSet is ignored (the spec): they go to the pushed set.
        std::vector<VkWriteDescriptorSet> writes(pDescriptorWrites, pDescriptorWrites + descriptorWriteCount);
        for (VkWriteDescriptorSet& w : writes) w.dstSet = to_handle(contents);
        tvk_UpdateDescriptorSets(to_handle(cb->pool->device), descriptorWriteCount, writes.data(), 0, nullptr);
    } catch (const std::bad_alloc&) {
        cb->out_of_memory();
        return;
    }
    bind_pushed_set(cb, pipelineBindPoint, set, contents);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdPushDescriptorSetWithTemplateKHR(VkCommandBuffer commandBuffer,
                                                                   VkDescriptorUpdateTemplate descriptorUpdateTemplate,
                                                                   VkPipelineLayout layout, uint32_t set,
                                                                   const void* pData) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    const DescriptorUpdateTemplate* t = from_handle<DescriptorUpdateTemplate>(descriptorUpdateTemplate);
    DescriptorSet* contents = new_pushed_set(cb, t->bind_point, layout, set, "vkCmdPushDescriptorSetWithTemplateKHR");
    if (contents == nullptr) return;
    tvk_UpdateDescriptorSetWithTemplate(to_handle(cb->pool->device), to_handle(contents), descriptorUpdateTemplate,
                                        pData);
    bind_pushed_set(cb, t->bind_point, set, contents);
}

}  // namespace tilevk::icd
