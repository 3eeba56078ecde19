// Internal to blend.cpp and blend_rgba8.cpp: the blend factor codes a prepared state carries.
#pragma once

#include <cstdint>

namespace tilevk::rast::fragment {

// Gallium's PIPE_BLENDFACTOR numbering: lavapipe's shortcut rules depend on it (complement = value ^ 0x10,
// "src < dst" picks the lerp direction).
enum PipeFactor : uint8_t {
    kOne = 0x01,
    kSrcColor = 0x02,
    kSrcAlpha = 0x03,
    kDstAlpha = 0x04,
    kDstColor = 0x05,
    kSrcAlphaSat = 0x06,
    kConstColor = 0x07,
    kConstAlpha = 0x08,
    kSrc1Color = 0x09,  // dual-source factors: the fragment shader's Location 0, Index 1 output
    kSrc1Alpha = 0x0A,
    kZero = 0x11,
    kInvSrcColor = 0x12,
    kInvSrcAlpha = 0x13,
    kInvDstAlpha = 0x14,
    kInvDstColor = 0x15,
    kInvConstColor = 0x17,
    kInvConstAlpha = 0x18,
    kInvSrc1Color = 0x19,
    kInvSrc1Alpha = 0x1A,
    kUnsupported = 0xff,
};

}  // namespace tilevk::rast::fragment
