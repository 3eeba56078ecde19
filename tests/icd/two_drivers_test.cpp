// Two drivers through the real loader (VK_ICD_FILENAMES = tilevk + lavapipe, set by meson), with
// VK_LAYER_KHRONOS_validation on and a debug-utils messenger counting messages: every query and object
// lifetime below must produce zero messages on both drivers.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "vk_harness.h"

namespace {

using tilevk::test::Device;
using tilevk::test::Harness;

const VkFormat kFormats[] = {
    VK_FORMAT_R8G8B8A8_UNORM,
    VK_FORMAT_B8G8R8A8_UNORM,
    VK_FORMAT_R8G8B8A8_SRGB,
    VK_FORMAT_B8G8R8A8_SRGB,
    VK_FORMAT_R8_UNORM,
    VK_FORMAT_R8G8_UNORM,
    VK_FORMAT_R16G16B16A16_SFLOAT,
    VK_FORMAT_R32_SFLOAT,
    VK_FORMAT_R32G32_SFLOAT,
    VK_FORMAT_R32G32B32A32_SFLOAT,
    VK_FORMAT_D16_UNORM,
    VK_FORMAT_D32_SFLOAT,
    VK_FORMAT_D32_SFLOAT_S8_UINT,
    VK_FORMAT_R32G32B32_SFLOAT,
    VK_FORMAT_R8G8B8A8_SNORM,
    VK_FORMAT_R16G16_SINT,
    VK_FORMAT_BC1_RGB_UNORM_BLOCK,
    VK_FORMAT_R64_SFLOAT,
};

void exercise_device(VkPhysicalDevice pd) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    VkPhysicalDeviceFeatures features;
    vkGetPhysicalDeviceFeatures(pd, &features);
    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> qf(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, qf.data());
    ASSERT_GE(nq, 1u);
    EXPECT_TRUE(qf[0].queueFlags & VK_QUEUE_GRAPHICS_BIT);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(pd, &mem);
    for (VkFormat f : kFormats) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, f, &fp);
        VkImageFormatProperties ifp;
        VkResult r = vkGetPhysicalDeviceImageFormatProperties(pd, f, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                                              VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0, &ifp);
        // Image format support must agree with the format features.
        const bool transfer = (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_TRANSFER_DST_BIT) != 0;
        if (!transfer) {
            EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << props.deviceName << " format " << f;
        }
        if (r == VK_SUCCESS) {
            EXPECT_GE(ifp.maxExtent.width, 4096u);
        }
    }
    uint32_t next = 0;
    EXPECT_EQ(vkEnumerateDeviceExtensionProperties(pd, nullptr, &next, nullptr), VK_SUCCESS);

    Device dev(pd);
    ASSERT_TRUE(dev.ok()) << props.deviceName;
    Device::Buffer buf = dev.make_buffer(4096);
    ASSERT_NE(buf.map, nullptr);
    std::memset(buf.map, 0x5a, 4096);
    Device::Image img = dev.make_image(VK_FORMAT_R8G8B8A8_UNORM, 64, 32, 3, 2, VK_SAMPLE_COUNT_1_BIT,
                                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    ASSERT_NE(img.image, VK_NULL_HANDLE);
    Device::Image depth = dev.make_image(VK_FORMAT_D32_SFLOAT, 16, 16, 1, 1, VK_SAMPLE_COUNT_4_BIT,
                                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    ASSERT_NE(depth.image, VK_NULL_HANDLE);
    dev.destroy(depth);
    dev.destroy(img);
    dev.destroy(buf);
}

TEST(TwoDrivers, ZeroValidationMessages) {
    Harness h;
    ASSERT_TRUE(h.ok()) << "instance with VK_LAYER_KHRONOS_validation failed";
    std::vector<VkPhysicalDevice> pds = h.physical_devices();
    ASSERT_EQ(pds.size(), 2u) << "expected exactly tilevk and llvmpipe";
    int tilevk = 0, llvmpipe = 0;
    for (VkPhysicalDevice pd : pds) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        if (std::strncmp(p.deviceName, "tilevk", 6) == 0) {
            ++tilevk;
        }
        if (std::strncmp(p.deviceName, "llvmpipe", 8) == 0) {
            ++llvmpipe;
        }
        SCOPED_TRACE(p.deviceName);
        exercise_device(pd);
    }
    EXPECT_EQ(tilevk, 1);
    EXPECT_EQ(llvmpipe, 1);
    EXPECT_EQ(h.message_count(), 0) << h.message_report();
}

// The negative control of ZeroValidationMessages: one invalid query per driver (usage 0 breaks
// VUID-vkGetPhysicalDeviceImageFormatProperties-usage-requiredbitmask) must reach the counter once per driver.
TEST(TwoDrivers, ValidationMessagesAreCounted) {
    Harness h;
    ASSERT_TRUE(h.ok());
    ASSERT_EQ(h.message_count(), 0) << h.message_report();
    std::vector<VkPhysicalDevice> pds = h.physical_devices();
    ASSERT_EQ(pds.size(), 2u);
    for (VkPhysicalDevice pd : pds) {
        VkImageFormatProperties ifp;
        vkGetPhysicalDeviceImageFormatProperties(pd, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_TYPE_2D,
                                                 VK_IMAGE_TILING_OPTIMAL, 0, 0, &ifp);
    }
    EXPECT_EQ(h.message_count(), 2) << h.message_report();
    EXPECT_NE(h.message_report().find("VUID-vkGetPhysicalDeviceImageFormatProperties-usage-requiredbitmask"),
              std::string::npos)
        << h.message_report();
}

// tilevk's reported properties, checked against the design (not against its own output).
TEST(TwoDrivers, TilevkProperties) {
    Harness h;
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    EXPECT_EQ(p.deviceType, VK_PHYSICAL_DEVICE_TYPE_CPU);
    EXPECT_EQ(VK_API_VERSION_MAJOR(p.apiVersion), 1u);
    EXPECT_EQ(VK_API_VERSION_MINOR(p.apiVersion), 3u);  // Vulkan 1.3 (icd/meson.build icd_api_minor)
    EXPECT_EQ(p.limits.subPixelPrecisionBits, 8u);
    EXPECT_EQ(p.limits.maxImageDimension2D, 16384u);
    EXPECT_EQ(p.limits.maxViewportDimensions[0], 16384u);
    EXPECT_EQ(p.limits.maxViewportDimensions[1], 16384u);
    EXPECT_LE(p.limits.viewportBoundsRange[0], -2.0f * 16384);
    EXPECT_GE(p.limits.viewportBoundsRange[1], 2.0f * 16384 - 1);
    const VkSampleCountFlags k14 = VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_4_BIT;
    EXPECT_EQ(p.limits.framebufferColorSampleCounts, k14);
    EXPECT_EQ(p.limits.framebufferDepthSampleCounts, k14);
    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, nullptr);
    ASSERT_EQ(nq, 1u);
    VkQueueFamilyProperties q;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, &q);
    EXPECT_EQ(q.queueFlags, VkQueueFlags(VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT | VK_QUEUE_TRANSFER_BIT));
    EXPECT_EQ(q.queueCount, 1u);
    VkPhysicalDeviceMemoryProperties m;
    vkGetPhysicalDeviceMemoryProperties(pd, &m);
    ASSERT_EQ(m.memoryTypeCount, 1u);
    ASSERT_EQ(m.memoryHeapCount, 1u);
    const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    EXPECT_EQ(m.memoryTypes[0].propertyFlags, want);
    // Sampled images of an attachment format may have 4 samples (texelFetch with a sample index), as the limits
    // say; storage images are single-sampled only, and only in the formats with the feature.
    VkImageFormatProperties ifp;
    ASSERT_EQ(vkGetPhysicalDeviceImageFormatProperties(pd, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_TYPE_2D,
                                                       VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_SAMPLED_BIT, 0, &ifp),
              VK_SUCCESS);
    EXPECT_EQ(ifp.sampleCounts, k14);
    EXPECT_EQ(p.limits.sampledImageColorSampleCounts, k14);
    EXPECT_EQ(p.limits.sampledImageIntegerSampleCounts, k14);
    EXPECT_EQ(p.limits.storageImageSampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT));
    ASSERT_EQ(vkGetPhysicalDeviceImageFormatProperties(pd, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_TYPE_2D,
                                                       VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_STORAGE_BIT, 0, &ifp),
              VK_SUCCESS);
    EXPECT_EQ(ifp.sampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT));
    // (R8_UNORM is a storage format since shaderStorageImageExtendedFormats, B8G8R8A8_UNORM as in lavapipe; sRGB
    // formats are none)
    EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(pd, VK_FORMAT_R8G8B8A8_SRGB, VK_IMAGE_TYPE_2D,
                                                       VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_STORAGE_BIT, 0, &ifp),
              VK_ERROR_FORMAT_NOT_SUPPORTED);
    // 1D images: transfers and sampling, no attachments (image_1d_test.cpp)
    EXPECT_EQ(
        vkGetPhysicalDeviceImageFormatProperties(pd, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_TYPE_1D,
                                                 VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0, &ifp),
        VK_SUCCESS);
    EXPECT_EQ(ifp.sampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT));
    EXPECT_EQ(
        vkGetPhysicalDeviceImageFormatProperties(pd, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_TYPE_1D,
                                                 VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0, &ifp),
        VK_ERROR_FORMAT_NOT_SUPPORTED);
    ASSERT_EQ(
        vkGetPhysicalDeviceImageFormatProperties(pd, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_TYPE_2D,
                                                 VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0, &ifp),
        VK_SUCCESS);
    EXPECT_EQ(ifp.sampleCounts, k14);
    EXPECT_EQ(h.message_count(), 0) << h.message_report();
}

// Unsupported requests fail with the right VkResult (no validation layer here: these calls are invalid on purpose).
TEST(TwoDrivers, TilevkRefusesWhatItLacks) {
    Harness h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    float prio = 1.0f;
    VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    q.queueCount = 1;
    q.pQueuePriorities = &prio;
    VkPhysicalDeviceFeatures want{};
    want.geometryShader = VK_TRUE;
    VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    ci.queueCreateInfoCount = 1;
    ci.pQueueCreateInfos = &q;
    ci.pEnabledFeatures = &want;
    VkDevice dev = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateDevice(pd, &ci, nullptr, &dev), VK_ERROR_FEATURE_NOT_PRESENT);
    ci.pEnabledFeatures = nullptr;
    const char* ext = "VK_EXT_mesh_shader";
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = &ext;
    EXPECT_EQ(vkCreateDevice(pd, &ci, nullptr, &dev), VK_ERROR_EXTENSION_NOT_PRESENT);

    // Every Vulkan 1.0 command has a proc address (the last 13 to arrive are listed); what tilevk cannot do fails
    // honestly: pipeline creation reports an error instead of returning a pipeline that would draw nothing, sparse
    // binding and pipeline-statistics pools are refused with an error.
    ci.enabledExtensionCount = 0;
    ASSERT_EQ(vkCreateDevice(pd, &ci, nullptr, &dev), VK_SUCCESS);
    for (const char* name :
         {"vkCreateQueryPool", "vkDestroyQueryPool", "vkGetQueryPoolResults", "vkCmdBeginQuery", "vkCmdEndQuery",
          "vkCmdResetQueryPool", "vkCmdWriteTimestamp", "vkCmdCopyQueryPoolResults", "vkCreateBufferView",
          "vkDestroyBufferView", "vkCmdDispatch", "vkCmdDispatchIndirect", "vkQueueBindSparse", "vkCmdCopyBuffer"})
        EXPECT_NE(vkGetDeviceProcAddr(dev, name), nullptr) << name;
    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
    qci.queryCount = 1;
    qci.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
    VkQueryPool qp = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateQueryPool(dev, &qci, nullptr, &qp), VK_ERROR_FEATURE_NOT_PRESENT);
    VkQueue queue = VK_NULL_HANDLE;
    vkGetDeviceQueue(dev, 0, 0, &queue);
    VkBindSparseInfo bind{VK_STRUCTURE_TYPE_BIND_SPARSE_INFO};
    EXPECT_EQ(vkQueueBindSparse(queue, 1, &bind, VK_NULL_HANDLE), VK_ERROR_FEATURE_NOT_PRESENT);
    VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    VkPipeline pipe = reinterpret_cast<VkPipeline>(uintptr_t(1));
    EXPECT_EQ(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gci, nullptr, &pipe), VK_ERROR_INITIALIZATION_FAILED);
    EXPECT_EQ(pipe, VK_NULL_HANDLE);
    vkDestroyDevice(dev, nullptr);
}

// Out-of-range regions (invalid usage, so no validation layer) are skipped with a message, never a crash.
TEST(TwoDrivers, TilevkSkipsOutOfRangeRegions) {
    Harness h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    Device dev(pd);
    ASSERT_TRUE(dev.ok());
    Device::Buffer buf = dev.make_buffer(64);
    std::memset(buf.map, 0x11, 64);
    Device::Image img = dev.make_image(VK_FORMAT_R8G8B8A8_UNORM, 4, 4, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    dev.run([&](VkCommandBuffer cb) {
        VkBufferCopy r{60, 0, 16};
        vkCmdCopyBuffer(cb, buf.buffer, buf.buffer, 1, &r);
        vkCmdFillBuffer(cb, buf.buffer, 128, 8, 0x22222222u);
        const uint32_t x = 0x33333333u;
        vkCmdUpdateBuffer(cb, buf.buffer, 64, 4, &x);
        VkBufferImageCopy bic{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {2, 2, 0}, {4, 4, 1}};
        vkCmdCopyBufferToImage(cb, buf.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &bic);
        VkBufferImageCopy big{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {4, 4, 1}};
        big.bufferRowLength = 1000;  // reads far past the 64-byte buffer
        vkCmdCopyBufferToImage(cb, buf.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &big);
        VkClearColorValue c{};
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 3, 1, 0, 1};  // level 3 does not exist
        vkCmdClearColorImage(cb, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &c, 1, &range);
    });
    const uint8_t* p = static_cast<const uint8_t*>(buf.map);
    for (int i = 0; i < 64; ++i) ASSERT_EQ(p[i], 0x11) << i;
    dev.destroy(img);
    dev.destroy(buf);
}

}  // namespace
