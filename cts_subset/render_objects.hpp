// The Vulkan objects a conformance-subset frame is made of (render.cpp builds and records the frame from them):
// buffers and images with their cleanup, texture contents, shader modules, pipelines and the render pass of a
// scene, and the formats' byte layouts.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "render.hpp"

namespace tilevk::cts::frame {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0);

bool has_stencil(VkFormat f);
bool has_depth(VkFormat f);
// Bytes of one depth texel in a buffer copy.
uint32_t depth_copy_bytes(VkFormat f);
// Bytes of one texel of a colour target.
uint32_t color_bytes(VkFormat f);
// Appends the colour c packed as the vertex format f (Draw::color_format); false for a format it does not know.
bool pack_color(VkFormat f, const float c[4], std::vector<uint8_t>& out);
// Bytes of one colour packed as the vertex format f (throws for a format pack_color does not know).
uint32_t packed_color_bytes(VkFormat f);

// A draw's vertex bindings and attributes: binding 0 holds Vertex (locations 0-3); with a packed colour format
// (Draw::color_format) location 1 reads binding 1 instead. make_pipeline bakes them, or with Draw::dynamic3
// render.cpp sets them by vkCmdSetVertexInputEXT.
struct VertexInputLayout {
    uint32_t binding_count = 1;
    VkVertexInputBindingDescription bindings[2];
    VkVertexInputAttributeDescription attributes[4];
};
VertexInputLayout vertex_input_of(const Draw& d);

// Destroys what was created, in reverse order, whether the scene finished or threw.
struct Cleanup {
    std::vector<std::function<void()>> steps;
    ~Cleanup() {
        for (auto it = steps.rbegin(); it != steps.rend(); ++it) (*it)();
    }
    void add(std::function<void()> f) { steps.push_back(std::move(f)); }
};

// A host-visible, coherent, mapped buffer.
struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
};
Buffer make_buffer(const DeviceContext& c, Cleanup& gc, VkDeviceSize size, VkBufferUsageFlags usage);
// depth > 1: a 3D image (and make_view's view_type VK_IMAGE_VIEW_TYPE_3D); one_d: a 1D image (h ignored); `layers`
// and `flags` (VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT) for cube textures.
VkImage make_image(const DeviceContext& c, Cleanup& gc, VkFormat format, uint32_t w, uint32_t h, uint32_t mips,
                   VkSampleCountFlagBits samples, VkImageUsageFlags usage, uint32_t depth = 1, bool one_d = false,
                   uint32_t layers = 1, VkImageCreateFlags flags = 0, VkImageTiling tiling = VK_IMAGE_TILING_OPTIMAL);
VkImageView make_view(const DeviceContext& c, Cleanup& gc, VkImage img, VkFormat f, VkImageAspectFlags aspect,
                      uint32_t mips, VkImageViewType view_type = VK_IMAGE_VIEW_TYPE_2D, uint32_t layers = 1);
void barrier(VkCommandBuffer cb, VkImage img, VkImageAspectFlags aspect, uint32_t mips, VkImageLayout from,
             VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
             VkPipelineStageFlags dst_stage);

// A sampled RGBA8 texture with its mip chain in a staging buffer, to be uploaded with `copies`.
struct Texture {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    Buffer staging;
    std::vector<VkBufferImageCopy> copies;
    uint32_t mips = 1;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};
Texture make_texture(const DeviceContext& c, Cleanup& gc, const TextureSpec& t);
// bc_texture.cpp: a BC-compressed texture (TextureSpec::format BC1-BC7) of seeded random and hand-made blocks.
bool is_bc_format(VkFormat f);
uint32_t bc_block_bytes(VkFormat f);
Texture make_bc_texture(const DeviceContext& c, Cleanup& gc, const TextureSpec& t);

// The draw's pipeline (its GLSL compiled here); the creation time is added to pipeline_ms.
VkPipeline make_pipeline(const DeviceContext& c, Cleanup& gc, const Scene& s, const Draw& d, VkRenderPass rp,
                         VkPipelineLayout layout, double& pipeline_ms);
// The target's render pass: colour, depth/stencil and resolve attachments, cleared, ready for the copies.
VkRenderPass make_render_pass(const DeviceContext& c, Cleanup& gc, const Target& t);

}  // namespace tilevk::cts::frame
