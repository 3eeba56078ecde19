// blit.*: vkCmdBlitImage cases. Each fills a source image (every level and layer) with deterministic texels, clears
// nothing but uploads another pattern into the destination, blits, and reads every destination level back as one
// plane ("color" / "depth" for level 0, "<name>.levelN" after it); judged byte for byte against the reference.
#include <array>
#include <cstring>
#include <memory>

#include "case.hpp"
#include "vk_context.hpp"
#include "vk_names.hpp"

namespace tilevk::cts {
namespace {

struct BlitSpec {
    VkFormat src_format, dst_format;
    uint32_t sw, sh, dw, dh;
    VkFilter filter;
    std::vector<VkImageBlit> regions;
    uint32_t layers = 1, src_levels = 1, dst_levels = 1;
    bool mip_chain = false;  // blit level i-1 -> i of the source itself, LINEAR (glGenerateMipmap style)
    uint32_t sd = 0, dd = 0;  // the depth of a VK_IMAGE_TYPE_3D source / destination; 0: a 2D image
};

uint32_t texel_bytes(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R8_UNORM:
        case VK_FORMAT_R8_SNORM:
            return 1;
        case VK_FORMAT_R8G8_UNORM:
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_R16_UNORM:
        case VK_FORMAT_R16_UINT:
        case VK_FORMAT_R5G6B5_UNORM_PACK16:
        case VK_FORMAT_A1R5G5B5_UNORM_PACK16:
        case VK_FORMAT_A4R4G4B4_UNORM_PACK16:
        case VK_FORMAT_A4B4G4R4_UNORM_PACK16:
            return 2;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R16G16B16A16_SNORM:
        case VK_FORMAT_R16G16B16A16_UNORM:
        case VK_FORMAT_R16G16B16A16_SINT:
        case VK_FORMAT_R32G32_SFLOAT:
            return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return 16;
        default:
            return 4;
    }
}
bool is_depth(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D32_SFLOAT;
}
VkImageAspectFlags aspect_of(VkFormat f) {
    return is_depth(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}
uint32_t minify(uint32_t v, uint32_t l) {
    return std::max(1u, v >> l);
}

// Random bytes for 8-bit formats; halves/floats in about [0, 1] for float formats; depth in [0, 1].
std::vector<uint8_t> pattern(VkFormat f, size_t texels, uint32_t seed) {
    Lcg g{seed};
    std::vector<uint8_t> b(texels * texel_bytes(f));
    if (f == VK_FORMAT_R16G16B16A16_SFLOAT) {
        for (size_t i = 0; i + 1 < b.size(); i += 2) {
            uint16_t h = uint16_t(uint32_t(g.next() * 15.0f) << 10 | uint32_t(g.next() * 1024.0f));
            std::memcpy(&b[i], &h, 2);
        }
    } else if (f == VK_FORMAT_R32_SFLOAT || f == VK_FORMAT_R32G32_SFLOAT || f == VK_FORMAT_R32G32B32A32_SFLOAT ||
               f == VK_FORMAT_D32_SFLOAT) {
        for (size_t i = 0; i + 3 < b.size(); i += 4) {
            float v = g.next();
            std::memcpy(&b[i], &v, 4);
        }
    } else {
        for (auto& x : b) x = uint8_t(g.next() * 256.0f);
    }
    return b;
}

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

// A region of 3D boxes: corners (x, y, z) in either order (the order flips); a 2D side gives z 0 and 1.
VkImageBlit region3d(std::array<int, 3> s0, std::array<int, 3> s1, std::array<int, 3> d0, std::array<int, 3> d1,
                     uint32_t src_level = 0, VkImageAspectFlags a = VK_IMAGE_ASPECT_COLOR_BIT) {
    VkImageBlit r{};
    r.srcSubresource = {a, src_level, 0, 1};
    r.dstSubresource = {a, 0, 0, 1};
    r.srcOffsets[0] = {s0[0], s0[1], s0[2]};
    r.srcOffsets[1] = {s1[0], s1[1], s1[2]};
    r.dstOffsets[0] = {d0[0], d0[1], d0[2]};
    r.dstOffsets[1] = {d1[0], d1[1], d1[2]};
    return r;
}

// Objects destroyed in reverse order of creation, after the queue is idle.
struct Objects {
    const DeviceContext& c;
    std::vector<std::function<void()>> undo;
    ~Objects() {
        vkQueueWaitIdle(c.queue);
        for (auto it = undo.rbegin(); it != undo.rend(); ++it) (*it)();
    }
    VkImage image(VkFormat f, uint32_t w, uint32_t h, uint32_t levels, uint32_t layers, uint32_t depth) {
        VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ci.imageType = depth ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
        ci.format = f;
        ci.extent = {w, h, depth ? depth : 1};
        ci.mipLevels = levels;
        ci.arrayLayers = layers;
        ci.samples = VK_SAMPLE_COUNT_1_BIT;
        ci.tiling = VK_IMAGE_TILING_OPTIMAL;
        ci.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        VkImage img;
        vk_check(vkCreateImage(c.device, &ci, nullptr, &img), "vkCreateImage");
        VkDevice dev = c.device;
        undo.push_back([dev, img] { vkDestroyImage(dev, img, nullptr); });
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(c.device, img, &req);
        vk_check(vkBindImageMemory(c.device, img, memory(req, 0, nullptr), 0), "vkBindImageMemory");
        return img;
    }
    VkBuffer buffer(VkDeviceSize size, void** map) {
        VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        ci.size = size;
        ci.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        VkBuffer b;
        vk_check(vkCreateBuffer(c.device, &ci, nullptr, &b), "vkCreateBuffer");
        VkDevice dev = c.device;
        undo.push_back([dev, b] { vkDestroyBuffer(dev, b, nullptr); });
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(c.device, b, &req);
        vk_check(vkBindBufferMemory(
                     c.device, b,
                     memory(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, map), 0),
                 "vkBindBufferMemory");
        return b;
    }
    VkDeviceMemory memory(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags, void** map) {
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = c.memory_type(req.memoryTypeBits, flags);
        VkDeviceMemory m;
        vk_check(vkAllocateMemory(c.device, &ai, nullptr, &m), "vkAllocateMemory");
        VkDevice dev = c.device;
        undo.push_back([dev, m] { vkFreeMemory(dev, m, nullptr); });
        if (map) vk_check(vkMapMemory(c.device, m, 0, VK_WHOLE_SIZE, 0, map), "vkMapMemory");
        return m;
    }
};

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

// Copies of levels [first, levels) of a w x h image (all layers; a 3D image's slices when depth > 0) packed one
// after another in a buffer.
std::vector<VkBufferImageCopy> level_copies(VkImageAspectFlags a, uint32_t w, uint32_t h, uint32_t layers,
                                            uint32_t first, uint32_t levels, uint32_t texel, uint32_t depth) {
    std::vector<VkBufferImageCopy> cs;
    VkDeviceSize off = 0;
    for (uint32_t l = 0; l < levels; ++l) {
        VkBufferImageCopy c{};
        c.bufferOffset = off;
        c.imageSubresource = {a, l, 0, layers};
        c.imageExtent = {minify(w, l), minify(h, l), depth ? minify(depth, l) : 1};
        off += VkDeviceSize(c.imageExtent.width) * c.imageExtent.height * c.imageExtent.depth * layers * texel;
        if (l >= first) cs.push_back(c);
    }
    return cs;
}

std::vector<Plane> run_blit(const DeviceContext& c, const BlitSpec& s) {
    constexpr VkImageLayout kDstL = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kSrcL = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const VkFormat df = s.mip_chain ? s.src_format : s.dst_format;
    const uint32_t sb = texel_bytes(s.src_format), db = texel_bytes(df);
    const uint32_t dw = s.mip_chain ? s.sw : s.dw, dh = s.mip_chain ? s.sh : s.dh;
    const uint32_t dst_levels = s.mip_chain ? s.src_levels : s.dst_levels;
    const uint32_t src_up_levels = s.mip_chain ? 1 : s.src_levels;
    const VkImageAspectFlags sa = aspect_of(s.src_format), da = aspect_of(df);
    Objects o{c, {}};
    const uint32_t dd = s.mip_chain ? s.sd : s.dd;
    VkImage src = o.image(s.src_format, s.sw, s.sh, s.src_levels, s.layers, s.sd);
    VkImage dst = s.mip_chain ? src : o.image(df, s.dw, s.dh, s.dst_levels, s.layers, s.dd);
    auto up_copies = level_copies(sa, s.sw, s.sh, s.layers, 0, src_up_levels, sb, s.sd);
    auto all_dst = level_copies(da, dw, dh, s.layers, 0, dst_levels, db, dd);
    auto init_copies = level_copies(da, dw, dh, s.layers, s.mip_chain ? 1 : 0, dst_levels, db, dd);
    auto end_of = [&s](const VkBufferImageCopy& c, uint32_t texel) {
        return c.bufferOffset +
               VkDeviceSize(c.imageExtent.width) * c.imageExtent.height * c.imageExtent.depth * s.layers * texel;
    };
    const VkDeviceSize src_bytes = end_of(up_copies.back(), sb), dst_bytes = end_of(all_dst.back(), db);
    void *up_map, *init_map, *down_map;
    VkBuffer up = o.buffer(src_bytes, &up_map), init = o.buffer(dst_bytes, &init_map),
             down = o.buffer(dst_bytes, &down_map);
    std::vector<uint8_t> p = pattern(s.src_format, src_bytes / sb, 12345), q = pattern(df, dst_bytes / db, 777);
    std::memcpy(up_map, p.data(), p.size());
    std::memcpy(init_map, q.data(), q.size());

    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = c.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb;
    vk_check(vkAllocateCommandBuffers(c.device, &ai, &cb), "vkAllocateCommandBuffers");
    VkDevice dev = c.device;
    VkCommandPool pool = c.pool;
    o.undo.push_back([dev, pool, cb] { vkFreeCommandBuffers(dev, pool, 1, &cb); });
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vk_check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
    barrier(cb, src, sa, VK_IMAGE_LAYOUT_UNDEFINED, kDstL, 0, s.src_levels);
    if (!s.mip_chain) barrier(cb, dst, da, VK_IMAGE_LAYOUT_UNDEFINED, kDstL, 0, dst_levels);
    if (!init_copies.empty())
        vkCmdCopyBufferToImage(cb, init, dst, kDstL, uint32_t(init_copies.size()), init_copies.data());
    vkCmdCopyBufferToImage(cb, up, src, kDstL, uint32_t(up_copies.size()), up_copies.data());
    // The blit overwrites texels the copies above just wrote: order the two writes (write-after-write).
    barrier(cb, dst, da, kDstL, kDstL, 0, dst_levels);
    if (s.mip_chain) {
        for (uint32_t l = 1; l < s.src_levels; ++l) {
            barrier(cb, src, sa, kDstL, kSrcL, l - 1, 1);
            VkImageBlit r = region(0, 0, int(minify(s.sw, l - 1)), int(minify(s.sh, l - 1)), 0, 0, int(minify(s.sw, l)),
                                   int(minify(s.sh, l)), da, l - 1, l, s.layers);
            vkCmdBlitImage(cb, src, kSrcL, src, kDstL, 1, &r, s.filter);
        }
        barrier(cb, src, sa, kDstL, kSrcL, s.src_levels - 1, 1);
    } else {
        barrier(cb, src, sa, kDstL, kSrcL, 0, s.src_levels);
        vkCmdBlitImage(cb, src, kSrcL, dst, kDstL, uint32_t(s.regions.size()), s.regions.data(), s.filter);
        barrier(cb, dst, da, kDstL, kSrcL, 0, dst_levels);
    }
    vkCmdCopyImageToBuffer(cb, dst, kSrcL, down, uint32_t(all_dst.size()), all_dst.data());
    vk_check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    vk_check(vkCreateFence(c.device, &fi, nullptr, &fence), "vkCreateFence");
    o.undo.push_back([dev, fence] { vkDestroyFence(dev, fence, nullptr); });
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    vk_check(vkQueueSubmit(c.queue, 1, &si, fence), "vkQueueSubmit");
    vk_check(vkWaitForFences(c.device, 1, &fence, VK_TRUE, 60ull * 1000 * 1000 * 1000), "vkWaitForFences");

    std::vector<Plane> planes;
    const uint8_t* bytes = static_cast<const uint8_t*>(down_map);
    for (uint32_t l = 0; l < dst_levels; ++l) {
        const VkBufferImageCopy& r = all_dst[l];
        Plane pl;
        pl.name = std::string(is_depth(df) ? "depth" : "color") + (l ? ".level" + std::to_string(l) : "");
        pl.format = df;
        pl.width = r.imageExtent.width;
        pl.height = r.imageExtent.height * s.layers * r.imageExtent.depth;  // layers (slices) stacked vertically
        pl.texel_bytes = db;
        pl.data.assign(bytes + r.bufferOffset, bytes + r.bufferOffset + size_t(pl.width) * pl.height * db);
        planes.push_back(std::move(pl));
    }
    return planes;
}

std::string blit_unsupported(const DeviceContext& c, const BlitSpec& s) {
    auto need = [&](VkFormat f, VkFormatFeatureFlags bits) -> std::string {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(c.physical, f, &fp);
        if ((fp.optimalTilingFeatures & bits) != bits)
            return std::string("format ") + format_name(f) + " lacks " +
                   format_features_name(bits & ~fp.optimalTilingFeatures);
        return {};
    };
    VkFormatFeatureFlags src_bits =
        VK_FORMAT_FEATURE_BLIT_SRC_BIT |
        (s.filter == VK_FILTER_LINEAR ? VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT : 0);
    if (s.mip_chain) src_bits |= VK_FORMAT_FEATURE_BLIT_DST_BIT;
    if (auto e = need(s.src_format, src_bits); !e.empty()) return e;
    auto need_3d = [&](VkFormat f, uint32_t depth) -> std::string {
        VkImageFormatProperties p;
        if (depth && vkGetPhysicalDeviceImageFormatProperties(
                         c.physical, f, VK_IMAGE_TYPE_3D, VK_IMAGE_TILING_OPTIMAL,
                         VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0, &p) != VK_SUCCESS)
            return std::string("format ") + format_name(f) + " has no VK_IMAGE_TYPE_3D images";
        return {};
    };
    if (auto e = need_3d(s.src_format, s.sd); !e.empty()) return e;
    if (auto e = need_3d(s.dst_format, s.dd); !e.empty()) return e;
    if (!s.mip_chain) {
        if (auto e = need(s.dst_format, VK_FORMAT_FEATURE_BLIT_DST_BIT); !e.empty()) return e;
    }
    return {};
}

void add(CaseList& out, const std::string& name, BlitSpec s, std::string note = {}) {
    auto spec = std::make_shared<BlitSpec>(std::move(s));
    Case c;
    c.name = "blit." + name;
    c.scene = [spec] {
        Scene sc;
        sc.run = [spec](const DeviceContext& ctx) { return run_blit(ctx, *spec); };
        sc.unsupported = [spec](const DeviceContext& ctx) { return blit_unsupported(ctx, *spec); };
        return sc;
    };
    c.note = std::move(note);
    out.push_back(std::move(c));
}

constexpr VkFormat kRgba8 = VK_FORMAT_R8G8B8A8_UNORM, kBgra8 = VK_FORMAT_B8G8R8A8_UNORM,
                   kSrgb8 = VK_FORMAT_R8G8B8A8_SRGB, kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT,
                   kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFilter kNearest = VK_FILTER_NEAREST, kLinear = VK_FILTER_LINEAR;
constexpr VkImageAspectFlags kC = VK_IMAGE_ASPECT_COLOR_BIT, kD = VK_IMAGE_ASPECT_DEPTH_BIT;

BlitSpec whole(VkFormat sf, uint32_t sw, uint32_t sh, VkFormat df, uint32_t dw, uint32_t dh, VkFilter f) {
    const VkImageAspectFlags a = is_depth(sf) ? kD : kC;
    return {sf, df, sw, sh, dw, dh, f, {region(0, 0, int(sw), int(sh), 0, 0, int(dw), int(dh), a)}};
}

// blit.3d.*: VK_IMAGE_TYPE_3D sources (u_blitter.c do_blits: one quad per destination slice, the source z
// centred and normalized by the depth, LINEAR through the 3D sampler; docs/lavapipe-rules.md §11).
BlitSpec box3d(VkFormat sf, std::array<uint32_t, 3> s, VkFormat df, std::array<uint32_t, 3> d, VkFilter f) {
    const std::array<int, 3> s1{int(s[0]), int(s[1]), int(s[2])}, d1{int(d[0]), int(d[1]), int(d[2])};
    BlitSpec b{sf, df, s[0], s[1], d[0], d[1], f, {region3d({0, 0, 0}, s1, {0, 0, 0}, d1, 0, aspect_of(sf))}};
    b.sd = s[2], b.dd = d[2];
    return b;
}

void add_blit_3d_cases(CaseList& out) {
    add(out, "3d.nearest_copy", box3d(kRgba8, {16, 16, 8}, kRgba8, {16, 16, 8}, kNearest));
    add(out, "3d.nearest_unscaled_to_float", box3d(kRgba8, {16, 12, 6}, kRgba32f, {16, 12, 6}, kNearest));
    add(out, "3d.linear_unscaled", box3d(kRgba8, {16, 12, 6}, kRgba8, {16, 12, 6}, kLinear));
    add(out, "3d.nearest_scale_z_up", box3d(kRgba8, {8, 8, 4}, kRgba8, {8, 8, 11}, kNearest));
    add(out, "3d.nearest_scale_z_down", box3d(kRgba8, {16, 16, 12}, kRgba8, {16, 16, 5}, kNearest));
    add(out, "3d.linear_scale_z_up", box3d(kRgba8, {8, 8, 4}, kRgba8, {8, 8, 11}, kLinear));
    add(out, "3d.linear_scale_up", box3d(kRgba8, {8, 8, 4}, kRgba8, {19, 13, 9}, kLinear));
    add(out, "3d.linear_scale_down", box3d(kRgba8, {16, 12, 10}, kRgba8, {7, 9, 3}, kLinear));
    add(out, "3d.nearest_scale_xyz", box3d(kRgba8, {13, 7, 5}, kRgba8, {21, 17, 9}, kNearest));
    add(out, "3d.half_linear_scale", box3d(kRgba16f, {12, 10, 6}, kRgba16f, {17, 7, 13}, kLinear));
    add(out, "3d.r32f_linear_scale_down",
        box3d(VK_FORMAT_R32_SFLOAT, {12, 10, 9}, VK_FORMAT_R32_SFLOAT, {7, 13, 4}, kLinear));
    add(out, "3d.rgba16_unorm_linear_to_half",
        box3d(VK_FORMAT_R16G16B16A16_UNORM, {10, 10, 7}, kRgba16f, {13, 9, 10}, kLinear));
    add(out, "3d.r16_uint_nearest_scale",
        box3d(VK_FORMAT_R16_UINT, {12, 10, 6}, VK_FORMAT_R16_UINT, {7, 13, 10}, kNearest));
    // a 3D B8G8R8A8_UNORM destination (a PIPE_TEXTURE_3D target: not llvmpipe's linear mode)
    add(out, "3d.bgra_dst_nearest_scale", box3d(kRgba8, {32, 32, 2}, kBgra8, {45, 21, 3}, kNearest));
    add(out, "3d.depth_d16_nearest_scale",
        box3d(VK_FORMAT_D16_UNORM, {12, 10, 6}, VK_FORMAT_D16_UNORM, {17, 7, 9}, kNearest));
    {
        BlitSpec d = box3d(VK_FORMAT_D32_SFLOAT, {12, 10, 6}, VK_FORMAT_D32_SFLOAT, {12, 10, 6}, kNearest);
        d.regions = {region3d({0, 0, 6}, {12, 10, 0}, {0, 0, 0}, {12, 10, 6}, 0, kD)};
        add(out, "3d.depth_d32_flip_z", d);
    }
    add(out, "3d.srgb_linear_scale", box3d(kSrgb8, {12, 10, 6}, kSrgb8, {17, 7, 4}, kLinear));
    {
        BlitSpec f = box3d(kRgba8, {12, 10, 8}, kRgba8, {12, 10, 8}, kNearest);
        f.regions = {region3d({0, 0, 8}, {12, 10, 0}, {0, 0, 0}, {12, 10, 8})};
        add(out, "3d.flip_z_nearest", f);
        BlitSpec g = box3d(kRgba8, {12, 10, 8}, kRgba8, {15, 11, 11}, kLinear);
        g.regions = {region3d({1, 0, 7}, {11, 10, 1}, {15, 0, 1}, {0, 11, 10})};
        add(out, "3d.flip_xz_linear_scaled", g);
        BlitSpec h = box3d(kRgba16f, {12, 10, 8}, kRgba16f, {12, 10, 8}, kNearest);
        h.regions = {region3d({0, 0, 0}, {12, 10, 8}, {0, 0, 7}, {12, 10, 1})};
        add(out, "3d.flip_z_scaled_half", h);
        BlitSpec m = box3d(kRgba8, {16, 16, 8}, kRgba8, {20, 20, 9}, kLinear);
        m.src_levels = 2;
        m.regions = {region3d({1, 1, 1}, {7, 8, 4}, {3, 2, 2}, {18, 19, 8}, 1),
                     region3d({0, 0, 0}, {16, 16, 8}, {0, 0, 0}, {2, 2, 1})};
        add(out, "3d.mip_level_sub_boxes", m);
        BlitSpec t = box3d(kRgba8, {12, 10, 8}, kRgba8, {15, 13, 0}, kLinear);
        t.regions = {region3d({0, 0, 2}, {12, 10, 7}, {0, 0, 0}, {15, 13, 1})};
        add(out, "3d.to_2d_linear", t);
        BlitSpec u = box3d(kRgba8, {12, 10, 8}, kRgba32f, {12, 10, 0}, kNearest);
        u.regions = {region3d({0, 0, 5}, {12, 10, 6}, {0, 0, 0}, {12, 10, 1})};
        add(out, "3d.slice_to_2d_nearest", u);
        BlitSpec v = box3d(kRgba8, {12, 10, 0}, kRgba8, {15, 13, 4}, kLinear);
        v.regions = {region3d({0, 0, 0}, {12, 10, 1}, {0, 0, 0}, {15, 13, 1})};
        add(out, "3d.from_2d_to_slice_0", v);
    }
}

BlitSpec chain(VkFormat f, uint32_t w, uint32_t h, uint32_t levels) {
    BlitSpec s = whole(f, w, h, f, w, h, kLinear);
    s.regions.clear();
    s.mip_chain = true;
    s.src_levels = levels;
    return s;
}

}  // namespace

void add_blit_cases(CaseList& out) {
    add(out, "nearest_copy", whole(kRgba8, 64, 64, kRgba8, 64, 64, kNearest));
    add(out, "linear_unscaled", whole(kRgba8, 64, 48, kRgba8, 64, 48, kLinear));
    add(out, "nearest_scale_up", whole(kRgba8, 16, 16, kRgba8, 64, 64, kNearest));
    add(out, "nearest_scale_up_odd", whole(kRgba8, 13, 7, kRgba8, 61, 45, kNearest));
    add(out, "nearest_scale_down", whole(kRgba8, 64, 64, kRgba8, 21, 19, kNearest));
    add(out, "linear_scale_up", whole(kRgba8, 16, 16, kRgba8, 57, 41, kLinear));
    add(out, "linear_scale_down", whole(kRgba8, 64, 64, kRgba8, 27, 13, kLinear));
    add(out, "mirror_x", {kRgba8, kRgba8, 48, 32, 48, 32, kNearest, {region(0, 0, 48, 32, 48, 0, 0, 32, kC)}});
    add(out, "mirror_y", {kRgba8, kRgba8, 48, 32, 48, 32, kNearest, {region(0, 0, 48, 32, 0, 32, 48, 0, kC)}});
    add(out, "mirror_xy_linear_scaled",
        {kRgba8, kRgba8, 24, 20, 50, 33, kLinear, {region(2, 1, 22, 19, 47, 30, 1, 3, kC)}});
    add(out, "format_convert_unorm_to_float", whole(kRgba8, 32, 32, kRgba32f, 32, 32, kNearest));
    add(out, "format_convert_unorm_to_float_linear", whole(kRgba8, 32, 32, kRgba32f, 45, 19, kLinear));
    add(out, "format_convert_float_to_unorm_linear", whole(kRgba32f, 30, 30, kRgba8, 17, 43, kLinear));
    add(out, "format_convert_unorm_to_half", whole(kRgba8, 32, 32, kRgba16f, 40, 40, kLinear));
    add(out, "format_convert_r8_to_rgba8", whole(VK_FORMAT_R8_UNORM, 32, 32, kRgba8, 32, 32, kNearest));
    add(out, "srgb", whole(kSrgb8, 32, 32, kSrgb8, 45, 21, kNearest));
    add(out, "srgb_linear_scale", whole(kSrgb8, 32, 32, kSrgb8, 45, 21, kLinear));
    add(out, "srgb_to_unorm", whole(kSrgb8, 32, 32, kRgba8, 32, 32, kNearest));
    add(out, "unorm_to_srgb", whole(kRgba8, 32, 32, kSrgb8, 32, 32, kNearest));
    add(out, "half_linear_scale", whole(kRgba16f, 32, 32, kRgba16f, 45, 21, kLinear));
    add(out, "r32f_linear_scale", whole(VK_FORMAT_R32_SFLOAT, 32, 32, VK_FORMAT_R32_SFLOAT, 45, 21, kLinear));
    add(out, "rg8_linear_scale", whole(VK_FORMAT_R8G8_UNORM, 32, 16, VK_FORMAT_R8G8_UNORM, 50, 9, kLinear));
    add(out, "bgra_src_linear_scale", whole(kBgra8, 32, 32, kRgba8, 47, 13, kLinear));
    // a sample of the further formats (tests/icd/blit_test.cpp Formats/* blits each of them)
    add(out, "r16_unorm_linear_scale", whole(VK_FORMAT_R16_UNORM, 32, 32, VK_FORMAT_R16_UNORM, 45, 21, kLinear));
    add(out, "r8_snorm_linear_scale", whole(VK_FORMAT_R8_SNORM, 32, 32, VK_FORMAT_R8_SNORM, 19, 41, kLinear));
    add(out, "rgba16_snorm_to_float", whole(VK_FORMAT_R16G16B16A16_SNORM, 30, 30, kRgba32f, 17, 43, kLinear));
    add(out, "r5g6b5_linear_scale",
        whole(VK_FORMAT_R5G6B5_UNORM_PACK16, 32, 32, VK_FORMAT_R5G6B5_UNORM_PACK16, 45, 21, kLinear));
    add(out, "a1r5g5b5_from_rgba8", whole(kRgba8, 32, 32, VK_FORMAT_A1R5G5B5_UNORM_PACK16, 40, 40, kNearest));
    add(out, "a4r4g4b4_linear_scale",
        whole(VK_FORMAT_A4R4G4B4_UNORM_PACK16, 32, 32, VK_FORMAT_A4R4G4B4_UNORM_PACK16, 45, 21, kLinear));
    add(out, "a4b4g4r4_from_rgba8", whole(kRgba8, 32, 32, VK_FORMAT_A4B4G4R4_UNORM_PACK16, 40, 40, kLinear));
    add(out, "a2b10g10r10_linear_scale",
        whole(VK_FORMAT_A2B10G10R10_UNORM_PACK32, 32, 24, VK_FORMAT_A2B10G10R10_UNORM_PACK32, 19, 41, kLinear));
    add(out, "r16_uint_nearest_scale", whole(VK_FORMAT_R16_UINT, 32, 32, VK_FORMAT_R16_UINT, 45, 21, kNearest));
    add(out, "rgba16_sint_to_rgba8_sint",
        whole(VK_FORMAT_R16G16B16A16_SINT, 30, 30, VK_FORMAT_R8G8B8A8_SINT, 17, 43, kNearest));
    {
        BlitSpec s{kRgba8, kRgba8, 64, 64, 64, 64, kLinear, {region(0, 0, 32, 32, 0, 0, 16, 16, kC, 1, 2)}};
        s.src_levels = s.dst_levels = 3;
        add(out, "mip_level_to_level", s);
        BlitSpec a{kRgba8, kRgba8, 20, 20, 33, 17, kLinear, {region(0, 0, 20, 20, 0, 0, 33, 17, kC, 0, 0, 3)}};
        a.layers = 3;
        add(out, "array_layers", a);
    }
    add(out, "regions",
        {kRgba8,
         kRgba8,
         40,
         40,
         50,
         50,
         kLinear,
         {region(3, 5, 17, 39, 1, 2, 30, 9, kC), region(20, 1, 38, 7, 49, 48, 33, 12, kC),
          region(0, 0, 1, 1, 40, 40, 50, 50, kC)}});
    add(out, "depth_d16_nearest_scale", whole(VK_FORMAT_D16_UNORM, 32, 32, VK_FORMAT_D16_UNORM, 45, 21, kNearest));
    add(out, "depth_d32_nearest_scale", whole(VK_FORMAT_D32_SFLOAT, 32, 32, VK_FORMAT_D32_SFLOAT, 45, 21, kNearest));
    add_blit_3d_cases(out);
    add(out, "mip_chain", chain(kRgba8, 64, 64, 7));
    add(out, "mip_chain_npot", chain(kRgba8, 75, 37, 7));
    add(out, "mip_chain_srgb", chain(kSrgb8, 48, 40, 6));
    add(out, "mip_chain_float", chain(kRgba32f, 40, 24, 5));
    add(out, "large_linear_up", whole(kRgba8, 300, 200, kRgba8, 1023, 517, kLinear));
    // lavapipe renders single-layer B8G8R8A8_UNORM destinations in its linear mode (icd/README.md, "Blits")
    add(out, "bgra_dst_linear_scale", whole(kRgba8, 32, 32, kBgra8, 47, 13, kLinear), "bgra-linear-path");
    add(out, "bgra_dst_nearest_scale", whole(kRgba8, 32, 32, kBgra8, 45, 21, kNearest), "bgra-linear-path");
}

}  // namespace tilevk::cts
