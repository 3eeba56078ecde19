// The per-view level table of the compiled tier's RGBA8 sampler (program.h ViewLevelTable), derived once per view.
#include <algorithm>
#include <array>

#include "format/texel_codec.h"
#include "shader/program.h"

namespace tilevk::shader {

// The compiled tier's RGBA8 sampler takes 2D RGBA8/BGRA8 UNORM views with the identity swizzle whose levels it can
// address with the gathers' signed 32-bit byte offsets from base; the rest of the table is only read for those.
ViewLevelTable level_table(const ImageView& view) {
    ViewLevelTable t;
    t.format = view.format;
    t.width = view.width, t.height = view.height, t.levels = view.levels;
    t.swizzle = view.swizzle;
    const format::FormatInfo& fi = format::format_info(view.format);
    const bool identity = view.swizzle == std::array<uint8_t, 4>{0, 1, 2, 3};
    if (!view.width || !view.height || !view.levels || view.levels > kMaxMipLevels || !view.layers ||
        fi.kind != format::ChannelKind::Unorm8 || fi.channels != 4 || fi.bytes != 4 || !identity)
        return t;
    for (uint32_t l = 0; l < kMaxMipLevels; ++l) {
        t.w[l] = int32_t(std::max(1u, view.width >> l));
        t.h[l] = int32_t(std::max(1u, view.height >> l));
    }
    for (uint32_t l = 0; l < view.levels; ++l) {
        const ImageLevel& lv = view.level[l];
        if (lv.row_pitch > 0x7fffffffu || lv.offset + lv.row_pitch * uint64_t(t.h[l]) > 0x7fffffffu) return t;
        t.offset[l] = int32_t(lv.offset);
        t.pitch[l] = int32_t(lv.row_pitch);
    }
    t.rgba8 = true;
    t.bgra = fi.bgra;
    return t;
}

void prepare_view(ImageView& view) {
    view.table = level_table(view);
}

}  // namespace tilevk::shader
