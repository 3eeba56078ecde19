// Draws at vkQueueSubmit: bound state -> rast::render (PipelineState, DrawCall, shader::Bindings), one Renderer per
// queue. The renderer's targets are sample planes (rast/render/targets.h), as tilevk images are (icd/image.h): every
// attachment whose texel is the renderer's element is rendered in place, at 1x and 4x. Only an aspect of a packed
// depth/stencil texel (D24_UNORM_S8_UINT, D32_SFLOAT_S8_UINT) is copied into planar staging memory when a subpass's
// rendering starts and copied back when it ends.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <deque>
#include <initializer_list>
#include <type_traits>

#include "buffer.h"
#include "buffer_view.h"
#include "compute_workers.h"
#include "descriptor_pool.h"
#include "execute.h"
#include "formats.h"
#include "framebuffer.h"
#include "image.h"
#include "physical_device.h"
#include "pipeline.h"
#include "rast/core/recycled_list.h"
#include "rast/core/thread_pool.h"
#include "rast/render/linear_mode.h"
#include "rast/render/renderer.h"
#include "rast/render/stage_timer.h"
#include "rast/render/vertex_stage.h"
#include "render_pass.h"
#include "render_state.h"
#include "sampler.h"
#include "workers.h"

namespace tilevk::icd {

// The limits physical_device.cpp reports are the sizes of what holds them here.
static_assert(BoundState::kMaxSets == kMaxBoundDescriptorSets);
static_assert(rast::render::kMaxVertexInputs == kMaxVertexInputs);  // maxVertexInputAttributes / Bindings
static_assert(rast::render::kMaxColorTargets == int(kMaxColorAttachments) &&
              shader::kMaxColorOutputs == int(kMaxColorAttachments));

namespace rr = rast::render;

// One aspect of an attachment copied out of the image: element (x, y, sample s) of the image lives at
// image + s*sample_pitch + y*row_pitch + x*texel_bytes + byte_offset, in the staging copy at
// plane + s*w*h*elem + (y*w + x)*elem.
struct Staged {
    uint8_t* image = nullptr;
    size_t row_pitch = 0, sample_pitch = 0;
    uint32_t samples = 1, texel_bytes = 0, byte_offset = 0, elem = 0, w = 0, h = 0;
    uint32_t copy_bytes = 0;  // bytes of each element that belong to this aspect (D24S8 depth: 3 of 4)
    std::vector<uint8_t> plane;
    void reset() {}  // RecycledList: every field is set by plane_of; the plane keeps its storage
};

// A translated draw state (draw_state), reused from pass to pass.
struct StateSlot {
    rr::PipelineState state;
    void reset() {}
};

struct DrawContext {
    explicit DrawContext(const std::atomic<bool>* stop) { renderer.set_stop_flag(stop); }
    rast::ThreadPool pool{rast::ThreadPool::threads_from_env()};
    rr::Renderer renderer{pool};
    std::vector<DrawOrigin> origins;  // this submission's draws; DrawCall::id indexes it
    bool active = false;
    // Kept alive until the renderer's pass ends: DrawRecords point at these. Reused from pass to pass: a steady
    // frame allocates nothing here.
    rast::RecycledList<StateSlot> states;
    const rr::PipelineState* current_state = nullptr;  // the last translated state (states.back())
    std::deque<shader::ImageView> views;               // views translated per draw (made before their image had memory)
    rast::RecycledList<Staged> staged;
    shader::Bindings bindings;  // the draw's descriptors, rebuilt per draw in reused storage
    bool warned = false;
    std::vector<ComputeWorker> compute_workers{pool.num_workers()};  // execute_compute.cpp
};

DrawContext* create_draw_context(const std::atomic<bool>* stop) {
    return new DrawContext(stop);
}
void destroy_draw_context(DrawContext* ctx) {
    delete ctx;
}
void begin_submission(DrawContext& ctx) {
    ctx.origins.clear();
    ctx.renderer.reset_interruption();
}
std::optional<DrawOrigin> interrupted_draw(const DrawContext& ctx) {
    const std::optional<uint32_t> id = ctx.renderer.interrupted_draw();
    if (!id || *id >= ctx.origins.size()) return std::nullopt;
    return ctx.origins[*id];
}

namespace {

// One row of one sample: w elements between the image (texel_bytes apart) and the plane (elem bytes apart). N is the
// element's copied bytes when the compiler may inline the copy, 0 for any other count.
template <size_t N>
void copy_row(const Staged& s, uint8_t* img, uint8_t* pl, bool to_staging) {
    const size_t bytes = N ? N : s.copy_bytes;
    for (uint32_t x = 0; x < s.w; ++x) {
        uint8_t* i = img + x * s.texel_bytes;
        uint8_t* p = pl + x * s.elem;
        if (to_staging)
            std::memcpy(p, i, bytes);
        else
            std::memcpy(i, p, bytes);
    }
}

// Copies rows [y0, y1) of every sample between the image and its staging planes.
void copy_plane_rows(Staged& s, bool to_staging, uint32_t y0, uint32_t y1) {
    const size_t plane_size = size_t(s.w) * s.h * s.elem;
    auto row_copier = [&s]() {
        switch (s.copy_bytes) {
            case 1:
                return &copy_row<1>;
            case 3:
                return &copy_row<3>;
            case 4:
                return &copy_row<4>;
            default:
                return &copy_row<0>;
        }
    };
    const auto copy = row_copier();
    for (uint32_t sm = 0; sm < s.samples; ++sm)
        for (uint32_t y = y0; y < y1; ++y)
            copy(s, s.image + sm * s.sample_pitch + y * s.row_pitch + s.byte_offset,
                 s.plane.data() + sm * plane_size + size_t(y) * s.w * s.elem, to_staging);
}

// Bands of rows on the pool's workers: each band is its own rows of image and planes.
void copy_planes(rast::ThreadPool& pool, Staged& s, bool to_staging) {
    const rast::render::StageScope timed(rast::render::Stage::kAttach);
    constexpr uint32_t kBandRows = 32;
    const size_t bands = (s.h + kBandRows - 1) / kBandRows;
    if (bands <= 1 || pool.num_workers() == 1) {
        copy_plane_rows(s, to_staging, 0, s.h);
        return;
    }
    pool.run(bands, [&](unsigned, size_t band) {
        const uint32_t y0 = uint32_t(band) * kBandRows;
        copy_plane_rows(s, to_staging, y0, std::min(s.h, y0 + kBandRows));
    });
}

// Points the renderer at one aspect of a view: in place when the image's texel is the renderer's element (the
// image's sample planes are the renderer's), else through staging. Returns (data, row pitch, sample stride).
struct PlaneRef {
    uint8_t* data;
    size_t row_pitch, sample_stride;
};
PlaneRef plane_of(DrawContext& ctx, const ImageView& v, uint32_t layer_offset, uint32_t elem, uint32_t byte_offset,
                  uint32_t w, uint32_t h, uint32_t copy_bytes = 0) {
    const Image& img = *v.image;
    const uint32_t level = v.range.baseMipLevel;
    uint8_t* base = img.texel(level, v.range.baseArrayLayer + layer_offset, 0, 0);
    const size_t pitch = img.layout.row_pitch[level];
    if (copy_bytes == 0) copy_bytes = elem;
    const size_t sample_pitch = img.samples > 1 ? size_t(img.sample_pitch(level)) : 0;
    if (img.format->bytes == elem && copy_bytes == elem) return {base + byte_offset, pitch, sample_pitch};
    Staged& s = ctx.staged.emplace_back();
    s.image = base;
    s.row_pitch = pitch;
    s.sample_pitch = sample_pitch;
    s.samples = img.samples;
    s.texel_bytes = img.format->bytes;
    s.byte_offset = byte_offset;
    s.elem = elem;
    s.copy_bytes = copy_bytes;
    s.w = w;
    s.h = h;
    s.plane.resize(size_t(w) * h * elem * s.samples);
    // The bytes of an element past copy_bytes (X8D24: the top byte) must read 0; a reused plane holds old ones.
    if (copy_bytes < elem) std::memset(s.plane.data(), 0, s.plane.size());
    copy_planes(ctx.pool, s, true);
    return {s.plane.data(), size_t(w) * elem, size_t(w) * h * elem};
}

// The framebuffer lavapipe binds for the subpass, in the terms of llvmpipe's linear-mode decision
// (rast/render/linear_mode.h).
rr::BoundFramebuffer bound_framebuffer(const Subpass& sp, const ExecState& st) {
    rr::BoundFramebuffer b;
    b.color_buffers = uint32_t(sp.colors.size());
    b.depth_stencil_bound = sp.depth_stencil.attachment != VK_ATTACHMENT_UNUSED;
    if (sp.colors.empty()) return b;
    if (const ImageView* view = attachment_view(st, sp.colors[0].attachment)) {
        b.color0_bound = true;
        b.color0_format = view->format->id;
        b.color0_samples = view->image->samples;
        b.color0_array_layers = view->image->array_layers;
    }
    return b;
}

// Starts the renderer on the current subpass's attachments.
void begin_rendering(ExecState& st, int pipeline_samples) {
    DrawContext& ctx = *st.draw;
    const Framebuffer& fbo = *st.framebuffer;
    const Subpass& sp = st.render_pass->subpasses[st.subpass];
    const uint32_t layer = view_layer_offset(st);  // multiview: the layer of the view being rendered
    rr::Framebuffer fb;
    fb.view_index = st.view_mask != 0 ? st.view : 0;
    fb.width = int32_t(fbo.width);
    fb.height = int32_t(fbo.height);
    fb.samples = pipeline_samples;
    fb.num_color = uint32_t(std::min<size_t>(sp.colors.size(), rr::kMaxColorTargets));
    for (uint32_t i = 0; i < fb.num_color; ++i) {
        const ImageView* view = attachment_view(st, sp.colors[i].attachment);
        if (view == nullptr) continue;
        const ImageView& v = *view;
        rr::ColorTarget& t = fb.color[i];
        if (!(image_features(*v.format) & format::kColorAttachment)) continue;
        t.format = v.format->id;
        fb.samples = int(v.image->samples);
        const PlaneRef p = plane_of(ctx, v, layer, v.format->bytes, 0, fbo.width, fbo.height);
        t.data = p.data;
        t.row_pitch = p.row_pitch;
        t.sample_stride = p.sample_stride;
    }
    if (const ImageView* view = attachment_view(st, sp.depth_stencil.attachment)) {
        const ImageView& v = *view;
        fb.samples = int(v.image->samples);
        rr::DepthStencilTarget& t = fb.depth_stencil;
        t.format = v.format->depth;
        if (t.format != rast::fragment::DepthFormat::None) {
            // X8D24 (D24_UNORM_S8_UINT): the renderer's 32-bit depth words get the 24 depth bits, the top byte
            // (the image's stencil) stays 0 in staging and is never written back.
            const uint32_t copy = t.format == rast::fragment::DepthFormat::X8D24 ? 3 : 0;
            const PlaneRef p =
                plane_of(ctx, v, layer, uint32_t(rr::depth_bytes(t.format)), 0, fbo.width, fbo.height, copy);
            t.depth = p.data;
            t.depth_row_pitch = p.row_pitch;
            t.depth_sample_stride = p.sample_stride;
        }
        if (v.format->aspects & VK_IMAGE_ASPECT_STENCIL_BIT) {
            const PlaneRef p = plane_of(ctx, v, layer, 1, aspect_offset(*v.format, VK_IMAGE_ASPECT_STENCIL_BIT),
                                        fbo.width, fbo.height);
            t.stencil = p.data;
            t.stencil_row_pitch = p.row_pitch;
            t.stencil_sample_stride = p.sample_stride;
        }
    }
    fb.linear_mode = rr::lavapipe_linear_mode(bound_framebuffer(sp, st));
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
    if (!writable) {
        // A uniform buffer's bound is DIV_ROUND_UP(range, 4) words (lp_state_cs.c num_elements, constant buffer
        // stride 4 under NIR), so the word straddling a range that is not a multiple of 4 is read whole
        // (robustUniformBufferAccessSizeAlignment 1); never past the end of the memory.
        const VkDeviceSize in_memory = d.buffer->memory->size - (d.buffer->memory_offset + off);
        out.buffer.size = std::min<VkDeviceSize>((out.buffer.size + 3) & ~VkDeviceSize(3), in_memory);
    }
    return out;
}

// Translated when the view was made (vkCreateImageView, vkCreateBufferView: image_view.h); a view made before its
// image had memory is translated here, per draw.
const shader::ImageView* image_of(DrawContext& ctx, const ImageView* v) {
    if (v == nullptr || v->image == nullptr || v->image->memory == nullptr) return nullptr;
    if (v->sampled_memory == v->image->memory) return v->sampled_ok ? &v->sampled : nullptr;
    shader::ImageView& out = ctx.views.emplace_back();
    return shader_view_of(*v, &out) ? &out : nullptr;
}

const shader::ImageView* texel_buffer_of(DrawContext& ctx, VkBufferView handle) {
    const BufferView* v = from_handle<BufferView>(handle);
    if (v == nullptr || v->buffer == nullptr || v->buffer->data() == nullptr) return nullptr;
    if (v->texel_memory == v->buffer->data()) return v->texel_ok ? &v->texel : nullptr;
    shader::ImageView& out = ctx.views.emplace_back();
    return texel_buffer_view_of(*v, &out) ? &out : nullptr;
}

// Element e of binding lb of the set bound at index si, as shader/ reads it.
shader::Descriptor descriptor_of(DrawContext& ctx, const BoundSets& bs, uint32_t si, const DescriptorSet& set,
                                 const LayoutBinding& lb, uint32_t e) {
    const Descriptor& d = set.slots[lb.first_slot + e];
    const uint32_t dyn_index = lb.first_dynamic + e;
    const uint32_t dyn =
        lb.dynamic() && dyn_index < BoundState::kMaxDynamicOffsets ? bs.dynamic_offsets[si][dyn_index] : 0;
    // Sampler states are translated when the sampler (or the layout holding immutable ones) was made.
    const shader::SamplerState* smp = !lb.immutable_states.empty() ? &lb.immutable_states[e]
                                      : d.sampler != nullptr       ? &d.sampler->state
                                                                   : nullptr;
    shader::Descriptor out;
    switch (lb.type) {
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC:
            return buffer_descriptor(d, dyn, false);
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC:
            return buffer_descriptor(d, dyn, true);
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
            out.image = image_of(ctx, d.image_view);
            out.sampler = smp;
            break;
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:  // read by subpassLoad as a texel fetch
            out.image = image_of(ctx, d.image_view);
            break;
        case VK_DESCRIPTOR_TYPE_SAMPLER:
            out.sampler = smp;
            break;
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
            out.image = texel_buffer_of(ctx, d.buffer_view);
            break;
        case VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK:  // the set's own bytes, read as a uniform buffer
            out.buffer.data = set.inline_data.data() + lb.inline_offset;
            out.buffer.size = lb.count;
            break;
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: {  // imageLoad / imageStore / atomics on the view's one row
            out.image = texel_buffer_of(ctx, d.buffer_view);
            const BufferView* v = from_handle<BufferView>(d.buffer_view);
            const FormatInfo* f = v != nullptr ? find_format(v->format) : nullptr;
            if (out.image != nullptr && f != nullptr && (f->buffer & format::kStorageTexelBuffer))
                out.image_writable = v->buffer->data() + v->offset;
            break;
        }
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:  // imageLoad / imageStore / imageSize on level 0 of the view
            out.image = image_of(ctx, d.image_view);
            if (out.image != nullptr && (format::image_features(*d.image_view->format) & format::kStorageImage))
                out.image_writable = d.image_view->image->memory->data + d.image_view->image->memory_offset;
            break;
        default:  // not reported as supported: reads as zero
            break;
    }
    return out;
}

// Only the bindings the pipeline's shaders declare are read: Vulkan requires valid descriptors only where a shader
// statically uses them (VUID-vkCmdDraw-None-02699), so the others may name image views, buffers or samplers that
// were destroyed since.
void collect_bindings(DrawContext& ctx, const BoundSets& bound, std::initializer_list<const shader::Program*> programs,
                      const BoundState& bs, shader::Bindings& b) {
    for (const shader::Program* program : programs) {
        if (program == nullptr) continue;
        for (const shader::DescriptorUse& use : program->interface().descriptors) {
            if (use.set >= BoundState::kMaxSets || b.find(use.set, use.binding, 0) != nullptr) continue;
            const DescriptorSet* set = bound.sets[use.set];
            const LayoutBinding* lb = set != nullptr && set->layout ? set->layout->find(use.binding) : nullptr;
            if (lb == nullptr) continue;
            for (uint32_t e = 0; e < lb->slots(); ++e)
                b.set(use.set, lb->binding, e, descriptor_of(ctx, bound, use.set, *set, *lb, e));
        }
    }
    b.push_constants =
        std::span<const std::byte>(reinterpret_cast<const std::byte*>(bs.push_constants), sizeof bs.push_constants);
}

void build_bindings(ExecState& st, shader::Bindings& b) {
    const BoundState& bs = st.bound;
    collect_bindings(*st.draw, bs.graphics, {bs.pipeline->vertex.get(), bs.pipeline->fragment.get()}, bs, b);
}

// The pipeline's state with the bound dynamic state applied: translated again only when the pipeline or a state it
// takes dynamically changed since the last draw (BoundState::dirty); otherwise the last draw's state is reused.
const rr::PipelineState& draw_state(ExecState& st) {
    const Pipeline& p = *st.bound.pipeline;
    BoundState& bs = st.bound;
    DrawContext& ctx = *st.draw;
    if (ctx.current_state != nullptr && !(bs.dirty & (BoundState::kDirtyPipeline | p.dynamic)))
        return *ctx.current_state;
    bs.dirty = 0;
    rr::PipelineState& s = ctx.states.emplace_back().state;
    s = p.state;
    ctx.current_state = &s;
    apply_dynamic_state(p.dynamic, p.statics, bs.dyn, s);
    // Rendering never leaves the framebuffer.
    s.scissor.x1 = std::min(s.scissor.x1, int32_t(st.framebuffer->width));
    s.scissor.y1 = std::min(s.scissor.y1, int32_t(st.framebuffer->height));
    return s;
}

void run_draw(ExecState& st, rr::DrawCall& call) {
    const Pipeline* p = st.bound.pipeline;
    const uint32_t draw_number = st.draw_number++;
    if (st.render_pass == nullptr || p == nullptr) return;
    const BoundState& bs = st.bound;
    if (call.indexed) {
        const Buffer* b = bs.index_buffer;
        if (b == nullptr || b->memory == nullptr || bs.index_offset > b->size) return;
        call.index_data = b->data() + bs.index_offset;
        call.index_bytes = uint32_t(std::min<VkDeviceSize>(b->size - bs.index_offset, UINT32_MAX));
        call.index_size = bs.index_type == VK_INDEX_TYPE_UINT8_EXT ? 1 : bs.index_type == VK_INDEX_TYPE_UINT16 ? 2 : 4;
    }
    const bool discarded = discards(p->dynamic, p->statics, bs.dyn);
    if (!st.statistics_queries.empty()) count_draw_statistics(st, call, draw_state(st), discarded);
    if (discarded) return;
    DrawContext& ctx = *st.draw;
    if (const std::string why = dynamic_refusal(p->dynamic, bs.dyn, p->state.samples); !why.empty()) {
        if (!ctx.warned) log_error("vkQueueSubmit: a draw was not rendered: %s", why.c_str());
        ctx.warned = true;
        return;
    }
    call.id = uint32_t(ctx.origins.size());
    ctx.origins.push_back({to_handle(const_cast<Pipeline*>(p)), st.submit_index, st.command_buffer_index, draw_number});
    if (!ctx.active) begin_rendering(st, p->state.samples);
    for (uint32_t i = 0; i < BoundState::kMaxVertexBuffers; ++i) {
        rr::VertexBufferBinding vb;
        if (const Buffer* b = bs.vertex_buffers[i]; b && b->memory && bs.vertex_offsets[i] <= b->size) {
            vb.data = b->data() + bs.vertex_offsets[i];
            const VkDeviceSize left = b->size - bs.vertex_offsets[i];
            const VkDeviceSize bound = bs.vertex_sizes[i] == VK_WHOLE_SIZE ? left : std::min(left, bs.vertex_sizes[i]);
            vb.size = uint32_t(std::min<VkDeviceSize>(bound, UINT32_MAX));
        }
        call.vertex_buffers.push_back(vb);
    }
    shader::Bindings& bindings = ctx.bindings;
    bindings.clear();
    build_bindings(st, bindings);
    call.samples_passed = active_occlusion_counter(st);
    call.statistics = active_raster_statistics(st);
    const std::string err = ctx.renderer.draw(draw_state(st), call, bindings);
    if (!err.empty() && !ctx.warned) {
        log_error("vkQueueSubmit: a draw was not rendered: %s", err.c_str());
        ctx.warned = true;
    }
}

}  // namespace

void build_compute_bindings(ExecState& st, const shader::Program& program, shader::Bindings& b) {
    DrawContext& ctx = *st.draw;
    // Views translated for an earlier dispatch are no longer read (dispatches run outside render passes, so no
    // binned draw points at them either).
    if (!ctx.active) ctx.views.clear();
    b.clear();
    collect_bindings(ctx, st.bound.compute, {&program}, st.bound, b);
}

void note_query_command_in_pass(ExecState& st) {
    if (st.render_pass == nullptr) return;
    if (st.draw->active)
        st.draw->renderer.mark_scene_not_linear();
    else
        st.query_command_pending = true;
}

bool finish_rendering(ExecState& st, const rr::TileResolves* resolves) {
    DrawContext& ctx = *st.draw;
    bool resolved = false;
    if (ctx.active) {
        resolved = ctx.renderer.end(resolves);
        for (size_t i = 0; i < ctx.staged.size(); ++i) copy_planes(ctx.pool, ctx.staged[i], false);
        ctx.staged.clear();
        ctx.states.clear();
        ctx.current_state = nullptr;
        ctx.views.clear();
        ctx.active = false;
    }
    // The draws of queries ended in this pass are rendered (and counted) now.
    publish_ended_queries(st);
    return resolved;
}

void run_on_workers(ExecState& st, size_t num_tasks, rast::FunctionRef<void(size_t task)> fn) {
    if (num_tasks == 0) return;
    if (num_tasks == 1) {
        fn(0);
        return;
    }
    st.draw->pool.run(num_tasks, [&fn](unsigned, size_t task) { fn(task); });
}

rast::ThreadPool& worker_pool(ExecState& st) {
    return st.draw->pool;
}

std::span<ComputeWorker> compute_workers(ExecState& st) {
    return st.draw->compute_workers;
}

namespace {
// A vkCmdSet* changed these dynamic states: the next draw whose pipeline takes one of them translates its state again.
void mark_dirty(ExecState& st, DynamicMask states) {
    st.bound.dirty |= states;
}
}  // namespace

void exec_state(ExecState& st, const CmdBindPipeline& c) {
    if (c.bind_point == VK_PIPELINE_BIND_POINT_COMPUTE) {
        st.bound.compute_pipeline = c.pipeline;
        return;
    }
    if (c.bind_point != VK_PIPELINE_BIND_POINT_GRAPHICS) return;
    st.bound.pipeline = c.pipeline;
    st.bound.dirty |= BoundState::kDirtyPipeline;
}

void exec_state(ExecState& st, const CmdBindDescriptorSets& c) {
    if (c.bind_point != VK_PIPELINE_BIND_POINT_GRAPHICS && c.bind_point != VK_PIPELINE_BIND_POINT_COMPUTE) return;
    BoundSets& bs = c.bind_point == VK_PIPELINE_BIND_POINT_COMPUTE ? st.bound.compute : st.bound.graphics;
    uint32_t next_dyn = 0;
    for (uint32_t i = 0; i < c.set_count && c.first_set + i < BoundSets::kMaxSets; ++i) {
        DescriptorSet* set = c.sets[i];
        const uint32_t si = c.first_set + i;
        bs.sets[si] = set;
        if (set == nullptr || set->layout == nullptr) continue;
        // This set's dynamic offsets come next in pDynamicOffsets, in binding order.
        for (uint32_t k = 0; k < set->layout->dynamic_count; ++k, ++next_dyn)
            if (k < BoundSets::kMaxDynamicOffsets && next_dyn < c.dynamic_offset_count)
                bs.dynamic_offsets[si][k] = c.dynamic_offsets[next_dyn];
    }
}

void exec_state(ExecState& st, const CmdBindVertexBuffers& c) {
    BoundState& bs = st.bound;
    for (uint32_t i = 0; i < c.count && c.first_binding + i < BoundState::kMaxVertexBuffers; ++i) {
        bs.vertex_buffers[c.first_binding + i] = c.buffers[i];
        bs.vertex_offsets[c.first_binding + i] = c.offsets[i];
        bs.vertex_sizes[c.first_binding + i] = c.sizes != nullptr ? c.sizes[i] : VK_WHOLE_SIZE;
        if (c.strides != nullptr && c.first_binding + i < DynamicValues::kMaxBindings)
            bs.dyn.strides[c.first_binding + i] = uint32_t(c.strides[i]);
    }
    if (c.strides != nullptr) mark_dirty(st, dynamic_bit(DynamicState::kVertexInputBindingStride));
}

void exec_state(ExecState& st, const CmdBindIndexBuffer& c) {
    st.bound.index_buffer = c.buffer;
    st.bound.index_offset = c.offset;
    st.bound.index_type = c.index_type;
}

void exec_state(ExecState& st, const CmdPushConstants& c) {
    BoundState& bs = st.bound;
    if (c.offset < sizeof bs.push_constants && c.values)
        std::memcpy(bs.push_constants + c.offset, c.values,
                    std::min<size_t>(c.size, sizeof bs.push_constants - c.offset));
}

void exec_state(ExecState& st, const CmdSetViewport& c) {
    if (c.first == 0 && c.count > 0) st.bound.dyn.viewport = c.viewports[0];
    mark_dirty(st, dynamic_bit(DynamicState::kViewport) | dynamic_bit(DynamicState::kViewportWithCount));
}

void exec_state(ExecState& st, const CmdSetScissor& c) {
    if (c.first == 0 && c.count > 0) st.bound.dyn.scissor = c.scissors[0];
    mark_dirty(st, dynamic_bit(DynamicState::kScissor) | dynamic_bit(DynamicState::kScissorWithCount));
}

void exec_state(ExecState& st, const CmdSetLineWidth& c) {
    st.bound.dyn.line_width = c.width;
    mark_dirty(st, dynamic_bit(DynamicState::kLineWidth));
}

void exec_state(ExecState& st, const CmdSetDepthBias& c) {
    st.bound.dyn.depth_bias[0] = c.constant_factor;
    st.bound.dyn.depth_bias[1] = c.clamp;
    st.bound.dyn.depth_bias[2] = c.slope_factor;
    mark_dirty(st, dynamic_bit(DynamicState::kDepthBias));
}

void exec_state(ExecState& st, const CmdSetBlendConstants& c) {
    std::memcpy(st.bound.dyn.blend_constants, c.constants, 16);
    mark_dirty(st, dynamic_bit(DynamicState::kBlendConstants));
}

namespace {
// Front value in v[0], back value in v[1].
void set_stencil_faces(uint32_t v[2], VkStencilFaceFlags faces, uint32_t value) {
    if (faces & VK_STENCIL_FACE_FRONT_BIT) v[0] = value;
    if (faces & VK_STENCIL_FACE_BACK_BIT) v[1] = value;
}
}  // namespace

void exec_state(ExecState& st, const CmdSetStencilCompareMask& c) {
    set_stencil_faces(st.bound.dyn.stencil_compare, c.faces, c.value);
    mark_dirty(st, dynamic_bit(DynamicState::kStencilCompareMask));
}

void exec_state(ExecState& st, const CmdSetStencilWriteMask& c) {
    set_stencil_faces(st.bound.dyn.stencil_write, c.faces, c.value);
    mark_dirty(st, dynamic_bit(DynamicState::kStencilWriteMask));
}

void exec_state(ExecState& st, const CmdSetStencilReference& c) {
    set_stencil_faces(st.bound.dyn.stencil_ref, c.faces, c.value);
    mark_dirty(st, dynamic_bit(DynamicState::kStencilReference));
}

void exec_state(ExecState& st, const CmdSetDynamic& c) {
    DynamicValues& v = st.bound.dyn;
    switch (c.state) {
        case DynamicState::kCullMode:
            v.cull_mode = c.value;
            break;
        case DynamicState::kFrontFace:
            v.front_face = VkFrontFace(c.value);
            break;
        case DynamicState::kPrimitiveTopology:
            v.topology = VkPrimitiveTopology(c.value);
            break;
        case DynamicState::kDepthTestEnable:
            v.depth_test = c.value != 0;
            break;
        case DynamicState::kDepthWriteEnable:
            v.depth_write = c.value != 0;
            break;
        case DynamicState::kDepthCompareOp:
            v.depth_compare = VkCompareOp(c.value);
            break;
        case DynamicState::kDepthBoundsTestEnable:
            v.depth_bounds_test = c.value != 0;
            break;
        case DynamicState::kStencilTestEnable:
            v.stencil_test = c.value != 0;
            break;
        case DynamicState::kRasterizerDiscardEnable:
            v.rasterizer_discard = c.value != 0;
            break;
        case DynamicState::kDepthBiasEnable:
            v.depth_bias_enable = c.value != 0;
            break;
        case DynamicState::kPrimitiveRestartEnable:
            v.primitive_restart = c.value != 0;
            break;
        case DynamicState::kLogicOp:
            v.logic_op = VkLogicOp(c.value);
            break;
        case DynamicState::kColorWriteEnable:
            v.color_write_enables = c.value;
            break;
        default:
            set_dynamic3(v, c.state, c.value);
            break;  // the other states have commands of their own
    }
    mark_dirty(st, dynamic_bit(c.state));
}

void exec_state(ExecState& st, const CmdSetVertexInput& c) {
    if (c.values == nullptr) return;  // out of memory when recorded
    DynamicValues& v = st.bound.dyn;
    v.vertex_input = *c.values;
    // Its strides replace those of an earlier vkCmdBindVertexBuffers2 (lavapipe's vb[].stride), for the bindings its
    // attributes read.
    for (uint32_t i = 0; i < c.values->attribute_count; ++i) {
        const uint32_t b = c.values->attributes[i].binding;
        v.strides[b] = c.values->bindings[b].stride;
    }
    mark_dirty(st, dynamic_bit(DynamicState::kVertexInput) | dynamic_bit(DynamicState::kVertexInputBindingStride));
}

void exec_state(ExecState& st, const CmdSetAttachmentDynamic& c) {
    DynamicValues& v = st.bound.dyn;
    for (uint32_t i = 0; i < c.count && c.first + i < DynamicValues::kMaxAttachments; ++i) {
        const uint32_t a = c.first + i;
        if (c.state == DynamicState::kColorBlendEnable)
            v.blend_enables = (v.blend_enables & ~(1u << a)) | uint32_t(c.values[i] != 0) << a;
        else if (c.state == DynamicState::kColorWriteMask)
            v.write_masks[a] = uint8_t(c.values[i]);
        else if (c.state == DynamicState::kColorBlendEquation)
            v.blend_equations[a] = c.equations[i];
    }
    mark_dirty(st, dynamic_bit(c.state));
}

void exec_state(ExecState& st, const CmdSetStencilOp& c) {
    if (c.faces & VK_STENCIL_FACE_FRONT_BIT) st.bound.dyn.stencil_ops[0] = c.ops;
    if (c.faces & VK_STENCIL_FACE_BACK_BIT) st.bound.dyn.stencil_ops[1] = c.ops;
    mark_dirty(st, dynamic_bit(DynamicState::kStencilOp));
}

void exec_draw(ExecState& st, const CmdDraw& c) {
    rr::DrawCall call;
    call.count = c.vertex_count;
    call.instance_count = c.instance_count;
    call.first = c.first_vertex;
    call.first_instance = c.first_instance;
    run_draw(st, call);
}

void exec_draw(ExecState& st, const CmdDrawIndexed& c) {
    rr::DrawCall call;
    call.indexed = true;
    call.count = c.index_count;
    call.instance_count = c.instance_count;
    call.first = c.first_index;
    call.vertex_offset = c.vertex_offset;
    call.first_instance = c.first_instance;
    run_draw(st, call);
}

namespace {
// The draws of vkCmdDrawIndirect (VkDrawIndirectCommand) or vkCmdDrawIndexedIndirect
// (VkDrawIndexedIndirectCommand), read from the buffer when they execute.
template <class IndirectCommand>
void draw_indirect(ExecState& st, const Buffer* buffer, VkDeviceSize offset, uint32_t draw_count, uint32_t stride) {
    constexpr bool kIndexed = std::is_same_v<IndirectCommand, VkDrawIndexedIndirectCommand>;
    for (uint32_t i = 0; i < draw_count; ++i) {
        const VkDeviceSize off = offset + VkDeviceSize(i) * stride;
        if (buffer == nullptr || buffer->memory == nullptr || off + sizeof(IndirectCommand) > buffer->size) break;
        IndirectCommand d;
        std::memcpy(&d, buffer->data() + off, sizeof d);
        rr::DrawCall call;
        call.indexed = kIndexed;
        call.instance_count = d.instanceCount;
        call.first_instance = d.firstInstance;
        call.draw_index = i;
        if constexpr (kIndexed) {
            call.count = d.indexCount;
            call.first = d.firstIndex;
            call.vertex_offset = d.vertexOffset;
        } else {
            call.count = d.vertexCount;
            call.first = d.firstVertex;
        }
        run_draw(st, call);
    }
}
}  // namespace

namespace {
// The number of draws of an indirect command: draw_count, or the count buffer's value capped at it.
template <class IndirectCmd>
uint32_t indirect_draw_count(const IndirectCmd& c) {
    if (c.count_buffer == nullptr) return c.draw_count;
    const Buffer* b = c.count_buffer;
    if (b->memory == nullptr || c.count_offset + sizeof(uint32_t) > b->size) {
        log_error("vkCmdDraw*IndirectCount: the count lies outside its buffer; no draws");
        return 0;
    }
    uint32_t n;
    std::memcpy(&n, b->data() + c.count_offset, sizeof n);
    return std::min(n, c.draw_count);
}
}  // namespace

void exec_draw(ExecState& st, const CmdDrawIndirect& c) {
    draw_indirect<VkDrawIndirectCommand>(st, c.buffer, c.offset, indirect_draw_count(c), c.stride);
}

void exec_draw(ExecState& st, const CmdDrawIndexedIndirect& c) {
    draw_indirect<VkDrawIndexedIndirectCommand>(st, c.buffer, c.offset, indirect_draw_count(c), c.stride);
}

// VK_EXT_multi_draw as lavapipe runs it: one draw_vbo whose instance loop is outside its loop over the entries
// (draw_pt.c draw_instances), DrawIndex the entry's number. With one instance or one entry that is the entries in
// order, all instances each; otherwise each entry is drawn once per instance, instance by instance.
void exec_draw(ExecState& st, const CmdDrawMulti& c) {
    const bool per_instance = c.instance_count > 1 && c.draw_count > 1;
    const uint32_t rounds = per_instance ? c.instance_count : 1;
    for (uint32_t inst = 0; inst < rounds; ++inst) {
        for (uint32_t i = 0; i < c.draw_count; ++i) {
            const VkMultiDrawIndexedInfoEXT& d = c.draws[i];
            rr::DrawCall call;
            call.indexed = c.indexed;
            call.count = d.indexCount;
            call.first = d.firstIndex;
            call.vertex_offset = d.vertexOffset;
            call.first_instance = c.first_instance;
            call.instance_count = per_instance ? 1 : c.instance_count;
            call.instance_begin = per_instance ? inst : 0;
            call.draw_index = i;
            run_draw(st, call);
        }
    }
}

}  // namespace tilevk::icd
