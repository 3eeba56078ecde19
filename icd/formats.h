// The formats tilevk supports and what it can do with each (only what really works is reported).
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

namespace tilevk::icd {

// How a colour clear value is packed for a format (mirrors lavapipe's util_format_pack_rgba choices).
enum class PackKind : uint8_t {
    kNone,     // not an image format
    kUnorm8,   // float_to_ubyte per channel
    kSrgb8,    // linear float -> sRGB 8-bit for RGB, float_to_ubyte for alpha
    kFloat16,  // IEEE half, rounded toward zero
    kFloat32,  // stored as is
    kD16,      // depth: lrint(z * 65535.0) in double
    kD32F,     // depth: (float)z
    kD32FS8,   // depth float at byte 0, stencil byte at byte 4 (8-byte texel)
    kD24S8,    // depth: lrint(z * 16777215.0) in double, low 24 bits (bytes 0-2); stencil at byte 3
};

struct FormatInfo {
    VkFormat format;
    uint32_t texel_bytes;  // bytes of one texel of one sample in tilevk's linear layout
    uint32_t channels;
    bool bgra;  // memory order B,G,R,A
    PackKind pack;
    VkImageAspectFlags aspects;
    VkFormatFeatureFlags optimal_features;
    VkFormatFeatureFlags linear_features;
    VkFormatFeatureFlags buffer_features;
};

// The table entry for `format`, or nullptr if tilevk does not know the format at all.
const FormatInfo* find_format(VkFormat format);

// True if images of the format may have 4 samples: every 4x colour format must be resolvable (execute_transfer.cpp
// implements lavapipe's resolve for UNORM8 and FLOAT32 only); depth formats are never resolved in Vulkan 1.0.
bool format_supports_msaa(const FormatInfo& f);

// Bytes of one aspect of a texel as laid out in a buffer for vkCmdCopyBufferToImage/ImageToBuffer.
uint32_t buffer_texel_bytes(const FormatInfo& f, VkImageAspectFlags aspect);
// Byte offset of `aspect` inside one tilevk texel.
uint32_t aspect_offset(const FormatInfo& f, VkImageAspectFlags aspect);

}  // namespace tilevk::icd
