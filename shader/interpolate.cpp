// Op::InterpolateAt: GLSL.std.450 InterpolateAtCentroid / AtSample / AtOffset, as llvmpipe evaluates them
// (lp_bld_interp.c lp_build_interp_soa, reached through lp_state_fs.c fs_interp for nir's interp_deref_at_*):
//
//   px = fl(lane_x + block_x)                       the lane's integer pixel coordinate (exact)
//   offset:   4x: px = fl(px + 0.5); then px = fl(px + offset.x)   (1x: the plane origin is the centre already)
//   sample:   4x: px = fl(px + sample_pos[id].x)                   1x: px unchanged
//   centroid: 4x: px = fl(px + centroid offset of the lane)        1x: px unchanged
//   a = fmuladd(dady, py, fmuladd(dadx, px, a0));  perspective: a = fl(a * fl(1 / w)), w at the pixel centre
//   flat: a0
//
// The offset is added as given: lavapipe does not clamp it to [minInterpolationOffset, maxInterpolationOffset].
#include <bit>
#include <cmath>
#include <cstdint>

#include "shader/ir.h"

namespace tilevk::shader {
namespace {

// fmuladd as LLVM lowers it: one rounding when fused, two otherwise (the project builds with -ffp-contract=off).
float fmuladd(float a, float b, float c, bool fused) {
    return fused ? std::fma(a, b, c) : a * b + c;
}

// calc_centroid_offsets: the pixel centre where all samples or none are covered, else the position of the lowest
// covered sample.
void centroid_offset(const InputPlanes& ip, int lane, float& ox, float& oy) {
    const uint32_t bit = 1u << lane;
    ox = oy = 0.5f;
    bool all = true;
    for (int s = ip.samples - 1; s >= 0; --s) {
        if (ip.masks[s] & bit) {
            ox = ip.sample_pos[s][0];
            oy = ip.sample_pos[s][1];
        } else {
            all = false;
        }
    }
    if (all) ox = oy = 0.5f;
}

}  // namespace

void exec_interpolate_at(const Inst& in, uint32_t* regs, const InputPlanes* planes) {
    uint32_t* d = regs + size_t(in.d) * kLanes;
    const uint32_t loc = in.imm / 4, comp = in.imm % 4;
    if (!planes || loc >= uint32_t(kMaxLocations) || planes->kind[loc] == InputPlanes::Kind::None) {
        for (int l = 0; l < kLanes; ++l) d[l] = 0;
        return;
    }
    const InputPlanes& ip = *planes;
    const InputPlanes::Kind kind = ip.kind[loc];
    const float a0 = ip.a0[loc][comp], dadx = ip.dadx[loc][comp], dady = ip.dady[loc][comp];
    if (kind == InputPlanes::Kind::Flat) {
        for (int l = 0; l < kLanes; ++l) d[l] = std::bit_cast<uint32_t>(a0);
        return;
    }
    const auto mode = InterpAt(in.pad);
    const uint32_t* a = in.a != kNoReg ? regs + size_t(in.a) * kLanes : nullptr;
    const uint32_t* b = in.b != kNoReg ? regs + size_t(in.b) * kLanes : nullptr;
    const bool msaa = ip.samples > 1;
    const float bx = float(ip.x), by = float(ip.y);
    float out[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        float px = float(lane_x(l)) + bx, py = float(lane_y(l)) + by;
        if (mode == InterpAt::Offset) {
            if (msaa) px = px + 0.5f, py = py + 0.5f;
            if (a) px = px + std::bit_cast<float>(a[l]);
            if (b) py = py + std::bit_cast<float>(b[l]);
        } else if (msaa && mode == InterpAt::Sample && a) {
            // lavapipe gathers from its 8-float table: an index outside 0..3 is undefined behaviour in Vulkan
            // and reads past lavapipe's table; tilevk takes it modulo 4 (not compared with lavapipe).
            const uint32_t s = a[l] & 3u;
            px = px + ip.sample_pos[s][0];
            py = py + ip.sample_pos[s][1];
        } else if (msaa && mode == InterpAt::Centroid) {
            float ox, oy;
            centroid_offset(ip, l, ox, oy);
            px = px + ox;
            py = py + oy;
        }
        const float v = fmuladd(dady, py, fmuladd(dadx, px, a0, ip.fused), ip.fused);
        out[l] = kind == InputPlanes::Kind::Perspective ? v * (1.0f / ip.w[l]) : v;
    }
    for (int l = 0; l < kLanes; ++l) d[l] = std::bit_cast<uint32_t>(out[l]);
}

}  // namespace tilevk::shader
