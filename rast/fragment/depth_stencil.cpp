#include "rast/fragment/depth_stencil.h"

#include <cmath>
#include <cstring>

namespace tilevk::rast::fragment {

namespace {
// SSE minps/maxps: when either operand is NaN the SECOND operand is returned.
inline float sse_min(float a, float b) {
    return a < b ? a : b;
}
inline float sse_max(float a, float b) {
    return a > b ? a : b;
}

inline float bits_float(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

}  // namespace

float clamp_depth(float z, const DepthStencilState& s, DepthFormat f) {
    // lp_build_clamp(z, lo, hi) = max(min(z, hi), lo)
    const bool restrict01 = !(s.unrestricted_depth && f == DepthFormat::D32F);
    // The clamps are SSE min/max run under MXCSR DAZ: a denormal z reads as zero (verified against lavapipe).
    if ((restrict01 || s.depth_clamp) && z != 0.0f && std::fabs(z) < 0x1p-126f) z = 0.0f;
    if (restrict01) z = sse_max(sse_min(z, 1.0f), 0.0f);
    if (s.depth_clamp) z = sse_max(sse_min(z, s.max_depth), s.min_depth);
    return z;
}

bool compare(CompareOp op, uint32_t a, uint32_t b) {
    return shader::compare_values(op, a, b);
}

bool compare_float(CompareOp op, float a, float b) {
    // lp_build_compare uses LLVM's UNORDERED predicates (ult, ueq, une, ...): any NaN operand makes every
    // comparison except NEVER true.
    // Compares run under DAZ: denormal operands compare as zero.
    if (a != 0.0f && std::fabs(a) < 0x1p-126f) a = 0.0f;
    if (b != 0.0f && std::fabs(b) < 0x1p-126f) b = 0.0f;
    if (std::isnan(a) || std::isnan(b)) return op != CompareOp::Never;
    return shader::compare_values(op, a, b);
}

uint8_t apply_stencil_op(StencilOp op, uint8_t v, uint8_t ref) {
    switch (op) {
        case StencilOp::Keep:
            return v;
        case StencilOp::Zero:
            return 0;
        case StencilOp::Replace:
            return ref;
        case StencilOp::IncrementAndClamp:
            return v == 255 ? 255 : uint8_t(v + 1);
        case StencilOp::DecrementAndClamp:
            return v == 0 ? 0 : uint8_t(v - 1);
        case StencilOp::Invert:
            return uint8_t(~v);
        case StencilOp::IncrementAndWrap:
            return uint8_t(v + 1);
        case StencilOp::DecrementAndWrap:
            return uint8_t(v - 1);
    }
    return v;
}

uint16_t depth_stencil_test(const DepthStencilState& s, DepthFormat f, bool front_facing, const float z[kBlockLanes],
                            uint16_t mask, DepthStencilBlock& zs, bool write) {
    const bool do_depth = s.depth_test && f != DepthFormat::None;
    const StencilFace& face = front_facing ? s.front : s.back;
    uint16_t pass = 0;
    for (int l = 0; l < kBlockLanes; ++l) {
        if (!(mask & (1u << l))) continue;
        uint8_t sv = zs.stencil[l];
        bool s_pass = true;
        if (s.stencil_test) {
            // ref & compare_mask  OP  stored & compare_mask
            s_pass = compare(face.compare_op, face.reference & face.compare_mask, sv & face.compare_mask);
        }
        bool z_pass = true;
        uint32_t z_src = 0;
        if (do_depth) {
            const float zc = clamp_depth(z[l], s, f);
            z_src = depth_to_stored(zc, f);
            const uint32_t z_dst = zs.depth[l];
            z_pass = (f == DepthFormat::D32F) ? compare_float(s.depth_compare, bits_float(z_src), bits_float(z_dst))
                                              : compare(s.depth_compare, z_src, z_dst);
        }
        uint8_t new_s = sv;
        if (s.stencil_test) {
            const StencilOp op = !s_pass ? face.fail_op : !z_pass ? face.depth_fail_op : face.pass_op;
            const uint8_t r = apply_stencil_op(op, sv, face.reference);
            // (res & wm) | (old & ~wm)
            new_s = uint8_t((r & face.write_mask) | (sv & ~face.write_mask));
        }
        const bool passed = s_pass && z_pass;
        if (write) {
            if (do_depth && s.depth_write && passed) zs.depth[l] = z_src;
            if (s.stencil_test) zs.stencil[l] = new_s;
        }
        if (passed) pass |= uint16_t(1u << l);
    }
    return pass;
}

uint8_t choose_depth_mode(const DepthStencilState& s, const ShaderDepthTraits& t, bool alpha_to_coverage) {
    if (!s.depth_test && !s.stencil_test) return 0;
    const bool stencil_writes = s.stencil_test && (s.front.write_mask != 0 || s.back.write_mask != 0);
    uint8_t mode;
    if (t.early_fragment_tests) {
        mode = kEarlyDepthTest | kEarlyDepthWrite;
    } else if (!t.writes_depth && !t.writes_stencil && !t.uses_fbfetch && !t.writes_memory) {
        if (alpha_to_coverage || t.uses_discard || t.writes_sample_mask) {
            // Early test, deferred write once the final mask is known; impossible if stencil is written.
            mode = stencil_writes ? (kLateDepthTest | kLateDepthWrite)
                                  : (kEarlyDepthTest | kLateDepthWrite | kEarlyDepthTestInferred);
        } else {
            mode = kEarlyDepthTest | kEarlyDepthWrite | kEarlyDepthTestInferred;
        }
    } else {
        mode = kLateDepthTest | kLateDepthWrite;
    }
    if (!(s.depth_test && s.depth_write) && !stencil_writes) mode &= uint8_t(~(kLateDepthWrite | kEarlyDepthWrite));
    return mode;
}

}  // namespace tilevk::rast::fragment
