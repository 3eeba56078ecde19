// Transfer commands: copies, clears, fills, updates and resolves on tilevk's plain linear layout (image.h).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "buffer.h"
#include "execute.h"
#include "host/cpu.h"
#include "image.h"
#include "rast/fragment/msaa.h"
#include "rast/geometry/viewport.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

uint32_t resolve_count(const Image& img, uint32_t base, uint32_t count, bool layers) {
    uint32_t total = layers ? img.array_layers : img.mip_levels;
    return count == (layers ? VK_REMAINING_ARRAY_LAYERS : VK_REMAINING_MIP_LEVELS) ? total - base : count;
}

// The stored layers (image.h) a copy region names: a 3D image's slices z .. z+depth-1, else its array layers. A
// negative z becomes a huge index, which image_ok refuses.
struct LayerSpan {
    uint32_t first, count;
};
LayerSpan region_layers(const Image& img, const VkImageSubresourceLayers& s, int32_t z, uint32_t depth) {
    if (img.type == VK_IMAGE_TYPE_3D) return {uint32_t(z), depth};
    return {s.baseArrayLayer, resolve_count(img, s.baseArrayLayer, s.layerCount, true)};
}

// The stored layers a clear range covers at `level`: every slice of a 3D image's level (its one array layer is the
// whole level), else the range's array layers.
LayerSpan clear_layers(const Image& img, const VkImageSubresourceRange& r, uint32_t level) {
    if (img.type == VK_IMAGE_TYPE_3D) return {0, img.level_depth(level)};
    return {r.baseArrayLayer, resolve_count(img, r.baseArrayLayer, r.layerCount, true)};
}

VkRect2D full_rect(const Image& img, uint32_t level) {
    return {{0, 0}, {img.level_width(level), img.level_height(level)}};
}

// Invalid commands (out-of-range regions, unbound memory) must not crash the process: every region is checked
// before it is touched and skipped with a message otherwise.
bool buffer_ok(const Buffer* b, VkDeviceSize offset, VkDeviceSize size, const char* what) {
    const bool ok = b != nullptr && b->memory != nullptr && offset <= b->size && size <= b->size - offset &&
                    b->memory_offset <= b->memory->size && b->size <= b->memory->size - b->memory_offset;
    if (!ok)
        log_error("%s: buffer range [%llu, +%llu) is outside the buffer or its memory; skipped", what,
                  (unsigned long long)offset, (unsigned long long)size);
    return ok;
}

// A copy region's texel rectangle in blocks (texels for uncompressed formats): the offset must start a block, the
// extent may end in a partial last block (the spec's "or reaches the edge of the subresource", checked by image_ok).
struct BlockRect {
    int32_t x, y;
    uint32_t w, h;
};
bool to_blocks(const FormatInfo& f, int32_t x, int32_t y, uint32_t w, uint32_t h, BlockRect& out, const char* what) {
    const int32_t bw = f.block_width, bh = f.block_height;
    if (x % bw != 0 || y % bh != 0) {
        log_error("%s: offset (%d, %d) of a %s region is not a multiple of its %dx%d blocks; skipped", what, x, y,
                  f.name, bw, bh);
        return false;
    }
    out = {x / bw, y / bh, uint32_t((uint64_t(w) + bw - 1) / bw), uint32_t((uint64_t(h) + bh - 1) / bh)};
    return true;
}

// `x`, `y`, `w`, `h` in blocks (image.h: texels for uncompressed formats).
bool image_ok(const Image* img, uint32_t level, uint32_t base_layer, uint32_t layers, int32_t x, int32_t y, uint32_t w,
              uint32_t h, const char* what) {
    bool ok = img != nullptr && img->memory != nullptr && level < img->mip_levels &&
              base_layer < img->level_layers(level) && layers <= img->level_layers(level) - base_layer && x >= 0 &&
              y >= 0 && img->memory_offset <= img->memory->size &&
              img->layout.size <= img->memory->size - img->memory_offset;
    if (ok) {
        ok = uint64_t(x) + w <= img->level_blocks_w(level) && uint64_t(y) + h <= img->level_blocks_h(level);
    }
    if (!ok)
        log_error("%s: image region (level %u, layers %u+%u, %d,%d %ux%u) is outside the image; skipped", what, level,
                  base_layer, layers, x, y, w, h);
    return ok;
}

// Copies one row of `width` texels of `aspect` between a buffer (packed aspect texels) and an image row.
void copy_row(const Image& img, VkImageAspectFlags aspect, uint8_t* image_row, uint8_t* buffer_row, uint32_t width,
              bool to_image) {
    const FormatInfo& f = *img.format;
    const uint32_t bytes = buffer_texel_bytes(f, aspect);
    if (f.depth == format::DepthFormat::X8D24 && aspect == VK_IMAGE_ASPECT_DEPTH_BIT) {
        // D24 depth in a 32-bit buffer word: the low 24 bits; the top byte (the image's stencil) is written as 0
        // (lavapipe's X8 bits) and never copied into the image.
        for (uint32_t x = 0; x < width; ++x) {
            uint8_t* t = image_row + size_t(x) * 4;
            uint8_t* b = buffer_row + size_t(x) * 4;
            if (to_image) {
                std::memcpy(t, b, 3);
            } else {
                std::memcpy(b, t, 3);
                b[3] = 0;
            }
        }
        return;
    }
    if (bytes == f.bytes) {
        if (to_image)
            std::memcpy(image_row, buffer_row, size_t(width) * bytes);
        else
            std::memcpy(buffer_row, image_row, size_t(width) * bytes);
        return;
    }
    // One aspect of an interleaved depth/stencil texel.
    const uint32_t off = aspect_offset(f, aspect);
    for (uint32_t x = 0; x < width; ++x) {
        uint8_t* t = image_row + size_t(x) * f.bytes + off;
        if (to_image)
            std::memcpy(t, buffer_row + size_t(x) * bytes, bytes);
        else
            std::memcpy(buffer_row + size_t(x) * bytes, t, bytes);
    }
}

void copy_buffer_image(Buffer& buf, const Image& img, const VkBufferImageCopy& r, bool to_image) {
    const VkImageSubresourceLayers& s = r.imageSubresource;
    const FormatInfo& f = *img.format;
    const uint32_t bytes = buffer_texel_bytes(f, s.aspectMask);
    // bufferRowLength and bufferImageHeight count texels; a compressed format's buffer holds whole blocks
    const uint64_t row_len =
        ((r.bufferRowLength ? r.bufferRowLength : r.imageExtent.width) + f.block_width - 1) / f.block_width;
    const uint64_t img_height =
        ((r.bufferImageHeight ? r.bufferImageHeight : r.imageExtent.height) + f.block_height - 1) / f.block_height;
    const auto [first, layers] = region_layers(img, s, r.imageOffset.z, r.imageExtent.depth);
    const char* what = to_image ? "vkCmdCopyBufferToImage" : "vkCmdCopyImageToBuffer";
    if (r.imageExtent.width == 0 || r.imageExtent.height == 0 || layers == 0) return;
    BlockRect b{};
    if (!to_blocks(f, r.imageOffset.x, r.imageOffset.y, r.imageExtent.width, r.imageExtent.height, b, what) ||
        !image_ok(&img, s.mipLevel, first, layers, b.x, b.y, b.w, b.h, what)) {
        return;
    }
    // the last block read or written: ((layers-1)*imageHeight + height-1)*rowLength + width blocks past bufferOffset
    const uint64_t span = ((uint64_t(layers - 1) * img_height + (b.h - 1)) * row_len + b.w) * bytes;
    if (!buffer_ok(&buf, r.bufferOffset, span, what)) return;
    for (uint32_t l = 0; l < layers; ++l) {
        for (uint32_t y = 0; y < b.h; ++y) {
            // block (x, y, layer or slice l) is at bufferOffset + ((l*imageHeight + y)*rowLength + x)*bytes
            uint8_t* brow = buf.data() + r.bufferOffset + ((l * img_height + y) * row_len) * bytes;
            uint8_t* irow = img.texel(s.mipLevel, first + l, uint32_t(b.x), uint32_t(b.y) + y);
            copy_row(img, s.aspectMask, irow, brow, b.w, to_image);
        }
    }
}

}  // namespace

void exec_copy_buffer(const CmdCopyBuffer& c) {
    for (uint32_t i = 0; i < c.count; ++i) {
        const VkBufferCopy& r = c.regions[i];
        if (!buffer_ok(c.src, r.srcOffset, r.size, "vkCmdCopyBuffer") ||
            !buffer_ok(c.dst, r.dstOffset, r.size, "vkCmdCopyBuffer")) {
            continue;
        }
        std::memmove(c.dst->data() + r.dstOffset, c.src->data() + r.srcOffset, size_t(r.size));
    }
}

void exec_copy_image(const CmdCopyImage& c) {
    if (c.src == nullptr || c.dst == nullptr) return;
    for (uint32_t i = 0; i < c.count; ++i) {
        const VkImageCopy& r = c.regions[i];
        const VkImageAspectFlags aspect = r.srcSubresource.aspectMask;
        // Between a 3D image and a 2D one (VK_KHR_maintenance1) the 3D side's extent.depth slices pair with the
        // 2D side's layers; the layer count of a 2D side is then extent.depth.
        const LayerSpan src = region_layers(*c.src, r.srcSubresource, r.srcOffset.z, r.extent.depth);
        const LayerSpan dst = region_layers(*c.dst, r.dstSubresource, r.dstOffset.z, r.extent.depth);
        const uint32_t layers = std::min(src.count, dst.count);
        const FormatInfo& f = *c.src->format;
        // The extent counts the source's texels; between a compressed and an uncompressed format (size-compatible:
        // one block is one texel of the same size) the same number of blocks is copied on both sides.
        BlockRect sb{}, db{};
        if (!to_blocks(f, r.srcOffset.x, r.srcOffset.y, r.extent.width, r.extent.height, sb, "vkCmdCopyImage") ||
            !to_blocks(*c.dst->format, r.dstOffset.x, r.dstOffset.y, 1, 1, db, "vkCmdCopyImage") ||
            !image_ok(c.src, r.srcSubresource.mipLevel, src.first, layers, sb.x, sb.y, sb.w, sb.h, "vkCmdCopyImage") ||
            !image_ok(c.dst, r.dstSubresource.mipLevel, dst.first, layers, db.x, db.y, sb.w, sb.h, "vkCmdCopyImage") ||
            c.dst->samples != c.src->samples || c.dst->format->bytes != f.bytes) {
            continue;
        }
        const bool whole_texel = buffer_texel_bytes(f, aspect) == f.bytes;
        const uint32_t off = aspect_offset(f, aspect), bytes = buffer_texel_bytes(f, aspect);
        const VkDeviceSize src_sample = c.src->sample_pitch(r.srcSubresource.mipLevel);
        const VkDeviceSize dst_sample = c.dst->sample_pitch(r.dstSubresource.mipLevel);
        for (uint32_t l = 0; l < layers * c.src->samples; ++l) {  // every sample plane of every layer
            const uint32_t layer = l / c.src->samples, sample = l % c.src->samples;
            for (uint32_t y = 0; y < sb.h; ++y) {
                const uint8_t* s =
                    c.src->texel(r.srcSubresource.mipLevel, src.first + layer, uint32_t(sb.x), uint32_t(sb.y) + y) +
                    sample * src_sample;
                uint8_t* d =
                    c.dst->texel(r.dstSubresource.mipLevel, dst.first + layer, uint32_t(db.x), uint32_t(db.y) + y) +
                    sample * dst_sample;
                const size_t texels = sb.w;
                if (whole_texel) {
                    std::memmove(d, s, texels * f.bytes);  // formats are size-compatible: a raw copy
                } else {
                    for (size_t x = 0; x < texels; ++x) {
                        std::memmove(d + x * f.bytes + off, s + x * f.bytes + off, bytes);
                    }
                }
            }
        }
    }
}

void exec_copy_buffer_to_image(const CmdCopyBufferToImage& c) {
    if (c.src == nullptr || c.dst == nullptr) return;
    for (uint32_t i = 0; i < c.count; ++i) copy_buffer_image(*c.src, *c.dst, c.regions[i], true);
}

void exec_copy_image_to_buffer(const CmdCopyImageToBuffer& c) {
    if (c.src == nullptr || c.dst == nullptr) return;
    for (uint32_t i = 0; i < c.count; ++i) copy_buffer_image(*c.dst, *c.src, c.regions[i], false);
}

void exec_update_buffer(const CmdUpdateBuffer& c) {
    if (c.data != nullptr && buffer_ok(c.dst, c.offset, c.size, "vkCmdUpdateBuffer"))
        std::memcpy(c.dst->data() + c.offset, c.data, size_t(c.size));
}

void exec_fill_buffer(const CmdFillBuffer& c) {
    // VK_WHOLE_SIZE fills to the end of the buffer, rounded down to a multiple of 4 bytes.
    if (!buffer_ok(c.dst, c.offset, 0, "vkCmdFillBuffer")) return;
    VkDeviceSize size = c.size == VK_WHOLE_SIZE ? (c.dst->size - c.offset) & ~VkDeviceSize(3) : c.size;
    if (!buffer_ok(c.dst, c.offset, size, "vkCmdFillBuffer")) return;
    uint8_t* p = c.dst->data() + c.offset;
    for (VkDeviceSize i = 0; i + 4 <= size; i += 4) std::memcpy(p + i, &c.data, 4);
}

void fill_rect(const Image& img, uint32_t level, uint32_t layer, const VkRect2D& rect, const uint8_t* texel,
               uint32_t byte_offset, uint32_t byte_count) {
    if (!image_ok(&img, level, layer, 1, rect.offset.x, rect.offset.y, rect.extent.width, rect.extent.height,
                  "clear")) {
        return;
    }
    const uint32_t tb = img.format->bytes;
    const size_t texels = rect.extent.width;
    if (rect.extent.height == 0 || texels == 0) return;
    uint8_t* first = img.texel(level, layer, uint32_t(rect.offset.x), uint32_t(rect.offset.y));
    for (size_t x = 0; x < texels; ++x) std::memcpy(first + x * tb + byte_offset, texel + byte_offset, byte_count);
    // Whole texels: the rows below (and every row of the other sample planes) are byte copies of the first (a
    // memcpy per row, not per texel). A partial texel (one aspect of a packed depth/stencil texel) must keep the
    // other bytes of each row.
    const bool whole_texels = byte_offset == 0 && byte_count == tb;
    const VkDeviceSize sample_pitch = img.sample_pitch(level);
    for (uint32_t i = 1; i < rect.extent.height * img.samples; ++i) {
        const uint32_t y = i % rect.extent.height, sample = i / rect.extent.height;
        uint8_t* row =
            img.texel(level, layer, uint32_t(rect.offset.x), uint32_t(rect.offset.y) + y) + sample * sample_pitch;
        if (whole_texels) {
            std::memcpy(row, first, texels * tb);
        } else {
            for (size_t x = 0; x < texels; ++x)
                std::memcpy(row + x * tb + byte_offset, texel + byte_offset, byte_count);
        }
    }
}

void clear_color_rect(const Image& img, const FormatInfo& as, uint32_t level, uint32_t base_layer, uint32_t layer_count,
                      const VkRect2D& rect, const VkClearColorValue& color) {
    if (as.layout == format::Layout::kCompressed || as.bytes != img.format->bytes) {
        // VUID-vkCmdClearColorImage-image-00007: never a compressed image (its blocks have no clear packing); a
        // view's format always has the image's texel size (compatible formats of a MUTABLE_FORMAT image).
        log_error("clear: %s as %s cannot be cleared; skipped", img.format->name, as.name);
        return;
    }
    uint8_t texel[16] = {};
    rast::fragment::pack_clear_color(as, color.float32, texel);
    for (uint32_t l = 0; l < layer_count; ++l) fill_rect(img, level, base_layer + l, rect, texel, 0, as.bytes);
}

void clear_depth_stencil_rect(const Image& img, uint32_t level, uint32_t base_layer, uint32_t layer_count,
                              const VkRect2D& rect, VkImageAspectFlags aspects, const VkClearDepthStencilValue& v) {
    const FormatInfo& f = *img.format;
    uint8_t texel[16] = {};
    // D16: 2 bytes, D24: the low 3 bytes of its 4-byte texel (a depth clear keeps the stencil byte), D32F: 4.
    const uint32_t depth_bits = rast::fragment::pack_clear_depth(f.depth, v.depth);
    const uint32_t depth_bytes =
        f.depth == format::DepthFormat::X8D24 ? 3 : buffer_texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT);
    std::memcpy(texel, &depth_bits, depth_bytes);
    if (f.aspects & VK_IMAGE_ASPECT_STENCIL_BIT)
        texel[aspect_offset(f, VK_IMAGE_ASPECT_STENCIL_BIT)] = uint8_t(v.stencil);
    for (uint32_t l = 0; l < layer_count; ++l) {
        if ((aspects & VK_IMAGE_ASPECT_DEPTH_BIT) && (f.aspects & VK_IMAGE_ASPECT_DEPTH_BIT)) {
            fill_rect(img, level, base_layer + l, rect, texel, 0, depth_bytes);
        }
        if ((aspects & VK_IMAGE_ASPECT_STENCIL_BIT) && (f.aspects & VK_IMAGE_ASPECT_STENCIL_BIT)) {
            fill_rect(img, level, base_layer + l, rect, texel, aspect_offset(f, VK_IMAGE_ASPECT_STENCIL_BIT), 1);
        }
    }
}

void exec_clear_color_image(const CmdClearColorImage& c) {
    if (c.image == nullptr) return;
    for (uint32_t i = 0; i < c.count; ++i) {
        const VkImageSubresourceRange& r = c.ranges[i];
        const uint32_t levels = resolve_count(*c.image, r.baseMipLevel, r.levelCount, false);
        for (uint32_t m = r.baseMipLevel; m < r.baseMipLevel + levels; ++m) {
            const LayerSpan l = clear_layers(*c.image, r, m);
            if (!image_ok(c.image, m, l.first, l.count, 0, 0, 0, 0, "vkCmdClearColorImage")) break;
            clear_color_rect(*c.image, *c.image->format, m, l.first, l.count, full_rect(*c.image, m), c.color);
        }
    }
}

void exec_clear_depth_stencil_image(const CmdClearDepthStencilImage& c) {
    if (c.image == nullptr) return;
    for (uint32_t i = 0; i < c.count; ++i) {
        const VkImageSubresourceRange& r = c.ranges[i];
        const uint32_t levels = resolve_count(*c.image, r.baseMipLevel, r.levelCount, false);
        for (uint32_t m = r.baseMipLevel; m < r.baseMipLevel + levels; ++m) {
            const LayerSpan l = clear_layers(*c.image, r, m);
            if (!image_ok(c.image, m, l.first, l.count, 0, 0, 0, 0, "vkCmdClearDepthStencilImage")) break;
            clear_depth_stencil_rect(*c.image, m, l.first, l.count, full_rect(*c.image, m), r.aspectMask, c.value);
        }
    }
}

bool can_resolve(const FormatInfo& f) {
    return f.kind != format::ChannelKind::None;
}

// lavapipe resolves with util_blitter's MSAA-resolve shader (docs/lavapipe-rules.md, "Resolve"): rast/fragment's
// resolve_rect, verified against lavapipe; the image's samples of a pixel are sample_pitch bytes apart.
void resolve_rect(const Image& src, uint32_t src_level, uint32_t src_layer, VkOffset2D src_offset, const Image& dst,
                  uint32_t dst_level, uint32_t dst_layer, VkOffset2D dst_offset, VkExtent2D extent) {
    if (!image_ok(&src, src_level, src_layer, 1, src_offset.x, src_offset.y, extent.width, extent.height, "resolve") ||
        !image_ok(&dst, dst_level, dst_layer, 1, dst_offset.x, dst_offset.y, extent.width, extent.height, "resolve")) {
        return;
    }
    if (src.samples != uint32_t(rast::fragment::kMaxSamples) || dst.samples != 1 ||
        dst.format->bytes != src.format->bytes) {
        log_error("resolve: %u samples into %u (only 4 into 1 are resolved); skipped", src.samples, dst.samples);
        return;
    }
    const uint32_t tb = src.format->bytes;
    rast::fragment::resolve_rect(
        src.format->id, src.texel(src_level, src_layer, uint32_t(src_offset.x), uint32_t(src_offset.y)),
        size_t(src.sample_pitch(src_level)), src.layout.row_pitch[src_level],
        dst.texel(dst_level, dst_layer, uint32_t(dst_offset.x), uint32_t(dst_offset.y)),
        dst.layout.row_pitch[dst_level], int(extent.width), int(extent.height), host::has_fma(), tb);
}

// The depth/stencil resolve of a render pass (VK_KHR_depth_stencil_resolve), SAMPLE_ZERO for every aspect as lavapipe
// 22.3 performs it: lvp_execute.c resolve_ds -> llvmpipe lp_surface.c lp_blit's sample0_only path,
// util_resource_copy_region of the source's first sample: sample 0's texel bytes as they are, all aspects. Source and
// destination have one format (render_pass.cpp check_ds_resolve). Not offered: lavapipe's AVERAGE, which
// util_blitter_blit (u_blitter.c) draws with util_make_fs_blit_msaa_depth (u_simple_shaders.c), a TXF of sample
// index 0 written as the fragment depth: sample 0 through a float (D24 rne(fl(fl(v * fl(1/(2^24-1))) * (2^24-1))),
// a denormal D32F +0), never an average.
void resolve_depth_stencil_rect(const Image& src, uint32_t src_level, uint32_t src_layer, const Image& dst,
                                uint32_t dst_level, uint32_t dst_layer, VkOffset2D offset, VkExtent2D extent) {
    if (!image_ok(&src, src_level, src_layer, 1, offset.x, offset.y, extent.width, extent.height, "resolve") ||
        !image_ok(&dst, dst_level, dst_layer, 1, offset.x, offset.y, extent.width, extent.height, "resolve")) {
        return;
    }
    if (dst.samples != 1 || dst.format != src.format) {
        log_error("depth/stencil resolve: %u samples of %s into %u of %s (one format into 1 sample only); skipped",
                  src.samples, vk_enum_name(vk_format(*src.format)), dst.samples, vk_enum_name(vk_format(*dst.format)));
        return;
    }
    // Sample 0 is the first sample plane: its rows are the destination's rows, byte for byte.
    const size_t row_bytes = size_t(extent.width) * src.format->bytes;
    for (uint32_t y = 0; y < extent.height; ++y) {
        const uint8_t* s = src.texel(src_level, src_layer, uint32_t(offset.x), uint32_t(offset.y) + y);
        uint8_t* d = dst.texel(dst_level, dst_layer, uint32_t(offset.x), uint32_t(offset.y) + y);
        std::memcpy(d, s, row_bytes);
    }
}

void exec_resolve_image(const CmdResolveImage& c) {
    if (c.src == nullptr || c.dst == nullptr) return;
    for (uint32_t i = 0; i < c.count; ++i) {
        const VkImageResolve& r = c.regions[i];
        if (!can_resolve(*c.src->format)) {
            log_error("vkCmdResolveImage: resolving %s is not implemented; region skipped",
                      vk_enum_name(vk_format(*c.src->format)));
            continue;
        }
        const uint32_t layers =
            resolve_count(*c.src, r.srcSubresource.baseArrayLayer, r.srcSubresource.layerCount, true);
        if (!image_ok(c.src, r.srcSubresource.mipLevel, r.srcSubresource.baseArrayLayer, layers, r.srcOffset.x,
                      r.srcOffset.y, r.extent.width, r.extent.height, "vkCmdResolveImage") ||
            !image_ok(c.dst, r.dstSubresource.mipLevel, r.dstSubresource.baseArrayLayer, layers, r.dstOffset.x,
                      r.dstOffset.y, r.extent.width, r.extent.height, "vkCmdResolveImage") ||
            c.dst->format->bytes != c.src->format->bytes || c.dst->samples != 1) {
            continue;
        }
        for (uint32_t l = 0; l < layers; ++l) {
            resolve_rect(*c.src, r.srcSubresource.mipLevel, r.srcSubresource.baseArrayLayer + l,
                         {r.srcOffset.x, r.srcOffset.y}, *c.dst, r.dstSubresource.mipLevel,
                         r.dstSubresource.baseArrayLayer + l, {r.dstOffset.x, r.dstOffset.y},
                         {r.extent.width, r.extent.height});
        }
    }
}

}  // namespace tilevk::icd
