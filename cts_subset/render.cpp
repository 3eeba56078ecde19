#include "render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "render_objects.hpp"

namespace tilevk::cts {
namespace {

using namespace frame;

struct Readback {
    VkImage image;
    VkImageAspectFlags aspect;
    Plane plane;
    Buffer buffer;
};

// Every draw's vertices, back to back in one vertex buffer.
Buffer upload_vertices(const DeviceContext& c, Cleanup& gc, const Scene& s) {
    size_t nverts = 0;
    for (const Draw& d : s.draws) nverts += d.vertices.size();
    Buffer vb = make_buffer(c, gc, std::max<size_t>(1, nverts) * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    size_t at = 0;
    for (const Draw& d : s.draws) {
        std::memcpy(static_cast<uint8_t*>(vb.mapped) + at * sizeof(Vertex), d.vertices.data(),
                    d.vertices.size() * sizeof(Vertex));
        at += d.vertices.size();
    }
    return vb;
}

// The target's attachments in render-pass order (colour, depth/stencil, resolve), the framebuffer, and the planes
// read back after the pass (the resolved colour first), each with its host-visible buffer.
struct Attachments {
    bool resolve = false;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
};
Attachments make_attachments(const DeviceContext& c, Cleanup& gc, const Target& t, VkRenderPass rp,
                             std::vector<Readback>& reads) {
    Attachments at;
    std::vector<VkImageView> views;
    const VkImageUsageFlags copy_src = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    at.resolve = t.samples != VK_SAMPLE_COUNT_1_BIT && t.color != VK_FORMAT_UNDEFINED;
    if (t.color != VK_FORMAT_UNDEFINED) {
        VkImage img = make_image(c, gc, t.color, t.width, t.height, 1, t.samples,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (at.resolve ? 0 : copy_src));
        views.push_back(make_view(c, gc, img, t.color, VK_IMAGE_ASPECT_COLOR_BIT, 1));
        if (!at.resolve)
            reads.push_back(
                {img, VK_IMAGE_ASPECT_COLOR_BIT, {"color", t.color, t.width, t.height, color_bytes(t.color)}, {}});
    }
    VkImage depth_img = VK_NULL_HANDLE;
    if (t.depth != VK_FORMAT_UNDEFINED) {
        depth_img = make_image(c, gc, t.depth, t.width, t.height, 1, t.samples,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | copy_src);
        VkImageAspectFlags aspects = (has_depth(t.depth) ? VK_IMAGE_ASPECT_DEPTH_BIT : 0) |
                                     (has_stencil(t.depth) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
        views.push_back(make_view(c, gc, depth_img, t.depth, aspects, 1));
    }
    if (at.resolve) {
        VkImage img = make_image(c, gc, t.color, t.width, t.height, 1, VK_SAMPLE_COUNT_1_BIT,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | copy_src);
        views.push_back(make_view(c, gc, img, t.color, VK_IMAGE_ASPECT_COLOR_BIT, 1));
        reads.insert(reads.begin(),
                     {img, VK_IMAGE_ASPECT_COLOR_BIT, {"color", t.color, t.width, t.height, color_bytes(t.color)}, {}});
    }
    // Multisampled depth cannot be copied to a buffer; only single-sampled depth/stencil is judged.
    if (depth_img && t.samples == VK_SAMPLE_COUNT_1_BIT) {
        if (has_depth(t.depth))
            reads.push_back({depth_img,
                             VK_IMAGE_ASPECT_DEPTH_BIT,
                             {"depth", t.depth, t.width, t.height, depth_copy_bytes(t.depth)},
                             {}});
        if (has_stencil(t.depth))
            reads.push_back({depth_img, VK_IMAGE_ASPECT_STENCIL_BIT, {"stencil", t.depth, t.width, t.height, 1}, {}});
    }
    for (Readback& r : reads)
        r.buffer = make_buffer(c, gc, VkDeviceSize(t.width) * t.height * r.plane.texel_bytes,
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = rp;
    fci.attachmentCount = uint32_t(views.size());
    fci.pAttachments = views.data();
    fci.width = t.width;
    fci.height = t.height;
    fci.layers = 1;
    VkDevice dev = c.device;
    vk_check(vkCreateFramebuffer(dev, &fci, nullptr, &at.framebuffer), "vkCreateFramebuffer");
    gc.add([dev, fb = at.framebuffer] { vkDestroyFramebuffer(dev, fb, nullptr); });
    return at;
}

// What each draw binds: its pipeline, texture set (set 0), uniform-buffer set (set 1), index and packed-colour
// buffers; one pipeline layout for all.
struct DrawResources {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkShaderStageFlags push_stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    std::vector<VkPipeline> pipes;
    std::vector<Texture> textures;
    std::vector<VkDescriptorSet> sets, ubo_sets;
    std::vector<VkBuffer> index_buffers, color_buffers, condition_buffers;
};

// The set layouts and the pipeline layout. The texture is set 0, the uniform buffer set 1: a set with an
// unwritten combined-image-sampler binding crashes lavapipe 22.3 when bound (valid Vulkan when the shader does not
// use it; found by cases_random.cpp), so a draw binds only sets whose every binding it writes. Set 1 and the
// push-constant range exist only when a draw uses them, so the scenes without them record exactly what they always
// did.
void make_layouts(const DeviceContext& c, Cleanup& gc, const Scene& s, VkDescriptorSetLayout dsl[2],
                  DrawResources& r) {
    VkDevice dev = c.device;
    bool any_uniforms = false, any_push = false;
    for (const Draw& d : s.draws) {
        any_uniforms |= !d.uniforms.empty();
        any_push |= !d.push_constants.empty();
    }
    const VkDescriptorSetLayoutBinding dslb[2] = {
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, r.push_stages, nullptr}};
    for (uint32_t k = 0; k < (any_uniforms ? 2u : 1u); ++k) {
        VkDescriptorSetLayoutCreateInfo dslci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        dslci.bindingCount = 1;
        dslci.pBindings = &dslb[k];
        vk_check(vkCreateDescriptorSetLayout(dev, &dslci, nullptr, &dsl[k]), "vkCreateDescriptorSetLayout");
        gc.add([dev, l = dsl[k]] { vkDestroyDescriptorSetLayout(dev, l, nullptr); });
    }
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = any_uniforms ? 2 : 1;
    plci.pSetLayouts = dsl;
    const VkPushConstantRange push_range{r.push_stages, 0, 128};
    plci.pushConstantRangeCount = any_push ? 1 : 0;
    plci.pPushConstantRanges = &push_range;
    vk_check(vkCreatePipelineLayout(dev, &plci, nullptr, &r.layout), "vkCreatePipelineLayout");
    gc.add([dev, layout = r.layout] { vkDestroyPipelineLayout(dev, layout, nullptr); });
}

// Pipelines, textures and uniform buffers with their descriptor sets, one per draw that uses them.
void make_draw_descriptors(const DeviceContext& c, Cleanup& gc, const Scene& s, VkRenderPass rp,
                           const VkDescriptorSetLayout dsl[2], double& pipeline_ms, DrawResources& r) {
    VkDevice dev = c.device;
    uint32_t ntex = 0, nubo = 0;
    for (const Draw& d : s.draws) {
        ntex += d.texture ? 1 : 0;
        nubo += d.uniforms.empty() ? 0 : 1;
    }
    VkDescriptorPool dpool = VK_NULL_HANDLE;
    if (ntex + nubo) {
        VkDescriptorPoolSize sizes[2];
        uint32_t nsizes = 0;
        if (ntex) sizes[nsizes++] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, ntex};
        if (nubo) sizes[nsizes++] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nubo};
        VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpci.maxSets = ntex + nubo;
        dpci.poolSizeCount = nsizes;
        dpci.pPoolSizes = sizes;
        vk_check(vkCreateDescriptorPool(dev, &dpci, nullptr, &dpool), "vkCreateDescriptorPool");
        gc.add([dev, dpool] { vkDestroyDescriptorPool(dev, dpool, nullptr); });
    }
    auto allocate_set = [&](VkDescriptorSetLayout l) {
        VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        dsai.descriptorPool = dpool;
        dsai.descriptorSetCount = 1;
        dsai.pSetLayouts = &l;
        VkDescriptorSet set;
        vk_check(vkAllocateDescriptorSets(dev, &dsai, &set), "vkAllocateDescriptorSets");
        return set;
    };
    r.textures.resize(s.draws.size());
    r.sets.assign(s.draws.size(), VK_NULL_HANDLE);
    r.ubo_sets.assign(s.draws.size(), VK_NULL_HANDLE);
    for (size_t i = 0; i < s.draws.size(); ++i) {
        const Draw& d = s.draws[i];
        r.pipes.push_back(make_pipeline(c, gc, s, d, rp, r.layout, pipeline_ms));
        if (d.texture) {
            r.sets[i] = allocate_set(dsl[0]);
            r.textures[i] = make_texture(c, gc, *d.texture);
            VkDescriptorImageInfo ii{r.textures[i].sampler, r.textures[i].view,
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = r.sets[i];
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            w.pImageInfo = &ii;
            vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
        }
        if (!d.uniforms.empty()) {
            r.ubo_sets[i] = allocate_set(dsl[1]);
            const VkDeviceSize bytes = (d.uniforms.size() * 4 + 15) / 16 * 16;  // whole vec4s (std140 arrays)
            Buffer ubo = make_buffer(c, gc, bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
            std::memset(ubo.mapped, 0, bytes);
            std::memcpy(ubo.mapped, d.uniforms.data(), d.uniforms.size() * 4);
            VkDescriptorBufferInfo bi{ubo.buffer, 0, bytes};
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = r.ubo_sets[i];
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            w.pBufferInfo = &bi;
            vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
        }
    }
}

// Indexed draws and packed colour attributes: one buffer each per draw that has them.
void make_draw_buffers(const DeviceContext& c, Cleanup& gc, const Scene& s, DrawResources& r) {
    r.index_buffers.assign(s.draws.size(), VK_NULL_HANDLE);
    r.color_buffers.assign(s.draws.size(), VK_NULL_HANDLE);
    r.condition_buffers.assign(s.draws.size(), VK_NULL_HANDLE);
    for (size_t i = 0; i < s.draws.size(); ++i) {
        const Draw& d = s.draws[i];
        if (d.condition) {
            const uint32_t words[2] = {~*d.condition, *d.condition};
            Buffer pb = make_buffer(c, gc, sizeof words, VK_BUFFER_USAGE_CONDITIONAL_RENDERING_BIT_EXT);
            std::memcpy(pb.mapped, words, sizeof words);
            r.condition_buffers[i] = pb.buffer;
        }
        if (!d.indices.empty()) {
            const size_t size = d.index_type == VK_INDEX_TYPE_UINT8_EXT ? 1
                                : d.index_type == VK_INDEX_TYPE_UINT16  ? 2
                                                                        : 4;
            Buffer ib = make_buffer(c, gc, d.indices.size() * size, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
            for (size_t k = 0; k < d.indices.size(); ++k) {
                const uint32_t v = d.indices[k];
                const uint8_t v8 = uint8_t(v);
                const uint16_t v16 = uint16_t(v);
                std::memcpy(static_cast<uint8_t*>(ib.mapped) + size * k,
                            size == 1   ? static_cast<const void*>(&v8)
                            : size == 2 ? static_cast<const void*>(&v16)
                                        : static_cast<const void*>(&v),
                            size);
            }
            r.index_buffers[i] = ib.buffer;
        }
        if (d.color_format != VK_FORMAT_R32G32B32A32_SFLOAT && !d.vertices.empty()) {
            std::vector<uint8_t> bytes;
            for (const Vertex& v : d.vertices) pack_color(d.color_format, v.color, bytes);
            Buffer cbuf = make_buffer(c, gc, bytes.size(), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
            std::memcpy(cbuf.mapped, bytes.data(), bytes.size());
            r.color_buffers[i] = cbuf.buffer;
        }
    }
}

// Texture uploads: staging buffer -> image, then SHADER_READ_ONLY for the fragment stage.
void record_texture_uploads(VkCommandBuffer cb, const std::vector<Texture>& textures) {
    for (const Texture& tex : textures) {
        if (!tex.image) continue;
        barrier(cb, tex.image, tex.aspect, tex.mips, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkCmdCopyBufferToImage(cb, tex.staging.buffer, tex.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(tex.copies.size()), tex.copies.data());
        barrier(cb, tex.image, tex.aspect, tex.mips, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    }
}

// Draw::dynamic3: the vertex input and the extended dynamic state 3 states through vkCmdSet* (make_pipeline baked
// other values).
void record_dynamic_state3(const DeviceContext& c, VkCommandBuffer cb, const Scene& s, const Draw& d) {
    const DeviceContext::DynamicStateCommands& f = c.cmd;
    const VertexInputLayout l = vertex_input_of(d);
    VkVertexInputBindingDescription2EXT bindings[2];
    VkVertexInputAttributeDescription2EXT attributes[4];
    for (uint32_t i = 0; i < l.binding_count; ++i)
        bindings[i] = {VK_STRUCTURE_TYPE_VERTEX_INPUT_BINDING_DESCRIPTION_2_EXT, nullptr, l.bindings[i].binding,
                       l.bindings[i].stride, l.bindings[i].inputRate, 1};
    for (uint32_t i = 0; i < 4; ++i)
        attributes[i] = {VK_STRUCTURE_TYPE_VERTEX_INPUT_ATTRIBUTE_DESCRIPTION_2_EXT, nullptr, l.attributes[i].location,
                         l.attributes[i].binding, l.attributes[i].format, l.attributes[i].offset};
    f.vertex_input(cb, l.binding_count, bindings, 4, attributes);
    f.polygon_mode(cb, d.polygon_mode);
    f.depth_clamp(cb, d.depth_clamp);
    if (d.depth_clip_enable) f.depth_clip(cb, *d.depth_clip_enable);
    f.negative_one_to_one(cb, d.negative_one_to_one);
    f.logic_op_enable(cb, d.logic_op.has_value());
    f.sample_mask(cb, s.target.samples, &d.sample_mask);
    f.alpha_to_coverage(cb, d.alpha_to_coverage);
    f.line_mode(cb, d.line_mode.value_or(VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT));
    f.line_stipple(cb, VK_FALSE);
    f.provoking_vertex(cb, d.provoking_last ? VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT
                                            : VK_PROVOKING_VERTEX_MODE_FIRST_VERTEX_EXT);
    if (s.target.color == VK_FORMAT_UNDEFINED) return;
    f.blend_enable(cb, 0, 1, &d.blend.blendEnable);
    const VkColorBlendEquationEXT eq = {d.blend.srcColorBlendFactor, d.blend.dstColorBlendFactor,
                                        d.blend.colorBlendOp,        d.blend.srcAlphaBlendFactor,
                                        d.blend.dstAlphaBlendFactor, d.blend.alphaBlendOp};
    f.blend_equation(cb, 0, 1, &eq);
    f.write_mask(cb, 0, 1, &d.blend.colorWriteMask);
}

// Draw::dynamic: the draw's own state through vkCmdSet* over a pipeline made with other values (make_pipeline).
void record_dynamic_state(const DeviceContext& c, VkCommandBuffer cb, const Scene& s, const Draw& d) {
    const DeviceContext::DynamicStateCommands& f = c.cmd;
    const Target& t = s.target;
    const VkViewport vp = d.viewport.value_or(VkViewport{0, 0, float(t.width), float(t.height), 0, 1});
    const VkRect2D sc = d.scissor.value_or(VkRect2D{{0, 0}, {t.width, t.height}});
    const std::vector<VkViewport> vps(d.viewport_count, vp);
    const std::vector<VkRect2D> scs(d.viewport_count, sc);
    f.cull_mode(cb, d.cull);
    f.front_face(cb, d.front_face);
    f.topology(cb, d.topology);
    f.viewport_with_count(cb, d.viewport_count, vps.data());
    f.scissor_with_count(cb, d.viewport_count, scs.data());
    f.depth_test(cb, d.depth_test);
    f.depth_write(cb, d.depth_write);
    f.depth_compare(cb, d.depth_op);
    f.depth_bounds_test(cb, VK_FALSE);
    f.stencil_test(cb, d.stencil_test);
    f.stencil_op(cb, VK_STENCIL_FACE_FRONT_BIT, d.stencil_front.failOp, d.stencil_front.passOp,
                 d.stencil_front.depthFailOp, d.stencil_front.compareOp);
    f.stencil_op(cb, VK_STENCIL_FACE_BACK_BIT, d.stencil_back.failOp, d.stencil_back.passOp, d.stencil_back.depthFailOp,
                 d.stencil_back.compareOp);
    f.rasterizer_discard(cb, VK_FALSE);
    f.depth_bias(cb, d.depth_bias);
    f.primitive_restart(cb, d.primitive_restart);
    if (f.logic_op) f.logic_op(cb, d.logic_op.value_or(VK_LOGIC_OP_COPY));
    if (d.dynamic3) record_dynamic_state3(c, cb, s, d);
}

// Draw::multi: the entries `kMultiStride` bytes apart (a word of padding after each: the stride is honoured).
void record_multi_draw(const DeviceContext& c, VkCommandBuffer cb, const Draw& d) {
    constexpr uint32_t kMultiStride = 16;
    std::vector<int32_t> words(d.multi.size() * kMultiStride / 4, -1);
    for (size_t e = 0; e < d.multi.size(); ++e)
        for (size_t w = 0; w < 3; ++w) words[e * kMultiStride / 4 + w] = d.multi[e][w];
    const uint32_t n = uint32_t(d.multi.size());
    if (!d.indices.empty()) {
        const int32_t* offset = d.multi_vertex_offset ? &*d.multi_vertex_offset : nullptr;
        c.cmd.draw_multi_indexed(cb, n, reinterpret_cast<const VkMultiDrawIndexedInfoEXT*>(words.data()), d.instances,
                                 0, kMultiStride, offset);
    } else {
        c.cmd.draw_multi(cb, n, reinterpret_cast<const VkMultiDrawInfoEXT*>(words.data()), d.instances, 0,
                         kMultiStride);
    }
}

// Draw::condition's vkCmdBeginConditionalRenderingEXT (ended after the draw) and Draw::clear_rect's clear.
void record_condition_and_clear(const DeviceContext& c, VkCommandBuffer cb, const Draw& d, VkBuffer predicate) {
    if (d.condition) {
        VkConditionalRenderingBeginInfoEXT info{VK_STRUCTURE_TYPE_CONDITIONAL_RENDERING_BEGIN_INFO_EXT};
        info.buffer = predicate;
        info.offset = 4;
        info.flags = d.condition_inverted ? VK_CONDITIONAL_RENDERING_INVERTED_BIT_EXT : 0;
        c.cmd.begin_conditional(cb, &info);
    }
    if (d.clear_rect) {
        VkClearAttachment a{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
        std::memcpy(a.clearValue.color.float32, d.clear_rect_color.data(), 16);
        const VkClearRect rect{*d.clear_rect, 0, 1};
        vkCmdClearAttachments(cb, 1, &a, 1, &rect);
    }
}

// The render pass with every draw, each wrapped in its occlusion query with QueryMode::kPerDraw.
void record_pass(const DeviceContext& c, VkCommandBuffer cb, const Scene& s, VkRenderPass rp, const Attachments& at,
                 const DrawResources& r, const Buffer& vb, VkQueryPool qpool, VkQueryControlFlags qflags) {
    const Target& t = s.target;
    VkClearValue clears[3];
    uint32_t nclear = 0;
    if (t.color != VK_FORMAT_UNDEFINED) std::memcpy(clears[nclear++].color.float32, t.clear_color, 16);
    if (t.depth != VK_FORMAT_UNDEFINED) clears[nclear++].depthStencil = {t.clear_depth, t.clear_stencil};
    if (at.resolve) clears[nclear++] = clears[0];
    VkRenderPassBeginInfo rpbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rpbi.renderPass = rp;
    rpbi.framebuffer = at.framebuffer;
    rpbi.renderArea = {{0, 0}, {t.width, t.height}};
    rpbi.clearValueCount = nclear;
    rpbi.pClearValues = clears;
    vkCmdBeginRenderPass(cb, &rpbi, VK_SUBPASS_CONTENTS_INLINE);
    VkDeviceSize first = 0;
    for (size_t i = 0; i < s.draws.size(); ++i) {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipes[i]);
        if (r.sets[i])
            vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 0, 1, &r.sets[i], 0, nullptr);
        if (r.ubo_sets[i])
            vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 1, 1, &r.ubo_sets[i], 0, nullptr);
        VkDeviceSize offset = first * sizeof(Vertex);
        const Draw& d = s.draws[i];
        if (d.dynamic) {
            record_dynamic_state(c, cb, s, d);
        }
        if (d.dynamic && !d.dynamic3) {  // with dynamic3 the strides are vkCmdSetVertexInputEXT's
            const VkDeviceSize stride = sizeof(Vertex);
            c.cmd.bind_vertex_buffers2(cb, 0, 1, &vb.buffer, &offset, nullptr, &stride);
        } else {
            vkCmdBindVertexBuffers(cb, 0, 1, &vb.buffer, &offset);
        }
        if (r.color_buffers[i]) {
            const VkDeviceSize zero = 0, whole = VK_WHOLE_SIZE, stride = packed_color_bytes(d.color_format);
            if (d.dynamic && !d.dynamic3)
                c.cmd.bind_vertex_buffers2(cb, 1, 1, &r.color_buffers[i], &zero, &whole, &stride);
            else
                vkCmdBindVertexBuffers(cb, 1, 1, &r.color_buffers[i], &zero);
        }
        if (!d.push_constants.empty())
            vkCmdPushConstants(cb, r.layout, r.push_stages, 0, uint32_t(d.push_constants.size() * 4),
                               d.push_constants.data());
        if (d.color_write_enable && d.color_write_dynamic) c.cmd.color_write_enable(cb, 1, &*d.color_write_enable);
        if (s.queries == QueryMode::kPerDraw) vkCmdBeginQuery(cb, qpool, uint32_t(i), qflags);
        if (r.index_buffers[i]) vkCmdBindIndexBuffer(cb, r.index_buffers[i], 0, d.index_type);
        record_condition_and_clear(c, cb, d, r.condition_buffers[i]);
        if (!d.multi.empty()) {
            record_multi_draw(c, cb, d);
        } else if (r.index_buffers[i]) {
            vkCmdDrawIndexed(cb, uint32_t(d.indices.size()), d.instances, 0, 0, 0);
        } else if (!d.vertices.empty()) {
            vkCmdDraw(cb, uint32_t(d.vertices.size()), d.instances, 0, 0);
        }
        if (d.condition) c.cmd.end_conditional(cb);
        if (s.queries == QueryMode::kPerDraw) vkCmdEndQuery(cb, qpool, uint32_t(i));
        first += s.draws[i].vertices.size();
    }
    vkCmdEndRenderPass(cb);
}

// The read-back copies and the barrier that makes them visible to the host.
void record_readbacks(VkCommandBuffer cb, const Target& t, const std::vector<Readback>& reads) {
    for (const Readback& r : reads) {
        VkBufferImageCopy region{};
        region.imageSubresource = {r.aspect, 0, 0, 1};
        region.imageExtent = {t.width, t.height, 1};
        vkCmdCopyImageToBuffer(cb, r.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.buffer.buffer, 1, &region);
    }
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0,
                         nullptr);
}

// SHADER_WRITE is not an access of the TRANSFER stage (VUID-vkCmdPipelineBarrier-srcAccessMask-02815); drivers
// ignore access masks, so only the validation layer notices (--selftest-validation).
void record_invalid_barrier(VkCommandBuffer cb) {
    VkMemoryBarrier bad{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_ACCESS_TRANSFER_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &bad, 0, nullptr, 0,
                         nullptr);
}

}  // namespace

struct Frame::Impl {
    Cleanup gc;  // first member: destroyed last, after the queue is idle
    const DeviceContext* c = nullptr;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    std::vector<Readback> reads;
    Buffer query_results{};  // QueryMode != kNone: 64-bit values, then 64-bit availability, per query
    uint32_t num_queries = 0;
    uint32_t query_stride = 16;
    double pipeline_ms = 0;
    std::function<std::vector<Plane>(const DeviceContext&)> run;  // a scene that runs its own commands
    std::vector<Plane> run_planes;
    ~Impl() {
        if (c) vkQueueWaitIdle(c->queue);
    }

    VkQueryPool make_queries(const Scene& s, VkCommandBuffer cb);
    void record_query_results(VkCommandBuffer cb, VkQueryPool qpool);
};

// The occlusion query pool and its result buffer, reset at the start of every submission (the frame is submitted
// again for timing); null without queries.
VkQueryPool Frame::Impl::make_queries(const Scene& s, VkCommandBuffer cb) {
    const uint32_t nqueries = s.queries == QueryMode::kPerDraw      ? uint32_t(s.draws.size())
                              : s.queries == QueryMode::kAcrossPass ? 1u
                                                                    : 0u;
    if (!nqueries) return VK_NULL_HANDLE;
    VkDevice dev = c->device;
    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = s.statistics ? VK_QUERY_TYPE_PIPELINE_STATISTICS : VK_QUERY_TYPE_OCCLUSION;
    qci.pipelineStatistics = s.statistics;
    qci.queryCount = nqueries;
    const uint32_t values = s.statistics ? uint32_t(__builtin_popcount(s.statistics)) : 1;  // occlusion: one
    query_stride = 8 * (values + 1);
    VkQueryPool qpool;
    vk_check(vkCreateQueryPool(dev, &qci, nullptr, &qpool), "vkCreateQueryPool");
    gc.add([dev, qpool] { vkDestroyQueryPool(dev, qpool, nullptr); });
    query_results = make_buffer(*c, gc, VkDeviceSize(query_stride) * nqueries, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    num_queries = nqueries;
    vkCmdResetQueryPool(cb, qpool, 0, nqueries);
    return qpool;
}

// vkCmdCopyQueryPoolResults into a buffer first filled with a marker (unwritten words show).
void Frame::Impl::record_query_results(VkCommandBuffer cb, VkQueryPool qpool) {
    if (!num_queries) return;
    vkCmdFillBuffer(cb, query_results.buffer, 0, VK_WHOLE_SIZE, 0xDEADBEEFu);
    VkMemoryBarrier fill{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                         VK_ACCESS_TRANSFER_WRITE_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &fill, 0, nullptr,
                         0, nullptr);
    vkCmdCopyQueryPoolResults(
        cb, qpool, 0, num_queries, query_results.buffer, 0, query_stride,
        VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
}

Frame::~Frame() = default;
double Frame::pipeline_ms() const {
    return impl_->pipeline_ms;
}

// Builds everything the scene needs and records one command buffer: texture uploads, the pass (with its queries),
// the query results, the read-back copies.
Frame::Frame(const DeviceContext& c, const Scene& s, bool selftest_bad_command) : impl_(std::make_unique<Impl>()) {
    Impl& f = *impl_;
    f.c = &c;
    if (s.run) {
        f.run = s.run;
        return;
    }
    VkDevice dev = c.device;
    const Buffer vb = upload_vertices(c, f.gc, s);
    VkRenderPass rp = make_render_pass(c, f.gc, s.target);
    const Attachments at = make_attachments(c, f.gc, s.target, rp, f.reads);
    DrawResources r;
    VkDescriptorSetLayout dsl[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    make_layouts(c, f.gc, s, dsl, r);
    make_draw_descriptors(c, f.gc, s, rp, dsl, f.pipeline_ms, r);
    make_draw_buffers(c, f.gc, s, r);

    VkCommandBufferAllocateInfo cbai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cbai.commandPool = c.pool;
    cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cbai.commandBufferCount = 1;
    VkCommandBuffer cb;
    vk_check(vkAllocateCommandBuffers(dev, &cbai, &cb), "vkAllocateCommandBuffers");
    f.gc.add([dev, pool = c.pool, cb] { vkFreeCommandBuffers(dev, pool, 1, &cb); });
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vk_check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
    record_texture_uploads(cb, r.textures);
    VkQueryPool qpool = f.make_queries(s, cb);
    // PRECISE asks for exact counts; both drivers report occlusionQueryPrecise (requirements.cpp checks it).
    // (PRECISE is for occlusion queries only.)
    const VkQueryControlFlags qflags = s.statistics ? 0 : VK_QUERY_CONTROL_PRECISE_BIT;
    if (s.queries == QueryMode::kAcrossPass) vkCmdBeginQuery(cb, qpool, 0, qflags);
    record_pass(c, cb, s, rp, at, r, vb, qpool, qflags);
    if (s.queries == QueryMode::kAcrossPass) vkCmdEndQuery(cb, qpool, 0);
    f.record_query_results(cb, qpool);
    if (selftest_bad_command) record_invalid_barrier(cb);
    record_readbacks(cb, s.target, f.reads);
    vk_check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");

    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    vk_check(vkCreateFence(dev, &fci, nullptr, &fence), "vkCreateFence");
    f.gc.add([dev, fence] { vkDestroyFence(dev, fence, nullptr); });
    f.cb = cb;
    f.fence = fence;
}

double Frame::submit() {
    const DeviceContext& c = *impl_->c;
    if (impl_->run) {
        auto t0 = Clock::now();
        impl_->run_planes = impl_->run(c);
        return ms_since(t0);
    }
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &impl_->cb;
    auto t0 = Clock::now();
    vk_check(vkQueueSubmit(c.queue, 1, &si, impl_->fence), "vkQueueSubmit");
    vk_check(vkWaitForFences(c.device, 1, &impl_->fence, VK_TRUE, 60ull * 1000 * 1000 * 1000), "vkWaitForFences");
    double ms = ms_since(t0);
    vk_check(vkResetFences(c.device, 1, &impl_->fence), "vkResetFences");
    return ms;
}

std::vector<Plane> Frame::planes() const {
    if (impl_->run) return impl_->run_planes;
    std::vector<Plane> out;
    for (const Readback& r : impl_->reads) {
        Plane p = r.plane;
        p.data.resize(size_t(p.width) * p.height * p.texel_bytes);
        std::memcpy(p.data.data(), r.buffer.mapped, p.data.size());
        out.push_back(std::move(p));
    }
    if (impl_->num_queries) {
        Plane p{"queries", VK_FORMAT_UNDEFINED, impl_->num_queries, 1, impl_->query_stride, {}};
        p.data.resize(size_t(impl_->query_stride) * impl_->num_queries);
        std::memcpy(p.data.data(), impl_->query_results.mapped, p.data.size());
        out.push_back(std::move(p));
    }
    return out;
}

RenderResult render(const DeviceContext& c, const Scene& s, int timing_reps, bool selftest_bad_command) {
    Frame f(c, s, selftest_bad_command);
    RenderResult out;
    f.submit();
    out.planes = f.planes();
    out.pipeline_ms = f.pipeline_ms();
    for (int i = 0; i < timing_reps; ++i) out.frame_ms.push_back(f.submit());
    return out;
}

}  // namespace tilevk::cts
