// texture.*: magnification and minification filters, mip selection and blending, and the wrap modes.
#include <limits>

#include "texture_case.hpp"

namespace tilevk::cts {
namespace {

// A quad showing the texture with coordinates [u0,u1] x [v0,v1], optionally with a perspective tilt.
Scene textured(TextureSpec t, float u0, float u1, float x_scale = 1.0f, bool projected = false, uint32_t size = 64) {
    return one_draw(textured_quad(t, {u0, u1, x_scale, projected}), size, size);
}

// VK_EXT_custom_border_color: RGBA8 and R8 textures under CLAMP_TO_BORDER with colours outside [0, 1] (gallivm
// clamps them to the format and, on R8, replaces red only), magnified and minified through mip levels, into a float
// target so that every bit of the border shows.
void add_custom_border_cases(CaseList& out) {
    struct Colour {
        const char* name;
        VkClearColorValue v;
    };
    const Colour colours[] = {{"out_of_range", {{0.25f, -0.5f, 2.0f, 0.75f}}},
                              {"in_range", {{0.9f, 0.1f, 0.6f, 0.3f}}}};
    for (VkFormat fmt : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8_UNORM})
        for (const Colour& col : colours)
            for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
                TextureSpec t;
                t.format = fmt;
                t.pattern = TexPattern::kGradient;
                t.width = t.height = 32;
                t.mip_levels = 6;
                t.mag = t.min = f;
                t.mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
                t.wrap = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
                t.border = VK_BORDER_COLOR_FLOAT_CUSTOM_EXT;
                t.custom_border = col.v;
                const std::string name = std::string("texture.custom_border.") +
                                         (fmt == VK_FORMAT_R8_UNORM ? "r8_" : "rgba8_") + col.name +
                                         (f == VK_FILTER_NEAREST ? "_nearest" : "_linear");
                out.push_back({name + "_magnified",
                               [=] {
                                   Scene s = textured(t, -0.3f, 1.4f);
                                   s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
                                   return s;
                               },
                               nullptr, ""});
                out.push_back({name + "_minified_projected",
                               [=] {
                                   Scene s = textured(t, -1.5f, 2.5f, 1.0f, true);
                                   s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
                                   return s;
                               },
                               nullptr, ""});
            }
}

// samplerFilterMinmax: an R8_UNORM checker (the one-channel format lavapipe reports FILTER_MINMAX for) reduced with
// MIN and MAX, minified across mip levels with a perspective tilt: CLAMP_TO_EDGE takes lavapipe's 8-bit filter
// (which also reduces between levels), MIRRORED_REPEAT its float filter (which lerps between levels).
void add_minmax_cases(CaseList& out) {
    for (VkSamplerReductionMode m : {VK_SAMPLER_REDUCTION_MODE_MIN, VK_SAMPLER_REDUCTION_MODE_MAX})
        for (VkSamplerAddressMode w : {VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT})
            for (VkSamplerMipmapMode mip : {VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_MIPMAP_MODE_LINEAR}) {
                TextureSpec t;
                t.format = VK_FORMAT_R8_UNORM;
                t.width = t.height = 64;
                t.mip_levels = 7;
                t.mag = t.min = VK_FILTER_LINEAR;
                t.mip_mode = mip;
                t.wrap = w;
                t.reduction = m;
                const std::string name = std::string("texture.minmax.") +
                                         (m == VK_SAMPLER_REDUCTION_MODE_MIN ? "min" : "max") +
                                         (w == VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE ? "_clamp_to_edge" : "_mirrored") +
                                         (mip == VK_SAMPLER_MIPMAP_MODE_NEAREST ? "_mip_nearest" : "_mip_linear");
                out.push_back({name,
                               [=] {
                                   Scene s = textured(t, -0.2f, 3.0f, 1.0f, true);
                                   s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
                                   return s;
                               },
                               nullptr, ""});
            }
}

}  // namespace

void add_texture_cases(CaseList& out) {
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
        const char* fname = f == VK_FILTER_NEAREST ? "nearest" : "linear";
        for (TexPattern p : {TexPattern::kChecker, TexPattern::kGradient}) {
            TextureSpec t;
            t.pattern = p;
            t.mag = t.min = f;
            out.push_back(
                {std::string("texture.filter.mag_") + fname + (p == TexPattern::kChecker ? "_checker" : "_gradient"),
                 [=] { return textured(t, 0.0f, 1.0f); },
                 // Nearest magnification of the checker shows only its two texel values (255 and 255/4 = 63).
                 f == VK_FILTER_NEAREST && p == TexPattern::kChecker
                     ? palette_only({rgba8(255, 255, 255, 255), rgba8(63, 63, 63, 255)})
                     : Check(),
                 ""});
        }
        for (VkSamplerMipmapMode m : {VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_MIPMAP_MODE_LINEAR}) {
            TextureSpec t;
            t.width = t.height = 128;
            t.mip_levels = 8;
            t.min = t.mag = f;
            t.mip_mode = m;
            std::string mname = m == VK_SAMPLER_MIPMAP_MODE_NEAREST ? "nearest" : "linear";
            out.push_back({std::string("texture.mipmap.min_") + fname + "_mip_" + mname,
                           [=] { return textured(t, 0.0f, 1.0f, 0.4f); }, nullptr, ""});
            out.push_back({std::string("texture.mipmap.min_") + fname + "_mip_" + mname + "_projected",
                           [=] { return textured(t, 0.0f, 4.0f, 1.0f, true); }, nullptr, ""});
        }
    }
    struct Wrap {
        const char* name;
        VkSamplerAddressMode mode;
    };
    const Wrap wraps[] = {{"repeat", VK_SAMPLER_ADDRESS_MODE_REPEAT},
                          {"mirrored_repeat", VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT},
                          {"clamp_to_edge", VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE},
                          {"clamp_to_border", VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER},
                          {"mirror_clamp_to_edge", VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE}};
    for (const Wrap& w : wraps)
        for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
            TextureSpec t;
            t.pattern = TexPattern::kGradient;
            t.width = t.height = 8;
            t.wrap = w.mode;
            t.mag = t.min = f;
            t.border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
            out.push_back({std::string("texture.wrap.") + w.name + (f == VK_FILTER_NEAREST ? "_nearest" : "_linear"),
                           [=] { return textured(t, -1.25f, 2.5f); }, nullptr, ""});
        }
    // The same textured rectangle on B8G8R8A8 without depth: lavapipe's linear path (lavapipe-rules §8) may shade it.
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
        TextureSpec t;
        t.mag = t.min = f;
        out.push_back(
            {std::string("texture.filter.mag_") + (f == VK_FILTER_NEAREST ? "nearest" : "linear") + "_bgra_linear",
             [=] {
                 Scene s = textured(t, 0.0f, 1.0f);
                 s.target.color = VK_FORMAT_B8G8R8A8_UNORM;
                 return s;
             },
             nullptr, "bgra-linear-path"});
    }
    TextureSpec lod0;
    lod0.width = lod0.height = 64;
    lod0.mip_levels = 7;
    lod0.max_lod = 0.0f;
    out.push_back({"texture.mipmap.max_lod_0", [=] { return textured(lod0, 0.0f, 1.0f, 0.3f); }, nullptr, ""});
    // Float targets keep the shader's texel values unrounded: an RGBA8 texel is float(c) * float(1/255) in lavapipe
    // (gallivm lp_build_unsigned_norm_to_float), which differs from c / 255 in the last bit for some c (found by the
    // random scene fuzzer). The gradient has 16 values per channel.
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR})
        out.push_back({std::string("texture.float_target.") + (f == VK_FILTER_NEAREST ? "nearest" : "linear"),
                       [=] {
                           TextureSpec t;
                           t.pattern = TexPattern::kGradient;
                           t.mag = t.min = f;
                           Scene s = textured(t, 0.0f, 1.0f);
                           s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
                           return s;
                       },
                       nullptr, ""});
    // gallivm's float filter blends two mip levels with lp_build_lerp, a fused multiply-add fma(f, l1 - l0, l0),
    // where tilevk computed l0 * (1 - f) + l1 * f: the last bits differ in float targets (found by the random
    // scene fuzzer, seeds 223 and 720). MIRRORED_REPEAT and CLAMP_TO_BORDER keep lavapipe off its 8-bit path.
    const Wrap float_wraps[] = {wraps[1], wraps[3], wraps[4]};
    for (const Wrap& w : float_wraps)
        out.push_back({std::string("texture.float_target.mip_linear_") + w.name,
                       [=] {
                           TextureSpec t;
                           t.pattern = TexPattern::kGradient;
                           t.width = 32, t.height = 21, t.mip_levels = 5;
                           t.mag = t.min = VK_FILTER_LINEAR;
                           t.mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
                           t.wrap = w.mode;
                           t.border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
                           Scene s = textured(t, -0.2f, 1.3f, 0.7f);
                           s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
                           return s;
                       },
                       nullptr, ""});
    add_custom_border_cases(out);
    add_minmax_cases(out);
    // A NaN coordinate (here every vertex's) with CLAMP_TO_BORDER: gallivm's float-to-int conversion gives INT_MIN,
    // so lavapipe reads the border (nearest) or the border lerped with a NaN weight (linear: NaN); tilevk read
    // texel 0 (found by the random scene fuzzer, seed 720, where a clipped noperspective triangle had NaN
    // coordinates).
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR})
        out.push_back({std::string("texture.float_target.nan_coordinate_clamp_to_border_") +
                           (f == VK_FILTER_NEAREST ? "nearest" : "linear"),
                       [=] {
                           TextureSpec t;
                           t.width = t.height = 8;
                           t.mag = t.min = f;
                           t.wrap = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
                           t.border = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;  // texel (0, 0) of the checker is white
                           const float nan = std::numeric_limits<float>::quiet_NaN();
                           Scene s = textured(t, nan, nan, 0.5f, false, 16);
                           s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
                           return s;
                       },
                       nullptr, ""});
}

}  // namespace tilevk::cts
