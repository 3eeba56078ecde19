// The input-attachment scene of three api_breadth suites (ApiBreadth.InputAttachmentsReadThePreviousSubpass,
// ApiImagelessFramebuffer, ApiRenderPass2Subpasses): subpass 0 draws kBothTriangles into colour (RGBA8, attachment
// 0) and depth (D32, attachment 1, LESS); subpass 1 reads both as input attachments (ab_subpass_load.frag) into an
// RGBA32F attachment 2 with one triangle covering the target. Each suite makes the render pass, the framebuffer and
// the begin / next / end commands its own way (1.0, 2, imageless); the images, the pass's parts, the pipelines and
// the draws are these.
#pragma once

#include <cstring>
#include <vector>

#include "api_breadth.h"

namespace tilevk::test::breadth {

class InputScene {
  public:
    static constexpr VkFormat kColour = VK_FORMAT_R8G8B8A8_UNORM;
    static constexpr VkFormat kDepth = VK_FORMAT_D32_SFLOAT;
    static constexpr VkFormat kOut = VK_FORMAT_R32G32B32A32_SFLOAT;
    static constexpr VkImageUsageFlags kColourUsage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    static constexpr VkImageUsageFlags kDepthUsage =
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
    static constexpr VkImageUsageFlags kOutUsage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

    // The three 32x32 images and their views.
    explicit InputScene(Kit& k)
        : k_(k),
          col_(k.image(kColour, 32, 32, kColourUsage)),
          dep_(k.image(kDepth, 32, 32, kDepthUsage)),
          out_(k.image(kOut, 32, 32, kOutUsage)),
          cv_(k.view(col_.image, kColour, VK_IMAGE_ASPECT_COLOR_BIT)),
          dv_(k.view(dep_.image, kDepth, VK_IMAGE_ASPECT_DEPTH_BIT)),
          ov_(k.view(out_.image, kOut, VK_IMAGE_ASPECT_COLOR_BIT)) {}
    // The subpasses point into this object.
    InputScene(const InputScene&) = delete;
    InputScene& operator=(const InputScene&) = delete;

    // The framebuffer's attachments: colour, depth, output.
    std::vector<VkImageView> views() const { return {cv_, dv_, ov_}; }
    static std::vector<VkAttachmentDescription> attachments() {
        return {attachment(kColour, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE),
                attachment(kDepth, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                           VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL),
                attachment(kOut, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)};
    }
    std::vector<VkSubpassDescription> subpasses() const {
        std::vector<VkSubpassDescription> subs = {subpass(&c0_, &d0_), subpass(&o1_)};
        subs[1].inputAttachmentCount = 2;
        subs[1].pInputAttachments = in1_;
        return subs;
    }
    // Subpass 0's colour and depth writes before subpass 1's input attachment reads, by region.
    static VkSubpassDependency dependency() {
        return {0,
                1,
                VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                VK_ACCESS_INPUT_ATTACHMENT_READ_BIT,
                VK_DEPENDENCY_BY_REGION_BIT};
    }
    // The clear values of the three attachments, in order.
    static std::vector<VkClearValue> clears() {
        return {clear_color(0, 0, 0.25f, 1), clear_depth(0.75f), clear_color(0, 0, 0, 0)};
    }

    // The two pipelines of `rp`, the input attachment set and the vertices.
    void build(VkRenderPass rp) {
        ds_ = depth_state(VK_COMPARE_OP_LESS);
        Pipe p0;
        p0.rp = rp;
        p0.ds = &ds_;
        pipe0_ = k_.pipeline(p0);
        const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
        VkDescriptorSetLayout dsl = k_.set_layout(
            {{0, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1, F}, {1, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1, F}});
        layout_ = k_.pipeline_layout({dsl});
        set_ = k_.descriptor_set(dsl);
        VkDescriptorImageInfo ci{VK_NULL_HANDLE, cv_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            di{VK_NULL_HANDLE, dv_, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
        k_.write(set_, 0, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, nullptr, &ci);
        k_.write(set_, 1, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, nullptr, &di);
        Pipe p1;
        p1.fs = SPV(ab_subpass_load_frag);
        p1.rp = rp;
        p1.subpass = 1;
        p1.layout = layout_;
        pipe1_ = k_.pipeline(p1);
        std::vector<Vertex> verts = kBothTriangles;
        verts.push_back(v(-1, -1, 0, 0.2f, 0.4f, 0.6f, 1));
        verts.push_back(v(3, -1, 0, 0.2f, 0.4f, 0.6f, 1));
        verts.push_back(v(-1, 3, 0, 0.2f, 0.4f, 0.6f, 1));
        vb_ = k_.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    }
    // Subpass 0's two triangles (after the begin command).
    void draw_subpass0(VkCommandBuffer c) const {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe0_);
        bind_vertices(c, vb_);
        vkCmdDraw(c, 6, 1, 0, 0);
    }
    // Subpass 1's covering triangle (after the next-subpass command).
    void draw_subpass1(VkCommandBuffer c) const {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe1_);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
        vkCmdDraw(c, 3, 1, 6, 0);  // covers the whole target
    }
    // The RGBA32F output then the RGBA8 colour, after an independent check at the corner (no triangle of subpass 0
    // there): colour (0, 0, 0.25, 1) read as .bgra -> (0.25, 0, 0, 1); 0.5 of it + 0.5 of the vertex colour + 0.25 *
    // depth 0.75 (ab_subpass_load.frag).
    Bytes read_checked() const {
        Bytes o = k_.read(out_.image, 32, 32, 16);
        float corner[4];
        std::memcpy(corner, o.data() + (31 * 32 + 0) * 16, 16);
        EXPECT_NEAR(corner[0], 0.125f + 0.1f + 0.1875f, 1e-3f);
        EXPECT_NEAR(corner[3], 0.5f + 0.5f + 0.1875f, 1e-3f);
        return concat({o, k_.read(col_.image, 32, 32, 4)});
    }

  private:
    Kit& k_;
    Device::Image col_, dep_, out_;
    VkImageView cv_, dv_, ov_;
    const VkAttachmentReference c0_{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference d0_{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference in1_[2] = {{0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                           {1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL}};
    const VkAttachmentReference o1_{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkPipelineDepthStencilStateCreateInfo ds_{};
    VkPipeline pipe0_ = VK_NULL_HANDLE, pipe1_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    Device::Buffer vb_;
};

}  // namespace tilevk::test::breadth
