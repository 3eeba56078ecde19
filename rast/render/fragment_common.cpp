// The fragment stage's helpers shared by the reference pipeline and every block function, built once (portable
// code: no instruction-set variant calls anything else through them).
#include <algorithm>
#include <cstring>

#include "rast/core/cpu.h"
#include "rast/fragment/block.h"
#include "rast/fragment/interp.h"
#include "rast/fragment/msaa.h"
#include "rast/render/fragment_plan.h"

namespace tilevk::rast::render {
namespace {

using fragment::kBlockLanes;

// Depth texels are 2 or 4 bytes: constant-size copies (inlined) instead of a memcpy call per lane.
uint32_t load_depth_texel(const uint8_t* src, size_t bytes) {
    if (bytes == 2) {
        uint16_t v;
        std::memcpy(&v, src, 2);
        return v;
    }
    uint32_t v = 0;
    if (bytes == 4) std::memcpy(&v, src, 4);
    return v;
}

void store_depth_texel(uint8_t* dst, size_t bytes, uint32_t v) {
    if (bytes == 2) {
        const uint16_t h = uint16_t(v);
        std::memcpy(dst, &h, 2);
    } else if (bytes == 4) {
        std::memcpy(dst, &v, 4);
    }
}

}  // namespace

BlockFn fast_block_function() {
#if TILEVK_AVX2_VARIANT
    if (kernel_isa() == Isa::kAvx2) return isa_avx2::shade_block_fast;
#endif
    return isa_base::shade_block_fast;
}

SquareFn fast_square_function() {
#if TILEVK_AVX2_VARIANT
    if (kernel_isa() == Isa::kAvx2) return isa_avx2::shade_square_fast;
#endif
    return nullptr;
}

Uniform4xFn fast_uniform_4x_function() {
#if TILEVK_AVX2_VARIANT
    if (kernel_isa() == Isa::kAvx2) return isa_avx2::shade_uniform_4x_blocks;
#endif
    return nullptr;
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

namespace {

// Where lavapipe interpolates the input at `loc` (the variable's Centroid / Sample decoration; 0 centre).
enum class InputSite : uint8_t { kCentre, kCentroid, kSample };
InputSite input_site(const shader::ProgramInterface& iface, uint32_t loc) {
    for (const shader::IoVariable& v : iface.inputs)
        if (v.location == loc)
            return v.sample ? InputSite::kSample : v.centroid ? InputSite::kCentroid : InputSite::kCentre;
    return InputSite::kCentre;
}

// FragCoord (xy and z at the run's sample in a per-sample run, else the centre; w at the centre) and the
// per-block built-ins: SampleMaskIn (the raster coverage, only the run's sample's bit in a per-sample run;
// lp_state_fs.c sample_mask_in), SampleId and SamplePosition (lavapipe's sample_pos_array: the 4x table at 4x, (0.5,
// 0.5) at 1x).
void set_builtin_inputs(shader::FragmentBlock& b, const shader::ProgramInterface& iface, const float* planes, int32_t x,
                        int32_t y, const RunSite& site, const float wl[kBlockLanes], bool fused) {
    const int s = site.sample;
    b.sample_id = s < 0 ? 0u : uint32_t(s);
    const float* pos = site.samples > 1 ? fragment::kSamplePos4x[s < 0 ? 0 : s] : nullptr;
    b.sample_position[0] = bits_of(pos ? pos[0] : 0.5f);
    b.sample_position[1] = bits_of(pos ? pos[1] : 0.5f);
    if (iface.builtins_read & shader::bit(shader::BuiltIn::FragCoord)) {
        float fx[kBlockLanes], fy[kBlockLanes], fz[kBlockLanes];
        fragment::frag_coord_xy(x, y, fragment::frag_coord_offset(site.samples, s), fx, fy);
        fragment::eval_depth(plane_of(planes, 2), planes[kPlaneFloats], x, y, fragment::plane_offset(site.samples, s),
                             fused, fz);
        for (int l = 0; l < kBlockLanes; ++l) {
            b.frag_coord[0][l] = bits_of(fx[l]);
            b.frag_coord[1][l] = bits_of(fy[l]);
            b.frag_coord[2][l] = bits_of(fz[l]);
            b.frag_coord[3][l] = bits_of(wl[l]);
        }
    }
    if (iface.builtins_read & shader::bit(shader::BuiltIn::SampleMask))
        for (int l = 0; l < kBlockLanes; ++l) {
            uint32_t m = 0;
            for (int k = 0; k < site.samples; ++k) m |= ((site.cover[k] >> l) & 1u) << k;
            b.sample_mask_in[l] = s < 0 ? m : m & (1u << s);
        }
}

// The planes of every input location, where the block is and its sample masks, for InterpolateAt*
// (shader/interpolate.cpp evaluates them; lp_bld_interp.c lp_build_interp_soa).
void set_input_planes(shader::InputPlanes& ip, const DrawRecord& draw, const float* attribs, int32_t x, int32_t y,
                      const RunSite& site, const float wl[kBlockLanes], bool fused) {
    std::fill(std::begin(ip.kind), std::end(ip.kind), shader::InputPlanes::Kind::None);
    for (size_t slot = 0; slot < draw.varyings.slot_location.size(); ++slot) {
        const uint32_t loc = draw.varyings.slot_location[slot];
        if (loc >= uint32_t(shader::kMaxLocations)) continue;
        const geometry::Interp interp = draw.varyings.slot_interp[slot];
        ip.kind[loc] = interp == geometry::Interp::kFlat          ? shader::InputPlanes::Kind::Flat
                       : interp == geometry::Interp::kPerspective ? shader::InputPlanes::Kind::Perspective
                                                                  : shader::InputPlanes::Kind::NoPerspective;
        const float* p = attribs + slot * kPlaneFloats;
        for (int c = 0; c < 4; ++c) {
            const fragment::Plane pl = plane_of(p, c);
            ip.a0[loc][c] = pl.a0;
            ip.dadx[loc][c] = pl.dadx;
            ip.dady[loc][c] = pl.dady;
        }
    }
    std::copy(wl, wl + kBlockLanes, ip.w);
    ip.x = x;
    ip.y = y;
    ip.samples = site.samples;
    ip.fused = fused;
    for (int s = 0; s < fragment::kMaxSamples; ++s) {
        ip.sample_pos[s][0] = fragment::kSamplePos4x[s][0];
        ip.sample_pos[s][1] = fragment::kSamplePos4x[s][1];
        ip.masks[s] = site.masks && s < site.samples ? site.masks[s] : 0;
    }
}

}  // namespace

void set_fragment_inputs(shader::FragmentBlock& b, const DrawRecord& draw, const float* planes, int32_t x, int32_t y,
                         const RunSite& site, bool fused) {
    const shader::ProgramInterface& iface = draw.pipe->fragment->interface();
    const fragment::EvalOffset centre = fragment::plane_offset(site.samples, -1);
    float wl[kBlockLanes], tmp[kBlockLanes], out[kBlockLanes];
    fragment::eval_plane(plane_of(planes, 3), x, y, centre, fused, wl);
    set_builtin_inputs(b, iface, planes, x, y, site, wl, fused);
    b.input_planes = nullptr;
    if (iface.interpolates_at && site.input_planes) {
        set_input_planes(*site.input_planes, draw, planes + kPrimHeaderFloats, x, y, site, wl, fused);
        b.input_planes = site.input_planes;
    }
    float cx[kBlockLanes], cy[kBlockLanes];
    bool have_centroid = false;
    const float* attribs = planes + kPrimHeaderFloats;
    const size_t num_slots = draw.varyings.slot_location.size();
    for (size_t slot = 0; slot < num_slots; ++slot) {
        const uint32_t loc = draw.varyings.slot_location[slot];
        const float* p = attribs + slot * kPlaneFloats;
        const geometry::Interp interp = draw.varyings.slot_interp[slot];
        // At 1x every site is the plane origin, the pixel centre (lp_bld_interp.c adds offsets at 4x only).
        const InputSite where = site.samples > 1 ? input_site(iface, loc) : InputSite::kCentre;
        if (where == InputSite::kCentroid && !have_centroid) {
            fragment::centroid_offsets(site.masks, cx, cy);
            have_centroid = true;
        }
        for (int c = 0; c < 4; ++c) {
            if (interp == geometry::Interp::kFlat) {
                for (int l = 0; l < kBlockLanes; ++l) b.inputs[loc][c][l] = bits_of(p[c]);
                continue;
            }
            if (where == InputSite::kCentroid)
                fragment::eval_plane_per_lane(plane_of(p, c), x, y, cx, cy, fused, tmp);
            else
                fragment::eval_plane(
                    plane_of(p, c), x, y,
                    where == InputSite::kSample ? fragment::plane_offset(site.samples, site.sample) : centre, fused,
                    tmp);
            if (interp == geometry::Interp::kPerspective) {
                fragment::perspective_divide(tmp, wl, out);
                for (int l = 0; l < kBlockLanes; ++l) b.inputs[loc][c][l] = bits_of(out[l]);
            } else {
                for (int l = 0; l < kBlockLanes; ++l) b.inputs[loc][c][l] = bits_of(tmp[l]);
            }
        }
    }
    if (draw.varyings.point_coord_slot >= 0) {  // gl_PointCoord: a perspective input (VaryingMap)
        const float* p = attribs + size_t(draw.varyings.point_coord_slot) * kPlaneFloats;
        for (int c = 0; c < 2; ++c) {
            fragment::eval_plane(plane_of(p, c), x, y, centre, fused, tmp);
            fragment::perspective_divide(tmp, wl, out);
            for (int l = 0; l < kBlockLanes; ++l) b.point_coord[c][l] = bits_of(out[l]);
        }
    }
}

void shader_coverage(const shader::Program* fs, bool alpha_to_coverage, const shader::FragmentBlock& b, int samples,
                     uint16_t final_mask[4]) {
    if (!fs) return;
    if (alpha_to_coverage) {
        float alpha[kBlockLanes];
        for (int l = 0; l < kBlockLanes; ++l) std::memcpy(&alpha[l], &b.outputs[0][3][l], 4);
        if (samples > 1)
            fragment::alpha_to_coverage_4x(alpha, final_mask);
        else
            final_mask[0] = fragment::alpha_to_coverage_1x(alpha, final_mask[0]);
    }
    if (fs->interface().builtins_written & shader::bit(shader::BuiltIn::SampleMask))
        for (int s = 0; s < samples; ++s)
            for (int l = 0; l < kBlockLanes; ++l)
                if (!((b.sample_mask[l] >> s) & 1u)) final_mask[s] &= uint16_t(~(1u << l));
}

bool scene_may_hide(const Framebuffer& fb, const DrawRecords& draws) {
    if (fb.linear_mode || fb.samples != 1 || fb.depth_stencil.depth || fb.depth_stencil.stencil) return false;
    bool any = false;
    for (size_t k = 0; k < draws.size(); ++k) {
        const DrawRecord& d = draws[k];
        if (d.samples_passed || d.statistics || !d.pipe) return false;  // llvmpipe: no bin reset in a query's scene
        if (const shader::Program* fs = d.pipe->fragment) {
            const shader::ProgramInterface& i = fs->interface();
            if (i.writes_device_addresses) return false;
            for (const shader::DescriptorUse& u : i.descriptors)
                if (u.written) return false;
        }
        any = any || draw_hides_earlier(d, fb);
    }
    return any;
}

bool draw_hides_earlier(const DrawRecord& draw, const Framebuffer& fb) {
    const PipelineState& pipe = *draw.pipe;
    if (!pipe.fragment || pipe.alpha_to_coverage || !(pipe.sample_mask & 1u)) return false;
    const shader::ProgramInterface& i = pipe.fragment->interface();
    if (i.uses_discard || (i.builtins_written & shader::bit(shader::BuiltIn::SampleMask))) return false;
    for (uint32_t c = 0; c < fb.num_color; ++c) {
        if (!fb.color[c].data) continue;
        if (c >= uint32_t(shader::kMaxColorOutputs)) return false;
        const fragment::BlendAttachment& b = pipe.blend[c];
        if (b.logic_op_enable || b.blend_enable || b.write_mask != 0xf) return false;
        uint32_t components = 0;  // bit k: component k of location c is an output
        for (const shader::IoVariable& v : i.outputs)
            if (v.location == c && v.component < 4)
                components |= ((1u << std::min<uint32_t>(v.components, 4 - v.component)) - 1u) << v.component;
        if (components != 0xf) return false;
    }
    return true;
}

}  // namespace tilevk::rast::render
