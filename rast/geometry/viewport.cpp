#include "rast/geometry/viewport.h"

#include <climits>
#include <cmath>

namespace tilevk::rast::geometry {

Viewport make_viewport(float x, float y, float width, float height, float min_depth, float max_depth, bool clip_halfz) {
    Viewport v{};
    const float half_width = 0.5f * width;
    const float half_height = 0.5f * height;
    v.scale[0] = half_width;
    v.translate[0] = half_width + x;
    v.scale[1] = half_height;
    v.translate[1] = half_height + y;
    const double n = min_depth;
    const double f = max_depth;
    if (clip_halfz) {
        v.scale[2] = static_cast<float>(f - n);
        v.translate[2] = static_cast<float>(n);
    } else {
        v.scale[2] = static_cast<float>(0.5 * (f - n));
        v.translate[2] = static_cast<float>(0.5 * (n + f));
    }
    return v;
}

void viewport_depth_range(const Viewport& vp, bool clip_halfz, float* zmin, float* zmax) {
    const float a = clip_halfz ? vp.translate[2] : vp.translate[2] - vp.scale[2];
    const float b = vp.translate[2] + vp.scale[2];
    *zmin = a < b ? a : b;
    *zmax = a < b ? b : a;
}

bool is_identity_viewport(const Viewport& vp) {
    return vp.scale[0] == 1.0f && vp.scale[1] == 1.0f && vp.scale[2] == 1.0f && vp.translate[0] == 0.0f &&
           vp.translate[1] == 0.0f && vp.translate[2] == 0.0f;
}

namespace {
int32_t cvtt(float f) {
    if (!(f > -2147483904.0f && f < 2147483648.0f)) return INT32_MIN;
    return static_cast<int32_t>(f);
}
}  // namespace

PixelRect viewport_pixel_rect(const Viewport& vp) {
    const float half_height = std::fabs(vp.scale[1]);
    const float x0 = vp.translate[0] - vp.scale[0];
    const float y0 = vp.translate[1] - half_height;
    PixelRect r;
    r.x0 = cvtt(x0 + 0.499f);
    const float xw = vp.scale[0] * 2.0f;
    const float xe = xw + x0;
    r.x1 = cvtt(xe - 0.501f);
    r.y0 = cvtt(y0 + 0.499f);
    const float yh = half_height * 2.0f;
    const float ye = yh + y0;
    r.y1 = cvtt(ye - 0.501f);
    // inclusive -> half-open, saturating
    r.x1 = r.x1 == INT32_MAX ? r.x1 : r.x1 + 1;
    r.y1 = r.y1 == INT32_MAX ? r.y1 : r.y1 + 1;
    return r;
}

void viewport_transform(const ViewportConfig& cfg, const float clip[4], float win[4]) {
    if (cfg.bypass) {
        for (int i = 0; i < 4; ++i) win[i] = clip[i];
        return;
    }
    const float oow = 1.0f / clip[3];
    for (int i = 0; i < 3; ++i) {
        const float p = clip[i] * oow;  // fl(x * oow)
        // fmuladd(p, scale, translate)
        win[i] =
            cfg.fused ? std::fma(p, cfg.vp.scale[i], cfg.vp.translate[i]) : p * cfg.vp.scale[i] + cfg.vp.translate[i];
    }
    win[3] = oow;
}

void viewport_transform_c(const Viewport& vp, const float clip[4], float win[4]) {
    const float oow = 1.0f / clip[3];
    for (int i = 0; i < 3; ++i) {
        const float p = clip[i] * oow;
        const float s = p * vp.scale[i];  // -ffp-contract=off keeps these two roundings
        win[i] = s + vp.translate[i];
    }
    win[3] = oow;
}

uint32_t compute_clipmask(const ClipMaskConfig& cfg, const float c[4]) {
    const float x = c[0], y = c[1], z = c[2], w = c[3];
    uint32_t m = 0;
    // !(a <= b) is the unordered a > b: true when either side is NaN
    if (cfg.clip_xy) {
        if (!(x <= w)) m |= kClipRight;
        if (!(0.0f <= x + w)) m |= kClipLeft;
        if (!(y <= w)) m |= kClipBottom;
        if (!(0.0f <= y + w)) m |= kClipTop;
    }
    if (cfg.clip_z) {
        if (cfg.clip_halfz) {
            if (!(0.0f <= z)) m |= kClipNear;
        } else {
            if (!(0.0f <= z + w)) m |= kClipNear;
        }
        if (!(z <= w)) m |= kClipFar;
    }
    return m;
}

uint32_t clip_distance_mask(const float* d, uint32_t n) {
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; ++i)
        if (!(0.0f <= d[i]) || std::isinf(d[i])) m |= 1u << (kClipUserShift + i);
    return m;
}

uint32_t prepare_vertex(const ClipMaskConfig& cm, const ViewportConfig& vp, float* record) {
    const uint32_t mask = compute_clipmask(cm, record);
    viewport_transform(vp, record, record + 4);
    return mask;
}

}  // namespace tilevk::rast::geometry
