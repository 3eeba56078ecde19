// Per 4x4 block: interpolate -> (early depth/stencil) -> fragment shader -> alpha to coverage -> (late
// depth/stencil) -> blend and write, per sample plane. Orders and formulas are lavapipe's (notes §3–§5).
#include "rast/render/fragment_stage.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "rast/fragment/blend.h"
#include "rast/fragment/block.h"
#include "rast/fragment/block_kernels.h"
#include "rast/fragment/interp.h"
#include "rast/fragment/msaa.h"
#include "shader/program.h"

namespace tilevk::rast::render {

struct FragmentStage::Worker {
    shader::Scratch scratch;
    shader::FragmentBlock block;
    // The primitive whose uniform shader result block.outputs holds (DrawPlan::uniform_shader), or null.
    const PrimRecord* uniform_prim = nullptr;
    bool uniform_front = false;
    std::vector<uint64_t> samples_passed;  // per draw record of the current scene
};

// One shader input component the fast path interpolates; loc kPointCoordLoc is gl_PointCoord (block.point_coord).
constexpr uint32_t kPointCoordLoc = ~0u;
struct InputPlan {
    uint32_t loc = 0, comp = 0;
    uint32_t plane = 0;  // float offset of its plane from the primitive's first attribute plane
    geometry::Interp interp = geometry::Interp::kPerspective;
};
uint32_t* input_lanes(shader::FragmentBlock& b, const InputPlan& in) {
    return in.loc == kPointCoordLoc ? b.point_coord[in.comp] : b.inputs[in.loc][in.comp];
}

enum class ColorPath : uint8_t { kGeneric, kNone, kOpaqueRgba8, kOpaqueBgra8, kRgba8 };

struct FragmentStage::DrawPlan {
    bool fast = false;              // false: the reference path (clears, unsupported states)
    std::vector<InputPlan> inputs;  // the declared components only: the shader cannot read the others
    bool perspective = false;       // some input divides by w
    bool uniform_shader = false;    // the shader's outputs are the same for every fragment of a primitive
    int copy_location = -1;         // >= 0: the shader only copies this vec4 input to colour output 0
    bool depth_fast = false;        // depth_block_fast handles the depth test
    fragment::DepthFast depth;
    ColorPath color[kMaxColorTargets] = {};
    fragment::Rgba8Blend rgba8[kMaxColorTargets];  // ColorPath::kRgba8: blending / partial write masks
    uint8_t color_bytes[kMaxColorTargets] = {};    // bytes per pixel of each target
};

namespace {
std::atomic<int> g_fast_paths{-1};  // -1: not read from the environment yet
}  // namespace

uint64_t FragmentStage::samples_passed(uint32_t draw) const {
    uint64_t n = 0;
    for (const auto& w : workers_)
        if (draw < w->samples_passed.size()) n += w->samples_passed[draw];
    return n;
}

uint64_t FragmentStage::loop_limit_hits() const {
    uint64_t hits = 0;
    for (const auto& w : workers_) hits += w->scratch.loop_limit_hits();
    return hits;
}

void set_fragment_fast_paths(bool on) {
    g_fast_paths.store(on ? 1 : 0);
}

bool fragment_fast_paths() {
    int v = g_fast_paths.load();
    if (v < 0) {
        const char* e = std::getenv("TILEVK_FRAG");
        v = (e && std::string_view(e) == "reference") ? 0 : 1;
        g_fast_paths.store(v);
    }
    return v != 0;
}

namespace {

using fragment::kBlockLanes;

fragment::Plane plane_of(const float* p, int c) {
    // AttribPlane layout: a0[4], dadx[4], dady[4]
    return {p[4 + c], p[8 + c], p[c]};
}

uint32_t bits_of(float f) {
    return std::bit_cast<uint32_t>(f);
}

// Raster-order coverage (bit y*4+x) of the pixels of a block that exist in the framebuffer.
uint16_t inside_mask(int32_t x, int32_t y, int32_t width, int32_t height) {
    uint16_t m = 0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            if (x + i < width && y + j < height) m |= uint16_t(1u << (j * 4 + i));
    return m;
}

// Depth texels are 2 or 4 bytes: constant-size copies (inlined) instead of a memcpy call per lane.
inline uint32_t load_depth_texel(const uint8_t* src, size_t bytes) {
    if (bytes == 2) {
        uint16_t v;
        std::memcpy(&v, src, 2);
        return v;
    }
    uint32_t v = 0;
    if (bytes == 4) std::memcpy(&v, src, 4);
    return v;
}

inline void store_depth_texel(uint8_t* dst, size_t bytes, uint32_t v) {
    if (bytes == 2) {
        const uint16_t h = uint16_t(v);
        std::memcpy(dst, &h, 2);
    } else if (bytes == 4) {
        std::memcpy(dst, &v, 4);
    }
}

void load_depth_stencil(const DepthStencilTarget& t, int sample, int32_t x, int32_t y, uint16_t lanes,
                        fragment::DepthStencilBlock& zs) {
    const size_t bytes = depth_bytes(t.format);
    for (int l = 0; l < kBlockLanes; ++l) {
        zs.depth[l] = 0;
        zs.stencil[l] = 0;
        if (!(lanes & (1u << l))) continue;
        const int32_t px = x + fragment::lane_x(l), py = y + fragment::lane_y(l);
        if (t.depth)
            zs.depth[l] = load_depth_texel(
                t.depth + size_t(sample) * t.depth_sample_stride + size_t(py) * t.depth_row_pitch + size_t(px) * bytes,
                bytes);
        if (t.stencil)
            zs.stencil[l] = t.stencil[size_t(sample) * t.stencil_sample_stride + size_t(py) * t.stencil_row_pitch + px];
    }
}

void store_depth_stencil(const DepthStencilTarget& t, int sample, int32_t x, int32_t y, uint16_t lanes,
                         const fragment::DepthStencilBlock& zs) {
    const size_t bytes = depth_bytes(t.format);
    for (int l = 0; l < kBlockLanes; ++l) {
        if (!(lanes & (1u << l))) continue;
        const int32_t px = x + fragment::lane_x(l), py = y + fragment::lane_y(l);
        if (t.depth)
            store_depth_texel(
                t.depth + size_t(sample) * t.depth_sample_stride + size_t(py) * t.depth_row_pitch + size_t(px) * bytes,
                bytes, zs.depth[l]);
        if (t.stencil)
            t.stencil[size_t(sample) * t.stencil_sample_stride + size_t(py) * t.stencil_row_pitch + px] = zs.stencil[l];
    }
}

// Occlusion counting: lavapipe adds popcount of the post-depth/stencil mask per sample (lp_state_fs.c,
// lp_build_occlusion_count inside the sample loop under MSAA), i.e. after discard, alpha to coverage, the shader's
// sample mask and the late test. The final masks here are exactly those.
template <class W>
inline void count_passed(W& w, uint32_t draw, const uint16_t final_mask[4], int samples) {
    uint64_t n = 0;
    for (int s = 0; s < samples; ++s) n += uint64_t(std::popcount(final_mask[s]));
    w.samples_passed[draw] += n;
}

// What the fast path needs to know about a draw, derived once per scene.
FragmentStage::DrawPlan make_plan(const DrawRecord& draw, const Framebuffer& fb) {
    FragmentStage::DrawPlan plan;
    if (draw.is_clear || !draw.pipe) return plan;
    const PipelineState& pipe = *draw.pipe;
    plan.fast = true;

    const shader::Program* fs = pipe.fragment;
    bool all_flat = true;
    if (fs) {
        const shader::ProgramInterface& iface = fs->interface();
        const size_t num_slots = draw.varyings.slot_location.size();
        for (size_t slot = 0; slot < num_slots; ++slot) {
            const uint32_t loc = draw.varyings.slot_location[slot];
            // Components the shader declares at this location (the interpreter copies only those in).
            uint32_t comps = 0;
            for (const shader::IoVariable& v : iface.inputs)
                if (v.location == loc) comps |= ((1u << v.components) - 1u) << v.component;
            const geometry::Interp interp = draw.varyings.slot_interp[slot];
            all_flat &= interp == geometry::Interp::kFlat;
            plan.perspective |= interp == geometry::Interp::kPerspective && (comps & 0xfu);
            for (uint32_t c = 0; c < 4; ++c)
                if (comps & (1u << c)) plan.inputs.push_back({loc, c, uint32_t(slot * kPlaneFloats), interp});
        }
        if (draw.varyings.point_coord_slot >= 0) {
            all_flat = false;
            plan.perspective = true;
            for (uint32_t c = 0; c < 2; ++c)
                plan.inputs.push_back({kPointCoordLoc, c, uint32_t(draw.varyings.point_coord_slot * kPlaneFloats),
                                       geometry::Interp::kPerspective});
        }
        // The outputs cannot vary across a primitive when every input is flat, no per-fragment built-in is read
        // (front facing is per primitive), nothing is discarded or written besides colour, and there are no
        // derivatives (helper lanes): one run per primitive then gives every fragment's result.
        bool writes_memory = false;
        for (const shader::DescriptorUse& d : iface.descriptors) writes_memory |= d.written;
        const uint32_t per_prim_builtins = shader::bit(shader::BuiltIn::FrontFacing);
        plan.uniform_shader = all_flat && !(iface.builtins_read & ~per_prim_builtins) && !iface.uses_discard &&
                              !iface.writes_frag_depth && !iface.uses_derivatives && iface.builtins_written == 0 &&
                              !writes_memory;
        // A plain copy (colour = one float vec4 input, unchanged; nothing else: no discard, no built-ins, no memory;
        // shader::Program::linear_shader) is its interpolated input: the run is a move of the same bits.
        plan.copy_location = fs->linear_copy_input();
    }

    const DepthStencilTarget& ds = fb.depth_stencil;
    plan.depth_fast = draw.depth_mode != 0 && ds.depth && fragment::depth_fast_supported(draw.depth_stencil, ds.format);
    if (plan.depth_fast) plan.depth = fragment::make_depth_fast(draw.depth_stencil, ds.format);

    for (uint32_t c = 0; c < fb.num_color && c < kMaxColorTargets; ++c) {
        const fragment::BlendAttachment& a = pipe.blend[c];
        const fragment::ColorFormat f = fb.color[c].format;
        plan.color_bytes[c] = fragment::format_info(f).bytes;
        const bool rgba8 = f == fragment::ColorFormat::R8G8B8A8_UNORM || f == fragment::ColorFormat::B8G8R8A8_UNORM;
        if ((a.write_mask & 0xf) == 0) {
            plan.color[c] = ColorPath::kNone;
        } else if (rgba8 && !a.blend_enable && (a.write_mask & 0xf) == 0xf) {
            plan.color[c] =
                f == fragment::ColorFormat::B8G8R8A8_UNORM ? ColorPath::kOpaqueBgra8 : ColorPath::kOpaqueRgba8;
        } else if (rgba8) {
            plan.rgba8[c] = fragment::prepare_rgba8_blend(a, f, pipe.blend_constants);
            if (plan.rgba8[c].ok) plan.color[c] = ColorPath::kRgba8;
        }
    }
    return plan;
}

}  // namespace

FragmentStage::FragmentStage() = default;
FragmentStage::~FragmentStage() = default;

void FragmentStage::prepare(const Framebuffer& fb, const std::deque<DrawRecord>& draws,
                            const std::vector<PrimRecord>& prims, const std::vector<float>& planes, bool fused,
                            unsigned workers) {
    fb_ = fb;
    draws_ = &draws;
    prims_ = &prims;
    planes_ = &planes;
    fused_ = fused;
    fast_ = fragment_fast_paths();
    while (workers_.size() < workers) workers_.push_back(std::make_unique<Worker>());
    for (auto& w : workers_) {
        w->uniform_prim = nullptr;  // prim records are rebuilt for every scene
        w->samples_passed.assign(draws.size(), 0);
    }
    plans_.clear();
    if (fast_) {
        plans_.reserve(draws.size());
        for (const DrawRecord& d : draws) plans_.push_back(make_plan(d, fb));
    }
}

void FragmentStage::set_linear(const std::vector<uint8_t>* tile_linear,
                               const std::vector<fragment::LinearRegion>* rect_boxes) {
    tile_linear_ = tile_linear;
    rect_boxes_ = rect_boxes;
}

void FragmentStage::begin_tile(unsigned, const TileInfo&) {}
void FragmentStage::end_tile(unsigned, const TileInfo&) {}

void FragmentStage::primitive(unsigned worker, const TileInfo& tile, const PrimCoverage& cov) {
    const PrimRecord& prim = (*prims_)[cov.payload];
    const DrawRecord& draw = (*draws_)[prim.draw];
    if (tile_linear_ && draw.linear && (*tile_linear_)[tile.index] &&
        (prim.kind == PrimKind::kRect || prim.kind == PrimKind::kTriangle)) {
        // llvmpipe's linear bin (lp_rast_linear.c): a rectangle's box within the tile (lp_rast_linear_rect) or the
        // whole tile of a whole-tile command (lp_rast_linear_tile; in a linear bin every triangle with coverage
        // has one), shaded from the region's own origin. When lp_fs_linear_run declines, llvmpipe runs its
        // general shader on the same pixels: the code below.
        fragment::LinearRegion r = {tile.x0, tile.y0, tile.width, tile.height};
        if (prim.kind == PrimKind::kRect) {
            const fragment::LinearRegion& b = (*rect_boxes_)[prim.rect];
            r.x = std::max(b.x, tile.x0);
            r.y = std::max(b.y, tile.y0);
            r.width = std::min(b.x + b.width, tile.x0 + tile.width) - r.x;
            r.height = std::min(b.y + b.height, tile.y0 + tile.height) - r.y;
        }
        const float* pl = planes_->data() + prim.plane_base;
        const float* input = draw.linear_slot >= 0
                                 ? pl + kPrimHeaderFloats + size_t(kPlaneFloats) * uint32_t(draw.linear_slot)
                                 : nullptr;
        if (r.width > 0 && r.height > 0 &&
            fragment::linear_shade(r, pl, input, draw.linear_perspective, draw.linear_channels, fb_.color[0].data,
                                   fb_.color[0].row_pitch, &draw.pipe->blend[0], draw.pipe->blend_constants)) {
            // Every pixel of the region was written: linear mode is 1x with no depth/stencil and the linear shader
            // class cannot discard. lavapipe's linear rasterizer forgets to count them (a named difference,
            // icd/README.md "Queries"); a precise occlusion query must.
            if (draw.samples_passed) workers_[worker]->samples_passed[prim.draw] += uint64_t(r.width) * r.height;
            return;
        }
    }
    Worker& w = *workers_[worker];
    const DrawPlan* plan = fast_ && plans_[prim.draw].fast ? &plans_[prim.draw] : nullptr;
    auto one_block = [&](int32_t x, int32_t y, const uint16_t masks[4]) {
        if (prim.kind == PrimKind::kClear)
            clear_block(draw.clear, x, y, masks);
        else if (plan)
            shade_block_fast(w, *plan, draw, prim, cov.front_facing, x, y, masks);
        else
            shade_block(w, draw, prim, cov.front_facing, x, y, masks);
    };
    for_each_block4(cov, one_block);
    for (size_t i = 0; i < cov.num_full; ++i) {
        const FullBlock& f = cov.full[i];
        for (int32_t by = f.y; by < f.y + f.size; by += 4)
            for (int32_t bx = f.x; bx < f.x + f.size; bx += 4) {
                // Full squares lie inside the framebuffer (coverage.h); the check costs two compares.
                const uint16_t inside = bx + 4 <= fb_.width && by + 4 <= fb_.height
                                            ? uint16_t(0xffff)
                                            : inside_mask(bx, by, fb_.width, fb_.height);
                uint16_t masks[4];
                for (int s = 0; s < 4; ++s) masks[s] = (cov.sample_mask >> s) & 1 ? inside : 0;
                one_block(bx, by, masks);
            }
    }
}

void FragmentStage::clear_block(const ClearRecord& clear, int32_t x, int32_t y, const uint16_t raster_masks[4]) {
    for (int s = 0; s < fb_.samples; ++s) {
        const uint16_t m = raster_masks[s];
        if (!m) continue;
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                if (!(m & (1u << (j * 4 + i)))) continue;
                const size_t px = size_t(x + i), py = size_t(y + j);
                for (uint32_t c = 0; c < fb_.num_color; ++c) {
                    const ColorTarget& t = fb_.color[c];
                    if (!t.data || !(clear.color_mask & (1u << c))) continue;
                    const size_t bytes = fragment::format_info(t.format).bytes;
                    std::memcpy(t.data + size_t(s) * t.sample_stride + py * t.row_pitch + px * bytes,
                                clear.color_bytes[c], bytes);
                }
                const DepthStencilTarget& ds = fb_.depth_stencil;
                if (clear.clear_depth && ds.depth) {
                    const size_t bytes = depth_bytes(ds.format);
                    std::memcpy(ds.depth + size_t(s) * ds.depth_sample_stride + py * ds.depth_row_pitch + px * bytes,
                                &clear.depth_bits, bytes);
                }
                if (clear.clear_stencil && ds.stencil)
                    ds.stencil[size_t(s) * ds.stencil_sample_stride + py * ds.stencil_row_pitch + px] = clear.stencil;
            }
    }
}

void FragmentStage::shade_block(Worker& w, const DrawRecord& draw, const PrimRecord& prim, bool front_facing, int32_t x,
                                int32_t y, const uint16_t raster_masks[4]) {
    w.uniform_prim = nullptr;  // block.outputs is about to change
    const PipelineState& pipe = *draw.pipe;
    const int samples = fb_.samples;
    const float* planes = planes_->data() + prim.plane_base;
    const float depth_offset = planes[kPlaneFloats];

    // Coverage per sample in shader lane order.
    uint16_t cover[4] = {0, 0, 0, 0};
    for (int s = 0; s < samples; ++s) cover[s] = fragment::raster_to_lanes(raster_masks[s]);
    uint16_t any = 0;
    for (int s = 0; s < samples; ++s) any |= cover[s];
    if (!any) return;

    // Depth per sample: 1x at the pixel centre (plane origin), 4x at each sample position.
    float z[4][kBlockLanes];
    const fragment::Plane zplane = plane_of(planes, 2);
    const bool depth_active = draw.depth_mode != 0;
    if (depth_active)
        for (int s = 0; s < samples; ++s)
            fragment::eval_depth(zplane, depth_offset, x, y, fragment::plane_offset(samples, samples > 1 ? s : -1),
                                 fused_, z[s]);

    const DepthStencilTarget& dst = fb_.depth_stencil;
    fragment::DepthStencilBlock zs[4];
    const bool early = draw.depth_mode & fragment::kEarlyDepthTest;
    const bool early_write = draw.depth_mode & fragment::kEarlyDepthWrite;
    uint16_t pass[4] = {cover[0], cover[1], cover[2], cover[3]};
    if (depth_active) {
        for (int s = 0; s < samples; ++s) {
            load_depth_stencil(dst, s, x, y, cover[s], zs[s]);
            if (early) {
                pass[s] = fragment::depth_stencil_test(draw.depth_stencil, dst.format, front_facing, z[s], cover[s],
                                                       zs[s], early_write);
                if (early_write) store_depth_stencil(dst, s, x, y, cover[s], zs[s]);
            }
        }
    }
    uint16_t shade_lanes = 0;
    for (int s = 0; s < samples; ++s) shade_lanes |= pass[s];
    if (!shade_lanes) return;

    // Fragment shader inputs.
    shader::FragmentBlock& b = w.block;
    const shader::Program* fs = pipe.fragment;
    uint16_t live = shade_lanes;
    if (fs) {
        b.cover_mask = shade_lanes;
        b.front_facing = front_facing ? 1u : 0u;
        b.sample_id = 0;
        const fragment::EvalOffset centre = fragment::plane_offset(samples, -1);
        float wlanes[kBlockLanes], tmp[kBlockLanes], out[kBlockLanes];
        fragment::eval_plane(plane_of(planes, 3), x, y, centre, fused_, wlanes);
        const shader::ProgramInterface& iface = fs->interface();
        if (iface.builtins_read & shader::bit(shader::BuiltIn::FragCoord)) {
            float fx[kBlockLanes], fy[kBlockLanes], fz[kBlockLanes];
            fragment::frag_coord_xy(x, y, fragment::frag_coord_offset(samples, -1), fx, fy);
            fragment::eval_depth(zplane, depth_offset, x, y, centre, fused_, fz);
            for (int l = 0; l < kBlockLanes; ++l) {
                b.frag_coord[0][l] = bits_of(fx[l]);
                b.frag_coord[1][l] = bits_of(fy[l]);
                b.frag_coord[2][l] = bits_of(fz[l]);
                b.frag_coord[3][l] = bits_of(wlanes[l]);
            }
        }
        if (iface.builtins_read & shader::bit(shader::BuiltIn::SampleMask))
            for (int l = 0; l < kBlockLanes; ++l) {
                uint32_t m = 0;
                for (int s = 0; s < samples; ++s) m |= ((cover[s] >> l) & 1u) << s;
                b.sample_mask_in[l] = m;
            }
        const float* attribs = planes + kPrimHeaderFloats;
        const size_t num_slots = draw.varyings.slot_location.size();
        for (size_t slot = 0; slot < num_slots; ++slot) {
            const uint32_t loc = draw.varyings.slot_location[slot];
            const float* p = attribs + slot * kPlaneFloats;
            const geometry::Interp interp = draw.varyings.slot_interp[slot];
            for (int c = 0; c < 4; ++c) {
                if (interp == geometry::Interp::kFlat) {
                    for (int l = 0; l < kBlockLanes; ++l) b.inputs[loc][c][l] = bits_of(p[c]);
                    continue;
                }
                fragment::eval_plane(plane_of(p, c), x, y, centre, fused_, tmp);
                if (interp == geometry::Interp::kPerspective) {
                    fragment::perspective_divide(tmp, wlanes, out);
                    for (int l = 0; l < kBlockLanes; ++l) b.inputs[loc][c][l] = bits_of(out[l]);
                } else {
                    for (int l = 0; l < kBlockLanes; ++l) b.inputs[loc][c][l] = bits_of(tmp[l]);
                }
            }
        }
        if (draw.varyings.point_coord_slot >= 0) {  // gl_PointCoord: a perspective input (VaryingMap)
            const float* p = attribs + size_t(draw.varyings.point_coord_slot) * kPlaneFloats;
            for (int c = 0; c < 2; ++c) {
                fragment::eval_plane(plane_of(p, c), x, y, centre, fused_, tmp);
                fragment::perspective_divide(tmp, wlanes, out);
                for (int l = 0; l < kBlockLanes; ++l) b.point_coord[c][l] = bits_of(out[l]);
            }
        }
        fs->run_fragment(draw.bindings, b, w.scratch);
        live = static_cast<uint16_t>(b.live_mask & shade_lanes);
        if (iface.writes_frag_depth && depth_active)
            for (int s = 0; s < samples; ++s)
                for (int l = 0; l < kBlockLanes; ++l) std::memcpy(&z[s][l], &b.frag_depth[l], 4);
    }

    // Per-sample survivors of the shader, alpha to coverage and the shader's sample mask.
    uint16_t final_mask[4];
    for (int s = 0; s < samples; ++s) final_mask[s] = pass[s] & live;
    if (fs && pipe.alpha_to_coverage) {
        float alpha[kBlockLanes];
        for (int l = 0; l < kBlockLanes; ++l) std::memcpy(&alpha[l], &b.outputs[0][3][l], 4);
        if (samples > 1)
            fragment::alpha_to_coverage_4x(alpha, final_mask);
        else
            final_mask[0] = fragment::alpha_to_coverage_1x(alpha, final_mask[0]);
    }
    if (fs && (fs->interface().builtins_written & shader::bit(shader::BuiltIn::SampleMask)))
        for (int s = 0; s < samples; ++s)
            for (int l = 0; l < kBlockLanes; ++l)
                if (!((b.sample_mask[l] >> s) & 1u)) final_mask[s] &= uint16_t(~(1u << l));

    // Late depth/stencil: lanes that failed the early test re-run it so their stencil fail ops apply.
    if (depth_active && !(early && early_write)) {
        for (int s = 0; s < samples; ++s) {
            const uint16_t test_lanes =
                early ? static_cast<uint16_t>((cover[s] & ~pass[s]) | final_mask[s]) : final_mask[s];
            if (!test_lanes) continue;
            const uint16_t late_pass = fragment::depth_stencil_test(draw.depth_stencil, dst.format, front_facing, z[s],
                                                                    test_lanes, zs[s], true);
            store_depth_stencil(dst, s, x, y, test_lanes, zs[s]);
            final_mask[s] &= late_pass;
        }
    }
    if (draw.samples_passed) count_passed(w, prim.draw, final_mask, samples);  // only inside a query
    if (!fs) return;

    // Blend and write each colour target, per sample plane.
    fragment::BlendOptions opt;
    opt.fused = fused_;
    float src[4][kBlockLanes];
    for (uint32_t c = 0; c < fb_.num_color && c < shader::kMaxColorOutputs; ++c) {
        const ColorTarget& t = fb_.color[c];
        if (!t.data) continue;
        for (int ch = 0; ch < 4; ++ch) std::memcpy(src[ch], b.outputs[c][ch], sizeof(float) * kBlockLanes);
        const size_t bytes = fragment::format_info(t.format).bytes;
        for (int s = 0; s < samples; ++s) {
            if (!final_mask[s]) continue;
            uint8_t* origin = t.data + size_t(s) * t.sample_stride + size_t(y) * t.row_pitch + size_t(x) * bytes;
            fragment::blend_block(pipe.blend[c], t.format, pipe.blend_constants, src, final_mask[s], origin,
                                  t.row_pitch, opt);
        }
    }
}

}  // namespace tilevk::rast::render

namespace tilevk::rast::render {

// The reference pipeline of shade_block, with each step replaced by what the draw's plan allows (see the header).
void FragmentStage::shade_block_fast(Worker& w, const DrawPlan& plan, const DrawRecord& draw, const PrimRecord& prim,
                                     bool front_facing, int32_t x, int32_t y, const uint16_t raster_masks[4]) {
    const PipelineState& pipe = *draw.pipe;
    const int samples = fb_.samples;
    const float* planes = planes_->data() + prim.plane_base;
    const float depth_offset = planes[kPlaneFloats];

    uint16_t cover[4] = {0, 0, 0, 0};
    uint16_t any = 0;
    for (int s = 0; s < samples; ++s) any |= cover[s] = fragment::raster_to_lanes(raster_masks[s]);
    if (!any) return;
    const bool inside = x + 4 <= fb_.width && y + 4 <= fb_.height;

    // Lane coordinates at the pixel centre; at 1x they are also the depth sample positions.
    fragment::LaneCoords centre;
    fragment::make_lane_coords(x, y, fragment::plane_offset(samples, -1), centre);

    float z[4][kBlockLanes];
    const fragment::Plane zplane = plane_of(planes, 2);
    const bool depth_active = draw.depth_mode != 0;
    if (depth_active)
        for (int s = 0; s < samples; ++s) {
            if (samples > 1) {
                fragment::LaneCoords at;
                fragment::make_lane_coords(x, y, fragment::plane_offset(samples, s), at);
                fragment::eval_plane_fast(zplane, at, fused_, z[s]);
            } else {
                fragment::eval_plane_fast(zplane, centre, fused_, z[s]);
            }
            for (int l = 0; l < kBlockLanes; ++l) z[s][l] = z[s][l] + depth_offset;  // eval_depth's plain add
        }

    const DepthStencilTarget& dst = fb_.depth_stencil;
    fragment::DepthStencilBlock zs[4];
    const bool early = draw.depth_mode & fragment::kEarlyDepthTest;
    const bool early_write = draw.depth_mode & fragment::kEarlyDepthWrite;
    const size_t zbytes = depth_bytes(dst.format);
    auto depth_origin = [&](int s) {
        return dst.depth + size_t(s) * dst.depth_sample_stride + size_t(y) * dst.depth_row_pitch + size_t(x) * zbytes;
    };
    uint16_t pass[4] = {cover[0], cover[1], cover[2], cover[3]};
    if (depth_active && early) {
        for (int s = 0; s < samples; ++s) {
            if (plan.depth_fast) {
                if (cover[s])
                    pass[s] = fragment::depth_block_fast(plan.depth, z[s], cover[s], depth_origin(s),
                                                         dst.depth_row_pitch, early_write, inside);
                continue;
            }
            load_depth_stencil(dst, s, x, y, cover[s], zs[s]);
            pass[s] = fragment::depth_stencil_test(draw.depth_stencil, dst.format, front_facing, z[s], cover[s], zs[s],
                                                   early_write);
            if (early_write) store_depth_stencil(dst, s, x, y, cover[s], zs[s]);
        }
    } else if (depth_active && !plan.depth_fast) {
        for (int s = 0; s < samples; ++s) load_depth_stencil(dst, s, x, y, cover[s], zs[s]);
    }
    uint16_t shade_lanes = 0;
    for (int s = 0; s < samples; ++s) shade_lanes |= pass[s];
    if (!shade_lanes) return;

    shader::FragmentBlock& b = w.block;
    const shader::Program* fs = pipe.fragment;
    uint16_t live = shade_lanes;
    if (fs && plan.uniform_shader) {
        // One run per primitive: every lane of it sees the same flat inputs, so block.outputs stays valid.
        if (w.uniform_prim != &prim || w.uniform_front != front_facing) {
            b.cover_mask = shader::kAllLanes;
            b.front_facing = front_facing ? 1u : 0u;
            b.sample_id = 0;
            const float* attribs = planes + kPrimHeaderFloats;
            for (const InputPlan& in : plan.inputs)
                for (int l = 0; l < kBlockLanes; ++l) input_lanes(b, in)[l] = bits_of(attribs[in.plane + in.comp]);
            fs->run_fragment(draw.bindings, b, w.scratch);
            w.uniform_prim = &prim;
            w.uniform_front = front_facing;
        }
    } else if (fs) {
        w.uniform_prim = nullptr;  // block.inputs/outputs are about to change
        b.cover_mask = shade_lanes;
        b.front_facing = front_facing ? 1u : 0u;
        b.sample_id = 0;
        const shader::ProgramInterface& iface = fs->interface();
        const bool frag_coord = iface.builtins_read & shader::bit(shader::BuiltIn::FragCoord);
        alignas(32) float wlanes[kBlockLanes], oow[kBlockLanes] = {};
        if (plan.perspective || frag_coord) fragment::eval_plane_fast(plane_of(planes, 3), centre, fused_, wlanes);
        if (frag_coord) {
            const fragment::EvalOffset off = fragment::plane_offset(samples, -1);
            float fx[kBlockLanes], fy[kBlockLanes], fz[kBlockLanes];
            fragment::frag_coord_xy(x, y, fragment::frag_coord_offset(samples, -1), fx, fy);
            fragment::eval_depth(zplane, depth_offset, x, y, off, fused_, fz);
            for (int l = 0; l < kBlockLanes; ++l) {
                b.frag_coord[0][l] = bits_of(fx[l]);
                b.frag_coord[1][l] = bits_of(fy[l]);
                b.frag_coord[2][l] = bits_of(fz[l]);
                b.frag_coord[3][l] = bits_of(wlanes[l]);
            }
        }
        if (iface.builtins_read & shader::bit(shader::BuiltIn::SampleMask))
            for (int l = 0; l < kBlockLanes; ++l) {
                uint32_t m = 0;
                for (int s = 0; s < samples; ++s) m |= ((cover[s] >> l) & 1u) << s;
                b.sample_mask_in[l] = m;
            }
        // perspective: a * fl(1/w), the reciprocal once per block
        if (plan.perspective) fragment::reciprocal_fast(wlanes, oow);
        const float* attribs = planes + kPrimHeaderFloats;
        for (const InputPlan& in : plan.inputs) {
            const float* p = attribs + in.plane;
            if (in.interp == geometry::Interp::kFlat) {
                for (int l = 0; l < kBlockLanes; ++l) input_lanes(b, in)[l] = bits_of(p[in.comp]);
                continue;
            }
            fragment::interpolate_input(plane_of(p, int(in.comp)), centre, fused_,
                                        in.interp == geometry::Interp::kPerspective ? oow : nullptr,
                                        input_lanes(b, in));
        }
        if (plan.copy_location >= 0) {
            std::memcpy(b.outputs[0], b.inputs[plan.copy_location], sizeof b.outputs[0]);  // what the run would do
        } else {
            fs->run_fragment(draw.bindings, b, w.scratch);
            live = static_cast<uint16_t>(b.live_mask & shade_lanes);
        }
        if (iface.writes_frag_depth && depth_active)
            for (int s = 0; s < samples; ++s)
                for (int l = 0; l < kBlockLanes; ++l) std::memcpy(&z[s][l], &b.frag_depth[l], 4);
    }

    uint16_t final_mask[4];
    for (int s = 0; s < samples; ++s) final_mask[s] = pass[s] & live;
    if (fs && pipe.alpha_to_coverage) {
        float alpha[kBlockLanes];
        for (int l = 0; l < kBlockLanes; ++l) std::memcpy(&alpha[l], &b.outputs[0][3][l], 4);
        if (samples > 1)
            fragment::alpha_to_coverage_4x(alpha, final_mask);
        else
            final_mask[0] = fragment::alpha_to_coverage_1x(alpha, final_mask[0]);
    }
    if (fs && (fs->interface().builtins_written & shader::bit(shader::BuiltIn::SampleMask)))
        for (int s = 0; s < samples; ++s)
            for (int l = 0; l < kBlockLanes; ++l)
                if (!((b.sample_mask[l] >> s) & 1u)) final_mask[s] &= uint16_t(~(1u << l));

    // Late depth/stencil, as shade_block: lanes that failed the early test re-run it.
    if (depth_active && !(early && early_write)) {
        for (int s = 0; s < samples; ++s) {
            const uint16_t test_lanes =
                early ? static_cast<uint16_t>((cover[s] & ~pass[s]) | final_mask[s]) : final_mask[s];
            if (!test_lanes) continue;
            if (plan.depth_fast) {
                final_mask[s] &= fragment::depth_block_fast(plan.depth, z[s], test_lanes, depth_origin(s),
                                                            dst.depth_row_pitch, true, inside);
                continue;
            }
            const uint16_t late_pass = fragment::depth_stencil_test(draw.depth_stencil, dst.format, front_facing, z[s],
                                                                    test_lanes, zs[s], true);
            store_depth_stencil(dst, s, x, y, test_lanes, zs[s]);
            final_mask[s] &= late_pass;
        }
    }
    if (draw.samples_passed) count_passed(w, prim.draw, final_mask, samples);  // only inside a query
    if (!fs) return;

    fragment::BlendOptions opt;
    opt.fused = fused_;
    alignas(32) float src[4][kBlockLanes];
    for (uint32_t c = 0; c < fb_.num_color && c < shader::kMaxColorOutputs; ++c) {
        const ColorTarget& t = fb_.color[c];
        if (!t.data || plan.color[c] == ColorPath::kNone) continue;
        std::memcpy(src, b.outputs[c], sizeof src);
        const size_t bytes = plan.color_bytes[c];
        for (int s = 0; s < samples; ++s) {
            if (!final_mask[s]) continue;
            uint8_t* origin = t.data + size_t(s) * t.sample_stride + size_t(y) * t.row_pitch + size_t(x) * bytes;
            if (plan.color[c] == ColorPath::kRgba8 && inside &&
                fragment::blend_rgba8_block(plan.rgba8[c], src, final_mask[s], origin, t.row_pitch))
                continue;
            if (plan.color[c] == ColorPath::kGeneric || plan.color[c] == ColorPath::kRgba8)
                fragment::blend_block(pipe.blend[c], t.format, pipe.blend_constants, src, final_mask[s], origin,
                                      t.row_pitch, opt);
            else
                fragment::store_rgba8_fast(plan.color[c] == ColorPath::kOpaqueBgra8, src, final_mask[s], origin,
                                           t.row_pitch, opt.unorm_path, inside);
        }
    }
}

}  // namespace tilevk::rast::render
