// Storage images through the API (suite ApiStorageImage): imageStore into every storage format, imageLoad ->
// transform -> imageStore between four images with loads and stores outside them, imageSize of level/layer views,
// and storage images between compute and draws (written by compute then read by a fragment shader, rendered by a
// draw then read by compute) — on tilevk and lavapipe with the validation layer, bytes compared, plus every result
// checked against values computed here from the stated rules (texel_codec.h "shader image stores").
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

#include "si_frag_load_frag.h"
#include "si_gradient_comp.h"
#include "si_load_a2b10g10r10_uint_comp.h"
#include "si_load_a2b10g10r10_unorm_comp.h"
#include "si_load_b10g11r11_ufloat_comp.h"
#include "si_load_r16_sfloat_comp.h"
#include "si_load_r16_sint_comp.h"
#include "si_load_r16_snorm_comp.h"
#include "si_load_r16_uint_comp.h"
#include "si_load_r16_unorm_comp.h"
#include "si_load_r16g16_sfloat_comp.h"
#include "si_load_r16g16_sint_comp.h"
#include "si_load_r16g16_snorm_comp.h"
#include "si_load_r16g16_uint_comp.h"
#include "si_load_r16g16_unorm_comp.h"
#include "si_load_r16g16b16a16_snorm_comp.h"
#include "si_load_r16g16b16a16_unorm_comp.h"
#include "si_load_r8_sint_comp.h"
#include "si_load_r8_snorm_comp.h"
#include "si_load_r8_uint_comp.h"
#include "si_load_r8_unorm_comp.h"
#include "si_load_r8g8_sint_comp.h"
#include "si_load_r8g8_snorm_comp.h"
#include "si_load_r8g8_uint_comp.h"
#include "si_load_r8g8_unorm_comp.h"
#include "si_readback_comp.h"
#include "si_size_comp.h"
#include "si_store_a2b10g10r10_uint_comp.h"
#include "si_store_a2b10g10r10_unorm_comp.h"
#include "si_store_b10g11r11_ufloat_comp.h"
#include "si_store_nofmt_f_comp.h"
#include "si_store_nofmt_i_comp.h"
#include "si_store_nofmt_u_comp.h"
#include "si_store_r16_sfloat_comp.h"
#include "si_store_r16_sint_comp.h"
#include "si_store_r16_snorm_comp.h"
#include "si_store_r16_uint_comp.h"
#include "si_store_r16_unorm_comp.h"
#include "si_store_r16g16_sfloat_comp.h"
#include "si_store_r16g16_sint_comp.h"
#include "si_store_r16g16_snorm_comp.h"
#include "si_store_r16g16_uint_comp.h"
#include "si_store_r16g16_unorm_comp.h"
#include "si_store_r16g16b16a16_sfloat_comp.h"
#include "si_store_r16g16b16a16_sint_comp.h"
#include "si_store_r16g16b16a16_snorm_comp.h"
#include "si_store_r16g16b16a16_uint_comp.h"
#include "si_store_r16g16b16a16_unorm_comp.h"
#include "si_store_r32_sfloat_comp.h"
#include "si_store_r32_sint_comp.h"
#include "si_store_r32_uint_comp.h"
#include "si_store_r32g32_sfloat_comp.h"
#include "si_store_r32g32_sint_comp.h"
#include "si_store_r32g32_uint_comp.h"
#include "si_store_r32g32b32a32_sfloat_comp.h"
#include "si_store_r32g32b32a32_sint_comp.h"
#include "si_store_r32g32b32a32_uint_comp.h"
#include "si_store_r8_sint_comp.h"
#include "si_store_r8_snorm_comp.h"
#include "si_store_r8_uint_comp.h"
#include "si_store_r8_unorm_comp.h"
#include "si_store_r8g8_sint_comp.h"
#include "si_store_r8g8_snorm_comp.h"
#include "si_store_r8g8_uint_comp.h"
#include "si_store_r8g8_unorm_comp.h"
#include "si_store_r8g8b8a8_sint_comp.h"
#include "si_store_r8g8b8a8_snorm_comp.h"
#include "si_store_r8g8b8a8_uint_comp.h"
#include "si_store_r8g8b8a8_unorm_comp.h"
#include "si_transform_comp.h"

struct ExtFormat;
class ApiStorageImage : public ApiBreadth {
  protected:
    void check_extended_store(const ExtFormat& ef);
    void load_transform_store(Device& tilevk, Device& lavapipe);
};

constexpr uint32_t kW = 16, kH = 8;  // every storage image here (the shaders' 2x2 workgroups of 8x4)
constexpr VkImageUsageFlags kStorageUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

// A layout change ordering everything before it against everything after it (lavapipe needs the barriers, the
// validation layer the layouts).
void image_barrier(VkCommandBuffer c, VkImage img, VkImageLayout from, VkImageLayout to, uint32_t levels = 1,
                   uint32_t layers = 1) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, layers};
    vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
}

// One set of the given descriptor types at bindings 0.. for `stages`, and its pipeline layout.
struct SetOf {
    VkDescriptorSetLayout dsl;
    VkPipelineLayout layout;
    VkDescriptorSet set;
};
SetOf set_of(Kit& k, const std::vector<VkDescriptorType>& types,
             VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (uint32_t i = 0; i < types.size(); ++i) bindings.push_back({i, types[i], 1, stages});
    SetOf s{};
    s.dsl = k.set_layout(bindings);
    s.layout = k.pipeline_layout({s.dsl});
    s.set = k.descriptor_set(s.dsl);
    return s;
}
void write_storage_image(Kit& k, VkDescriptorSet s, uint32_t binding, VkImageView v) {
    const VkDescriptorImageInfo ii{VK_NULL_HANDLE, v, VK_IMAGE_LAYOUT_GENERAL};
    k.write(s, binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &ii);
}
void write_buffer(Kit& k, VkDescriptorSet s, uint32_t binding, const Device::Buffer& b) {
    const VkDescriptorBufferInfo bi{b.buffer, 0, VK_WHOLE_SIZE};
    k.write(s, binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bi, nullptr);
}

// Copies `data` into level 0 of a kW x kH image and leaves it in GENERAL.
void fill(Kit& k, VkImage img, const std::vector<uint8_t>& data) {
    Device::Buffer src = k.buffer_of(data, 0);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        image_barrier(c, img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy r{};
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        r.imageExtent = {kW, kH, 1};
        vkCmdCopyBufferToImage(c, src.buffer, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
        image_barrier(c, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    }),
              VK_SUCCESS);
}

float f32(uint32_t u) {
    return std::bit_cast<float>(u);
}

// ---- The store rules, written out here (lavapipe's lp_build_insert_soa_chan; texel_codec.h states them) ----------

enum class Kind { Unorm, Snorm, Uint, Sint, Float };

// clamp(x, lo, hi) taking the upper bound first with MINPS/MAXPS semantics: NaN becomes hi.
float clamp_upper_first(float x, float lo, float hi) {
    const float m = x < hi ? x : hi;
    return m > lo ? m : lo;
}

// The largest half not above |x| (toward zero), by search over every finite half; past 65504: 65504.
uint16_t half_toward_zero(float x) {
    static const std::vector<float> halves = [] {
        std::vector<float> v;
        for (uint32_t h = 0; h < 0x7c00; ++h) {  // every finite non-negative half, increasing
            const uint32_t e = h >> 10, m = h & 0x3ff;
            v.push_back(e == 0 ? std::ldexp(float(m), -24) : std::ldexp(float(m | 0x400), int(e) - 25));
        }
        return v;
    }();
    const float a = std::fabs(x);
    const auto it = std::upper_bound(halves.begin(), halves.end(), a);
    const uint16_t mag = uint16_t((it - halves.begin()) - 1);
    return uint16_t((std::signbit(x) ? 0x8000 : 0) | mag);
}

uint32_t expected_channel(Kind kind, int bits, uint32_t word) {
    const uint32_t mask = bits == 32 ? 0xffffffffu : (1u << bits) - 1u;
    switch (kind) {
        case Kind::Unorm: {  // n = 8: the low 8 bits of fl(fl(c * 255/256) + 32768) = rne(c * 255) as floats do it
            const float c = clamp_upper_first(f32(word), 0.0f, 1.0f);
            return std::bit_cast<uint32_t>(c * (255.0f / 256.0f) + 32768.0f) & mask;
        }
        case Kind::Snorm: {
            const float c = clamp_upper_first(f32(word), -1.0f, 1.0f) * 127.0f;
            return uint32_t(int32_t(std::nearbyint(c))) & mask;
        }
        case Kind::Uint:
            return std::min(word, mask);
        case Kind::Sint: {
            if (bits == 32) return word;
            const int32_t hi = int32_t(mask >> 1);
            return uint32_t(std::clamp(int32_t(word), -hi - 1, hi)) & mask;
        }
        case Kind::Float:
            return bits == 16 ? half_toward_zero(f32(word)) : word;
    }
    return 0;
}

struct StoreFormat {
    VkFormat format;
    Spv spv;
    Kind kind;
    int channels, bits;
};

// The words a shader stores: edge cases first, then random values of the kind.
std::vector<uint32_t> store_words(const StoreFormat& sf, uint32_t seed) {
    std::vector<uint32_t> w;
    const bool norm = sf.kind == Kind::Unorm || sf.kind == Kind::Snorm;
    if (norm || (sf.kind == Kind::Float && sf.bits == 32)) {
        for (float f : {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1.5f, -0.2f, 0.5f / 255.0f, 1.5f / 255.0f, 2.5f / 127.0f,
                        -2.5f / 127.0f, 0.99f, 1e-30f, -1e30f, 3.0e38f})
            w.push_back(std::bit_cast<uint32_t>(f));
        for (uint32_t bitsv : {0x7fc00000u, 0xffc00001u, 0x7f800000u, 0xff800000u, 0x7f800001u})  // NaNs, infinities
            w.push_back(bitsv);
    } else if (sf.kind == Kind::Float) {  // halves: finite, normal inputs (exact, inexact, past 65504)
        for (float f : {0.0f, -0.0f, 1.0f, -2.25f, 0.1f, -0.1f, 65504.0f, 65519.0f, 70000.0f, -1e6f, 6.103515625e-05f,
                        3.14159f, 1e-3f, 2049.0f, 2051.0f})
            w.push_back(std::bit_cast<uint32_t>(f));
    } else {
        for (uint32_t u : {0u, 1u, 127u, 128u, 255u, 256u, 0xffffff7fu, 0xffffff80u, 0xffffff7eu, 32767u, 32768u,
                           65535u, 65536u, 0xffff7fffu, 0xffff8000u, 0x7fffffffu, 0x80000000u, 0xffffffffu})
            w.push_back(u);
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.3f, 1.3f), wide(-70000.0f, 70000.0f);
    while (w.size() < size_t(kW) * kH * 4) {
        if (norm)
            w.push_back(std::bit_cast<uint32_t>(unit(rng)));
        else if (sf.kind == Kind::Float)
            w.push_back(std::bit_cast<uint32_t>(sf.bits == 16 ? wide(rng) : wide(rng) * unit(rng)));
        else
            w.push_back(uint32_t(rng()) >> (rng() % 24));  // all magnitudes
    }
    return w;
}

// si_store.comp for one format: the words stored into a kW x kH image, read back.
Bytes store_scene(Kit& k, const StoreFormat& sf, const std::vector<uint32_t>& words) {
    Device::Image img = k.image(sf.format, kW, kH, kStorageUsage);
    const VkImageView v = k.view(img.image, sf.format, VK_IMAGE_ASPECT_COLOR_BIT);
    const Device::Buffer src = k.buffer_of(words, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const SetOf s = set_of(k, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    write_storage_image(k, s.set, 0, v);
    write_buffer(k, s.set, 1, src);
    const VkPipeline p = compute_pipeline(k, sf.spv, s.layout);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        image_barrier(c, img.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdDispatch(c, kW / 8, kH / 4, 1);
        image_barrier(c, img.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    }),
              VK_SUCCESS);
    return k.read(img.image, kW, kH, uint32_t(sf.channels * sf.bits / 8));
}

// Every storage format Vulkan requires (the ones tilevk reports): each texel as the store rules make it, on both
// drivers.
TEST_F(ApiStorageImage, EveryStorageFormatStoresByTheRules) {
    const StoreFormat formats[] = {
        {VK_FORMAT_R8G8B8A8_UNORM, SPV(si_store_r8g8b8a8_unorm_comp), Kind::Unorm, 4, 8},
        {VK_FORMAT_R8G8B8A8_SNORM, SPV(si_store_r8g8b8a8_snorm_comp), Kind::Snorm, 4, 8},
        {VK_FORMAT_R8G8B8A8_UINT, SPV(si_store_r8g8b8a8_uint_comp), Kind::Uint, 4, 8},
        {VK_FORMAT_R8G8B8A8_SINT, SPV(si_store_r8g8b8a8_sint_comp), Kind::Sint, 4, 8},
        {VK_FORMAT_R16G16B16A16_UINT, SPV(si_store_r16g16b16a16_uint_comp), Kind::Uint, 4, 16},
        {VK_FORMAT_R16G16B16A16_SINT, SPV(si_store_r16g16b16a16_sint_comp), Kind::Sint, 4, 16},
        {VK_FORMAT_R16G16B16A16_SFLOAT, SPV(si_store_r16g16b16a16_sfloat_comp), Kind::Float, 4, 16},
        {VK_FORMAT_R32_UINT, SPV(si_store_r32_uint_comp), Kind::Uint, 1, 32},
        {VK_FORMAT_R32_SINT, SPV(si_store_r32_sint_comp), Kind::Sint, 1, 32},
        {VK_FORMAT_R32_SFLOAT, SPV(si_store_r32_sfloat_comp), Kind::Float, 1, 32},
        {VK_FORMAT_R32G32_UINT, SPV(si_store_r32g32_uint_comp), Kind::Uint, 2, 32},
        {VK_FORMAT_R32G32_SINT, SPV(si_store_r32g32_sint_comp), Kind::Sint, 2, 32},
        {VK_FORMAT_R32G32_SFLOAT, SPV(si_store_r32g32_sfloat_comp), Kind::Float, 2, 32},
        {VK_FORMAT_R32G32B32A32_UINT, SPV(si_store_r32g32b32a32_uint_comp), Kind::Uint, 4, 32},
        {VK_FORMAT_R32G32B32A32_SINT, SPV(si_store_r32g32b32a32_sint_comp), Kind::Sint, 4, 32},
        {VK_FORMAT_R32G32B32A32_SFLOAT, SPV(si_store_r32g32b32a32_sfloat_comp), Kind::Float, 4, 32},
    };
    for (const StoreFormat& sf : formats) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), sf.format, &fp);
        EXPECT_TRUE(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) << "format " << sf.format;
        const std::vector<uint32_t> words = store_words(sf, uint32_t(sf.format));
        const Bytes got = both([&](Kit& k) { return store_scene(k, sf, words); });
        const size_t texel = size_t(sf.channels * sf.bits / 8);
        ASSERT_EQ(got.size(), texel * kW * kH);
        size_t wrong = 0;
        for (size_t t = 0; t < size_t(kW) * kH; ++t) {
            for (int ch = 0; ch < sf.channels; ++ch) {
                const uint32_t want = expected_channel(sf.kind, sf.bits, words[t * 4 + size_t(ch)]);
                uint32_t have = 0;
                std::memcpy(&have, &got[t * texel + size_t(ch * sf.bits / 8)], size_t(sf.bits / 8));
                if (have != want && wrong++ < 4)
                    ADD_FAILURE() << "format " << sf.format << " texel " << t << " channel " << ch << ": stored "
                                  << have << ", the rule says " << want << " (word " << words[t * 4 + size_t(ch)]
                                  << ")";
            }
        }
        EXPECT_EQ(wrong, 0u) << "format " << sf.format;
    }
}

// shaderStorageImageWriteWithoutFormat: one module per sampled type whose image has no format (Unknown) stores
// into views of several formats; the view's format converts, so each texel follows the same store rules as with
// the format declared, on both drivers (devices with the feature enabled). STORAGE_WRITE_WITHOUT_FORMAT is reported
// (VkFormatProperties3) exactly on the storage formats.
TEST_F(ApiStorageImage, WriteWithoutFormatConvertsByTheViewsFormat) {
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.features.shaderStorageImageWriteWithoutFormat = VK_TRUE;
    auto dev = device_pair({}, &f2);
    ASSERT_TRUE(dev->ok());
    const StoreFormat formats[] = {
        {VK_FORMAT_R8G8B8A8_UNORM, SPV(si_store_nofmt_f_comp), Kind::Unorm, 4, 8},
        {VK_FORMAT_R8G8B8A8_SNORM, SPV(si_store_nofmt_f_comp), Kind::Snorm, 4, 8},
        {VK_FORMAT_R16G16B16A16_SFLOAT, SPV(si_store_nofmt_f_comp), Kind::Float, 4, 16},
        {VK_FORMAT_R32_SFLOAT, SPV(si_store_nofmt_f_comp), Kind::Float, 1, 32},
        {VK_FORMAT_R32G32B32A32_SFLOAT, SPV(si_store_nofmt_f_comp), Kind::Float, 4, 32},
        {VK_FORMAT_R8G8B8A8_UINT, SPV(si_store_nofmt_u_comp), Kind::Uint, 4, 8},
        {VK_FORMAT_R16G16B16A16_UINT, SPV(si_store_nofmt_u_comp), Kind::Uint, 4, 16},
        {VK_FORMAT_R32_UINT, SPV(si_store_nofmt_u_comp), Kind::Uint, 1, 32},
        {VK_FORMAT_R32G32_SINT, SPV(si_store_nofmt_i_comp), Kind::Sint, 2, 32},
        {VK_FORMAT_R8G8B8A8_SINT, SPV(si_store_nofmt_i_comp), Kind::Sint, 4, 8},
        // Storage formats beyond Vulkan's lists (lavapipe's too), whose bytes are those of RGBA8.
        {VK_FORMAT_A8B8G8R8_UNORM_PACK32, SPV(si_store_nofmt_f_comp), Kind::Unorm, 4, 8},
        {VK_FORMAT_A8B8G8R8_SNORM_PACK32, SPV(si_store_nofmt_f_comp), Kind::Snorm, 4, 8},
        {VK_FORMAT_A8B8G8R8_UINT_PACK32, SPV(si_store_nofmt_u_comp), Kind::Uint, 4, 8},
        {VK_FORMAT_A8B8G8R8_SINT_PACK32, SPV(si_store_nofmt_i_comp), Kind::Sint, 4, 8},
    };
    for (const StoreFormat& sf : formats) {
        VkFormatProperties3 p3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
        VkFormatProperties2 p2{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2, &p3};
        vkGetPhysicalDeviceFormatProperties2(tilevk_->physical(), sf.format, &p2);
        EXPECT_TRUE(p3.optimalTilingFeatures & VK_FORMAT_FEATURE_2_STORAGE_WRITE_WITHOUT_FORMAT_BIT) << sf.format;
        EXPECT_FALSE(p3.optimalTilingFeatures & VK_FORMAT_FEATURE_2_STORAGE_READ_WITHOUT_FORMAT_BIT) << sf.format;
        const std::vector<uint32_t> words = store_words(sf, uint32_t(sf.format) + 5);
        const Bytes got = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) { return store_scene(k, sf, words); });
        const size_t texel = size_t(sf.channels * sf.bits / 8);
        ASSERT_EQ(got.size(), texel * kW * kH);
        size_t wrong = 0;
        for (size_t t = 0; t < size_t(kW) * kH; ++t)
            for (int ch = 0; ch < sf.channels; ++ch) {
                uint32_t have = 0;
                std::memcpy(&have, &got[t * texel + size_t(ch * sf.bits / 8)], size_t(sf.bits / 8));
                wrong += have != expected_channel(sf.kind, sf.bits, words[t * 4 + size_t(ch)]);
            }
        EXPECT_EQ(wrong, 0u) << "format " << sf.format;
    }
    VkFormatProperties3 p3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
    VkFormatProperties2 p2{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2, &p3};
    vkGetPhysicalDeviceFormatProperties2(tilevk_->physical(), VK_FORMAT_R8G8B8A8_SRGB, &p2);  // not a storage format
    EXPECT_FALSE(p3.optimalTilingFeatures & VK_FORMAT_FEATURE_2_STORAGE_WRITE_WITHOUT_FORMAT_BIT);
    vkGetPhysicalDeviceFormatProperties2(tilevk_->physical(), VK_FORMAT_R32_UINT, &p2);
    EXPECT_TRUE(p3.bufferFeatures & VK_FORMAT_FEATURE_2_STORAGE_WRITE_WITHOUT_FORMAT_BIT);
}

// si_transform.comp: four storage images at once (maxPerStageDescriptorStorageImages = 4). RGBA8 and R32_UINT
// sources loaded one texel off (loads outside the image give 0, alpha 1 where the format has no alpha), the results
// transformed into RGBA32F / RGBA32UI, plus stores outside the destination, which change nothing.
void ApiStorageImage::load_transform_store(Device& tilevk, Device& lavapipe) {
    std::vector<uint8_t> rgba8(size_t(kW) * kH * 4), r32(size_t(kW) * kH * 4);
    std::mt19937 rng(12);
    for (auto& b : rgba8) b = uint8_t(rng());
    for (auto& b : r32) b = uint8_t(rng() | (rng() % 7 == 0 ? 0xff : 0));  // some 0xffffffff (wraps to 0)
    const Bytes got = both_on(tilevk, lavapipe, [&](Kit& k) {
        Device::Image src = k.image(VK_FORMAT_R8G8B8A8_UNORM, kW, kH, kStorageUsage);
        Device::Image srcu = k.image(VK_FORMAT_R32_UINT, kW, kH, kStorageUsage);
        Device::Image dst = k.image(VK_FORMAT_R32G32B32A32_SFLOAT, kW, kH, kStorageUsage);
        Device::Image dstu = k.image(VK_FORMAT_R32G32B32A32_UINT, kW, kH, kStorageUsage);
        fill(k, src.image, rgba8);
        fill(k, srcu.image, r32);
        const VkDescriptorType si = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        const SetOf s = set_of(k, {si, si, si, si});
        write_storage_image(k, s.set, 0, k.view(src.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT));
        write_storage_image(k, s.set, 1, k.view(srcu.image, VK_FORMAT_R32_UINT, VK_IMAGE_ASPECT_COLOR_BIT));
        write_storage_image(k, s.set, 2, k.view(dst.image, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_ASPECT_COLOR_BIT));
        write_storage_image(k, s.set, 3, k.view(dstu.image, VK_FORMAT_R32G32B32A32_UINT, VK_IMAGE_ASPECT_COLOR_BIT));
        const VkPipeline p = compute_pipeline(k, SPV(si_transform_comp), s.layout);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            for (VkImage i : {dst.image, dstu.image})
                image_barrier(c, i, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
            vkCmdDispatch(c, kW / 8, kH / 4, 1);
            for (VkImage i : {dst.image, dstu.image})
                image_barrier(c, i, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        }),
                  VK_SUCCESS);
        return concat({k.read(dst.image, kW, kH, 16), k.read(dstu.image, kW, kH, 16)});
    });
    ASSERT_EQ(got.size(), size_t(kW) * kH * 32);
    const auto inside = [](int x, int y) { return x >= 0 && y >= 0 && x < int(kW) && y < int(kH); };
    size_t wrong = 0;
    for (int y = 0; y < int(kH); ++y) {
        for (int x = 0; x < int(kW); ++x) {
            const size_t t = size_t(y) * kW + size_t(x);
            float want[4];
            for (int c = 0; c < 4; ++c) {  // UNORM8 loads c * fl(1/255); outside: (0, 0, 0, 0) (RGBA8 has alpha)
                const float v =
                    inside(x - 2, y + 1)
                        ? float(rgba8[(size_t(y + 1) * kW + size_t(x - 2)) * 4 + size_t(c)]) * float(1.0 / 255.0)
                        : 0.0f;
                want[c] = v * 2.0f - 0.25f;
            }
            uint32_t wantu[4] = {1, 1, 1, 2};  // outside: (0, 0, 0, 1) + 1
            if (inside(x + 3, y - 1))
                std::memcpy(&wantu[0], &r32[(size_t(y - 1) * kW + size_t(x + 3)) * 4], 4), ++wantu[0];
            wrong += std::memcmp(&got[t * 16], want, 16) != 0;
            wrong += std::memcmp(&got[size_t(kW) * kH * 16 + t * 16], wantu, 16) != 0;
        }
    }
    EXPECT_EQ(wrong, 0u);
}

TEST_F(ApiStorageImage, LoadTransformStoreWithOutOfBoundsAccesses) {
    load_transform_store(*tilevk_, *lavapipe_);
}

// The same with robustImageAccess (VK_EXT_image_robustness, Vulkan 1.3) enabled: its texel replacement for loads
// outside the image ((0, 0, 0, 0), or alpha 1 for a format without alpha) and stores outside doing nothing are what
// the loads and stores above check, on both drivers.
TEST_F(ApiStorageImage, RobustImageAccessFeature) {
    VkPhysicalDeviceImageRobustnessFeatures rf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGE_ROBUSTNESS_FEATURES};
    rf.robustImageAccess = VK_TRUE;
    auto dev = device_pair({VK_EXT_IMAGE_ROBUSTNESS_EXTENSION_NAME}, &rf);
    ASSERT_TRUE(dev->ok());
    load_transform_store(dev->tilevk, dev->lavapipe);
}

// si_size.comp: imageSize of a 2D-array view of level 1, layers 1-2 of a 32x16 image with 3 levels and 4 layers
// (16, 8, 2), of a 2D view of level 2, layer 3 (8, 4), and a load from the array view's second layer (image layer
// 2 of level 1, cleared to 51, 102, 153, 204 while the other layers hold other values).
TEST_F(ApiStorageImage, SizeAndLoadOfLevelAndLayerViews) {
    const Bytes got = both([&](Kit& k) {
        const VkFormat f = VK_FORMAT_R8G8B8A8_UNORM;
        Device::Image img = k.image(f, 32, 16, kStorageUsage, 3, 4);
        const Device::Buffer out = k.buffer(48, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        const SetOf s = set_of(
            k, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        write_storage_image(k, s.set, 0,
                            k.view(img.image, f, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 1, 1, 1, 2));
        write_storage_image(k, s.set, 1,
                            k.view(img.image, f, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_VIEW_TYPE_2D, 2, 1, 3, 1));
        write_buffer(k, s.set, 2, out);
        const VkPipeline p = compute_pipeline(k, SPV(si_size_comp), s.layout);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            image_barrier(c, img.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 3, 4);
            const VkClearColorValue other{{1.0f, 0.0f, 1.0f, 0.0f}};
            const VkClearColorValue layer2{{0.2f, 0.4f, 0.6f, 0.8f}};
            const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 3, 0, 4};
            const VkImageSubresourceRange one{VK_IMAGE_ASPECT_COLOR_BIT, 1, 1, 2, 1};
            vkCmdClearColorImage(c, img.image, VK_IMAGE_LAYOUT_GENERAL, &other, 1, &all);
            image_barrier(c, img.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL, 3, 4);
            vkCmdClearColorImage(c, img.image, VK_IMAGE_LAYOUT_GENERAL, &layer2, 1, &one);
            image_barrier(c, img.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL, 3, 4);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
            vkCmdDispatch(c, 1, 1, 1);
        }),
                  VK_SUCCESS);
        return Kit::bytes(out);
    });
    ASSERT_EQ(got.size(), 48u);
    int32_t sizes[8];
    std::memcpy(sizes, got.data(), 32);
    const int32_t want_sizes[8] = {16, 8, 2, 0, 8, 4, 0, 0};
    for (int i = 0; i < 8; ++i) EXPECT_EQ(sizes[i], want_sizes[i]) << "component " << i;
    float texel[4];
    std::memcpy(texel, got.data() + 32, 16);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(texel[c], float(51 * (c + 1)) * float(1.0 / 255.0)) << "channel " << c;
}

// The rule's UNORM8 store of x (texel_codec.h), for the expected gradient.
uint8_t unorm8_store(float x) {
    return uint8_t(expected_channel(Kind::Unorm, 8, std::bit_cast<uint32_t>(x)));
}

// Compute writes a gradient into a storage image (si_gradient.comp), a draw reads it with imageLoad in its fragment
// shader (si_frag_load.frag, swizzled .bgra) into a colour target; then a draw renders a triangle into an image
// that compute reads back with imageLoad (si_readback.comp) into a buffer. Pipeline barriers between them.
TEST_F(ApiStorageImage, ComputeThenDrawAndDrawThenCompute) {
    const Bytes got = both([&](Kit& k) {
        const VkFormat f = VK_FORMAT_R8G8B8A8_UNORM;
        Device::Image grad = k.image(f, kW, kH, kStorageUsage);
        const SetOf cs = set_of(k, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
        write_storage_image(k, cs.set, 0, k.view(grad.image, f, VK_IMAGE_ASPECT_COLOR_BIT));
        const VkPipeline gp = compute_pipeline(k, SPV(si_gradient_comp), cs.layout);
        const SetOf fs = set_of(k, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, VK_SHADER_STAGE_FRAGMENT_BIT);
        write_storage_image(k, fs.set, 0, k.view(grad.image, f, VK_IMAGE_ASPECT_COLOR_BIT));
        Target tg = target(k, f, kW, kH);
        const VkPipeline dp = k.pipeline(fullscreen_pipe(SPV(si_frag_load_frag), tg, fs.layout));
        // the second half: a triangle rendered into an image compute reads
        Device::Image drawn =
            k.image(f, kW, kH,
                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        const VkImageView drawn_view = k.view(drawn.image, f, VK_IMAGE_ASPECT_COLOR_BIT);
        const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        const VkRenderPass rp = k.render_pass(
            {attachment(f, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_GENERAL)},
            {subpass(&ref)});
        const VkFramebuffer fb = k.framebuffer(rp, {drawn_view}, kW, kH);
        Pipe tri;
        tri.rp = rp;
        tri.width = kW;
        tri.height = kH;
        const VkPipeline trip = k.pipeline(tri);
        const Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        const Device::Buffer out = k.buffer(size_t(kW) * kH * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        const SetOf rs = set_of(k, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        write_storage_image(k, rs.set, 0, drawn_view);
        write_buffer(k, rs.set, 1, out);
        const VkPipeline rp_read = compute_pipeline(k, SPV(si_readback_comp), rs.layout);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            image_barrier(c, grad.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, gp);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, cs.layout, 0, 1, &cs.set, 0, nullptr);
            vkCmdDispatch(c, kW / 8, kH / 4, 1);
            image_barrier(c, grad.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL);
            draw_fullscreen(c, tg, dp, fs.layout, fs.set);
            begin_pass(c, rp, fb, kW, kH, {clear_color(0.1f, 0.2f, 0.3f, 1.0f)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, trip);
            bind_vertices(c, vb);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
            image_barrier(c, drawn.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, rp_read);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, rs.layout, 0, 1, &rs.set, 0, nullptr);
            vkCmdDispatch(c, kW / 8, kH / 4, 1);
            image_barrier(c, drawn.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        }),
                  VK_SUCCESS);
        return concat({k.read(tg.image.image, kW, kH, 4), k.read(drawn.image, kW, kH, 4), Kit::bytes(out)});
    });
    const size_t n = size_t(kW) * kH;
    ASSERT_EQ(got.size(), n * 24);
    size_t wrong = 0;
    for (uint32_t y = 0; y < kH; ++y) {
        for (uint32_t x = 0; x < kW; ++x) {
            const size_t t = size_t(y) * kW + x;
            // the gradient as stored, read back through imageLoad (c / 255) and written out again (.bgra)
            const uint8_t g[4] = {unorm8_store(float(x) / 15.0f), unorm8_store(float(y) / 7.0f),
                                  unorm8_store(float(x + y) / 22.0f), 255};
            const uint8_t want[4] = {g[2], g[1], g[0], g[3]};
            wrong += std::memcmp(&got[t * 4], want, 4) != 0;
            // compute's imageLoad of the drawn image, rounded back to bytes: the drawn bytes
            uint32_t words[4];
            std::memcpy(words, &got[n * 8 + t * 16], 16);
            for (int c = 0; c < 4; ++c) wrong += words[c] != got[n * 4 + t * 4 + size_t(c)];
        }
    }
    EXPECT_EQ(wrong, 0u);
}

// ---- shaderStorageImageExtendedFormats --------------------------------------------------------------------------

// One channel of a texel read as a little-endian integer: its RGBA index, first bit and width (the spec's format
// definitions: array formats from the lowest address, packed formats from the top bit down).
struct ExtChannel {
    int rgba, shift, bits;
};
struct ExtFormat {
    VkFormat format;
    Spv store, load;
    Kind kind;
    bool ufloat;  // B10G11R11: unsigned 11/11/10-bit floats, 5-bit exponents
    uint32_t bytes;
    std::vector<ExtChannel> channels;
};

std::vector<ExtFormat> extended_formats() {
    const std::vector<ExtChannel> r8{{0, 0, 8}}, rg8{{0, 0, 8}, {1, 8, 8}}, r16{{0, 0, 16}},
        rg16{{0, 0, 16}, {1, 16, 16}}, rgba16{{0, 0, 16}, {1, 16, 16}, {2, 32, 16}, {3, 48, 16}},
        a2b10g10r10{{0, 0, 10}, {1, 10, 10}, {2, 20, 10}, {3, 30, 2}}, b10g11r11{{0, 0, 11}, {1, 11, 11}, {2, 22, 10}};
#define EXT(F, name, kind, uf, bytes, ch) \
    { VK_FORMAT_##F, SPV(si_store_##name##_comp), SPV(si_load_##name##_comp), Kind::kind, uf, bytes, ch }
    return {
        EXT(R16G16_SFLOAT, r16g16_sfloat, Float, false, 4, rg16),
        EXT(B10G11R11_UFLOAT_PACK32, b10g11r11_ufloat, Float, true, 4, b10g11r11),
        EXT(R16_SFLOAT, r16_sfloat, Float, false, 2, r16),
        EXT(R16G16B16A16_UNORM, r16g16b16a16_unorm, Unorm, false, 8, rgba16),
        EXT(A2B10G10R10_UNORM_PACK32, a2b10g10r10_unorm, Unorm, false, 4, a2b10g10r10),
        EXT(R16G16_UNORM, r16g16_unorm, Unorm, false, 4, rg16),
        EXT(R8G8_UNORM, r8g8_unorm, Unorm, false, 2, rg8),
        EXT(R16_UNORM, r16_unorm, Unorm, false, 2, r16),
        EXT(R8_UNORM, r8_unorm, Unorm, false, 1, r8),
        EXT(R16G16B16A16_SNORM, r16g16b16a16_snorm, Snorm, false, 8, rgba16),
        EXT(R16G16_SNORM, r16g16_snorm, Snorm, false, 4, rg16),
        EXT(R8G8_SNORM, r8g8_snorm, Snorm, false, 2, rg8),
        EXT(R16_SNORM, r16_snorm, Snorm, false, 2, r16),
        EXT(R8_SNORM, r8_snorm, Snorm, false, 1, r8),
        EXT(R16G16_SINT, r16g16_sint, Sint, false, 4, rg16),
        EXT(R8G8_SINT, r8g8_sint, Sint, false, 2, rg8),
        EXT(R16_SINT, r16_sint, Sint, false, 2, r16),
        EXT(R8_SINT, r8_sint, Sint, false, 1, r8),
        EXT(A2B10G10R10_UINT_PACK32, a2b10g10r10_uint, Uint, false, 4, a2b10g10r10),
        EXT(R16G16_UINT, r16g16_uint, Uint, false, 4, rg16),
        EXT(R8G8_UINT, r8g8_uint, Uint, false, 2, rg8),
        EXT(R16_UINT, r16_uint, Uint, false, 2, r16),
        EXT(R8_UINT, r8_uint, Uint, false, 1, r8),
    };
#undef EXT
}

// lavapipe's float -> unsigned small float (lp_bld_format_float.c lp_build_float_to_smallfloat, as the rule states
// it): negative and -Inf -> 0, +Inf -> Inf, NaN -> exponent and top mantissa bit set; otherwise the mantissa cut to
// `mbits` bits, the largest finite value past it, and below 2^-14 the float product x * 2^-112 (a float denormal:
// round to nearest even at 2^-149) whose mantissa keeps its top `mbits` bits.
uint32_t expected_ufloat(uint32_t word, int mbits) {
    const uint32_t exp_ones = 31u << mbits;
    if ((word & 0x7fffffffu) > 0x7f800000u) return exp_ones | (1u << (mbits - 1));
    if (word == 0x7f800000u) return exp_ones;
    if (word >> 31) return 0;
    const uint32_t cut = word & ~((1u << (23 - mbits)) - 1u);
    const double v = double(f32(cut));
    const double largest = std::ldexp(double((2u << mbits) - 1u), 15 - mbits);  // 2^15 * (2 - 2^-mbits)
    if (v >= largest) return (30u << mbits) | ((1u << mbits) - 1u);
    if (v >= std::ldexp(1.0, -14)) {
        int e = 0;
        const double m = std::frexp(v, &e);  // v = m * 2^e, m in [0.5, 1)
        return uint32_t(e - 1 + 15) << mbits | (uint32_t(std::ldexp(m, mbits + 1)) & ((1u << mbits) - 1u));
    }
    const auto denormal = uint32_t(std::nearbyint(std::ldexp(v, 37)));  // x * 2^-112 in units of 2^-149
    return denormal >> (23 - mbits);
}

// The words stored into a format: the kind's edge cases, then random values (store_words); for the small floats
// their own edges (the largest finite values, denormals, the cut mantissa) and values up to 70000.
std::vector<uint32_t> extended_store_words(const ExtFormat& ef) {
    if (!ef.ufloat)
        return store_words(StoreFormat{ef.format, {}, ef.kind, 4, ef.channels[0].bits}, uint32_t(ef.format));
    std::vector<uint32_t> w;
    for (float f : {0.0f,     -0.0f,    1.0f,     -1.0f,    0.1f,        65024.0f,         65023.0f,
                    64512.0f, 64600.0f, 65100.0f, 70000.0f, 1e-5f,       6.103515625e-05f, 6.0e-05f,
                    3.0e-6f,  1e-9f,    1e-30f,   3.0e38f,  1.00390625f, 1.0078125f,       1.015625f})
        w.push_back(std::bit_cast<uint32_t>(f));
    for (uint32_t b : {0x7fc00000u, 0xffc00001u, 0x7f800000u, 0xff800000u, 0x7f800001u, 0x00000001u}) w.push_back(b);
    std::mt19937 rng(uint32_t(ef.format));
    std::uniform_real_distribution<float> small(-0.01f, 1e-4f), wide(-100.0f, 70000.0f);
    while (w.size() < size_t(kW) * kH * 4) w.push_back(std::bit_cast<uint32_t>(rng() % 3 ? wide(rng) : small(rng)));
    return w;
}

uint32_t expected_ext_store(const ExtFormat& ef, const ExtChannel& ch, uint32_t word) {
    if (ef.ufloat) return expected_ufloat(word, ch.bits - 5);
    const uint32_t mask = ch.bits == 32 ? 0xffffffffu : (1u << ch.bits) - 1u;
    switch (ef.kind) {
        case Kind::Unorm: {  // the low n bits of fl(fl(c * (2^n-1)/2^n) + 2^(23-n)): rne(c * (2^n-1)) in floats
            const float c = clamp_upper_first(f32(word), 0.0f, 1.0f);
            const float scale = float(double(mask) / double(mask + 1u));
            return std::bit_cast<uint32_t>(c * scale + float(1u << (23 - ch.bits))) & mask;
        }
        case Kind::Snorm:
            return uint32_t(int32_t(std::nearbyint(clamp_upper_first(f32(word), -1.0f, 1.0f) * float(mask >> 1)))) &
                   mask;
        default:
            return expected_channel(ef.kind, ch.bits, word);
    }
}

uint64_t texel_bits(const Bytes& b, size_t at, uint32_t bytes) {
    uint64_t v = 0;
    std::memcpy(&v, &b[at], bytes);
    return v;
}

// si_store.comp into one extended format, every texel checked against
// the rules above; the bytes are compared with lavapipe by both().
void ApiStorageImage::check_extended_store(const ExtFormat& ef) {
    const std::vector<uint32_t> words = extended_store_words(ef);
    const StoreFormat sf{ef.format, ef.store, ef.kind, 1, int(ef.bytes * 8)};
    const Bytes got = both([&](Kit& k) { return store_scene(k, sf, words); });
    ASSERT_EQ(got.size(), size_t(ef.bytes) * kW * kH) << "format " << ef.format;
    size_t wrong = 0;
    for (size_t i = 0; i < size_t(kW) * kH; ++i) {
        const uint64_t texel = texel_bits(got, i * ef.bytes, ef.bytes);
        for (const ExtChannel& ch : ef.channels) {
            const uint32_t word = words[i * 4 + size_t(ch.rgba)];
            const auto have = uint32_t((texel >> ch.shift) & ((uint64_t(1) << ch.bits) - 1u));
            const uint32_t want = expected_ext_store(ef, ch, word);
            if (have != want && wrong++ < 4)
                ADD_FAILURE() << "format " << ef.format << " texel " << i << " channel " << ch.rgba << ": stored 0x"
                              << std::hex << have << ", the rule says 0x" << want << " (word 0x" << word << ")"
                              << std::dec;
        }
    }
    EXPECT_EQ(wrong, 0u) << "format " << ef.format;
}

// Every format of shaderStorageImageExtendedFormats reports STORAGE_IMAGE on tilevk and stores by the rules.
TEST_F(ApiStorageImage, EveryExtendedFormatStoresByTheRules) {
    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(tilevk_->physical(), &features);
    EXPECT_TRUE(features.shaderStorageImageExtendedFormats);
    for (const ExtFormat& ef : extended_formats()) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), ef.format, &fp);
        EXPECT_TRUE(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) << "format " << ef.format;
        check_extended_store(ef);
    }
}

// A half's value (exact; NaNs quieted with their payload kept, as VCVTPH2PS).
uint32_t half_bits_to_float_bits(uint32_t h) {
    const uint32_t sign = (h & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
    if (e == 31) return sign | 0x7f800000u | (m << 13) | (m ? 0x400000u : 0u);
    const float mag = e == 0 ? std::ldexp(float(m), -24) : std::ldexp(float(m | 0x400u), int(e) - 25);
    return sign | std::bit_cast<uint32_t>(mag);
}

// An unsigned small float's value (5-bit exponent, `mbits` mantissa): exact; Inf and NaN with the mantissa on top.
uint32_t ufloat_bits_to_float_bits(uint32_t v, int mbits) {
    const uint32_t e = (v >> mbits) & 0x1fu, m = v & ((1u << mbits) - 1u);
    if (e == 31) return 0x7f800000u | (m << (23 - mbits));
    return std::bit_cast<uint32_t>(e == 0 ? std::ldexp(float(m), -14 - mbits)
                                          : std::ldexp(float(m | (1u << mbits)), int(e) - 15 - mbits));
}

// One loaded channel, as a texel fetch decodes it: UNORM c * fl(1/(2^n-1)), SNORM max(c * fl(1/(2^(n-1)-1)), -1),
// integers zero- or sign-extended.
uint32_t expected_ext_load(const ExtFormat& ef, const ExtChannel& ch, uint32_t c) {
    const uint32_t mask = (1u << ch.bits) - 1u;
    const auto sext = [&] { return int32_t(c << (32 - ch.bits)) >> (32 - ch.bits); };
    if (ef.ufloat) return ufloat_bits_to_float_bits(c, ch.bits - 5);
    switch (ef.kind) {
        case Kind::Unorm:
            return std::bit_cast<uint32_t>(float(c) * float(1.0 / double(mask)));
        case Kind::Snorm:
            return std::bit_cast<uint32_t>(std::max(float(sext()) * float(1.0 / double(mask >> 1)), -1.0f));
        case Kind::Float:
            return half_bits_to_float_bits(c);
        case Kind::Uint:
            return c;
        case Kind::Sint:
            return uint32_t(sext());
    }
    return 0;
}

// si_load.comp on every extended format filled with random bytes, each invocation loading the texel to its left
// (column 0 loads outside: (0, 0, 0) and alpha 0, or 1 when the format has no alpha); missing channels read 0 and
// alpha 1 (the integer 1 for integer formats).
TEST_F(ApiStorageImage, EveryExtendedFormatLoadsLikeATexelFetch) {
    for (const ExtFormat& ef : extended_formats()) {
        std::vector<uint8_t> data(size_t(ef.bytes) * kW * kH);
        std::mt19937 rng(uint32_t(ef.format) * 7u);
        for (auto& b : data) b = uint8_t(rng());
        const Bytes got = both([&](Kit& k) {
            Device::Image img = k.image(ef.format, kW, kH, kStorageUsage);
            fill(k, img.image, data);
            const Device::Buffer out = k.buffer(size_t(kW) * kH * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
            const SetOf s = set_of(k, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
            write_storage_image(k, s.set, 0, k.view(img.image, ef.format, VK_IMAGE_ASPECT_COLOR_BIT));
            write_buffer(k, s.set, 1, out);
            const VkPipeline p = compute_pipeline(k, ef.load, s.layout);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
                vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
                vkCmdDispatch(c, kW / 8, kH / 4, 1);
            }),
                      VK_SUCCESS);
            return Kit::bytes(out);
        });
        ASSERT_EQ(got.size(), size_t(kW) * kH * 16) << "format " << ef.format;
        const bool integer = ef.kind == Kind::Uint || ef.kind == Kind::Sint;
        const uint32_t one = integer ? 1u : std::bit_cast<uint32_t>(1.0f);
        const bool has_alpha = ef.channels.size() == 4;
        size_t wrong = 0;
        for (uint32_t y = 0; y < kH; ++y) {
            for (uint32_t x = 0; x < kW; ++x) {
                uint32_t want[4] = {0, 0, 0, one};
                if (x == 0) {
                    want[3] = has_alpha ? 0u : one;
                } else {
                    const uint64_t texel = texel_bits(data, (size_t(y) * kW + x - 1) * ef.bytes, ef.bytes);
                    for (const ExtChannel& ch : ef.channels)
                        want[ch.rgba] =
                            expected_ext_load(ef, ch, uint32_t((texel >> ch.shift) & ((uint64_t(1) << ch.bits) - 1u)));
                }
                uint32_t have[4];
                std::memcpy(have, &got[(size_t(y) * kW + x) * 16], 16);
                if (std::memcmp(have, want, 16) != 0 && wrong++ < 4)
                    ADD_FAILURE() << "format " << ef.format << " (" << x << ", " << y << "): loaded " << std::hex
                                  << have[0] << " " << have[1] << " " << have[2] << " " << have[3] << ", want "
                                  << want[0] << " " << want[1] << " " << want[2] << " " << want[3] << std::dec;
            }
        }
        EXPECT_EQ(wrong, 0u) << "format " << ef.format;
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
