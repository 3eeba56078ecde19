// VK_EXT_shader_atomic_float (suite ApiAtomicFloat): what tilevk reports equals lavapipe's report, member by member
// and for the R32_SFLOAT atomic format bits, and what it reports works: buffer, shared-memory and image float atomics
// (cp_atomic_float.comp) on both drivers with the extension and its six 32-bit features enabled, the validation layer
// on, bytes compared and every value checked against the answers computed here.
#include <algorithm>
#include <cstring>
#include <vector>

#include "api_breadth.h"
// after api_breadth.h, which includes <cstdint> for the generated array
#include "cp_atomic_float_comp.h"

namespace tilevk::test::breadth {
namespace {

constexpr uint32_t kGroups = 4, kN = kGroups * 64;
constexpr uint32_t kWords = 8 + kN + 2 * kN + 16;  // cp_atomic_float.comp's block B
constexpr uint32_t kImgW = 16, kImgH = 17;         // row 0: contended adds; rows 1..16: one exchange per texel

VkPhysicalDeviceShaderAtomicFloatFeaturesEXT reported(VkInstance instance, VkPhysicalDevice pd) {
    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f;
    auto get = reinterpret_cast<PFN_vkGetPhysicalDeviceFeatures2KHR>(
        vkGetInstanceProcAddr(instance, "vkGetPhysicalDeviceFeatures2KHR"));
    EXPECT_NE(get, nullptr);
    if (get != nullptr) get(pd, &f2);
    return f;
}

class ApiAtomicFloat : public ApiBreadth {
  protected:
    void SetUp() override {
        features_ = reported(harness_->instance(), tilevk_->physical());
        features_.pNext = nullptr;
        dev_ = device_pair({VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME}, &features_);
        ASSERT_TRUE(dev_->ok());
    }
    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT features_{};
    std::unique_ptr<DevicePair> dev_;
};

float quarter(uint32_t i) {
    return float(int32_t(i % 13u) - 6) * 0.25f;
}

// Block B (initial words: sums k / 2, own i * 0.7 - 40, ret and shout markers) and the R32_SFLOAT image (texel t
// = t / 8 - 5), the dispatch, then both read back: block B's words, then the image's texels.
Bytes atomic_float_scene(Kit& k) {
    std::vector<float> b(kWords, 0.0f);
    for (uint32_t s = 0; s < 8; ++s) b[s] = float(s) * 0.5f;
    for (uint32_t i = 0; i < kN; ++i) b[8 + i] = float(i) * 0.7f - 40.0f;
    std::vector<float> texels(kImgW * kImgH);
    for (uint32_t t = 0; t < texels.size(); ++t) texels[t] = float(t) / 8.0f - 5.0f;
    Device::Buffer buf = k.buffer_of(b, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Device::Buffer src = k.buffer_of(texels, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Device::Image img = k.image(VK_FORMAT_R32_SFLOAT, kImgW, kImgH, usage);
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const VkDescriptorSetLayout dsl =
        k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs}});
    const VkPipelineLayout layout = k.pipeline_layout({dsl});
    const VkDescriptorSet set = k.descriptor_set(dsl);
    const VkDescriptorBufferInfo bi{buf.buffer, 0, VK_WHOLE_SIZE};
    k.write(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bi, nullptr);
    const VkDescriptorImageInfo ii{VK_NULL_HANDLE, k.view(img.image, VK_FORMAT_R32_SFLOAT, VK_IMAGE_ASPECT_COLOR_BIT),
                                   VK_IMAGE_LAYOUT_GENERAL};
    k.write(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &ii);
    const VkPipeline p = compute_pipeline(k, SPV(cp_atomic_float_comp), layout);
    if (p == VK_NULL_HANDLE) return {};
    const VkImageAspectFlags color = VK_IMAGE_ASPECT_COLOR_BIT;
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        transition(c, img.image, color, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy r{};
        r.imageSubresource = {color, 0, 0, 1};
        r.imageExtent = {kImgW, kImgH, 1};
        vkCmdCopyBufferToImage(c, src.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
        transition(c, img.image, color, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdDispatch(c, kGroups, 1, 1);
        transition(c, img.image, color, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr,
                             0, nullptr);
    }),
              VK_SUCCESS);
    Bytes out = Kit::bytes(buf);
    const Bytes image = k.read(img.image, kImgW, kImgH, 4);
    out.insert(out.end(), image.begin(), image.end());
    return out;
}

}  // namespace

// Member by member the answer of lavapipe 22.3.6 (lvp_device.c): the 32-bit buffer, shared and image atomics and adds,
// no 64-bit ones, no sparse ones; STORAGE_IMAGE_ATOMIC and STORAGE_TEXEL_BUFFER_ATOMIC on R32_SFLOAT.
TEST_F(ApiAtomicFloat, ReportsWhatLavapipeReports) {
    const VkPhysicalDeviceShaderAtomicFloatFeaturesEXT t = reported(harness_->instance(), tilevk_->physical());
    const VkPhysicalDeviceShaderAtomicFloatFeaturesEXT l = reported(harness_->instance(), lavapipe_->physical());
    const size_t body = offsetof(VkPhysicalDeviceShaderAtomicFloatFeaturesEXT, shaderBufferFloat32Atomics);
    EXPECT_EQ(std::memcmp(reinterpret_cast<const char*>(&t) + body, reinterpret_cast<const char*>(&l) + body,
                          sizeof t - body),
              0);
    EXPECT_TRUE(t.shaderBufferFloat32AtomicAdd && t.shaderSharedFloat32AtomicAdd && t.shaderImageFloat32AtomicAdd);
    EXPECT_FALSE(t.shaderBufferFloat64Atomics || t.shaderSharedFloat64AtomicAdd || t.sparseImageFloat32Atomics);
    for (VkPhysicalDevice pd : {tilevk_->physical(), lavapipe_->physical()}) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, VK_FORMAT_R32_SFLOAT, &fp);
        EXPECT_TRUE(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_ATOMIC_BIT);
        EXPECT_TRUE(fp.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_ATOMIC_BIT);
    }
}

// The feature struct of type T (sType t) as the physical device reports it.
template <class T>
T reported_struct(VkInstance instance, VkPhysicalDevice pd, VkStructureType t) {
    T f{};
    f.sType = t;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f;
    auto get = reinterpret_cast<PFN_vkGetPhysicalDeviceFeatures2KHR>(
        vkGetInstanceProcAddr(instance, "vkGetPhysicalDeviceFeatures2KHR"));
    if (get != nullptr) get(pd, &f2);
    f.pNext = nullptr;
    return f;
}

// VK_EXT_shader_atomic_float2 and VK_KHR_shader_atomic_int64, member by member lavapipe 22.3.6's answer (with LLVM
// 15: the three 32-bit MinMax members; buffer and shared 64-bit integer atomics), and both extensions offered.
TEST_F(ApiAtomicFloat, Float2AndInt64ReportWhatLavapipeReports) {
    const VkInstance in = harness_->instance();
    using F2 = VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT;
    using I64 = VkPhysicalDeviceShaderAtomicInt64Features;
    const auto f2 = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_2_FEATURES_EXT;
    const auto i64 = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES;
    const F2 t2 = reported_struct<F2>(in, tilevk_->physical(), f2),
             l2 = reported_struct<F2>(in, lavapipe_->physical(), f2);
    const I64 t64 = reported_struct<I64>(in, tilevk_->physical(), i64),
              l64 = reported_struct<I64>(in, lavapipe_->physical(), i64);
    EXPECT_EQ(std::memcmp(&t2, &l2, sizeof t2), 0);
    EXPECT_EQ(std::memcmp(&t64, &l64, sizeof t64), 0);
    EXPECT_TRUE(t2.shaderBufferFloat32AtomicMinMax && t2.shaderSharedFloat32AtomicMinMax &&
                t2.shaderImageFloat32AtomicMinMax);
    EXPECT_FALSE(t2.shaderBufferFloat16Atomics || t2.shaderBufferFloat64AtomicMinMax ||
                 t2.sparseImageFloat32AtomicMinMax);
    EXPECT_TRUE(t64.shaderBufferInt64Atomics && t64.shaderSharedInt64Atomics);
    for (VkPhysicalDevice pd : {tilevk_->physical(), lavapipe_->physical()}) {
        uint32_t n = 0;
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
        std::vector<VkExtensionProperties> e(n);
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, e.data());
        for (const char* want :
             {VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME, VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME})
            EXPECT_TRUE(std::any_of(e.begin(), e.end(), [&](const VkExtensionProperties& x) {
                return std::strcmp(x.extensionName, want) == 0;
            })) << want;
    }
}

// cp_atomic_float.comp on both drivers: the same bytes, and the sums, returns and exchanged texels computed here
// (contended sums of quarters are exact in any order; every kept return is a one-writer word's).
TEST_F(ApiAtomicFloat, BufferSharedAndImageAtomicsWork) {
    const Bytes got = both_on(dev_->tilevk, dev_->lavapipe, atomic_float_scene);
    ASSERT_EQ(got.size(), size_t(kWords + kImgW * kImgH) * 4);
    std::vector<float> w(kWords + kImgW * kImgH);
    std::memcpy(w.data(), got.data(), got.size());
    const float* img = w.data() + kWords;
    float sums[8], acc[kGroups][4], row0[4];
    for (uint32_t s = 0; s < 8; ++s) sums[s] = float(s) * 0.5f;
    for (uint32_t x = 0; x < 4; ++x) row0[x] = float(x) / 8.0f - 5.0f;
    for (uint32_t i = 0; i < kN; ++i) {
        if (i % 64 < 4) acc[i / 64][i % 64] = float(i % 64) * 10.0f;
    }
    for (uint32_t i = 0; i < kN; ++i) {
        sums[i % 8] += quarter(i);
        acc[i / 64][i % 64 % 4] += quarter(i);
        row0[i % 4] += quarter(i);
    }
    for (uint32_t s = 0; s < 8; ++s) EXPECT_EQ(w[s], sums[s]) << "sums " << s;
    for (uint32_t i = 0; i < kN; ++i) {
        const float own = float(i) * 0.7f - 40.0f;
        EXPECT_EQ(w[8 + i], own + 0.1f) << "own " << i;
        EXPECT_EQ(w[8 + kN + 2 * i], own) << "add's return " << i;
        const uint32_t t = (1 + i / 16) * kImgW + i % 16;
        EXPECT_EQ(w[8 + kN + 2 * i + 1], float(t) / 8.0f - 5.0f) << "exchange's return " << i;
        EXPECT_EQ(img[t], float(i) * 0.5f) << "texel " << t;
    }
    for (uint32_t g = 0; g < kGroups; ++g)
        for (uint32_t s = 0; s < 4; ++s) EXPECT_EQ(w[8 + 3 * kN + g * 4 + s], acc[g][s]) << "shared " << g << " " << s;
    for (uint32_t x = 0; x < 4; ++x) EXPECT_EQ(img[x], row0[x]) << "row 0 texel " << x;
    for (uint32_t x = 4; x < kImgW; ++x) EXPECT_EQ(img[x], float(x) / 8.0f - 5.0f) << "row 0 texel " << x;
}

}  // namespace tilevk::test::breadth
