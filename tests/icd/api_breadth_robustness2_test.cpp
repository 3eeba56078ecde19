// VK_EXT_robustness2 (suite ApiRobustness2): the features and properties both drivers report, and on tilevk alone
// (no validation layer: the calls are invalid usage without the feature) that VK_NULL_HANDLE descriptors and vertex
// buffers are refused by name unless nullDescriptor is enabled. What null descriptors read and write, and the exact
// bounds, are compared with lavapipe byte for byte by cts compute.robustness2.*.
#include <algorithm>
#include <cstring>

#include "api_breadth.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

const std::vector<const char*> kExtensions = {VK_EXT_ROBUSTNESS_2_EXTENSION_NAME};

class ApiRobustness2 : public ApiBreadth {};

// lavapipe 22.3.6 (lvp_device.c): every member VK_TRUE, both alignments 1.
TEST_F(ApiRobustness2, FeaturesAndPropertiesAsLavapipe) {
    for (VkPhysicalDevice pd : {tilevk_->physical(), lavapipe_->physical()}) {
        VkPhysicalDeviceRobustness2FeaturesEXT f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f};
        vkGetPhysicalDeviceFeatures2(pd, &f2);
        EXPECT_EQ(f.robustBufferAccess2, VK_TRUE);
        EXPECT_EQ(f.robustImageAccess2, VK_TRUE);
        EXPECT_EQ(f.nullDescriptor, VK_TRUE);
        VkPhysicalDeviceRobustness2PropertiesEXT p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_PROPERTIES_EXT};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p};
        vkGetPhysicalDeviceProperties2(pd, &p2);
        EXPECT_EQ(p.robustStorageBufferAccessSizeAlignment, 1u);
        EXPECT_EQ(p.robustUniformBufferAccessSizeAlignment, 1u);
        uint32_t n = 0;
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
        std::vector<VkExtensionProperties> exts(n);
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
        EXPECT_TRUE(std::any_of(exts.begin(), exts.end(), [](const VkExtensionProperties& e) {
            return std::strcmp(e.extensionName, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME) == 0;
        }));
    }
}

// Without nullDescriptor, each kind of null descriptor write (directly and through a template) and a null vertex
// buffer give one stderr line naming the feature and the VUID; with it, none.
TEST_F(ApiRobustness2, NullHandlesNeedTheNullDescriptorFeature) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    VkPhysicalDeviceRobustness2FeaturesEXT r2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
    for (bool feature : {false, true}) {
        r2.nullDescriptor = feature;
        Device dev(plain.find_device("tilevk"), nullptr, kExtensions, &r2);
        ASSERT_TRUE(dev.ok());
        Kit k(dev);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_ALL},
                          {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_ALL},
                          {2, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 1, VK_SHADER_STAGE_ALL}});
        VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorBufferInfo null_buffer{VK_NULL_HANDLE, 0, VK_WHOLE_SIZE};
        const VkDescriptorImageInfo null_image{VK_NULL_HANDLE, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL};
        const VkBufferView null_view = VK_NULL_HANDLE;
        struct Case {
            VkWriteDescriptorSet w;
            const char* vuid;
        };
        Case cases[3] = {{{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, "VUID-VkDescriptorBufferInfo-buffer-02998"},
                         {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, "VUID-VkWriteDescriptorSet-descriptorType-02997"},
                         {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, "VUID-VkWriteDescriptorSet-descriptorType-02995"}};
        const VkDescriptorType types[3] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                           VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER};
        for (uint32_t i = 0; i < 3; ++i) {
            VkWriteDescriptorSet& w = cases[i].w;
            w.dstSet = set;
            w.dstBinding = i;
            w.descriptorCount = 1;
            w.descriptorType = types[i];
            w.pBufferInfo = &null_buffer;
            w.pImageInfo = &null_image;
            w.pTexelBufferView = &null_view;
            StderrCapture capture;
            vkUpdateDescriptorSets(dev.device(), 1, &w, 0, nullptr);
            const std::string err = capture.text();
            if (feature) {
                EXPECT_EQ(err, "") << cases[i].vuid;
            } else {
                EXPECT_NE(err.find("VkPhysicalDeviceRobustness2FeaturesEXT"), std::string::npos) << err;
                EXPECT_NE(err.find(cases[i].vuid), std::string::npos) << err;
            }
        }
        // A descriptor update template writes through the same checks.
        const VkDescriptorUpdateTemplateEntry entry{
            0, 0, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0, sizeof(VkDescriptorBufferInfo)};
        VkDescriptorUpdateTemplateCreateInfo tci{VK_STRUCTURE_TYPE_DESCRIPTOR_UPDATE_TEMPLATE_CREATE_INFO};
        tci.descriptorUpdateEntryCount = 1;
        tci.pDescriptorUpdateEntries = &entry;
        tci.templateType = VK_DESCRIPTOR_UPDATE_TEMPLATE_TYPE_DESCRIPTOR_SET;
        tci.descriptorSetLayout = dsl;
        VkDescriptorUpdateTemplate tmpl = VK_NULL_HANDLE;
        ASSERT_EQ(vkCreateDescriptorUpdateTemplate(dev.device(), &tci, nullptr, &tmpl), VK_SUCCESS);
        {
            StderrCapture capture;
            vkUpdateDescriptorSetWithTemplate(dev.device(), set, tmpl, &null_buffer);
            const std::string err = capture.text();
            EXPECT_EQ(err.find("VUID-VkDescriptorBufferInfo-buffer-02998") != std::string::npos, !feature) << err;
        }
        vkDestroyDescriptorUpdateTemplate(dev.device(), tmpl, nullptr);
        StderrCapture capture;
        EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
            const VkBuffer none = VK_NULL_HANDLE;
            const VkDeviceSize zero = 0;
            vkCmdBindVertexBuffers(cb, 0, 1, &none, &zero);
        }),
                  VK_SUCCESS);
        const std::string err = capture.text();
        if (feature) {
            EXPECT_EQ(err, "");
        } else {
            EXPECT_NE(err.find("VUID-vkCmdBindVertexBuffers-pBuffers-04001"), std::string::npos) << err;
        }
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
