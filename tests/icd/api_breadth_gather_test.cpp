// OpImageGather / OpImageDrefGather (textureGather, textureGatherOffset with a constant offset): cp_gather.comp on
// both drivers for every address mode tilevk offers, byte for byte, and the texels the Vulkan spec's linear
// footprint selects, worked out here for coordinates away from texel-centre crossovers.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "api_breadth.h"
#include "cp_gather_comp.h"
#include "sampler_readback.h"

namespace tilevk::test::breadth {
namespace {

constexpr uint32_t kW = 5, kH = 3;  // the colour texture: not a power of two
constexpr uint32_t kResults = 11;   // vec4 results per coordinate (cp_gather.comp)

// The coordinates: (s, t, layer, depth reference). Texel-centre crossovers (u - 0.5 integral), both sides of 0 and 1,
// far outside, and the non-finite values.
std::vector<std::array<float, 4>> coordinates() {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<std::array<float, 4>> c = {{0.37f, 0.61f, 0.0f, 0.5f},
                                           {0.5f / kW, 0.5f / kH, 1.0f, 0.25f},
                                           {0.0f, 0.0f, 2.0f, 0.75f},
                                           {1.0f, 1.0f, 1.4f, 0.1f},
                                           {0.05f, 0.95f, 1.6f, 0.9f},
                                           {-0.05f, -0.4f, -1.0f, 0.5f},
                                           {1.3f, 2.7f, 7.0f, 0.3f},
                                           {-1.3f, -2.2f, 0.5f, 0.6f},
                                           {1.5f / kW, 2.5f / kH, 2.5f, 0.45f},
                                           {0.999f, 0.001f, 0.0f, 0.0f},
                                           {3.1e4f, -2.7e4f, 1.0f, 1.0f},
                                           {1e9f, -1e9f, 2.0f, 0.5f},
                                           {nan, 0.5f, nan, 0.5f},
                                           {0.5f, inf, 1.0f, 0.5f},
                                           {-inf, 0.25f, 0.0f, nan},
                                           {0.7f, 0.2f, 0.0f, 0.55f}};
    return c;
}

// One dispatch of cp_gather.comp with every sampler in `mode` (nearest for the gathers: gather ignores the filter;
// linear for float_tex, nearest for float_nearest_tex); returns the results, kResults vec4 per coordinate.
Bytes gather_all(Kit& k, VkSamplerAddressMode mode) {
    const VkShaderStageFlags C = VK_SHADER_STAGE_COMPUTE_BIT;
    const VkDescriptorType S = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    VkDescriptorSetLayout dsl = k.set_layout({{0, S, 1, C},
                                              {1, S, 1, C},
                                              {2, S, 1, C},
                                              {3, S, 1, C},
                                              {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, C},
                                              {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, C},
                                              {6, S, 1, C},
                                              {7, S, 1, C}});
    VkPipelineLayout layout = k.pipeline_layout({dsl});
    VkDescriptorSet set = k.descriptor_set(dsl);
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Device::Image color = k.image(VK_FORMAT_R8G8B8A8_UNORM, kW, kH, usage);
    upload_rgba8(k, color.image, kW, kH, 3);
    Device::Image array = k.image(VK_FORMAT_R8G8B8A8_UNORM, 4, 4, usage, 1, 3);
    upload_rgba8(k, array.image, 4, 4, 4, 3);
    Device::Image uint_tex = k.image(VK_FORMAT_R8G8B8A8_UINT, 4, 4, usage);
    upload(k, k.buffer_of(texel_data(VK_FORMAT_R8G8B8A8_UINT, 16, 5), 0), uint_tex.image, VK_IMAGE_ASPECT_COLOR_BIT, 4,
           4);
    const VkFormat F = VK_FORMAT_R32G32B32A32_SFLOAT;
    Device::Image float_tex = k.image(F, kW, kH, usage);
    upload(k, k.buffer_of(texel_data(F, kW * kH, 7), 0), float_tex.image, VK_IMAGE_ASPECT_COLOR_BIT, kW, kH);
    Device::Image depth = k.image(VK_FORMAT_D32_SFLOAT, 4, 4, usage);
    upload(k, k.buffer_of(texel_data(VK_FORMAT_D32_SFLOAT, 16, 6), 0), depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, 4, 4);
    VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
    sci.addressModeU = sci.addressModeV = sci.addressModeW = mode;
    sci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    VkSampler plain = VK_NULL_HANDLE, compare = VK_NULL_HANDLE, linear = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateSampler(k.d, &sci, nullptr, &plain), VK_SUCCESS);
    sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;
    EXPECT_EQ(vkCreateSampler(k.d, &sci, nullptr, &linear), VK_SUCCESS);
    sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
    sci.compareEnable = VK_TRUE;
    sci.compareOp = VK_COMPARE_OP_LESS;
    EXPECT_EQ(vkCreateSampler(k.d, &sci, nullptr, &compare), VK_SUCCESS);
    k.undo(VK_OBJECT_TYPE_SAMPLER, plain, [&k, plain] { vkDestroySampler(k.d, plain, nullptr); });
    k.undo(VK_OBJECT_TYPE_SAMPLER, compare, [&k, compare] { vkDestroySampler(k.d, compare, nullptr); });
    k.undo(VK_OBJECT_TYPE_SAMPLER, linear, [&k, linear] { vkDestroySampler(k.d, linear, nullptr); });
    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkDescriptorImageInfo ii[4] = {
        {plain, k.view(color.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT), ro},
        {plain,
         k.view(array.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 1, 0,
                3),
         ro},
        {plain, k.view(uint_tex.image, VK_FORMAT_R8G8B8A8_UINT, VK_IMAGE_ASPECT_COLOR_BIT), ro},
        {compare, k.view(depth.image, VK_FORMAT_D32_SFLOAT, VK_IMAGE_ASPECT_DEPTH_BIT), ro}};
    for (uint32_t b = 0; b < 4; ++b) k.write(set, b, S, nullptr, &ii[b]);
    const VkDescriptorImageInfo fi{linear, k.view(float_tex.image, F, VK_IMAGE_ASPECT_COLOR_BIT), ro};
    k.write(set, 6, S, nullptr, &fi);
    const VkDescriptorImageInfo fn{plain, fi.imageView, ro};
    k.write(set, 7, S, nullptr, &fn);
    return dispatch_per_coordinate(k, SPV(cp_gather_comp), layout, set, 4, coordinates(), size_t(kResults) * 16);
}

// upload_rgba8's byte at (x, y), channel ch of a w-wide image.
float rgba8_texel(uint32_t seed, uint32_t w, int32_t x, int32_t y, int ch) {
    const size_t i = (size_t(y) * w + size_t(x)) * 4 + size_t(ch);
    return float((i * 37 + seed * 101 + (i >> 5) * 11) & 255) * (1.0f / 255.0f);
}

// The spec's linear footprint on one axis for a coordinate whose u - 0.5 is not an integer: i0 = floor(u - 0.5),
// i1 = i0 + 1, each wrapped (REPEAT) or clamped (CLAMP_TO_EDGE).
int32_t wrapped(int32_t i, int32_t n, VkSamplerAddressMode m) {
    if (m == VK_SAMPLER_ADDRESS_MODE_REPEAT) return ((i % n) + n) % n;
    return std::clamp(i, 0, n - 1);
}

class ApiGather : public ApiBreadth {};

TEST_F(ApiGather, EveryFormAndAddressModeAsLavapipe) {
    const auto coords = coordinates();
    for (VkSamplerAddressMode mode : {VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT,
                                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER}) {
        SCOPED_TRACE("address mode " + std::to_string(int(mode)));
        const Bytes got = both([&](Kit& k) { return gather_all(k, mode); });
        ASSERT_EQ(got.size(), coords.size() * kResults * 16);
        if (mode != VK_SAMPLER_ADDRESS_MODE_REPEAT && mode != VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) continue;
        // textureGather(color_tex, c.xy, comp): (i0, j1), (i1, j1), (i1, j0), (i0, j0) of the footprint
        size_t checked = 0;
        for (size_t n = 0; n < coords.size(); ++n) {
            const float u = coords[n][0] * kW - 0.5f, v = coords[n][1] * kH - 0.5f;
            if (!std::isfinite(u) || !std::isfinite(v) || std::fabs(u) > 1e5f || std::fabs(v) > 1e5f ||
                u == std::floor(u) || v == std::floor(v))
                continue;
            const int32_t i0 = int32_t(std::floor(u)), j0 = int32_t(std::floor(v));
            const int32_t x[2] = {wrapped(i0, kW, mode), wrapped(i0 + 1, kW, mode)};
            const int32_t y[2] = {wrapped(j0, kH, mode), wrapped(j0 + 1, kH, mode)};
            for (int comp = 0; comp < 4; ++comp) {
                float r[4];
                std::memcpy(r, got.data() + (n * kResults + size_t(comp)) * 16, 16);
                const float want[4] = {rgba8_texel(3, kW, x[0], y[1], comp), rgba8_texel(3, kW, x[1], y[1], comp),
                                       rgba8_texel(3, kW, x[1], y[0], comp), rgba8_texel(3, kW, x[0], y[0], comp)};
                for (int e = 0; e < 4; ++e)
                    EXPECT_EQ(r[e], want[e]) << "coordinate " << n << " component " << comp << " texel " << e;
            }
            ++checked;
        }
        EXPECT_GE(checked, 6u);  // the coordinates away from crossovers and the non-finite ones
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
