// tilevk's format answers against lavapipe's, for every VkFormat vk.xml defines (the generated icd/vk_names.h
// names them; a value it does not name is not a registry format). Both drivers are reached through the loader.
// Queried: vkGetPhysicalDeviceFormatProperties2 with VkFormatProperties3 (linear, optimal and buffer features as
// 64-bit VkFormatFeatureFlags2), and vkGetPhysicalDeviceImageFormatProperties for 2D images in both tilings with each
// image usage alone. The assertion: tilevk never reports more than lavapipe (a feature bit, an accepted image, a
// sample count), since everything tilevk reports is compared with lavapipe byte for byte (format/support.txt). What
// lavapipe offers and tilevk lacks is printed as the list of gaps (TILEVK_FORMAT_GAPS=1 prints it per format; the
// summary is always printed). That each reported feature works is checked elsewhere: api_breadth
// EveryReportedImageFormatWorks (render, sample, filter against lavapipe), ImageFormatPropertiesMatchFeatures
// (every accepted format x usage is created), the storage-image and texel-buffer walks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "vk_names.h"

namespace {

using tilevk::icd::vk_enum_name;
using tilevk::icd::vk_flags_name;
using tilevk::icd::vk_VkFormatFeatureFlagBits2_name;

// Every registry VkFormat: core values are below 1000, extension values are 1000000000 + 1000 * (extension number
// - 1) + offset (the registry's rule for extension enums); an extension adds far fewer than 100 formats.
std::vector<VkFormat> registry_formats() {
    std::vector<VkFormat> out;
    const auto named = [](long long v) { return std::strncmp(vk_enum_name(VkFormat(v)), "VK_FORMAT_", 10) == 0; };
    for (long long v = 1; v < 1000; ++v)
        if (named(v)) out.push_back(VkFormat(v));
    for (long long ext = 0; ext < 1000; ++ext)
        for (long long off = 0; off < 100; ++off)
            if (named(1000000000LL + ext * 1000 + off)) out.push_back(VkFormat(1000000000LL + ext * 1000 + off));
    return out;
}

struct Answers {
    VkFormatFeatureFlags2 linear = 0, optimal = 0, buffer = 0;
};

class FormatCompare : public ::testing::Test {
  protected:
    void SetUp() override {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.apiVersion = VK_API_VERSION_1_3;
        VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ci.pApplicationInfo = &app;
        ASSERT_EQ(vkCreateInstance(&ci, nullptr, &instance_), VK_SUCCESS);
        uint32_t n = 0;
        vkEnumeratePhysicalDevices(instance_, &n, nullptr);
        std::vector<VkPhysicalDevice> pds(n);
        vkEnumeratePhysicalDevices(instance_, &n, pds.data());
        for (VkPhysicalDevice pd : pds) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(pd, &p);
            if (std::strncmp(p.deviceName, "tilevk", 6) == 0) tilevk_ = pd;
            if (std::strncmp(p.deviceName, "llvmpipe", 8) == 0) lavapipe_ = pd;
        }
        ASSERT_NE(tilevk_, VK_NULL_HANDLE);
        ASSERT_NE(lavapipe_, VK_NULL_HANDLE) << "lavapipe is the reference; its manifest must be in VK_ICD_FILENAMES";
    }
    void TearDown() override {
        if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
    }

    static Answers features(VkPhysicalDevice pd, VkFormat f) {
        VkFormatProperties3 p3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
        VkFormatProperties2 p2{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2, &p3};
        vkGetPhysicalDeviceFormatProperties2(pd, f, &p2);
        return {p3.linearTilingFeatures, p3.optimalTilingFeatures, p3.bufferFeatures};
    }

    VkInstance instance_ = VK_NULL_HANDLE;
    VkPhysicalDevice tilevk_ = VK_NULL_HANDLE, lavapipe_ = VK_NULL_HANDLE;
};

bool verbose() {
    const char* e = std::getenv("TILEVK_FORMAT_GAPS");
    return e && *e == '1';
}

TEST_F(FormatCompare, RegistryFormatListIsComplete) {
    const std::vector<VkFormat> all = registry_formats();
    // Vulkan 1.3's core formats 1..184 are all named, and the extension formats include the YCbCr ones
    // (VK_KHR_sampler_ycbcr_conversion, extension 157) and the ASTC HDR ones (extension 67).
    EXPECT_GE(all.size(), 184u + 34u + 14u);
    EXPECT_EQ(all.front(), VK_FORMAT_R4G4_UNORM_PACK8);
    EXPECT_NE(std::find(all.begin(), all.end(), VK_FORMAT_G8B8G8R8_422_UNORM), all.end());
    EXPECT_NE(std::find(all.begin(), all.end(), VK_FORMAT_ASTC_12x12_SFLOAT_BLOCK), all.end());
}

// Format features (VkFormatProperties3, which holds every VkFormatFeatureFlags2 bit): tilevk's are a subset of
// lavapipe's in each of the three sets; also VkFormatProperties agrees with the low 32 bits of the 64-bit answer.
TEST_F(FormatCompare, FormatFeaturesNeverExceedLavapipe) {
    int gaps = 0, reported = 0;
    std::map<std::string, int> gap_bits;  // a missing bit's name -> formats lacking it
    for (VkFormat f : registry_formats()) {
        const Answers t = features(tilevk_, f), l = features(lavapipe_, f);
        const char* name = vk_enum_name(f);
        const std::pair<const char*, std::pair<VkFormatFeatureFlags2, VkFormatFeatureFlags2>> sets[] = {
            {"linear", {t.linear, l.linear}}, {"optimal", {t.optimal, l.optimal}}, {"buffer", {t.buffer, l.buffer}}};
        for (const auto& [set, tl] : sets) {
            const auto [tv, lv] = tl;
            EXPECT_EQ(tv & ~lv, 0u) << name << " " << set << ": tilevk reports what lavapipe does not: "
                                    << vk_VkFormatFeatureFlagBits2_name(tv & ~lv);
            if (tv) ++reported;
            const VkFormatFeatureFlags2 missing = lv & ~tv;
            if (!missing) continue;
            ++gaps;
            if (verbose()) std::printf("gap %s %s: %s\n", name, set, vk_VkFormatFeatureFlagBits2_name(missing).c_str());
            for (int b = 0; b < 64; ++b)
                if (missing & (VkFormatFeatureFlags2(1) << b))
                    ++gap_bits[vk_VkFormatFeatureFlagBits2_name(VkFormatFeatureFlags2(1) << b) + " (" + set + ")"];
        }
        VkFormatProperties p1;
        vkGetPhysicalDeviceFormatProperties(tilevk_, f, &p1);
        EXPECT_EQ(p1.optimalTilingFeatures, VkFormatFeatureFlags(t.optimal & 0xffffffffu)) << name;
        EXPECT_EQ(p1.linearTilingFeatures, VkFormatFeatureFlags(t.linear & 0xffffffffu)) << name;
        EXPECT_EQ(p1.bufferFeatures, VkFormatFeatureFlags(t.buffer & 0xffffffffu)) << name;
    }
    std::printf("format feature sets lavapipe reports more of: %d (tilevk reports %d non-empty sets)\n", gaps,
                reported);
    for (const auto& [bit, count] : gap_bits) std::printf("  %4d formats lack %s\n", count, bit.c_str());
    EXPECT_GT(reported, 100);
}

// Image format properties of 2D images, each usage alone, both tilings: what tilevk accepts, lavapipe accepts, with
// at least the same sample counts. Limits (extent, levels, layers, size) are printed where they differ.
TEST_F(FormatCompare, ImageFormatPropertiesNeverExceedLavapipe) {
    const VkImageUsageFlagBits usages[] = {
        VK_IMAGE_USAGE_TRANSFER_SRC_BIT,     VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        VK_IMAGE_USAGE_SAMPLED_BIT,          VK_IMAGE_USAGE_STORAGE_BIT,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
        VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT};
    int accepted = 0, lavapipe_only = 0, limit_differences = 0;
    std::map<std::string, int> gap_usages;
    for (VkFormat f : registry_formats()) {
        for (VkImageTiling tiling : {VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_TILING_LINEAR}) {
            for (VkImageUsageFlagBits usage : usages) {
                VkImageFormatProperties tp{}, lp{};
                const VkResult tr =
                    vkGetPhysicalDeviceImageFormatProperties(tilevk_, f, VK_IMAGE_TYPE_2D, tiling, usage, 0, &tp);
                const VkResult lr =
                    vkGetPhysicalDeviceImageFormatProperties(lavapipe_, f, VK_IMAGE_TYPE_2D, tiling, usage, 0, &lp);
                const std::string what = std::string(vk_enum_name(f)) + " " + vk_enum_name(tiling) + " " +
                                         vk_flags_name<VkImageUsageFlagBits>(usage);
                ASSERT_TRUE(tr == VK_SUCCESS || tr == VK_ERROR_FORMAT_NOT_SUPPORTED) << what << ": " << tr;
                if (lr == VK_SUCCESS && tr != VK_SUCCESS) {
                    ++lavapipe_only;
                    ++gap_usages[std::string(vk_enum_name(tiling)) + " " + vk_flags_name<VkImageUsageFlagBits>(usage)];
                    if (verbose()) std::printf("gap %s: lavapipe accepts, tilevk refuses\n", what.c_str());
                }
                if (tr != VK_SUCCESS) continue;
                ++accepted;
                EXPECT_EQ(lr, VK_SUCCESS) << what << ": tilevk accepts an image lavapipe refuses";
                if (lr != VK_SUCCESS) continue;
                EXPECT_EQ(tp.sampleCounts & ~lp.sampleCounts, 0u)
                    << what << ": sample counts lavapipe lacks: "
                    << vk_flags_name<VkSampleCountFlagBits>(tp.sampleCounts & ~lp.sampleCounts);
                const bool same = tp.maxExtent.width == lp.maxExtent.width &&
                                  tp.maxExtent.height == lp.maxExtent.height && tp.maxMipLevels == lp.maxMipLevels &&
                                  tp.maxArrayLayers == lp.maxArrayLayers && tp.sampleCounts == lp.sampleCounts;
                if (!same) {
                    ++limit_differences;
                    if (verbose())
                        std::printf(
                            "limits %s: tilevk %ux%u levels %u layers %u samples %s, lavapipe %ux%u levels "
                            "%u layers %u samples %s\n",
                            what.c_str(), tp.maxExtent.width, tp.maxExtent.height, tp.maxMipLevels, tp.maxArrayLayers,
                            vk_flags_name<VkSampleCountFlagBits>(tp.sampleCounts).c_str(), lp.maxExtent.width,
                            lp.maxExtent.height, lp.maxMipLevels, lp.maxArrayLayers,
                            vk_flags_name<VkSampleCountFlagBits>(lp.sampleCounts).c_str());
                }
            }
        }
    }
    std::printf("2D format x tiling x usage: tilevk accepts %d, lavapipe alone accepts %d, limits differ in %d\n",
                accepted, lavapipe_only, limit_differences);
    for (const auto& [u, count] : gap_usages)
        std::printf("  %4d formats lavapipe alone accepts for %s\n", count, u.c_str());
    EXPECT_GT(accepted, 100);
}

}  // namespace
