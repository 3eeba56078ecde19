// Memory shared outside the device (suite ApiExternalMemory): VK_KHR_external_memory_fd (OPAQUE_FD) and
// VK_EXT_external_memory_host (HOST_ALLOCATION), on tilevk and lavapipe with the validation layer on, plus the
// refusals of what tilevk does not import or export (suite ExternalMemoryRefusals: invalid usage on purpose, so no
// validation layer there).
#include <unistd.h>

#include <cstdlib>

#include "api_breadth.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

using ApiExternalMemory = ApiBreadth;

constexpr VkDeviceSize kPage = 4096;

const VkExternalMemoryHandleTypeFlagBits kMemoryHandleTypes[] = {
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT,
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_WIN32_BIT,
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_WIN32_KMT_BIT,
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_D3D11_TEXTURE_BIT,
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_D3D12_HEAP_BIT,
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_DMA_BUF_BIT_EXT,
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT,
    VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_MAPPED_FOREIGN_MEMORY_BIT_EXT};

// What the spec's tables and lavapipe's source say each handle type offers: OPAQUE_FD exportable and importable,
// HOST_ALLOCATION importable, nothing else.
VkExternalMemoryProperties expected_properties(VkExternalMemoryHandleTypeFlagBits type) {
    if (type == VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT)
        return {VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT | VK_EXTERNAL_MEMORY_FEATURE_IMPORTABLE_BIT, type, type};
    if (type == VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT)
        return {VK_EXTERNAL_MEMORY_FEATURE_IMPORTABLE_BIT, 0, type};
    return {};
}

VkExternalMemoryProperties buffer_properties(VkPhysicalDevice pd, VkExternalMemoryHandleTypeFlagBits type) {
    VkPhysicalDeviceExternalBufferInfo bi{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_BUFFER_INFO};
    bi.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    bi.handleType = type;
    VkExternalBufferProperties bp{VK_STRUCTURE_TYPE_EXTERNAL_BUFFER_PROPERTIES};
    bp.externalMemoryProperties = {~0u, ~0u, ~0u};
    vkGetPhysicalDeviceExternalBufferProperties(pd, &bi, &bp);
    return bp.externalMemoryProperties;
}

// A buffer that may live in memory of handle type `type`, and its requirements.
VkBuffer external_buffer(VkDevice dv, VkDeviceSize size, VkExternalMemoryHandleTypeFlagBits type,
                         VkMemoryRequirements& req) {
    VkExternalMemoryBufferCreateInfo ext{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
    ext.handleTypes = type;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, &ext};
    bci.size = size;
    bci.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer buf = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateBuffer(dv, &bci, nullptr, &buf), VK_SUCCESS);
    vkGetBufferMemoryRequirements(dv, buf, &req);
    return buf;
}

VkDeviceMemory allocate(VkDevice dv, const VkMemoryRequirements& req, const void* chain) {
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, chain};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = uint32_t(__builtin_ctz(req.memoryTypeBits));
    VkDeviceMemory mem = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateMemory(dv, &mai, nullptr, &mem), VK_SUCCESS);
    return mem;
}

uint8_t* map(VkDevice dv, VkDeviceMemory mem) {
    void* p = nullptr;
    EXPECT_EQ(vkMapMemory(dv, mem, 0, VK_WHOLE_SIZE, 0, &p), VK_SUCCESS);
    return static_cast<uint8_t*>(p);
}

// Every query answers for each memory handle type exactly what lavapipe answers and what the extensions promise;
// an image format query with a handle type tilevk cannot import says VK_ERROR_FORMAT_NOT_SUPPORTED, as the spec asks.
TEST_F(ApiExternalMemory, PropertiesOfEachHandleTypeAreLavapipes) {
    for (const VkExternalMemoryHandleTypeFlagBits type : kMemoryHandleTypes) {
        const VkExternalMemoryProperties t = buffer_properties(tilevk_->physical(), type);
        const VkExternalMemoryProperties l = buffer_properties(lavapipe_->physical(), type);
        const VkExternalMemoryProperties want = expected_properties(type);
        EXPECT_EQ(t.externalMemoryFeatures, want.externalMemoryFeatures) << type;
        EXPECT_EQ(t.exportFromImportedHandleTypes, want.exportFromImportedHandleTypes) << type;
        EXPECT_EQ(t.compatibleHandleTypes, want.compatibleHandleTypes) << type;
        EXPECT_EQ(l.externalMemoryFeatures, want.externalMemoryFeatures) << type;
        EXPECT_EQ(l.compatibleHandleTypes, want.compatibleHandleTypes) << type;

        VkPhysicalDeviceExternalImageFormatInfo ext{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_IMAGE_FORMAT_INFO};
        ext.handleType = type;
        VkPhysicalDeviceImageFormatInfo2 info{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGE_FORMAT_INFO_2, &ext};
        info.format = VK_FORMAT_R8G8B8A8_UNORM;
        info.type = VK_IMAGE_TYPE_2D;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        VkExternalImageFormatProperties ext_props{VK_STRUCTURE_TYPE_EXTERNAL_IMAGE_FORMAT_PROPERTIES};
        VkImageFormatProperties2 props{VK_STRUCTURE_TYPE_IMAGE_FORMAT_PROPERTIES_2, &ext_props};
        const VkResult r = vkGetPhysicalDeviceImageFormatProperties2(tilevk_->physical(), &info, &props);
        if (want.externalMemoryFeatures == 0) {
            EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << type;
            continue;
        }
        ASSERT_EQ(r, VK_SUCCESS) << type;
        EXPECT_EQ(ext_props.externalMemoryProperties.externalMemoryFeatures, want.externalMemoryFeatures) << type;
        EXPECT_EQ(ext_props.externalMemoryProperties.compatibleHandleTypes, want.compatibleHandleTypes) << type;
        EXPECT_GE(props.imageFormatProperties.maxExtent.width, 4096u) << type;
    }
    for (VkPhysicalDevice pd : {tilevk_->physical(), lavapipe_->physical()}) {
        VkPhysicalDeviceExternalMemoryHostPropertiesEXT host{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &host};
        vkGetPhysicalDeviceProperties2(pd, &p2);
        EXPECT_EQ(host.minImportedHostPointerAlignment, kPage);
    }
}

// OPAQUE_FD: memory exported as a file descriptor and imported again (on the same device) is the same bytes — a
// write through either mapping is seen through the other, and a copy on the device reads the imported bytes.
TEST_F(ApiExternalMemory, OpaqueFdExportAndImportShareTheBytes) {
    auto d = device_pair({VK_KHR_EXTERNAL_MEMORY_EXTENSION_NAME, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME});
    ASSERT_TRUE(d->ok());
    constexpr VkDeviceSize kSize = 3 * kPage + 100;
    constexpr auto kFd = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    for (Device* dev : {&d->tilevk, &d->lavapipe}) {
        const VkDevice dv = dev->device();
        auto get_fd = device_proc<PFN_vkGetMemoryFdKHR>(dv, "vkGetMemoryFdKHR");
        VkMemoryRequirements req{};
        const VkBuffer exported_buf = external_buffer(dv, kSize, kFd, req);
        VkExportMemoryAllocateInfo exp{VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO, nullptr, kFd};
        const VkDeviceMemory exported = allocate(dv, req, &exp);
        ASSERT_EQ(vkBindBufferMemory(dv, exported_buf, exported, 0), VK_SUCCESS);
        uint8_t* a = map(dv, exported);
        for (VkDeviceSize i = 0; i < kSize; ++i) a[i] = uint8_t(i * 7 + 3);

        VkMemoryGetFdInfoKHR gi{VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR, nullptr, exported, kFd};
        int fd = -1, fd2 = -1;
        ASSERT_EQ(get_fd(dv, &gi, &fd), VK_SUCCESS);
        ASSERT_EQ(get_fd(dv, &gi, &fd2), VK_SUCCESS);
        EXPECT_GE(fd, 0);
        EXPECT_NE(fd, fd2);  // each call makes a new descriptor the application owns
        close(fd2);

        VkMemoryRequirements req2{};
        const VkBuffer imported_buf = external_buffer(dv, kSize, kFd, req2);
        VkImportMemoryFdInfoKHR imp{VK_STRUCTURE_TYPE_IMPORT_MEMORY_FD_INFO_KHR, nullptr, kFd, fd};
        const VkDeviceMemory imported = allocate(dv, req, &imp);  // fd now belongs to the driver
        ASSERT_EQ(vkBindBufferMemory(dv, imported_buf, imported, 0), VK_SUCCESS);
        uint8_t* b = map(dv, imported);
        ASSERT_NE(a, b);
        for (VkDeviceSize i = 0; i < kSize; ++i) ASSERT_EQ(b[i], uint8_t(i * 7 + 3)) << i;
        b[kPage + 5] = 0xa5;
        EXPECT_EQ(a[kPage + 5], 0xa5);

        Device::Buffer copy = dev->make_buffer(kSize);
        ASSERT_EQ(dev->run([&](VkCommandBuffer c) {
            const VkBufferCopy region{0, 0, kSize};
            vkCmdCopyBuffer(c, imported_buf, copy.buffer, 1, &region);
        }),
                  VK_SUCCESS);
        EXPECT_EQ(std::memcmp(copy.map, a, kSize), 0);
        dev->destroy(copy);
        vkDestroyBuffer(dv, imported_buf, nullptr);
        vkDestroyBuffer(dv, exported_buf, nullptr);
        vkFreeMemory(dv, imported, nullptr);
        vkFreeMemory(dv, exported, nullptr);
    }
    EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
}

// HOST_ALLOCATION: the application's own pages are the memory — a fill on the device lands in them in place, and
// the bytes around it stay the application's.
TEST_F(ApiExternalMemory, HostPointerMemoryIsTheApplicationsPages) {
    auto d = device_pair({VK_KHR_EXTERNAL_MEMORY_EXTENSION_NAME, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME});
    ASSERT_TRUE(d->ok());
    constexpr VkDeviceSize kSize = 4 * kPage;
    constexpr auto kHost = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
    for (Device* dev : {&d->tilevk, &d->lavapipe}) {
        const VkDevice dv = dev->device();
        auto* pages = static_cast<uint8_t*>(std::aligned_alloc(kPage, kSize));
        std::memset(pages, 0x11, kSize);
        auto host_props =
            device_proc<PFN_vkGetMemoryHostPointerPropertiesEXT>(dv, "vkGetMemoryHostPointerPropertiesEXT");
        VkMemoryHostPointerPropertiesEXT hp{VK_STRUCTURE_TYPE_MEMORY_HOST_POINTER_PROPERTIES_EXT};
        ASSERT_EQ(host_props(dv, kHost, pages, &hp), VK_SUCCESS);
        EXPECT_EQ(hp.memoryTypeBits, 1u);

        VkMemoryRequirements req{};
        const VkBuffer buf = external_buffer(dv, kSize, kHost, req);
        req.size = kSize;  // the import spans exactly the application's pages
        req.memoryTypeBits &= hp.memoryTypeBits;
        VkImportMemoryHostPointerInfoEXT imp{VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT, nullptr, kHost,
                                             pages};
        const VkDeviceMemory mem = allocate(dv, req, &imp);
        ASSERT_EQ(vkBindBufferMemory(dv, buf, mem, 0), VK_SUCCESS);
        EXPECT_EQ(map(dv, mem), pages);
        vkUnmapMemory(dv, mem);
        ASSERT_EQ(dev->run([&](VkCommandBuffer c) { vkCmdFillBuffer(c, buf, kPage + 64, 256, 0xdeadbeefu); }),
                  VK_SUCCESS);
        for (VkDeviceSize i = 0; i < kSize; ++i) {
            const bool filled = i >= kPage + 64 && i < kPage + 64 + 256;
            const uint8_t want = filled ? uint8_t(0xdeadbeefu >> (8 * (i % 4))) : 0x11;
            ASSERT_EQ(pages[i], want) << i;
        }
        vkDestroyBuffer(dv, buf, nullptr);
        vkFreeMemory(dv, mem, nullptr);
        std::free(pages);
    }
    EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
}

// What tilevk does not import or export fails with VK_ERROR_INVALID_EXTERNAL_HANDLE and a line naming the Vulkan
// rule, and creates nothing. Invalid usage on purpose: no validation layer.
TEST(ExternalMemoryRefusals, EachRefusalNamesItsRule) {
    Harness h(false);
    ASSERT_TRUE(h.instance() != VK_NULL_HANDLE);
    Device dev(h.find_device("tilevk"), nullptr,
               {VK_KHR_EXTERNAL_MEMORY_EXTENSION_NAME, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME,
                VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME});
    ASSERT_TRUE(dev.ok());
    const VkDevice dv = dev.device();
    auto try_allocate = [&](VkDeviceSize size, const void* chain, const char* says) {
        VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, chain, size, 0};
        VkDeviceMemory mem = VK_NULL_HANDLE;
        StderrCapture err;
        EXPECT_EQ(vkAllocateMemory(dv, &mai, nullptr, &mem), VK_ERROR_INVALID_EXTERNAL_HANDLE) << says;
        EXPECT_EQ(mem, VK_NULL_HANDLE) << says;
        EXPECT_NE(err.text().find(says), std::string::npos) << err.text();
    };
    auto* pages = static_cast<uint8_t*>(std::aligned_alloc(kPage, 2 * kPage));
    VkImportMemoryHostPointerInfoEXT host{VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT, nullptr,
                                          VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT, pages + 64};
    try_allocate(kPage, &host, "pHostPointer-01749");
    host.pHostPointer = pages;
    try_allocate(kPage + 16, &host, "allocationSize-01745");
    host.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_MAPPED_FOREIGN_MEMORY_BIT_EXT;
    try_allocate(kPage, &host, "VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT");
    VkExportMemoryAllocateInfo exp{VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO, nullptr,
                                   VK_EXTERNAL_MEMORY_HANDLE_TYPE_DMA_BUF_BIT_EXT};
    try_allocate(kPage, &exp, "exports only VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT");
    VkImportMemoryFdInfoKHR imp{VK_STRUCTURE_TYPE_IMPORT_MEMORY_FD_INFO_KHR, nullptr,
                                VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT, -1};
    try_allocate(kPage, &imp, "is not a file exported by vkGetMemoryFdKHR");
    std::free(pages);

    // Memory allocated without VkExportMemoryAllocateInfo has no descriptor to give.
    VkMemoryAllocateInfo plain{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, kPage, 0};
    VkDeviceMemory mem = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateMemory(dv, &plain, nullptr, &mem), VK_SUCCESS);
    auto get_fd = device_proc<PFN_vkGetMemoryFdKHR>(dv, "vkGetMemoryFdKHR");
    VkMemoryGetFdInfoKHR gi{VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR, nullptr, mem,
                            VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT};
    int fd = 12345;
    {
        StderrCapture err;
        EXPECT_NE(get_fd(dv, &gi, &fd), VK_SUCCESS);
        EXPECT_NE(err.text().find("VUID-VkMemoryGetFdInfoKHR-handleType-00671"), std::string::npos) << err.text();
    }
    EXPECT_EQ(fd, 12345);
    vkFreeMemory(dv, mem, nullptr);
}

}  // namespace
}  // namespace tilevk::test::breadth
