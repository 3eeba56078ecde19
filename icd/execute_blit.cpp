// vkCmdBlitImage: recording, and the mapping of each VkImageBlit region onto rast::render::blit (which computes
// what lavapipe computes; icd/README.md "Blits").
#include "execute_blit.h"

#include <algorithm>

#include "command_buffer.h"
#include "entrypoints.h"
#include "execute.h"
#include "host/cpu.h"
#include "image.h"
#include "rast/geometry/viewport.h"
#include "rast/render/blit.h"
#include "workers.h"

namespace tilevk::icd {

// ---- recording ----------------------------------------------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdBlitImage(VkCommandBuffer commandBuffer, VkImage srcImage, VkImageLayout,
                                            VkImage dstImage, VkImageLayout, uint32_t regionCount,
                                            const VkImageBlit* pRegions, VkFilter filter) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    if (auto* c = cb->append<CmdBlitImage>()) {
        c->src = from_handle<Image>(srcImage);
        c->dst = from_handle<Image>(dstImage);
        c->count = regionCount;
        c->regions = cb->copy(pRegions, regionCount);
        c->filter = filter;
    }
}

bool blit_supported(const FormatInfo& f, bool source) {
    // the BC formats are blit sources only (the sampler decodes them), as lavapipe's
    return (image_features(f) & (source ? format::kBlitSrc : format::kBlitDst)) != 0;
}

namespace {

// Checks a blit region's box against its subresource (invalid usage must not crash): offsets inside the level (z
// inside a 3D level's depth, else 0..1), layers inside the image, memory bound.
bool region_ok(const Image* img, const VkImageSubresourceLayers& sub, const VkOffset3D (&o)[2], bool source) {
    const char* which = source ? "source" : "destination";
    bool ok = img != nullptr && img->memory != nullptr && sub.mipLevel < img->mip_levels &&
              sub.baseArrayLayer < img->array_layers && sub.layerCount >= 1 &&
              sub.layerCount <= img->array_layers - sub.baseArrayLayer && img->samples == 1 &&
              blit_supported(*img->format, source) && img->memory_offset <= img->memory->size &&
              img->layout.size <= img->memory->size - img->memory_offset;
    if (ok) {
        const int64_t w = img->level_width(sub.mipLevel), h = img->level_height(sub.mipLevel);
        for (const VkOffset3D& p : o) ok = ok && p.x >= 0 && p.x <= w && p.y >= 0 && p.y <= h;
        if (img->type == VK_IMAGE_TYPE_3D) {
            const int64_t d = img->level_depth(sub.mipLevel);
            for (const VkOffset3D& p : o) ok = ok && p.z >= 0 && p.z <= d;
        } else {
            ok = ok && std::min(o[0].z, o[1].z) == 0 && std::max(o[0].z, o[1].z) == 1;
        }
    }
    if (!ok)
        log_error(
            "vkCmdBlitImage: %s region (level %u, layers %u+%u, (%d,%d,%d)-(%d,%d,%d)) is invalid for the image; "
            "region skipped",
            which, sub.mipLevel, sub.baseArrayLayer, sub.layerCount, o[0].x, o[0].y, o[0].z, o[1].x, o[1].y, o[1].z);
    return ok;
}

// The valid-usage rules between the two images of a region that rast/'s blitter relies on; each failure is logged
// with its VUID and the region skipped.
bool regions_compatible(const Image& src, const Image& dst, const VkImageBlit& r) {
    const format::Numeric sn = src.format->channel[0].numeric, dn = dst.format->channel[0].numeric;
    if ((sn == format::Numeric::kSint) != (dn == format::Numeric::kSint)) {
        log_error(
            "vkCmdBlitImage: VUID-vkCmdBlitImage-srcImage-00229: a signed integer format is blitted from or to "
            "a format that is not signed integer (VK_FORMAT_%s to VK_FORMAT_%s); region skipped",
            src.format->name, dst.format->name);
        return false;
    }
    if ((sn == format::Numeric::kUint) != (dn == format::Numeric::kUint)) {
        log_error(
            "vkCmdBlitImage: VUID-vkCmdBlitImage-srcImage-00230: an unsigned integer format is blitted from or "
            "to a format that is not unsigned integer (VK_FORMAT_%s to VK_FORMAT_%s); region skipped",
            src.format->name, dst.format->name);
        return false;
    }
    if (r.srcSubresource.layerCount != r.dstSubresource.layerCount) {
        log_error("vkCmdBlitImage: source and destination layer counts differ; region skipped");
        return false;
    }
    const bool src_3d = src.type == VK_IMAGE_TYPE_3D, dst_3d = dst.type == VK_IMAGE_TYPE_3D;
    if ((src_3d || dst_3d) && (r.srcSubresource.baseArrayLayer != 0 || r.srcSubresource.layerCount != 1 ||
                               r.dstSubresource.baseArrayLayer != 0 || r.dstSubresource.layerCount != 1)) {
        log_error(
            "vkCmdBlitImage: VUID-vkCmdBlitImage-srcImage-00240: a VK_IMAGE_TYPE_3D image is blitted with a "
            "baseArrayLayer other than 0 or a layerCount other than 1; region skipped");
        return false;
    }
    // lavapipe takes a 2D source's box z from the subresources (lvp_execute.c handle_blit_image), so it writes
    // slice 0 of a 3D destination whatever dstOffsets say; tilevk cannot match that and honour the region
    if (dst_3d && !src_3d && std::max(r.dstOffsets[0].z, r.dstOffsets[1].z) != 1) {
        log_error(
            "vkCmdBlitImage: a VK_IMAGE_TYPE_2D source into slices %d..%d of a VK_IMAGE_TYPE_3D destination is "
            "not implemented (lavapipe 22.3 writes slice 0 instead; icd/README.md \"Blits\"); region skipped",
            std::min(r.dstOffsets[0].z, r.dstOffsets[1].z), std::max(r.dstOffsets[0].z, r.dstOffsets[1].z));
        return false;
    }
    return true;
}

// One level of an image as rast/ sees it: every array layer (or depth slice) from layer 0.
rast::render::BlitSurface surface_of(const Image& img, uint32_t level) {
    rast::render::BlitSurface s;
    s.base = img.texel(level, 0, 0, 0);
    s.format = img.format->id;
    s.width = img.level_width(level), s.height = img.level_height(level);
    s.layers = img.level_layers(level);
    s.three_d = img.type == VK_IMAGE_TYPE_3D;
    s.row_pitch = img.layout.row_pitch[level], s.layer_pitch = img.layout.layer_pitch[level];
    return s;
}

void blit_region(ExecState& st, const Image& src, const Image& dst, const VkImageBlit& r, VkFilter filter) {
    if (!region_ok(&src, r.srcSubresource, r.srcOffsets, true) ||
        !region_ok(&dst, r.dstSubresource, r.dstOffsets, false) || !regions_compatible(src, dst, r)) {
        return;
    }
    rast::render::BlitRegion region;
    for (int corner = 0; corner < 2; ++corner) {
        region.src[corner][0] = r.srcOffsets[corner].x, region.src[corner][1] = r.srcOffsets[corner].y;
        region.dst[corner][0] = r.dstOffsets[corner].x, region.dst[corner][1] = r.dstOffsets[corner].y;
    }
    // lvp_execute.c handle_blit_image: a 3D source's boxes take z from the offsets, any other's from the layers
    if (src.type == VK_IMAGE_TYPE_3D) {
        for (int corner = 0; corner < 2; ++corner) {
            region.src[corner][2] = r.srcOffsets[corner].z;
            region.dst[corner][2] = r.dstOffsets[corner].z;
        }
    } else {
        region.src[0][2] = int32_t(r.srcSubresource.baseArrayLayer);
        region.src[1][2] = int32_t(r.srcSubresource.baseArrayLayer + r.srcSubresource.layerCount);
        region.dst[0][2] = int32_t(r.dstSubresource.baseArrayLayer);
        region.dst[1][2] = int32_t(r.dstSubresource.baseArrayLayer + r.dstSubresource.layerCount);
    }
    static const bool fused = host::has_fma();
    rast::render::blit(
        surface_of(src, r.srcSubresource.mipLevel), surface_of(dst, r.dstSubresource.mipLevel), region,
        filter == VK_FILTER_LINEAR ? rast::render::BlitFilter::kLinear : rast::render::BlitFilter::kNearest, fused,
        worker_pool(st));
}

}  // namespace

void exec_blit_image(ExecState& st, const CmdBlitImage& c) {
    if (c.src == nullptr || c.dst == nullptr || c.regions == nullptr) return;
    for (uint32_t i = 0; i < c.count; ++i) blit_region(st, *c.src, *c.dst, c.regions[i], c.filter);
}

}  // namespace tilevk::icd
