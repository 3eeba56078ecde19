// Executing recorded command buffers at vkQueueSubmit (on the submitting thread, in submission order).
#pragma once
#include "command_buffer.h"
#include "formats.h"

namespace tilevk::icd {

struct Image;
struct ImageView;
struct RenderPass;
struct Framebuffer;

// State that lives across commands while a queue runs one command buffer.
struct ExecState {
    RenderPass* render_pass = nullptr;
    Framebuffer* framebuffer = nullptr;
    uint32_t subpass = 0;
    VkRect2D area{};
    const VkClearValue* clears = nullptr;
    bool draw_warned = false;
};

void execute_command_buffer(CommandBuffer* cb, ExecState& st);

// ---- transfer operations (execute_transfer.cpp) ----
void exec_copy_buffer(const CmdCopyBuffer& c);
void exec_copy_image(const CmdCopyImage& c);
void exec_copy_buffer_to_image(const CmdCopyBufferToImage& c);
void exec_copy_image_to_buffer(const CmdCopyImageToBuffer& c);
void exec_update_buffer(const CmdUpdateBuffer& c);
void exec_fill_buffer(const CmdFillBuffer& c);
void exec_clear_color_image(const CmdClearColorImage& c);
void exec_clear_depth_stencil_image(const CmdClearDepthStencilImage& c);
void exec_resolve_image(const CmdResolveImage& c);

// ---- building blocks shared with render passes ----
// Writes bytes [byte_offset, byte_offset + byte_count) of `texel` into every sample of every texel of `rect`.
void fill_rect(const Image& img, uint32_t level, uint32_t layer, const VkRect2D& rect, const uint8_t* texel,
               uint32_t byte_offset, uint32_t byte_count);
// Packs and writes a colour clear into rect of `layer_count` layers from `base_layer`.
void clear_color_rect(const Image& img, uint32_t level, uint32_t base_layer, uint32_t layer_count, const VkRect2D& rect,
                      const VkClearColorValue& color);
// Clears the given aspects of a depth/stencil image in rect.
void clear_depth_stencil_rect(const Image& img, uint32_t level, uint32_t base_layer, uint32_t layer_count,
                              const VkRect2D& rect, VkImageAspectFlags aspects, const VkClearDepthStencilValue& v);
// Resolves a 4x region into a 1x one, as lavapipe's blitter does (see execute_transfer.cpp).
void resolve_rect(const Image& src, uint32_t src_level, uint32_t src_layer, VkOffset2D src_offset, const Image& dst,
                  uint32_t dst_level, uint32_t dst_layer, VkOffset2D dst_offset, VkExtent2D extent);
// True if resolve_rect implements the format.
bool can_resolve(const FormatInfo& f);

}  // namespace tilevk::icd
