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
    kZero = 0x11,
    kInvSrcColor = 0x12,
    kInvSrcAlpha = 0x13,
    kInvDstAlpha = 0x14,
    kInvDstColor = 0x15,
    kInvConstColor = 0x17,
    kInvConstAlpha = 0x18,
    kUnsupported = 0xff,
};

}  // namespace tilevk::rast::fragment
