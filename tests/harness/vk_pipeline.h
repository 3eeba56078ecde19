// The shared harness's pipeline and render pass helpers (implemented in vk_harness.cpp), for the tests that build
// their own graphics pipelines and passes rather than use api_breadth.h's Kit.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace tilevk::test {

// A shader stage with entry point "main".
VkPipelineShaderStageCreateInfo shader_stage(VkShaderStageFlagBits stage, VkShaderModule module);

// The state of a graphics pipeline that draws triangle lists into one colour attachment: no vertex input, one
// viewport and scissor covering `width` x `height`, filled, no culling, 1 sample, no depth/stencil state
// (depth_stencil_enabled false), the attachment written without blending. A test changes the members it needs,
// then create() points the create info at them.
struct PipelineStates {
    PipelineStates(uint32_t width, uint32_t height);
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    VkViewport viewport{};
    VkRect2D scissor{};
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    VkPipelineDepthStencilStateCreateInfo depth_stencil{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    bool depth_stencil_enabled = false;  // pDepthStencilState: &depth_stencil, else null
    VkPipelineColorBlendAttachmentState blend{};
    VkPipelineColorBlendStateCreateInfo color_blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    // vkCreateGraphicsPipelines's result; the pipeline in *out (VK_NULL_HANDLE on failure).
    VkResult create(VkDevice device, VkRenderPass pass, VkPipelineLayout layout,
                    const VkPipelineShaderStageCreateInfo* stages, uint32_t stage_count, VkPipeline* out);
};

// An image as the only attachment of a one-subpass render pass: its 2D view of level 0, layer 0 (`aspect`), the
// pass (`attachment` as a colour attachment, or as the depth/stencil one when `aspect` is depth and/or stencil;
// `dependencies` as given) and a width x height framebuffer. Each creation is expected to succeed.
struct SingleAttachmentPass {
    SingleAttachmentPass() = default;
    SingleAttachmentPass(VkDevice device, VkImage image, const VkAttachmentDescription& attachment,
                         VkImageAspectFlags aspect, uint32_t width, uint32_t height,
                         const std::vector<VkSubpassDependency>& dependencies = {});
    void destroy(VkDevice device);
    VkImageView view = VK_NULL_HANDLE;
    VkRenderPass pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
};

}  // namespace tilevk::test
