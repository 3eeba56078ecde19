// Draws at vkQueueSubmit: bound state -> rast::render (PipelineState, DrawCall, shader::Bindings), one Renderer per
// queue. The renderer's targets are sample planes (rast/render/targets.h) while tilevk images interleave samples
// per pixel and keep D32_SFLOAT_S8_UINT's stencil in the texel (icd/image.h): such attachments are copied into
// planar staging memory when a subpass's rendering starts and copied back when it ends. 1x single-aspect
// attachments are rendered in place.
#include <cstdio>
#include <cstring>
#include <deque>

#include "buffer.h"
#include "buffer_view.h"
#include "descriptor_pool.h"
#include "execute.h"
#include "formats.h"
#include "framebuffer.h"
#include "image.h"
#include "physical_device.h"
#include "pipeline.h"
#include "rast/core/thread_pool.h"
#include "rast/render/renderer.h"
#include "render_pass.h"
#include "render_state.h"
#include "sampler.h"
#include "workers.h"

namespace tilevk::icd {

namespace rr = rast::render;

// One plane of an attachment copied out of the image: element (x, y, sample s) of the image lives at
// image + y*row_pitch + (x*samples + s)*texel_bytes + byte_offset, in the staging copy at
// plane + s*w*h*elem + (y*w + x)*elem.
struct Staged {
    uint8_t* image = nullptr;
    size_t row_pitch = 0;
    uint32_t samples = 1, texel_bytes = 0, byte_offset = 0, elem = 0, w = 0, h = 0;
    uint32_t copy_bytes = 0;  // bytes of each element that belong to this aspect (D24S8 depth: 3 of 4)
    std::vector<uint8_t> plane;
};

struct DrawContext {
    rast::ThreadPool pool{rast::ThreadPool::threads_from_env()};
    rr::Renderer renderer{pool};
    bool active = false;
    // Kept alive until the renderer's pass ends: DrawRecords point at these.
    std::deque<rr::PipelineState> states;
    std::deque<shader::ImageView> views;
    std::deque<shader::SamplerState> samplers;
    std::deque<Staged> staged;
    bool warned = false;
};

DrawContext* create_draw_context() {
    return new DrawContext();
}
void destroy_draw_context(DrawContext* ctx) {
    delete ctx;
}
uint64_t shader_watchdog_hits(const DrawContext& ctx) {
    return ctx.renderer.shader_loop_limit_hits();
}

namespace {

void copy_planes(Staged& s, bool to_staging) {
    const size_t plane_size = size_t(s.w) * s.h * s.elem;
    for (uint32_t sm = 0; sm < s.samples; ++sm)
        for (uint32_t y = 0; y < s.h; ++y)
            for (uint32_t x = 0; x < s.w; ++x) {
                uint8_t* img = s.image + y * s.row_pitch + (size_t(x) * s.samples + sm) * s.texel_bytes + s.byte_offset;
                uint8_t* pl = s.plane.data() + sm * plane_size + (size_t(y) * s.w + x) * s.elem;
                if (to_staging)
                    std::memcpy(pl, img, s.copy_bytes);
                else
                    std::memcpy(img, pl, s.copy_bytes);
            }
}

// Points the renderer at one aspect of a view: in place when the image layout already is a sample plane,
// else through staging. Returns (data, row pitch, sample stride).
struct PlaneRef {
    uint8_t* data;
    size_t row_pitch, sample_stride;
};
PlaneRef plane_of(DrawContext& ctx, const ImageView& v, uint32_t elem, uint32_t byte_offset, uint32_t w, uint32_t h,
                  uint32_t copy_bytes = 0) {
    const Image& img = *v.image;
    const uint32_t level = v.range.baseMipLevel;
    uint8_t* base = img.texel(level, v.range.baseArrayLayer, 0, 0);
    const size_t pitch = img.layout.row_pitch[level];
    if (copy_bytes == 0) copy_bytes = elem;
    if (img.samples == 1 && img.format->texel_bytes == elem && copy_bytes == elem)
        return {base + byte_offset, pitch, 0};
    Staged& s = ctx.staged.emplace_back();
    s.image = base;
    s.row_pitch = pitch;
    s.samples = img.samples;
    s.texel_bytes = img.format->texel_bytes;
    s.byte_offset = byte_offset;
    s.elem = elem;
    s.copy_bytes = copy_bytes;
    s.w = w;
    s.h = h;
    s.plane.resize(size_t(w) * h * elem * s.samples);
    copy_planes(s, true);
    return {s.plane.data(), size_t(w) * elem, size_t(w) * h * elem};
}

// llvmpipe's linear mode (lp_state_derived.c check_linear_rasterizer, notes §0.3): lavapipe binds the subpass's
// colour attachments as cbufs (VK_ATTACHMENT_UNUSED ones as NULL) and its depth/stencil attachment as zsbuf; the
// mode needs exactly one cbuf, non-null, of format B8G8R8A8_UNORM (the view's format; B8G8R8X8_UNORM has no
// Vulkan format lavapipe maps to it), single-sampled, whose resource is PIPE_TEXTURE_2D (lvp_image.c: a 2D image
// with one array layer), no zsbuf, and no shader writing a viewport index (tilevk exposes no such output).
bool lavapipe_linear_mode(const Subpass& sp, const Framebuffer& fbo) {
    if (sp.colors.size() != 1 || sp.depth_stencil.attachment != VK_ATTACHMENT_UNUSED) return false;
    const uint32_t a = sp.colors[0].attachment;
    if (a == VK_ATTACHMENT_UNUSED || a >= fbo.attachments.size()) return false;
    const ImageView& v = *fbo.attachments[a];
    return v.format->format == VK_FORMAT_B8G8R8A8_UNORM && v.image->samples == 1 && v.image->array_layers == 1;
}

// Starts the renderer on the current subpass's attachments.
void begin_rendering(ExecState& st, int pipeline_samples) {
    DrawContext& ctx = *st.draw;
    const Framebuffer& fbo = *st.framebuffer;
    const Subpass& sp = st.render_pass->subpasses[st.subpass];
    rr::Framebuffer fb;
    fb.width = int32_t(fbo.width);
    fb.height = int32_t(fbo.height);
    fb.samples = pipeline_samples;
    fb.num_color = uint32_t(std::min<size_t>(sp.colors.size(), rr::kMaxColorTargets));
    for (uint32_t i = 0; i < fb.num_color; ++i) {
        const uint32_t a = sp.colors[i].attachment;
        if (a == VK_ATTACHMENT_UNUSED || a >= fbo.attachments.size()) continue;
        const ImageView& v = *fbo.attachments[a];
        rr::ColorTarget& t = fb.color[i];
        if (!color_format_of(v.format->format, &t.format)) continue;
        fb.samples = int(v.image->samples);
        const PlaneRef p = plane_of(ctx, v, v.format->texel_bytes, 0, fbo.width, fbo.height);
        t.data = p.data;
        t.row_pitch = p.row_pitch;
        t.sample_stride = p.sample_stride;
    }
    const uint32_t d = sp.depth_stencil.attachment;
    if (d != VK_ATTACHMENT_UNUSED && d < fbo.attachments.size()) {
        const ImageView& v = *fbo.attachments[d];
        fb.samples = int(v.image->samples);
        rr::DepthStencilTarget& t = fb.depth_stencil;
        t.format = depth_format_of(v.format->format);
        if (t.format != rast::fragment::DepthFormat::None) {
            // X8D24 (D24_UNORM_S8_UINT): the renderer's 32-bit depth words get the 24 depth bits, the top byte
            // (the image's stencil) stays 0 in staging and is never written back.
            const uint32_t copy = t.format == rast::fragment::DepthFormat::X8D24 ? 3 : 0;
            const PlaneRef p = plane_of(ctx, v, uint32_t(rr::depth_bytes(t.format)), 0, fbo.width, fbo.height, copy);
            t.depth = p.data;
            t.depth_row_pitch = p.row_pitch;
            t.depth_sample_stride = p.sample_stride;
        }
        if (v.format->aspects & VK_IMAGE_ASPECT_STENCIL_BIT) {
            const PlaneRef p =
                plane_of(ctx, v, 1, aspect_offset(*v.format, VK_IMAGE_ASPECT_STENCIL_BIT), fbo.width, fbo.height);
            t.stencil = p.data;
            t.stencil_row_pitch = p.row_pitch;
            t.stencil_sample_stride = p.sample_stride;
        }
    }
    fb.linear_mode = lavapipe_linear_mode(sp, fbo);
    ctx.renderer.begin(fb);
    if (st.query_command_pending) {
        ctx.renderer.mark_scene_not_linear();
        st.query_command_pending = false;
    }
    ctx.active = true;
}

shader::Descriptor buffer_descriptor(const Descriptor& d, uint32_t dyn, bool writable) {
    shader::Descriptor out;
    if (d.buffer == nullptr) return out;
    const VkDeviceSize off = d.offset + dyn;
    if (off > d.buffer->size) return out;
    uint8_t* p = d.buffer->data() + off;
    out.buffer.data = p;
    out.buffer.writable = writable ? p : nullptr;
    out.buffer.size = std::min<VkDeviceSize>(d.range, d.buffer->size - off);
    return out;
}

const shader::ImageView* image_of(DrawContext& ctx, const ImageView* v) {
    if (v == nullptr || v->image == nullptr || v->image->memory == nullptr) return nullptr;
    const Image& img = *v->image;
    shader::ImageView& out = ctx.views.emplace_back();
    out.format = shader_format_of(v->format->format);
    if (out.format == shader::Format::Undefined || img.samples != 1) return nullptr;
    const uint32_t b = v->range.baseMipLevel;
    out.base = img.memory->data + img.memory_offset;
    out.width = img.level_width(b);
    out.height = img.level_height(b);
    out.levels = std::min<uint32_t>(v->range.levelCount, uint32_t(out.level.size()));
    out.layers = v->range.layerCount;
    const VkComponentSwizzle mapping[4] = {v->components.r, v->components.g, v->components.b, v->components.a};
    for (uint8_t c = 0; c < 4; ++c) {
        switch (mapping[c]) {
            case VK_COMPONENT_SWIZZLE_ZERO:
                out.swizzle[c] = shader::kSwizzleZero;
                break;
            case VK_COMPONENT_SWIZZLE_ONE:
                out.swizzle[c] = shader::kSwizzleOne;
                break;
            case VK_COMPONENT_SWIZZLE_R:
            case VK_COMPONENT_SWIZZLE_G:
            case VK_COMPONENT_SWIZZLE_B:
            case VK_COMPONENT_SWIZZLE_A:
                out.swizzle[c] = uint8_t(mapping[c] - VK_COMPONENT_SWIZZLE_R);
                break;
            default:  // IDENTITY
                out.swizzle[c] = c;
                break;
        }
    }
    for (uint32_t i = 0; i < out.levels; ++i) {
        out.level[i].offset =
            img.layout.level_offset[b + i] + VkDeviceSize(v->range.baseArrayLayer) * img.layout.layer_pitch[b + i];
        out.level[i].row_pitch = img.layout.row_pitch[b + i];
        out.level[i].layer_pitch = img.layout.layer_pitch[b + i];
    }
    return &out;
}

// A uniform texel buffer as shader/ reads it: one row of range / texel-size texels (level 0, one layer), fetched
// with texelFetch like a 1D image.
const shader::ImageView* texel_buffer_of(DrawContext& ctx, VkBufferView handle) {
    const BufferView* v = from_handle<BufferView>(handle);
    if (v == nullptr || v->buffer == nullptr || v->buffer->data() == nullptr) return nullptr;
    const FormatInfo* f = find_format(v->format);
    if (f == nullptr || !(f->buffer_features & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT)) return nullptr;
    if (v->offset > v->buffer->size) return nullptr;
    const VkDeviceSize range = std::min(v->range, v->buffer->size - v->offset);
    const VkDeviceSize texels = std::min<VkDeviceSize>(range / f->texel_bytes, kMaxTexelBufferElements);
    if (texels == 0) return nullptr;
    shader::ImageView& out = ctx.views.emplace_back();
    out.format = shader_format_of(v->format);
    if (out.format == shader::Format::Undefined) return nullptr;
    out.base = v->buffer->data() + v->offset;
    out.width = uint32_t(texels);
    out.height = 1;
    out.levels = 1;
    out.layers = 1;
    out.level[0].offset = 0;
    out.level[0].row_pitch = texels * f->texel_bytes;
    out.level[0].layer_pitch = out.level[0].row_pitch;
    return &out;
}

const shader::SamplerState* sampler_of(DrawContext& ctx, const Sampler* s) {
    if (s == nullptr) return nullptr;
    return &ctx.samplers.emplace_back(sampler_state_of(s->info));
}

void build_bindings(ExecState& st, shader::Bindings& b) {
    DrawContext& ctx = *st.draw;
    const BoundState& bs = st.bound;
    for (uint32_t si = 0; si < BoundState::kMaxSets; ++si) {
        const DescriptorSet* set = bs.sets[si];
        if (set == nullptr || set->layout == nullptr) continue;
        uint32_t dyn_index = 0;
        for (const LayoutBinding& lb : set->layout->bindings) {
            for (uint32_t e = 0; e < lb.count; ++e) {
                const Descriptor& d = set->slots[lb.first_slot + e];
                const bool dynamic = lb.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC ||
                                     lb.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC;
                const uint32_t dyn =
                    dynamic && dyn_index < BoundState::kMaxDynamicOffsets ? bs.dynamic_offsets[si][dyn_index] : 0;
                if (dynamic) ++dyn_index;
                const Sampler* smp = !lb.immutable_samplers.empty() ? lb.immutable_samplers[e] : d.sampler;
                shader::Descriptor out;
                switch (lb.type) {
                    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
                    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC:
                        out = buffer_descriptor(d, dyn, false);
                        break;
                    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
                    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC:
                        out = buffer_descriptor(d, dyn, true);
                        break;
                    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
                        out.image = image_of(ctx, d.image_view);
                        out.sampler = sampler_of(ctx, smp);
                        break;
                    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
                    case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:  // read by subpassLoad as a texel fetch
                        out.image = image_of(ctx, d.image_view);
                        break;
                    case VK_DESCRIPTOR_TYPE_SAMPLER:
                        out.sampler = sampler_of(ctx, smp);
                        break;
                    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
                        out.image = texel_buffer_of(ctx, d.buffer_view);
                        break;
                    default:
                        continue;  // not reported as supported
                }
                b.set(si, lb.binding, e, out);
            }
        }
    }
    b.push_constants =
        std::span<const std::byte>(reinterpret_cast<const std::byte*>(bs.push_constants), sizeof bs.push_constants);
}

// The pipeline's state with the bound dynamic state applied.
rr::PipelineState& draw_state(ExecState& st) {
    const Pipeline& p = *st.bound.pipeline;
    const BoundState& bs = st.bound;
    rr::PipelineState& s = st.draw->states.emplace_back(p.state);
    auto dyn = [&](VkDynamicState d) { return (p.dynamic & dynamic_bit(d)) != 0; };
    if (dyn(VK_DYNAMIC_STATE_VIEWPORT)) {
        const VkViewport& v = bs.viewport;
        s.viewport = {v.x, v.y, v.width, v.height, v.minDepth, v.maxDepth};
    }
    if (dyn(VK_DYNAMIC_STATE_SCISSOR)) {
        const VkRect2D& r = bs.scissor;
        s.scissor = {r.offset.x, r.offset.y, int32_t(r.offset.x + int64_t(r.extent.width)),
                     int32_t(r.offset.y + int64_t(r.extent.height))};
    }
    if (dyn(VK_DYNAMIC_STATE_LINE_WIDTH)) s.line_width = bs.line_width;
    if (dyn(VK_DYNAMIC_STATE_DEPTH_BIAS)) {
        s.depth_bias.constant_factor = bs.depth_bias[0];
        s.depth_bias.clamp = bs.depth_bias[1];
        s.depth_bias.slope_factor = bs.depth_bias[2];
    }
    if (dyn(VK_DYNAMIC_STATE_BLEND_CONSTANTS)) std::memcpy(s.blend_constants, bs.blend_constants, 16);
    rast::fragment::StencilFace* faces[2] = {&s.depth_stencil.front, &s.depth_stencil.back};
    for (int f = 0; f < 2; ++f) {
        if (dyn(VK_DYNAMIC_STATE_STENCIL_COMPARE_MASK)) faces[f]->compare_mask = uint8_t(bs.stencil_compare[f]);
        if (dyn(VK_DYNAMIC_STATE_STENCIL_WRITE_MASK)) faces[f]->write_mask = uint8_t(bs.stencil_write[f]);
        if (dyn(VK_DYNAMIC_STATE_STENCIL_REFERENCE)) faces[f]->reference = uint8_t(bs.stencil_ref[f]);
    }
    // Rendering never leaves the framebuffer.
    s.scissor.x1 = std::min(s.scissor.x1, int32_t(st.framebuffer->width));
    s.scissor.y1 = std::min(s.scissor.y1, int32_t(st.framebuffer->height));
    return s;
}

void run_draw(ExecState& st, rr::DrawCall& call) {
    const Pipeline* p = st.bound.pipeline;
    if (st.render_pass == nullptr || p == nullptr || p->rasterizer_discard) return;
    DrawContext& ctx = *st.draw;
    if (!ctx.active) begin_rendering(st, p->state.samples);
    const BoundState& bs = st.bound;
    for (uint32_t i = 0; i < BoundState::kMaxVertexBuffers; ++i) {
        rr::VertexBufferBinding vb;
        if (const Buffer* b = bs.vertex_buffers[i]; b && b->memory && bs.vertex_offsets[i] <= b->size) {
            vb.data = b->data() + bs.vertex_offsets[i];
            vb.size = uint32_t(std::min<VkDeviceSize>(b->size - bs.vertex_offsets[i], UINT32_MAX));
        }
        call.vertex_buffers.push_back(vb);
    }
    if (call.indexed) {
        const Buffer* b = bs.index_buffer;
        if (b == nullptr || b->memory == nullptr || bs.index_offset > b->size) return;
        call.index_data = b->data() + bs.index_offset;
        call.index_bytes = uint32_t(std::min<VkDeviceSize>(b->size - bs.index_offset, UINT32_MAX));
        call.index_size = bs.index_type == VK_INDEX_TYPE_UINT16 ? 2 : 4;
    }
    shader::Bindings bindings;
    build_bindings(st, bindings);
    call.samples_passed = active_occlusion_counter(st);
    const std::string err = ctx.renderer.draw(draw_state(st), call, bindings);
    if (!err.empty() && !ctx.warned) {
        log_error("vkQueueSubmit: a draw was not rendered: %s", err.c_str());
        ctx.warned = true;
    }
}

}  // namespace

void note_query_command_in_pass(ExecState& st) {
    if (st.render_pass == nullptr) return;
    if (st.draw->active)
        st.draw->renderer.mark_scene_not_linear();
    else
        st.query_command_pending = true;
}

void finish_rendering(ExecState& st) {
    DrawContext& ctx = *st.draw;
    if (ctx.active) {
        ctx.renderer.end();
        for (Staged& s : ctx.staged) copy_planes(s, false);
        ctx.staged.clear();
        ctx.states.clear();
        ctx.views.clear();
        ctx.samplers.clear();
        ctx.active = false;
    }
    // The draws of queries ended in this pass are rendered (and counted) now.
    publish_ended_queries(st);
}

void run_on_workers(ExecState& st, size_t num_tasks, const std::function<void(size_t task)>& fn) {
    if (num_tasks == 0) return;
    if (num_tasks == 1) {
        fn(0);
        return;
    }
    st.draw->pool.run(num_tasks, [&fn](unsigned, size_t task) { fn(task); });
}

void exec_state_command(ExecState& st, const Cmd& cmd) {
    BoundState& bs = st.bound;
    switch (cmd.type) {
        case CmdType::kBindPipeline: {
            const auto& c = static_cast<const CmdBindPipeline&>(cmd);
            if (c.bind_point == VK_PIPELINE_BIND_POINT_GRAPHICS) bs.pipeline = c.pipeline;
            break;
        }
        case CmdType::kBindDescriptorSets: {
            const auto& c = static_cast<const CmdBindDescriptorSets&>(cmd);
            if (c.bind_point != VK_PIPELINE_BIND_POINT_GRAPHICS) break;
            uint32_t next_dyn = 0;
            for (uint32_t i = 0; i < c.set_count && c.first_set + i < BoundState::kMaxSets; ++i) {
                DescriptorSet* set = c.sets[i];
                const uint32_t si = c.first_set + i;
                bs.sets[si] = set;
                if (set == nullptr || set->layout == nullptr) continue;
                uint32_t k = 0;
                for (const LayoutBinding& lb : set->layout->bindings) {
                    if (lb.type != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC &&
                        lb.type != VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC)
                        continue;
                    for (uint32_t e = 0; e < lb.count; ++e, ++k, ++next_dyn)
                        if (k < BoundState::kMaxDynamicOffsets && next_dyn < c.dynamic_offset_count)
                            bs.dynamic_offsets[si][k] = c.dynamic_offsets[next_dyn];
                }
            }
            break;
        }
        case CmdType::kBindVertexBuffers: {
            const auto& c = static_cast<const CmdBindVertexBuffers&>(cmd);
            for (uint32_t i = 0; i < c.count && c.first_binding + i < BoundState::kMaxVertexBuffers; ++i) {
                bs.vertex_buffers[c.first_binding + i] = c.buffers[i];
                bs.vertex_offsets[c.first_binding + i] = c.offsets[i];
            }
            break;
        }
        case CmdType::kBindIndexBuffer: {
            const auto& c = static_cast<const CmdBindIndexBuffer&>(cmd);
            bs.index_buffer = c.buffer;
            bs.index_offset = c.offset;
            bs.index_type = c.index_type;
            break;
        }
        case CmdType::kPushConstants: {
            const auto& c = static_cast<const CmdPushConstants&>(cmd);
            if (c.offset < sizeof bs.push_constants && c.values)
                std::memcpy(bs.push_constants + c.offset, c.values,
                            std::min<size_t>(c.size, sizeof bs.push_constants - c.offset));
            break;
        }
        case CmdType::kSetViewport: {
            const auto& c = static_cast<const CmdSetViewport&>(cmd);
            if (c.first == 0 && c.count > 0) bs.viewport = c.viewports[0];
            break;
        }
        case CmdType::kSetScissor: {
            const auto& c = static_cast<const CmdSetScissor&>(cmd);
            if (c.first == 0 && c.count > 0) bs.scissor = c.scissors[0];
            break;
        }
        case CmdType::kSetLineWidth:
            bs.line_width = static_cast<const CmdSetLineWidth&>(cmd).width;
            break;
        case CmdType::kSetDepthBias: {
            const auto& c = static_cast<const CmdSetDepthBias&>(cmd);
            bs.depth_bias[0] = c.constant_factor;
            bs.depth_bias[1] = c.clamp;
            bs.depth_bias[2] = c.slope_factor;
            break;
        }
        case CmdType::kSetBlendConstants:
            std::memcpy(bs.blend_constants, static_cast<const CmdSetBlendConstants&>(cmd).constants, 16);
            break;
        case CmdType::kSetStencilCompareMask:
        case CmdType::kSetStencilWriteMask:
        case CmdType::kSetStencilReference: {
            // The three commands share one layout: faces, value.
            const auto& c = static_cast<const CmdSetStencilReference&>(cmd);
            uint32_t* v = cmd.type == CmdType::kSetStencilCompareMask ? bs.stencil_compare
                          : cmd.type == CmdType::kSetStencilWriteMask ? bs.stencil_write
                                                                      : bs.stencil_ref;
            if (c.faces & VK_STENCIL_FACE_FRONT_BIT) v[0] = c.value;
            if (c.faces & VK_STENCIL_FACE_BACK_BIT) v[1] = c.value;
            break;
        }
        default:
            break;
    }
}

void exec_draw_command(ExecState& st, const Cmd& cmd) {
    switch (cmd.type) {
        case CmdType::kDraw: {
            const auto& c = static_cast<const CmdDraw&>(cmd);
            rr::DrawCall call;
            call.count = c.vertex_count;
            call.instance_count = c.instance_count;
            call.first = c.first_vertex;
            call.first_instance = c.first_instance;
            run_draw(st, call);
            break;
        }
        case CmdType::kDrawIndexed: {
            const auto& c = static_cast<const CmdDrawIndexed&>(cmd);
            rr::DrawCall call;
            call.indexed = true;
            call.count = c.index_count;
            call.instance_count = c.instance_count;
            call.first = c.first_index;
            call.vertex_offset = c.vertex_offset;
            call.first_instance = c.first_instance;
            run_draw(st, call);
            break;
        }
        case CmdType::kDrawIndirect:
        case CmdType::kDrawIndexedIndirect: {
            const auto& c = static_cast<const CmdDrawIndirect&>(cmd);  // same layout as CmdDrawIndexedIndirect
            const bool indexed = cmd.type == CmdType::kDrawIndexedIndirect;
            const size_t size = indexed ? sizeof(VkDrawIndexedIndirectCommand) : sizeof(VkDrawIndirectCommand);
            for (uint32_t i = 0; i < c.draw_count; ++i) {
                const VkDeviceSize off = c.offset + VkDeviceSize(i) * c.stride;
                if (c.buffer == nullptr || off + size > c.buffer->size) break;
                rr::DrawCall call;
                call.indexed = indexed;
                if (indexed) {
                    VkDrawIndexedIndirectCommand d;
                    std::memcpy(&d, c.buffer->data() + off, sizeof d);
                    call.count = d.indexCount;
                    call.instance_count = d.instanceCount;
                    call.first = d.firstIndex;
                    call.vertex_offset = d.vertexOffset;
                    call.first_instance = d.firstInstance;
                } else {
                    VkDrawIndirectCommand d;
                    std::memcpy(&d, c.buffer->data() + off, sizeof d);
                    call.count = d.vertexCount;
                    call.instance_count = d.instanceCount;
                    call.first = d.firstVertex;
                    call.first_instance = d.firstInstance;
                }
                run_draw(st, call);
            }
            break;
        }
        default:
            break;
    }
}

}  // namespace tilevk::icd
