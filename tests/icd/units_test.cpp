// Unit tests of icd/ internals: the format mapping, the image layout and the generated entry-point table.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "entrypoints.h"
#include "formats.h"
#include "image.h"
#include "object.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

// The generated VkFormat <-> table mapping covers every registry format both ways, and names the row.
TEST(FormatMap, EveryRowMapsBothWays) {
    for (size_t i = 1; i < size_t(format::Format::kCount); ++i) {
        const format::Format f = format::Format(i);
        const VkFormat vk = to_vk_format(f);
        ASSERT_NE(vk, VK_FORMAT_UNDEFINED) << i;
        EXPECT_EQ(to_format(vk), f) << vk_enum_name(vk);
        EXPECT_STREQ(vk_enum_name(vk) + 10, format::format_info(f).name);  // after "VK_FORMAT_"
        EXPECT_EQ(find_format(vk), &format::format_info(f));
    }
    EXPECT_EQ(find_format(VK_FORMAT_UNDEFINED), nullptr);
    EXPECT_EQ(find_format(VkFormat(987654)), nullptr);
}

// The default allocation callbacks keep the spec's pfnReallocation contract: growing and shrinking keep the
// contents and the alignment, size 0 frees, a null old pointer allocates.
TEST(DefaultAllocator, ReallocationKeepsContentsAndAlignment) {
    const VkAllocationCallbacks& a = default_allocator();
    const VkSystemAllocationScope scope = VK_SYSTEM_ALLOCATION_SCOPE_OBJECT;
    auto* p = static_cast<uint8_t*>(a.pfnReallocation(a.pUserData, nullptr, 100, 64, scope));
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % 64, 0u);
    for (int i = 0; i < 100; ++i) p[i] = uint8_t(i * 7);
    auto* q = static_cast<uint8_t*>(a.pfnReallocation(a.pUserData, p, 100000, 256, scope));
    ASSERT_NE(q, nullptr);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(q) % 256, 0u);
    for (int i = 0; i < 100; ++i) ASSERT_EQ(q[i], uint8_t(i * 7)) << i;
    auto* r = static_cast<uint8_t*>(a.pfnReallocation(a.pUserData, q, 10, 16, scope));
    ASSERT_NE(r, nullptr);
    for (int i = 0; i < 10; ++i) ASSERT_EQ(r[i], uint8_t(i * 7)) << i;
    EXPECT_EQ(a.pfnReallocation(a.pUserData, r, 0, 16, scope), nullptr);  // frees
}

// Hand-computed: 5x3 RGBA8, 3 levels, 2 layers. Level 0: rows of 20 B, layers of 60 B -> 120 B.
// Level 1 (2x1) at 128: rows 8 B, layers 8 B -> ends at 144. Level 2 (1x1) at 192: 4 B x 2 -> 200 -> size 256.
TEST(ImageLayout, PlainLinearLayout) {
    ImageLayout l = compute_image_layout(*find_format(VK_FORMAT_R8G8B8A8_UNORM), {5, 3, 1}, 3, 2, 1);
    EXPECT_EQ(l.level_offset[0], 0u);
    EXPECT_EQ(l.row_pitch[0], 20u);
    EXPECT_EQ(l.layer_pitch[0], 60u);
    EXPECT_EQ(l.level_offset[1], 128u);
    EXPECT_EQ(l.row_pitch[1], 8u);
    EXPECT_EQ(l.layer_pitch[1], 8u);
    EXPECT_EQ(l.level_offset[2], 192u);
    EXPECT_EQ(l.row_pitch[2], 4u);
    EXPECT_EQ(l.size, 256u);
    // 4 samples, 2 layers: a layer holds 4 sample planes of 3 rows of 5 texels of 8 B (120 B each), each plane
    // padded to 4 KiB plus 1088 B (image.cpp sample_plane_pitch): 5184 B apart.
    ImageLayout m = compute_image_layout(*find_format(VK_FORMAT_D32_SFLOAT_S8_UINT), {5, 3, 1}, 1, 2, 4);
    EXPECT_EQ(m.row_pitch[0], 40u);
    EXPECT_EQ(m.sample_pitch[0], 5184u);
    EXPECT_EQ(m.layer_pitch[0], 4u * 5184u);
    EXPECT_EQ(m.size, 2u * 4u * 5184u);
    // 1920x1080 RGBA8 (8 294 400 B, a multiple of 4 KiB): the four samples of a pixel sit at four page offsets.
    ImageLayout f = compute_image_layout(*find_format(VK_FORMAT_R8G8B8A8_UNORM), {1920, 1080, 1}, 1, 1, 4);
    EXPECT_EQ(f.sample_pitch[0] % 4096, 1088u);
}

TEST(EntryPoints, TableIsSortedAndLevelsFollowTheFirstParameter) {
    size_t n = 0;
    const EntryPoint* e = entry_points(&n);
    ASSERT_GT(n, 100u);
    for (size_t i = 1; i < n; ++i) EXPECT_LT(std::strcmp(e[i - 1].name, e[i].name), 0);
    struct Case {
        const char* name;
        EntryLevel level;
    } cases[] = {{"vkCreateInstance", EntryLevel::kGlobal},
                 {"vkGetInstanceProcAddr", EntryLevel::kGlobal},
                 {"vkEnumerateInstanceExtensionProperties", EntryLevel::kGlobal},
                 {"vkDestroyInstance", EntryLevel::kInstance},
                 {"vkEnumeratePhysicalDevices", EntryLevel::kInstance},
                 {"vkCreateDevice", EntryLevel::kPhysicalDevice},
                 {"vkGetPhysicalDeviceFormatProperties", EntryLevel::kPhysicalDevice},
                 {"vkGetDeviceProcAddr", EntryLevel::kDevice},
                 {"vkQueueSubmit", EntryLevel::kDevice},
                 {"vkCmdCopyBuffer", EntryLevel::kDevice}};
    for (const Case& c : cases) {
        const EntryPoint* p = find_entry_point(c.name);
        ASSERT_NE(p, nullptr) << c.name;
        EXPECT_EQ(p->level, c.level) << c.name;
        EXPECT_EQ(p->core_version, VK_MAKE_API_VERSION(0, 1, 0, 0)) << c.name;
    }
    EXPECT_NE(find_entry_point("vkCmdBlitImage"), nullptr);
    EXPECT_NE(find_entry_point("vkCmdDispatch"), nullptr);
    const EntryPoint* count = find_entry_point("vkCmdDrawIndirectCount");  // Vulkan 1.2 core (and its KHR alias)
    ASSERT_NE(count, nullptr);
    EXPECT_EQ(count->core_version, VK_MAKE_API_VERSION(0, 1, 2, 0));
    const EntryPoint* rendering = find_entry_point("vkCmdBeginRendering");  // Vulkan 1.3 core
    ASSERT_NE(rendering, nullptr);
    EXPECT_EQ(rendering->core_version, VK_MAKE_API_VERSION(0, 1, 3, 0));
    EXPECT_EQ(find_entry_point("vkCmdDrawMeshTasksEXT"), nullptr);  // an extension tilevk does not offer
    EXPECT_EQ(find_entry_point(nullptr), nullptr);
}

// The generated names come from vk.xml: spot checks against the spec's spelling, and offsets that agree with the
// compiler's layout of the structs.
TEST(VkNames, EnumsFlagsAndFeatureMembers) {
    EXPECT_STREQ(vk_enum_name(VK_FORMAT_R8G8B8A8_UINT), "VK_FORMAT_R8G8B8A8_UINT");
    EXPECT_STREQ(vk_enum_name(VK_FORMAT_D24_UNORM_S8_UINT), "VK_FORMAT_D24_UNORM_S8_UINT");
    EXPECT_STREQ(vk_enum_name(VK_FORMAT_G8_B8R8_2PLANE_420_UNORM), "VK_FORMAT_G8_B8R8_2PLANE_420_UNORM");
    EXPECT_STREQ(vk_enum_name(VK_ERROR_OUT_OF_DATE_KHR), "VK_ERROR_OUT_OF_DATE_KHR");
    EXPECT_STREQ(vk_enum_name(VkFormat(987654)), "VkFormat(987654)");
    EXPECT_EQ(vk_flags_name<VkShaderStageFlagBits>(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_COMPUTE_BIT),
              "VK_SHADER_STAGE_VERTEX_BIT|VK_SHADER_STAGE_COMPUTE_BIT");
    EXPECT_EQ(vk_flags_name<VkShaderStageFlagBits>(0), "0");
    EXPECT_EQ(vk_flags_name<VkSampleCountFlagBits>(VK_SAMPLE_COUNT_4_BIT | 0x10000000u),
              "VK_SAMPLE_COUNT_4_BIT|0x10000000");
    EXPECT_EQ(vk_VkPipelineStageFlagBits2_name(VK_PIPELINE_STAGE_2_COPY_BIT), "VK_PIPELINE_STAGE_2_COPY_BIT");

    const FeatureStruct& f10 = features10();
    ASSERT_EQ(f10.count, sizeof(VkPhysicalDeviceFeatures) / sizeof(VkBool32));
    EXPECT_STREQ(f10.members[0], "robustBufferAccess");
    EXPECT_EQ(f10.offsets[4], offsetof(VkPhysicalDeviceFeatures, geometryShader));
    EXPECT_STREQ(f10.members[4], "geometryShader");

    const FeatureStruct* v11 = find_feature_struct(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES);
    ASSERT_NE(v11, nullptr);
    EXPECT_STREQ(v11->name, "VkPhysicalDeviceVulkan11Features");
    EXPECT_EQ(v11->size, sizeof(VkPhysicalDeviceVulkan11Features));
    EXPECT_STREQ(v11->members[v11->count - 1], "shaderDrawParameters");
    EXPECT_EQ(v11->offsets[v11->count - 1], offsetof(VkPhysicalDeviceVulkan11Features, shaderDrawParameters));
    const FeatureStruct* dr = find_feature_struct(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES);
    ASSERT_NE(dr, nullptr);
    EXPECT_EQ(dr->count, 1u);
    EXPECT_EQ(find_feature_struct(VK_STRUCTURE_TYPE_APPLICATION_INFO), nullptr);
    size_t n = 0;
    const FeatureStruct* all = feature_structs(&n);
    EXPECT_GT(n, 100u);
    for (size_t i = 0; i < n; ++i) {  // every member is a VkBool32 inside the struct, after sType and pNext
        for (uint32_t m = 0; m < all[i].count; ++m) {
            EXPECT_GE(all[i].offsets[m], sizeof(VkBaseOutStructure)) << all[i].name;
            EXPECT_LE(all[i].offsets[m] + sizeof(VkBool32), all[i].size) << all[i].name;
        }
    }
}

}  // namespace
}  // namespace tilevk::icd
