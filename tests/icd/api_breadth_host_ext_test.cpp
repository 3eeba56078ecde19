// Device extensions with nothing to draw (suite ApiHostExtensions), on tilevk and lavapipe with the validation layer
// on: VK_KHR_external_memory / _fence / _semaphore with no handle type (tilevk exports and imports no fence or
// semaphore, and says so in every external-properties query), and VK_EXT_calibrated_timestamps (the device domain is
// the clock of vkCmdWriteTimestamp, CLOCK_MONOTONIC nanoseconds, as lavapipe's).
#include <time.h>

#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

using ApiHostExtensions = ApiBreadth;

// Objects made with the export/external structs of the three extensions and handleTypes 0, which Vulkan allows
// whatever handle types a driver supports: each is made on both drivers without a validation message.
TEST_F(ApiHostExtensions, ExternalStructsWithNoHandleTypes) {
    auto d = device_pair({VK_KHR_EXTERNAL_MEMORY_EXTENSION_NAME, VK_KHR_EXTERNAL_FENCE_EXTENSION_NAME,
                          VK_KHR_EXTERNAL_SEMAPHORE_EXTENSION_NAME});
    ASSERT_TRUE(d->ok());
    for (Device* dev : {&d->tilevk, &d->lavapipe}) {
        const VkDevice dv = dev->device();
        VkExternalMemoryBufferCreateInfo ext_buf{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
        VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, &ext_buf};
        bci.size = 256;
        bci.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        VkBuffer buf = VK_NULL_HANDLE;
        ASSERT_EQ(vkCreateBuffer(dv, &bci, nullptr, &buf), VK_SUCCESS);
        VkExternalMemoryImageCreateInfo ext_img{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_IMAGE_CREATE_INFO};
        VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, &ext_img};
        ici.imageType = VK_IMAGE_TYPE_2D;
        ici.format = VK_FORMAT_R8G8B8A8_UNORM;
        ici.extent = {16, 16, 1};
        ici.mipLevels = ici.arrayLayers = 1;
        ici.samples = VK_SAMPLE_COUNT_1_BIT;
        ici.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        VkImage img = VK_NULL_HANDLE;
        ASSERT_EQ(vkCreateImage(dv, &ici, nullptr, &img), VK_SUCCESS);
        VkMemoryRequirements req{};
        vkGetBufferMemoryRequirements(dv, buf, &req);
        VkExportMemoryAllocateInfo export_mem{VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO};
        VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &export_mem};
        mai.allocationSize = req.size;
        mai.memoryTypeIndex = uint32_t(__builtin_ctz(req.memoryTypeBits));
        VkDeviceMemory mem = VK_NULL_HANDLE;
        ASSERT_EQ(vkAllocateMemory(dv, &mai, nullptr, &mem), VK_SUCCESS);
        EXPECT_EQ(vkBindBufferMemory(dv, buf, mem, 0), VK_SUCCESS);
        VkExportFenceCreateInfo export_fence{VK_STRUCTURE_TYPE_EXPORT_FENCE_CREATE_INFO};
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, &export_fence, VK_FENCE_CREATE_SIGNALED_BIT};
        VkFence fence = VK_NULL_HANDLE;
        ASSERT_EQ(vkCreateFence(dv, &fci, nullptr, &fence), VK_SUCCESS);
        EXPECT_EQ(vkGetFenceStatus(dv, fence), VK_SUCCESS);
        VkExportSemaphoreCreateInfo export_sem{VK_STRUCTURE_TYPE_EXPORT_SEMAPHORE_CREATE_INFO};
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &export_sem};
        VkSemaphore sem = VK_NULL_HANDLE;
        ASSERT_EQ(vkCreateSemaphore(dv, &sci, nullptr, &sem), VK_SUCCESS);
        vkDestroySemaphore(dv, sem, nullptr);
        vkDestroyFence(dv, fence, nullptr);
        vkDestroyBuffer(dv, buf, nullptr);
        vkDestroyImage(dv, img, nullptr);
        vkFreeMemory(dv, mem, nullptr);
    }
    EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
}

// tilevk can export and import no fence or semaphore handle type: every query of the *_capabilities extensions says
// so for each handle type of Vulkan 1.1 and the Linux sync fd, so a program never picks one. (Memory handle types:
// api_breadth_external_memory_test.cpp.)
TEST_F(ApiHostExtensions, NoExternalSyncHandleTypeIsOffered) {
    const VkPhysicalDevice pd = tilevk_->physical();
    for (const VkExternalFenceHandleTypeFlagBits bit :
         {VK_EXTERNAL_FENCE_HANDLE_TYPE_OPAQUE_FD_BIT, VK_EXTERNAL_FENCE_HANDLE_TYPE_OPAQUE_WIN32_BIT,
          VK_EXTERNAL_FENCE_HANDLE_TYPE_SYNC_FD_BIT}) {
        VkPhysicalDeviceExternalFenceInfo fi{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_FENCE_INFO};
        fi.handleType = bit;
        VkExternalFenceProperties fp{VK_STRUCTURE_TYPE_EXTERNAL_FENCE_PROPERTIES};
        fp.externalFenceFeatures = ~0u;
        vkGetPhysicalDeviceExternalFenceProperties(pd, &fi, &fp);
        EXPECT_EQ(fp.externalFenceFeatures, 0u) << bit;
    }
    for (const VkExternalSemaphoreHandleTypeFlagBits bit :
         {VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT, VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_WIN32_BIT,
          VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_SYNC_FD_BIT}) {
        VkPhysicalDeviceExternalSemaphoreInfo si{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_SEMAPHORE_INFO};
        si.handleType = bit;
        VkExternalSemaphoreProperties sp{VK_STRUCTURE_TYPE_EXTERNAL_SEMAPHORE_PROPERTIES};
        sp.externalSemaphoreFeatures = ~0u;
        vkGetPhysicalDeviceExternalSemaphoreProperties(pd, &si, &sp);
        EXPECT_EQ(sp.externalSemaphoreFeatures, 0u) << bit;
    }
}

uint64_t monotonic_ns() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}

// VK_EXT_calibrated_timestamps: the domains are lavapipe's (DEVICE and CLOCK_MONOTONIC, in its order); one call reads
// both domains at the same instant of CLOCK_MONOTONIC (read here before and after), and a vkCmdWriteTimestamp value
// lies between the device-domain readings taken before the submit and after its fence.
TEST_F(ApiHostExtensions, CalibratedTimestampsShareTheTimestampClock) {
    auto domains = [](VkPhysicalDevice pd) {
        auto get = reinterpret_cast<PFN_vkGetPhysicalDeviceCalibrateableTimeDomainsEXT>(
            vkGetInstanceProcAddr(harness_->instance(), "vkGetPhysicalDeviceCalibrateableTimeDomainsEXT"));
        uint32_t n = 0;
        EXPECT_EQ(get(pd, &n, nullptr), VK_SUCCESS);
        std::vector<VkTimeDomainEXT> all(n);
        EXPECT_EQ(get(pd, &n, all.data()), VK_SUCCESS);
        if (n > 1) {
            uint32_t one = 1;
            EXPECT_EQ(get(pd, &one, all.data()), VK_INCOMPLETE);
        }
        return all;
    };
    const std::vector<VkTimeDomainEXT> t = domains(tilevk_->physical());
    EXPECT_EQ(t, domains(lavapipe_->physical()));
    ASSERT_EQ(t, (std::vector<VkTimeDomainEXT>{VK_TIME_DOMAIN_DEVICE_EXT, VK_TIME_DOMAIN_CLOCK_MONOTONIC_EXT}));

    auto d = device_pair({VK_EXT_CALIBRATED_TIMESTAMPS_EXTENSION_NAME});
    ASSERT_TRUE(d->ok());
    const VkDevice dv = d->tilevk.device();
    auto calibrated = device_proc<PFN_vkGetCalibratedTimestampsEXT>(dv, "vkGetCalibratedTimestampsEXT");
    const VkCalibratedTimestampInfoEXT infos[2] = {
        {VK_STRUCTURE_TYPE_CALIBRATED_TIMESTAMP_INFO_EXT, nullptr, VK_TIME_DOMAIN_DEVICE_EXT},
        {VK_STRUCTURE_TYPE_CALIBRATED_TIMESTAMP_INFO_EXT, nullptr, VK_TIME_DOMAIN_CLOCK_MONOTONIC_EXT}};
    uint64_t before[2] = {}, after[2] = {}, deviation = 0;
    const uint64_t host0 = monotonic_ns();
    ASSERT_EQ(calibrated(dv, 2, infos, before, &deviation), VK_SUCCESS);
    const uint64_t host1 = monotonic_ns();
    EXPECT_EQ(before[0], before[1]);
    EXPECT_LE(host0, before[1]);
    EXPECT_LE(before[1], host1);
    EXPECT_GE(deviation, 1u);

    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qci.queryCount = 1;
    VkQueryPool pool = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateQueryPool(dv, &qci, nullptr, &pool), VK_SUCCESS);
    EXPECT_EQ(d->tilevk.run([&](VkCommandBuffer c) {
        vkCmdResetQueryPool(c, pool, 0, 1);
        vkCmdWriteTimestamp(c, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool, 0);
    }),
              VK_SUCCESS);
    ASSERT_EQ(calibrated(dv, 2, infos, after, &deviation), VK_SUCCESS);
    uint64_t written = 0;
    ASSERT_EQ(vkGetQueryPoolResults(dv, pool, 0, 1, sizeof written, &written, sizeof written,
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              VK_SUCCESS);
    vkDestroyQueryPool(dv, pool, nullptr);
    EXPECT_LE(before[0], written);
    EXPECT_LE(written, after[0]);
    EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
}

}  // namespace
}  // namespace tilevk::test::breadth
