// vkCmdBlitImage on both drivers (tilevk and lavapipe, through the loader with validation on). Each case fills a
// source with pseudo-random texels, blits, reads every level and layer of the destination back, and the bytes must
// equal lavapipe's. Analytic cases check tilevk against expectations computed here (copy, 2x duplicate, mirror).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <ostream>
#include <string>

#include "vk_harness.h"

namespace {

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::transition;
using tilevk::test::TwoDriverSuite;
using Bytes = std::vector<uint8_t>;

constexpr VkImageLayout kGeneral = VK_IMAGE_LAYOUT_GENERAL;
constexpr VkImageUsageFlags kXfer = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

uint32_t texel_bytes(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R8_UNORM:
        case VK_FORMAT_R8_SNORM:
        case VK_FORMAT_R8_UINT:
        case VK_FORMAT_R8_SINT:
            return 1;
        case VK_FORMAT_R8G8_UNORM:
        case VK_FORMAT_R8G8_SNORM:
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_R16_UNORM:
        case VK_FORMAT_R16_UINT:
        case VK_FORMAT_R16_SINT:
        case VK_FORMAT_R8G8_UINT:
        case VK_FORMAT_R8G8_SINT:
        case VK_FORMAT_R16_SNORM:
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_B4G4R4A4_UNORM_PACK16:
        case VK_FORMAT_A4R4G4B4_UNORM_PACK16:
        case VK_FORMAT_A4B4G4R4_UNORM_PACK16:
        case VK_FORMAT_R5G6B5_UNORM_PACK16:
        case VK_FORMAT_B5G6R5_UNORM_PACK16:
        case VK_FORMAT_R5G5B5A1_UNORM_PACK16:
        case VK_FORMAT_B5G5R5A1_UNORM_PACK16:
        case VK_FORMAT_A1R5G5B5_UNORM_PACK16:
            return 2;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R16G16B16A16_UNORM:
        case VK_FORMAT_R16G16B16A16_SINT:
        case VK_FORMAT_R16G16B16A16_UINT:
        case VK_FORMAT_R32G32_UINT:
        case VK_FORMAT_R32G32_SINT:
        case VK_FORMAT_R16G16B16A16_SNORM:
        case VK_FORMAT_R32G32_SFLOAT:
            return 8;
        case VK_FORMAT_R32G32B32_SFLOAT:
            return 12;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
        case VK_FORMAT_R32G32B32A32_SINT:
        case VK_FORMAT_R32G32B32A32_UINT:
            return 16;
        default:
            return 4;
    }
}
bool is_depth(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D32_SFLOAT;
}
VkImageAspectFlags aspect(VkFormat f) {
    return is_depth(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

struct Lcg {
    uint32_t s;
    uint32_t next() { return s = s * 1664525u + 1013904223u; }
    float unit() { return float(next() >> 8) * (1.0f / 16777216.0f); }
};

// Deterministic texels: random bytes for 8-bit formats, values in [0,1] (some just past) for float formats.
Bytes pattern(VkFormat f, size_t texels, uint32_t seed) {
    Lcg g{seed};
    Bytes b(texels * texel_bytes(f));
    switch (f) {
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R16G16B16A16_SFLOAT:
            for (size_t i = 0; i + 1 < b.size(); i += 2) {
                // halves in [0, 1]: exponent 0..14 with any mantissa, or exactly 1.0
                uint16_t h = uint16_t(((g.next() >> 8) % 15) << 10 | ((g.next() >> 8) & 1023));
                std::memcpy(&b[i], &h, 2);
            }
            break;
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
        case VK_FORMAT_R32G32B32_SFLOAT:
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            for (size_t i = 0; i + 3 < b.size(); i += 4) {
                float v = g.unit() * 1.25f - 0.125f;
                std::memcpy(&b[i], &v, 4);
            }
            break;
        case VK_FORMAT_D32_SFLOAT:
            for (size_t i = 0; i + 3 < b.size(); i += 4) {
                float v = g.unit();
                std::memcpy(&b[i], &v, 4);
            }
            break;
        default:
            for (auto& x : b) x = uint8_t(g.next() >> 24);
    }
    return b;
}

struct Spec {
    std::string name;
    VkFormat src_format, dst_format;
    uint32_t sw, sh, dw, dh;
    VkFilter filter;
    std::vector<VkImageBlit> regions;
    uint32_t layers = 1, src_levels = 1, dst_levels = 1;
    bool mip_chain = false;  // blit level i-1 -> i of the source image itself (dst_* unused)
};

VkImageBlit region(int sx0, int sy0, int sx1, int sy1, int dx0, int dy0, int dx1, int dy1, VkImageAspectFlags a,
                   uint32_t src_level = 0, uint32_t dst_level = 0, uint32_t layers = 1) {
    VkImageBlit r{};
    r.srcSubresource = {a, src_level, 0, layers};
    r.dstSubresource = {a, dst_level, 0, layers};
    r.srcOffsets[0] = {sx0, sy0, 0};
    r.srcOffsets[1] = {sx1, sy1, 1};
    r.dstOffsets[0] = {dx0, dy0, 0};
    r.dstOffsets[1] = {dx1, dy1, 1};
    return r;
}

// A barrier moving `levels` levels from `base` of an image between transfer layouts.
void barrier(VkCommandBuffer cb, VkImage image, VkImageAspectFlags a, VkImageLayout from, VkImageLayout to,
             uint32_t base, uint32_t levels) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = from == VK_IMAGE_LAYOUT_UNDEFINED ? 0 : VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {a, base, levels, 0, VK_REMAINING_ARRAY_LAYERS};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         1, &b);
}

// Buffer <-> image copies of levels [first, levels) of a w x h image, all layers, packed one after another.
std::vector<VkBufferImageCopy> level_copies(VkImageAspectFlags a, uint32_t w, uint32_t h, uint32_t layers,
                                            uint32_t first, uint32_t levels, uint32_t texel) {
    std::vector<VkBufferImageCopy> cs;
    VkDeviceSize off = 0;
    for (uint32_t l = first; l < levels; ++l) {
        VkBufferImageCopy c{};
        c.bufferOffset = off;
        c.imageSubresource = {a, l, 0, layers};
        c.imageExtent = {std::max(1u, w >> l), std::max(1u, h >> l), 1};
        off += VkDeviceSize(c.imageExtent.width) * c.imageExtent.height * layers * texel;
        cs.push_back(c);
    }
    return cs;
}

size_t texel_count(uint32_t w, uint32_t h, uint32_t layers, uint32_t levels) {
    size_t n = 0;
    for (uint32_t l = 0; l < levels; ++l) n += size_t(std::max(1u, w >> l)) * std::max(1u, h >> l) * layers;
    return n;
}

// Runs one spec on a device: returns every level and layer of the destination, level-major, tightly packed.
Bytes run_spec(Device& d, const Spec& s) {
    constexpr VkImageLayout kDstL = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kSrcL = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const VkFormat df = s.mip_chain ? s.src_format : s.dst_format;
    const uint32_t sb = texel_bytes(s.src_format), db = texel_bytes(df);
    const uint32_t dst_w = s.mip_chain ? s.sw : s.dw, dst_h = s.mip_chain ? s.sh : s.dh;
    const uint32_t dst_levels = s.mip_chain ? s.src_levels : s.dst_levels;
    const VkImageAspectFlags sa = aspect(s.src_format), da = aspect(df);
    Device::Image src = d.make_image(s.src_format, s.sw, s.sh, s.src_levels, s.layers, VK_SAMPLE_COUNT_1_BIT, kXfer);
    Device::Image dst =
        s.mip_chain ? src : d.make_image(df, s.dw, s.dh, s.dst_levels, s.layers, VK_SAMPLE_COUNT_1_BIT, kXfer);
    EXPECT_NE(src.image, VK_NULL_HANDLE);
    EXPECT_NE(dst.image, VK_NULL_HANDLE);
    if (src.image == VK_NULL_HANDLE || dst.image == VK_NULL_HANDLE) return {};
    // every source level gets the source pattern (a mip chain: level 0 only), every destination level another one
    const uint32_t src_up_levels = s.mip_chain ? 1 : s.src_levels;
    const size_t src_texels = texel_count(s.sw, s.sh, s.layers, src_up_levels);
    const size_t dst_texels = texel_count(dst_w, dst_h, s.layers, dst_levels);
    Device::Buffer up = d.make_buffer(src_texels * sb), init = d.make_buffer(dst_texels * db),
                   down = d.make_buffer(dst_texels * db);
    Bytes p = pattern(s.src_format, src_texels, 12345), q = pattern(df, dst_texels, 777);
    std::memcpy(up.map, p.data(), p.size());
    std::memcpy(init.map, q.data(), q.size());
    d.run([&](VkCommandBuffer cb) {
        barrier(cb, src.image, sa, VK_IMAGE_LAYOUT_UNDEFINED, kDstL, 0, s.src_levels);
        if (!s.mip_chain) barrier(cb, dst.image, da, VK_IMAGE_LAYOUT_UNDEFINED, kDstL, 0, dst_levels);
        auto init_copies = level_copies(da, dst_w, dst_h, s.layers, 0, dst_levels, db);
        if (s.mip_chain) {  // levels 1.. start from the destination pattern, level 0 from the source pattern
            init_copies.erase(init_copies.begin());
        }
        if (!init_copies.empty())
            vkCmdCopyBufferToImage(cb, init.buffer, dst.image, kDstL, uint32_t(init_copies.size()), init_copies.data());
        auto up_copies = level_copies(sa, s.sw, s.sh, s.layers, 0, src_up_levels, sb);
        vkCmdCopyBufferToImage(cb, up.buffer, src.image, kDstL, uint32_t(up_copies.size()), up_copies.data());
        if (s.mip_chain) {
            for (uint32_t l = 1; l < s.src_levels; ++l) {
                barrier(cb, src.image, sa, kDstL, kSrcL, l - 1, 1);
                VkImageBlit r =
                    region(0, 0, int(std::max(1u, s.sw >> (l - 1))), int(std::max(1u, s.sh >> (l - 1))), 0, 0,
                           int(std::max(1u, s.sw >> l)), int(std::max(1u, s.sh >> l)), da, l - 1, l, s.layers);
                vkCmdBlitImage(cb, src.image, kSrcL, src.image, kDstL, 1, &r, s.filter);
            }
            barrier(cb, src.image, sa, kDstL, kSrcL, s.src_levels - 1, 1);
        } else {
            barrier(cb, src.image, sa, kDstL, kSrcL, 0, s.src_levels);
            vkCmdBlitImage(cb, src.image, kSrcL, dst.image, kDstL, uint32_t(s.regions.size()), s.regions.data(),
                           s.filter);
            barrier(cb, dst.image, da, kDstL, kSrcL, 0, dst_levels);
        }
        auto back = level_copies(da, dst_w, dst_h, s.layers, 0, dst_levels, db);
        vkCmdCopyImageToBuffer(cb, dst.image, kSrcL, down.buffer, uint32_t(back.size()), back.data());
    });
    Bytes out(static_cast<uint8_t*>(down.map), static_cast<uint8_t*>(down.map) + down.size);
    d.destroy(up);
    d.destroy(init);
    d.destroy(down);
    if (!s.mip_chain) d.destroy(dst);
    d.destroy(src);
    return out;
}

void PrintTo(const Spec& s, std::ostream* os) {
    *os << s.name;
}

class Blit : public TwoDriverSuite {
  protected:
};

constexpr VkFormat kRgba8 = VK_FORMAT_R8G8B8A8_UNORM, kBgra8 = VK_FORMAT_B8G8R8A8_UNORM,
                   kSrgb8 = VK_FORMAT_R8G8B8A8_SRGB, kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT,
                   kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFilter kNearest = VK_FILTER_NEAREST, kLinear = VK_FILTER_LINEAR;
constexpr VkImageAspectFlags kC = VK_IMAGE_ASPECT_COLOR_BIT, kD = VK_IMAGE_ASPECT_DEPTH_BIT;

// A whole-image blit (src w x h -> dst w x h) of one format pair.
Spec whole(std::string name, VkFormat sf, uint32_t sw, uint32_t sh, VkFormat df, uint32_t dw, uint32_t dh, VkFilter f) {
    const VkImageAspectFlags a = is_depth(sf) ? kD : kC;
    return {name, sf, df, sw, sh, dw, dh, f, {region(0, 0, int(sw), int(sh), 0, 0, int(dw), int(dh), a)}};
}

std::vector<Spec> specs() {
    std::vector<Spec> v;
    v.push_back(whole("nearest_copy", kRgba8, 32, 32, kRgba8, 32, 32, kNearest));
    v.push_back({"nearest_copy_subrect",
                 kRgba8,
                 kRgba8,
                 32,
                 32,
                 32,
                 32,
                 kNearest,
                 {region(4, 5, 20, 17, 10, 3, 26, 15, kC), region(0, 0, 3, 2, 29, 30, 32, 32, kC)}});
    v.push_back(whole("linear_unscaled", kRgba8, 32, 24, kRgba8, 32, 24, kLinear));
    v.push_back(whole("nearest_scale_up_2x", kRgba8, 16, 16, kRgba8, 32, 32, kNearest));
    v.push_back(whole("nearest_scale_up_odd", kRgba8, 13, 7, kRgba8, 40, 29, kNearest));
    v.push_back(whole("nearest_scale_down", kRgba8, 64, 64, kRgba8, 21, 19, kNearest));
    v.push_back(whole("linear_scale_up", kRgba8, 16, 16, kRgba8, 37, 41, kLinear));
    v.push_back(whole("linear_scale_down_2x", kRgba8, 64, 48, kRgba8, 32, 24, kLinear));
    v.push_back(whole("linear_scale_down_odd", kRgba8, 64, 64, kRgba8, 27, 13, kLinear));
    v.push_back({"mirror_x", kRgba8, kRgba8, 32, 32, 32, 32, kNearest, {region(0, 0, 32, 32, 32, 0, 0, 32, kC)}});
    v.push_back({"mirror_y", kRgba8, kRgba8, 32, 32, 32, 32, kNearest, {region(0, 0, 32, 32, 0, 32, 32, 0, kC)}});
    v.push_back({"mirror_src_xy", kRgba8, kRgba8, 32, 32, 32, 32, kNearest, {region(32, 32, 0, 0, 0, 0, 32, 32, kC)}});
    v.push_back(
        {"mirror_x_scaled_linear", kRgba8, kRgba8, 24, 20, 50, 33, kLinear, {region(2, 1, 22, 19, 47, 3, 1, 30, kC)}});
    v.push_back(whole("format_convert_unorm_to_float", kRgba8, 32, 32, kRgba32f, 32, 32, kNearest));
    v.push_back(whole("format_convert_unorm_to_float_linear", kRgba8, 32, 32, kRgba32f, 45, 19, kLinear));
    v.push_back(whole("format_convert_float_to_unorm", kRgba32f, 32, 32, kRgba8, 32, 32, kNearest));
    v.push_back(whole("format_convert_float_to_unorm_linear", kRgba32f, 30, 30, kRgba8, 17, 43, kLinear));
    v.push_back(whole("format_convert_rgba_to_bgra", kRgba8, 32, 32, kBgra8, 32, 32, kNearest));
    v.push_back(whole("format_convert_bgra_to_rgba_linear", kBgra8, 32, 32, kRgba8, 20, 50, kLinear));
    v.push_back(whole("bgra_linear_scale", kBgra8, 32, 32, kBgra8, 47, 13, kLinear));
    v.push_back(whole("r8_linear_scale", VK_FORMAT_R8_UNORM, 32, 16, VK_FORMAT_R8_UNORM, 50, 9, kLinear));
    v.push_back(whole("rg8_nearest_scale", VK_FORMAT_R8G8_UNORM, 32, 16, VK_FORMAT_R8G8_UNORM, 50, 9, kNearest));
    v.push_back(whole("r8_to_rgba8", VK_FORMAT_R8_UNORM, 16, 16, kRgba8, 16, 16, kNearest));
    v.push_back(whole("srgb_copy_unscaled_linear", kSrgb8, 32, 32, kSrgb8, 32, 32, kLinear));
    v.push_back(whole("srgb_nearest_scale", kSrgb8, 32, 32, kSrgb8, 45, 21, kNearest));
    v.push_back(whole("srgb_linear_scale", kSrgb8, 32, 32, kSrgb8, 45, 21, kLinear));
    v.push_back(whole("srgb_to_unorm", kSrgb8, 32, 32, kRgba8, 32, 32, kNearest));
    v.push_back(whole("unorm_to_srgb", kRgba8, 32, 32, kSrgb8, 32, 32, kNearest));
    v.push_back(whole("half_linear_scale", kRgba16f, 32, 32, kRgba16f, 45, 21, kLinear));
    v.push_back(whole("half_to_float", kRgba16f, 32, 32, kRgba32f, 32, 32, kNearest));
    v.push_back(whole("float_to_half_linear", kRgba32f, 32, 32, kRgba16f, 19, 40, kLinear));
    v.push_back(whole("r32f_linear_scale", VK_FORMAT_R32_SFLOAT, 32, 32, VK_FORMAT_R32_SFLOAT, 45, 21, kLinear));
    v.push_back(
        whole("rg32f_nearest_scale", VK_FORMAT_R32G32_SFLOAT, 32, 32, VK_FORMAT_R32G32_SFLOAT, 45, 21, kNearest));
    v.push_back(whole("rgba32f_linear_down", kRgba32f, 64, 64, kRgba32f, 32, 32, kLinear));
    {
        Spec s{"mip_levels", kRgba8, kRgba8, 64, 64, 64, 64, kLinear, {region(0, 0, 32, 32, 0, 0, 16, 16, kC, 1, 2)}};
        s.src_levels = s.dst_levels = 3;
        v.push_back(s);
    }
    {
        Spec s{
            "array_layers", kRgba8, kRgba8, 20, 20, 33, 17, kLinear, {region(0, 0, 20, 20, 0, 0, 33, 17, kC, 0, 0, 3)}};
        s.layers = 3;
        v.push_back(s);
    }
    v.push_back(whole("depth_d16_nearest_scale", VK_FORMAT_D16_UNORM, 32, 32, VK_FORMAT_D16_UNORM, 45, 21, kNearest));
    v.push_back(whole("depth_d32_nearest_scale", VK_FORMAT_D32_SFLOAT, 32, 32, VK_FORMAT_D32_SFLOAT, 45, 21, kNearest));
    v.push_back({"depth_d32_mirror",
                 VK_FORMAT_D32_SFLOAT,
                 VK_FORMAT_D32_SFLOAT,
                 32,
                 32,
                 32,
                 32,
                 kNearest,
                 {region(0, 0, 32, 32, 32, 32, 0, 0, kD)}});
    {
        Spec s = whole("mip_chain_pot", kRgba8, 64, 64, kRgba8, 0, 0, kLinear);
        s.mip_chain = true;
        s.src_levels = 7;
        v.push_back(s);
        Spec n = whole("mip_chain_npot", kRgba8, 75, 37, kRgba8, 0, 0, kLinear);
        n.mip_chain = true;
        n.src_levels = 7;
        v.push_back(n);
        Spec f = whole("mip_chain_float", kRgba32f, 40, 24, kRgba8, 0, 0, kLinear);
        f.mip_chain = true;
        f.src_levels = 5;
        v.push_back(f);
    }
    // B8G8R8A8_UNORM single-layer destinations: lavapipe's "linear" mode (one rectangle, lavapipe-rules §8); a 2-layer
    // destination is a 2D array there and takes the triangle path
    v.push_back(whole("bgra_dst_nearest_scale", kRgba8, 32, 32, kBgra8, 45, 21, kNearest));
    v.push_back(whole("bgra_dst_from_float_nearest", VK_FORMAT_R32_SFLOAT, 32, 32, kBgra8, 45, 21, kNearest));
    v.push_back(whole("bgra_to_bgra_nearest_scale", kBgra8, 32, 32, kBgra8, 45, 21, kNearest));
    v.push_back(whole("bgra_to_bgra_linear_up", kBgra8, 13, 11, kBgra8, 64, 70, kLinear));
    v.push_back(
        {"bgra_to_bgra_mirror", kBgra8, kBgra8, 32, 32, 32, 32, kNearest, {region(0, 0, 32, 32, 32, 0, 0, 32, kC)}});
    v.push_back({"bgra_to_bgra_mirror_scaled",
                 kBgra8,
                 kBgra8,
                 32,
                 32,
                 40,
                 40,
                 kNearest,
                 {region(0, 0, 32, 32, 40, 40, 0, 0, kC)}});
    v.push_back({"bgra_array_dst_nearest_scale",
                 kRgba8,
                 kBgra8,
                 32,
                 32,
                 45,
                 21,
                 kNearest,
                 {region(0, 0, 32, 32, 0, 0, 45, 21, kC, 0, 0, 2)},
                 2});
    // sub-rectangles, several regions, extreme factors
    v.push_back({"regions_scaled_offsets",
                 kRgba8,
                 kRgba8,
                 40,
                 40,
                 50,
                 50,
                 kLinear,
                 {region(3, 5, 17, 39, 1, 2, 30, 9, kC), region(20, 1, 38, 7, 49, 48, 33, 12, kC),
                  region(0, 0, 1, 1, 40, 40, 50, 50, kC)}});
    v.push_back(whole("one_texel_to_many", kRgba32f, 1, 1, kRgba32f, 64, 48, kLinear));
    v.push_back(whole("many_to_one_texel", kRgba8, 64, 48, kRgba8, 1, 1, kLinear));
    v.push_back(whole("thin_strip", kRgba16f, 100, 3, kRgba16f, 7, 90, kLinear));
    v.push_back(whole("large_linear_up", kRgba8, 300, 200, kRgba8, 1023, 517, kLinear));
    v.push_back(whole("large_nearest_down", kRgba8, 1000, 700, kRgba8, 333, 229, kNearest));
    return v;
}

// Every further colour format tilevk reports BLIT bits on (format/support.txt `@blit`), each blitted scaled NEAREST and
// LINEAR, into another format of its class, mirrored, and between a mip level and array layers of two-layer images.
struct FormatCase {
    const char* name;
    VkFormat format, partner;  // partner: a format of the same class for the converting blit
};
constexpr FormatCase kFormatCases[] = {
    {"a8b8g8r8_unorm", VK_FORMAT_A8B8G8R8_UNORM_PACK32, VK_FORMAT_R8G8B8A8_UNORM},
    {"a8b8g8r8_srgb", VK_FORMAT_A8B8G8R8_SRGB_PACK32, VK_FORMAT_R8G8B8A8_UNORM},
    {"r16_unorm", VK_FORMAT_R16_UNORM, VK_FORMAT_R8G8B8A8_UNORM},
    {"rg16_unorm", VK_FORMAT_R16G16_UNORM, VK_FORMAT_R16G16B16A16_UNORM},
    {"rgba16_unorm", VK_FORMAT_R16G16B16A16_UNORM, VK_FORMAT_R32G32B32A32_SFLOAT},
    {"r8_snorm", VK_FORMAT_R8_SNORM, VK_FORMAT_R16_SNORM},
    {"rg8_snorm", VK_FORMAT_R8G8_SNORM, VK_FORMAT_R8G8B8A8_SNORM},
    {"rgba8_snorm", VK_FORMAT_R8G8B8A8_SNORM, VK_FORMAT_R32G32B32A32_SFLOAT},
    {"bgra8_snorm", VK_FORMAT_B8G8R8A8_SNORM, VK_FORMAT_R8G8B8A8_SNORM},
    {"a8b8g8r8_snorm", VK_FORMAT_A8B8G8R8_SNORM_PACK32, VK_FORMAT_R16G16B16A16_SNORM},
    {"r16_snorm", VK_FORMAT_R16_SNORM, VK_FORMAT_R32_SFLOAT},
    {"rg16_snorm", VK_FORMAT_R16G16_SNORM, VK_FORMAT_R8G8_SNORM},
    {"rgba16_snorm", VK_FORMAT_R16G16B16A16_SNORM, VK_FORMAT_R16G16B16A16_SFLOAT},
    {"r16_sfloat", VK_FORMAT_R16_SFLOAT, VK_FORMAT_R32_SFLOAT},
    {"rg16_sfloat", VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM},
    {"bgra4_unorm", VK_FORMAT_B4G4R4A4_UNORM_PACK16, VK_FORMAT_R8G8B8A8_UNORM},
    {"a4r4g4b4_unorm", VK_FORMAT_A4R4G4B4_UNORM_PACK16, VK_FORMAT_B4G4R4A4_UNORM_PACK16},  // VK_EXT_4444_formats
    {"a4b4g4r4_unorm", VK_FORMAT_A4B4G4R4_UNORM_PACK16, VK_FORMAT_R8G8B8A8_UNORM},
    {"r5g6b5_unorm", VK_FORMAT_R5G6B5_UNORM_PACK16, VK_FORMAT_R8G8B8A8_UNORM},
    {"r5g5b5a1_unorm", VK_FORMAT_R5G5B5A1_UNORM_PACK16, VK_FORMAT_B5G5R5A1_UNORM_PACK16},
    {"b5g5r5a1_unorm", VK_FORMAT_B5G5R5A1_UNORM_PACK16, VK_FORMAT_A1R5G5B5_UNORM_PACK16},
    {"a1r5g5b5_unorm", VK_FORMAT_A1R5G5B5_UNORM_PACK16, VK_FORMAT_R8G8B8A8_UNORM},
    {"a2b10g10r10_unorm", VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_FORMAT_R16G16B16A16_UNORM},
};

// Two specs both format tables add: a mirrored region (`mirror`) and a blit from level 1 of two layers (`layers`).
void add_mirror_and_level_layers(std::vector<Spec>& v, const std::string& mirror, const std::string& layers, VkFormat f,
                                 VkFilter filter) {
    v.push_back({mirror, f, f, 24, 20, 50, 33, filter, {region(2, 1, 22, 19, 47, 3, 1, 30, kC)}});
    Spec m{layers, f, f, 40, 40, 40, 40, filter, {region(0, 0, 20, 20, 3, 2, 37, 31, kC, 1, 0, 2)}};
    m.src_levels = 2;
    m.layers = 2;
    v.push_back(m);
}

std::vector<Spec> format_specs() {
    std::vector<Spec> v;
    for (const FormatCase& c : kFormatCases) {
        const std::string n = c.name;
        v.push_back(whole(n + "_nearest_scale", c.format, 32, 32, c.format, 45, 21, kNearest));
        v.push_back(whole(n + "_linear_scale", c.format, 32, 24, c.format, 19, 41, kLinear));
        v.push_back(whole(n + "_to_partner_linear", c.format, 30, 30, c.partner, 17, 43, kLinear));
        v.push_back(whole(n + "_from_partner_nearest", c.partner, 32, 32, c.format, 32, 32, kNearest));
        add_mirror_and_level_layers(v, n + "_mirror_linear", n + "_level_layers", c.format, kLinear);
    }
    return v;
}

// The integer formats: NEAREST only (no FILTER_LINEAR), uint to uint and sint to sint (Vulkan forbids mixing), the
// partner of another width so that the store saturates or widens.
constexpr FormatCase kIntFormatCases[] = {
    {"r8_uint", VK_FORMAT_R8_UINT, VK_FORMAT_R32_UINT},
    {"rg8_uint", VK_FORMAT_R8G8_UINT, VK_FORMAT_R16G16_UINT},
    {"rgba8_uint", VK_FORMAT_R8G8B8A8_UINT, VK_FORMAT_A8B8G8R8_UINT_PACK32},
    {"bgra8_uint", VK_FORMAT_B8G8R8A8_UINT, VK_FORMAT_R8G8B8A8_UINT},
    {"a8b8g8r8_uint", VK_FORMAT_A8B8G8R8_UINT_PACK32, VK_FORMAT_R16G16B16A16_UINT},
    {"r8_sint", VK_FORMAT_R8_SINT, VK_FORMAT_R32_SINT},
    {"rg8_sint", VK_FORMAT_R8G8_SINT, VK_FORMAT_R16G16_SINT},
    {"rgba8_sint", VK_FORMAT_R8G8B8A8_SINT, VK_FORMAT_R16G16B16A16_SINT},
    {"bgra8_sint", VK_FORMAT_B8G8R8A8_SINT, VK_FORMAT_A8B8G8R8_SINT_PACK32},
    {"a8b8g8r8_sint", VK_FORMAT_A8B8G8R8_SINT_PACK32, VK_FORMAT_R8G8B8A8_SINT},
    {"r16_uint", VK_FORMAT_R16_UINT, VK_FORMAT_R8_UINT},
    {"rg16_uint", VK_FORMAT_R16G16_UINT, VK_FORMAT_R32G32_UINT},
    {"rgba16_uint", VK_FORMAT_R16G16B16A16_UINT, VK_FORMAT_A2B10G10R10_UINT_PACK32},
    {"r16_sint", VK_FORMAT_R16_SINT, VK_FORMAT_R8_SINT},
    {"rg16_sint", VK_FORMAT_R16G16_SINT, VK_FORMAT_R8G8_SINT},
    {"rgba16_sint", VK_FORMAT_R16G16B16A16_SINT, VK_FORMAT_R32G32B32A32_SINT},
    {"r32_uint", VK_FORMAT_R32_UINT, VK_FORMAT_R16_UINT},
    {"rg32_uint", VK_FORMAT_R32G32_UINT, VK_FORMAT_R8G8_UINT},
    {"rgba32_uint", VK_FORMAT_R32G32B32A32_UINT, VK_FORMAT_R16G16B16A16_UINT},
    {"r32_sint", VK_FORMAT_R32_SINT, VK_FORMAT_R16_SINT},
    {"rg32_sint", VK_FORMAT_R32G32_SINT, VK_FORMAT_R32_SINT},
    {"rgba32_sint", VK_FORMAT_R32G32B32A32_SINT, VK_FORMAT_R8G8B8A8_SINT},
    {"a2r10g10b10_uint", VK_FORMAT_A2R10G10B10_UINT_PACK32, VK_FORMAT_R8G8B8A8_UINT},
    {"a2b10g10r10_uint", VK_FORMAT_A2B10G10R10_UINT_PACK32, VK_FORMAT_A2R10G10B10_UINT_PACK32},
};

std::vector<Spec> int_specs() {
    std::vector<Spec> v;
    for (const FormatCase& c : kIntFormatCases) {
        const std::string n = c.name;
        v.push_back(whole(n + "_nearest_scale", c.format, 32, 32, c.format, 45, 21, kNearest));
        v.push_back(whole(n + "_to_partner_nearest", c.format, 30, 30, c.partner, 17, 43, kNearest));
        v.push_back(whole(n + "_from_partner_nearest", c.partner, 32, 32, c.format, 32, 32, kNearest));
        add_mirror_and_level_layers(v, n + "_mirror_nearest", n + "_level_layers", c.format, kNearest);
    }
    return v;
}

// The formats that are blit sources only (BLIT_SRC without BLIT_DST, as lavapipe reports them): sampled by the
// blitter into formats that hold their values, scaled both ways, unscaled (texel fetch) and mirrored.
std::vector<Spec> source_format_specs() {
    std::vector<Spec> v;
    const std::pair<const char*, VkFormat> formats[] = {{"b10g11r11_ufloat", VK_FORMAT_B10G11R11_UFLOAT_PACK32},
                                                        {"e5b9g9r9_ufloat", VK_FORMAT_E5B9G9R9_UFLOAT_PACK32}};
    for (const auto& [name, f] : formats) {
        const std::string n = name;
        v.push_back(whole(n + "_nearest_scale", f, 32, 32, kRgba32f, 45, 21, kNearest));
        v.push_back(whole(n + "_linear_scale", f, 32, 24, kRgba32f, 19, 41, kLinear));
        v.push_back(whole(n + "_unscaled", f, 16, 16, kRgba32f, 16, 16, kLinear));
        v.push_back(whole(n + "_to_half_linear", f, 30, 30, kRgba16f, 17, 43, kLinear));
        v.push_back({n + "_mirror_linear_to_rgba8",
                     f,
                     kRgba8,
                     24,
                     20,
                     50,
                     33,
                     kLinear,
                     {region(2, 1, 22, 19, 47, 3, 1, 30, kC)}});
    }
    return v;
}

class BlitVsLavapipe : public Blit, public ::testing::WithParamInterface<Spec> {};

TEST_P(BlitVsLavapipe, BytesEqual) {
    const Spec& s = GetParam();
    Bytes t = run_spec(*tilevk_, s), l = run_spec(*lavapipe_, s);
    ASSERT_EQ(t.size(), l.size());
    ASSERT_FALSE(t.empty());
    const uint32_t tb = texel_bytes(s.mip_chain ? s.src_format : s.dst_format);
    size_t diffs = 0, first = ~size_t(0);
    int max_byte_diff = 0;
    for (size_t i = 0; i < t.size(); i += tb) {
        if (std::memcmp(&t[i], &l[i], tb) != 0) {
            if (first == ~size_t(0)) first = i / tb;
            ++diffs;
            for (uint32_t k = 0; k < tb; ++k) max_byte_diff = std::max(max_byte_diff, std::abs(t[i + k] - l[i + k]));
        }
    }
    EXPECT_EQ(diffs, 0u) << s.name << ": " << diffs << " of " << t.size() / tb << " texels differ, first texel "
                         << first << ", max byte difference " << max_byte_diff;
}

// ---- analytic checks on tilevk alone: expectations from the source pattern, not from either driver ----------------
// 32-bit texel (x, y) of a w-wide RGBA8 image.
uint32_t texel32(const Bytes& b, uint32_t w, uint32_t x, uint32_t y) {
    uint32_t v;
    std::memcpy(&v, &b[(size_t(y) * w + x) * 4], 4);
    return v;
}

TEST_F(Blit, OneToOneEqualsCopy) {
    const Bytes src = pattern(kRgba8, 32 * 32, 12345);
    for (VkFilter f : {kNearest, kLinear}) {  // NEAREST: the copy path; LINEAR: the texel-fetch path
        Bytes out = run_spec(*tilevk_, whole("copy", kRgba8, 32, 32, kRgba8, 32, 32, f));
        EXPECT_EQ(out, src) << "filter " << int(f);
    }
    // float texels go through the fetch path unchanged as well
    const Bytes fsrc = pattern(kRgba32f, 16 * 16, 12345);
    EXPECT_EQ(run_spec(*tilevk_, whole("copyf", kRgba32f, 16, 16, kRgba32f, 16, 16, kLinear)), fsrc);
}

TEST_F(Blit, NearestUpscale2xDuplicatesTexels) {
    const Bytes src = pattern(kRgba8, 16 * 16, 12345);
    Bytes out = run_spec(*tilevk_, whole("up2", kRgba8, 16, 16, kRgba8, 32, 32, kNearest));
    ASSERT_EQ(out.size(), 32u * 32 * 4);
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x)
            ASSERT_EQ(texel32(out, 32, x, y), texel32(src, 16, x / 2, y / 2)) << x << "," << y;
}

TEST_F(Blit, NearestDownscale2xTakesOneTexelOfFour) {
    // the sample point of destination pixel x is source coordinate 2x + 1 (the centre of the 2x2 footprint): the
    // nearest texel is 2x+1 in both axes
    const Bytes src = pattern(kRgba8, 32 * 32, 12345);
    Bytes out = run_spec(*tilevk_, whole("down2", kRgba8, 32, 32, kRgba8, 16, 16, kNearest));
    ASSERT_EQ(out.size(), 16u * 16 * 4);
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x)
            ASSERT_EQ(texel32(out, 16, x, y), texel32(src, 32, 2 * x + 1, 2 * y + 1)) << x << "," << y;
}

TEST_F(Blit, MirrorFlips) {
    const Bytes src = pattern(kRgba8, 32 * 32, 12345);
    Spec mx{"mx", kRgba8, kRgba8, 32, 32, 32, 32, kNearest, {region(0, 0, 32, 32, 32, 0, 0, 32, kC)}};
    Spec my{"my", kRgba8, kRgba8, 32, 32, 32, 32, kLinear, {region(0, 0, 32, 32, 0, 32, 32, 0, kC)}};
    Bytes ox = run_spec(*tilevk_, mx), oy = run_spec(*tilevk_, my);
    ASSERT_EQ(ox.size(), src.size());
    ASSERT_EQ(oy.size(), src.size());
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            ASSERT_EQ(texel32(ox, 32, x, y), texel32(src, 32, 31 - x, y)) << x << "," << y;
            ASSERT_EQ(texel32(oy, 32, x, y), texel32(src, 32, x, 31 - y)) << x << "," << y;
        }
}

TEST_F(Blit, UnormToFloatIsByteTimesOneOver255) {
    const Bytes src = pattern(kRgba8, 8 * 8, 12345);
    Bytes out = run_spec(*tilevk_, whole("u2f", kRgba8, 8, 8, kRgba32f, 8, 8, kNearest));
    ASSERT_EQ(out.size(), src.size() * 4);
    for (size_t i = 0; i < src.size(); ++i) {
        float v;
        std::memcpy(&v, &out[i * 4], 4);
        ASSERT_EQ(v, float(src[i]) * (1.0f / 255.0f)) << i;
    }
}

TEST_F(Blit, WritesOnlyTheDestinationBox) {
    const Bytes init = pattern(kRgba8, 32 * 32, 777), src = pattern(kRgba8, 32 * 32, 12345);
    Spec s{"box", kRgba8, kRgba8, 32, 32, 32, 32, kLinear, {region(3, 4, 20, 30, 5, 6, 17, 11, kC)}};
    Bytes out = run_spec(*tilevk_, s);
    ASSERT_EQ(out.size(), init.size());
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const bool inside = x >= 5 && x < 17 && y >= 6 && y < 11;
            if (!inside) {
                ASSERT_EQ(texel32(out, 32, x, y), texel32(init, 32, x, y)) << x << "," << y;
            }
        }
}

// ---- 3D images (tilevk alone; the bytes against lavapipe: cts blit.3d.*) -------------------------------------------
// One blit of `r` from a w x h x sd image to a w x h x dd one (depth 0: a 2D image), RGBA8 formats of one texel
// size; the source holds pattern 12345, the destination pattern 777 before. Returns every destination slice.
Bytes run_3d(Device& d, VkFormat sf, VkFormat df, uint32_t w, uint32_t h, uint32_t sd, uint32_t dd,
             const VkImageBlit& r, VkFilter filter) {
    constexpr VkImageLayout kDstL = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kSrcL = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    auto info = [&](VkFormat f, uint32_t depth) {
        VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ci.imageType = depth ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
        ci.format = f;
        ci.extent = {w, h, std::max(depth, 1u)};
        ci.mipLevels = ci.arrayLayers = 1;
        ci.samples = VK_SAMPLE_COUNT_1_BIT;
        ci.usage = kXfer;
        return ci;
    };
    Device::Image src = d.make_image(info(sf, sd)), dst = d.make_image(info(df, dd));
    if (src.image == VK_NULL_HANDLE || dst.image == VK_NULL_HANDLE) return {};
    const size_t sn = size_t(w) * h * std::max(sd, 1u), dn = size_t(w) * h * std::max(dd, 1u);
    Device::Buffer up = d.make_buffer(sn * 4), down = d.make_buffer(dn * 4), init = d.make_buffer(dn * 4);
    const Bytes p = pattern(sf, sn, 12345), q = pattern(df, dn, 777);
    std::memcpy(up.map, p.data(), p.size());
    std::memcpy(init.map, q.data(), q.size());
    d.run([&](VkCommandBuffer cb) {
        barrier(cb, src.image, kC, VK_IMAGE_LAYOUT_UNDEFINED, kDstL, 0, 1);
        barrier(cb, dst.image, kC, VK_IMAGE_LAYOUT_UNDEFINED, kDstL, 0, 1);
        VkBufferImageCopy c{};
        c.imageSubresource = {kC, 0, 0, 1};
        c.imageExtent = {w, h, std::max(sd, 1u)};
        vkCmdCopyBufferToImage(cb, up.buffer, src.image, kDstL, 1, &c);
        c.imageExtent.depth = std::max(dd, 1u);
        vkCmdCopyBufferToImage(cb, init.buffer, dst.image, kDstL, 1, &c);
        barrier(cb, src.image, kC, kDstL, kSrcL, 0, 1);
        barrier(cb, dst.image, kC, kDstL, kDstL, 0, 1);
        vkCmdBlitImage(cb, src.image, kSrcL, dst.image, kDstL, 1, &r, filter);
        barrier(cb, dst.image, kC, kDstL, kSrcL, 0, 1);
        vkCmdCopyImageToBuffer(cb, dst.image, kSrcL, down.buffer, 1, &c);
    });
    Bytes out(static_cast<uint8_t*>(down.map), static_cast<uint8_t*>(down.map) + dn * 4);
    for (Device::Buffer* b : {&up, &down, &init}) d.destroy(*b);
    d.destroy(src);
    d.destroy(dst);
    return out;
}

VkImageBlit region_z(uint32_t w, uint32_t h, int sz0, int sz1, int dz0, int dz1) {
    VkImageBlit r = region(0, 0, int(w), int(h), 0, 0, int(w), int(h), kC);
    r.srcOffsets[0].z = sz0, r.srcOffsets[1].z = sz1, r.dstOffsets[0].z = dz0, r.dstOffsets[1].z = dz1;
    return r;
}

// The spec's NEAREST rule on the z axis (x and y unscaled): destination slice z reads source slice
// floor(z0 + (z + 0.5) * (z1 - z0) / depth). The depths are chosen so that no sample lands within 1/(2 depth) of a
// slice boundary: (2z + 1) * S / (2 D) is never an integer for S = 2 mod 4 and D even.
TEST_F(Blit, NearestSliceOfAScaledOrFlippedZIsTheSpecsFloor) {
    const uint32_t w = 5, h = 3;
    struct Z {
        int s, d;
        bool flip;
    };
    for (const Z z : {Z{6, 16, false}, Z{10, 4, false}, Z{14, 6, true}, Z{6, 10, true}, Z{2, 8, true}}) {
        const int z0 = z.flip ? z.s : 0, z1 = z.flip ? 0 : z.s;
        const Bytes src = pattern(kRgba8, size_t(w) * h * z.s, 12345);
        const Bytes out = run_3d(*tilevk_, kRgba8, kRgba8, w, h, z.s, z.d, region_z(w, h, z0, z1, 0, z.d), kNearest);
        ASSERT_EQ(out.size(), size_t(w) * h * z.d * 4);
        for (int dz = 0; dz < z.d; ++dz) {
            const int want = int(std::floor(z0 + (dz + 0.5) * (z1 - z0) / z.d));
            for (uint32_t i = 0; i < w * h; ++i)
                ASSERT_EQ(texel32(out, w, i % w, dz * h + i / w), texel32(src, w, i % w, want * h + i / w))
                    << z.s << " -> " << z.d << (z.flip ? " flipped" : "") << ", slice " << dz << ", texel " << i;
        }
    }
}

// Invalid usage and the case lavapipe gets wrong: logged with the VUID or the reason, the region skipped (the
// destination keeps its texels). No validation layer: these blits are refused on purpose.
TEST(BlitRefusals, IntegerAgainstNonIntegerAnd2DIntoLaterSlices) {
    Harness h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    Device d(pd);
    ASSERT_TRUE(d.ok());
    struct Refusal {
        VkFormat sf, df;
        uint32_t sd, dd;
        VkImageBlit r;
        const char* says;
    };
    const Refusal cases[] = {
        {VK_FORMAT_R8G8B8A8_UINT, kRgba8, 0, 0, region_z(4, 4, 0, 1, 0, 1), "VUID-vkCmdBlitImage-srcImage-00230"},
        {kRgba8, VK_FORMAT_R8G8B8A8_UINT, 0, 0, region_z(4, 4, 0, 1, 0, 1), "VUID-vkCmdBlitImage-srcImage-00230"},
        {VK_FORMAT_R8G8B8A8_SINT, kRgba8, 0, 0, region_z(4, 4, 0, 1, 0, 1), "VUID-vkCmdBlitImage-srcImage-00229"},
        {VK_FORMAT_R8G8B8A8_SINT, VK_FORMAT_R8G8B8A8_UINT, 0, 0, region_z(4, 4, 0, 1, 0, 1),
         "VUID-vkCmdBlitImage-srcImage-00229"},
        {kRgba8, kRgba8, 0, 4, region_z(4, 4, 0, 1, 2, 3), "writes slice 0 instead"},
    };
    for (const Refusal& c : cases) {
        testing::internal::CaptureStderr();
        const Bytes out = run_3d(d, c.sf, c.df, 4, 4, c.sd, c.dd, c.r, kNearest);
        EXPECT_NE(testing::internal::GetCapturedStderr().find(c.says), std::string::npos) << c.says;
        EXPECT_EQ(out, pattern(c.df, size_t(16) * std::max(c.dd, 1u), 777)) << c.says;
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, BlitVsLavapipe, ::testing::ValuesIn(specs()),
                         [](const ::testing::TestParamInfo<Spec>& i) { return i.param.name; });
INSTANTIATE_TEST_SUITE_P(Formats, BlitVsLavapipe, ::testing::ValuesIn(format_specs()),
                         [](const ::testing::TestParamInfo<Spec>& i) { return i.param.name; });
INSTANTIATE_TEST_SUITE_P(SourceFormats, BlitVsLavapipe, ::testing::ValuesIn(source_format_specs()),
                         [](const ::testing::TestParamInfo<Spec>& i) { return i.param.name; });
INSTANTIATE_TEST_SUITE_P(IntFormats, BlitVsLavapipe, ::testing::ValuesIn(int_specs()),
                         [](const ::testing::TestParamInfo<Spec>& i) { return i.param.name; });

}  // namespace
