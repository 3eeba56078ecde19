#include "memory_external.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>

#include "entrypoints.h"
#include "object.h"

namespace tilevk::icd {

namespace {

VkDeviceSize round_up(VkDeviceSize v, VkDeviceSize to) {
    return (v + to - 1) / to * to;
}

// Maps `bytes` of the shared file `fd` into `mem`, which owns fd from then on.
VkResult map_shared_file(int fd, VkDeviceSize bytes, DeviceMemory& mem, const char* what) {
    const size_t length = size_t(round_up(bytes, VkDeviceSize(sysconf(_SC_PAGESIZE))));
    void* p = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (p == MAP_FAILED) {
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory: cannot map the %s file of %llu bytes", what,
                    (unsigned long long)bytes);
    }
    mem.data = static_cast<uint8_t*>(p);
    mem.mapped_bytes = length;
    mem.fd = fd;
    mem.backing = DeviceMemory::Backing::SharedFile;
    return VK_SUCCESS;
}

// A new OPAQUE_FD allocation: an anonymous shared file (memfd), zero-filled by the kernel.
VkResult export_new_file(VkDeviceSize size, DeviceMemory& mem) {
    const int fd = memfd_create("tilevk-device-memory", MFD_CLOEXEC);
    if (fd < 0) return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory: memfd_create failed");
    if (ftruncate(fd, off_t(size)) != 0) {
        close(fd);
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory: cannot size a shared file of %llu bytes",
                    (unsigned long long)size);
    }
    const VkResult r = map_shared_file(fd, size, mem, "exportable");
    if (r != VK_SUCCESS) close(fd);
    return r;
}

VkResult import_file(const VkImportMemoryFdInfoKHR& import, VkDeviceSize size, DeviceMemory& mem) {
    if (import.handleType != VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkAllocateMemory: VkImportMemoryFdInfoKHR::handleType %#x is not importable: tilevk imports only "
                    "VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT",
                    unsigned(import.handleType));
    }
    struct stat st {};
    if (import.fd < 0 || fstat(import.fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkAllocateMemory: VkImportMemoryFdInfoKHR::fd %d is not a file exported by vkGetMemoryFdKHR",
                    import.fd);
    }
    if (VkDeviceSize(st.st_size) < size) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkAllocateMemory: the imported file holds %llu bytes, fewer than allocationSize %llu",
                    (unsigned long long)st.st_size, (unsigned long long)size);
    }
    return map_shared_file(import.fd, size, mem, "imported");
}

VkResult import_host_pointer(const VkImportMemoryHostPointerInfoEXT& import, VkDeviceSize size, DeviceMemory& mem) {
    if (import.handleType != VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkAllocateMemory: VkImportMemoryHostPointerInfoEXT::handleType %#x is not importable: tilevk "
                    "imports only VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT",
                    unsigned(import.handleType));
    }
    if (reinterpret_cast<uintptr_t>(import.pHostPointer) % kMinImportedHostPointerAlignment != 0 ||
        size % kMinImportedHostPointerAlignment != 0) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkAllocateMemory: pHostPointer and allocationSize must be multiples of "
                    "minImportedHostPointerAlignment (%llu; VUID-VkImportMemoryHostPointerInfoEXT-pHostPointer-01749, "
                    "VUID-VkMemoryAllocateInfo-allocationSize-01745)",
                    (unsigned long long)kMinImportedHostPointerAlignment);
    }
    mem.data = static_cast<uint8_t*>(import.pHostPointer);
    mem.backing = DeviceMemory::Backing::HostPointer;
    return VK_SUCCESS;
}

VkResult allocate_heap(VkDeviceSize size, DeviceMemory& mem) {
    // Device memory is not host memory in Vulkan's sense: it does not go through the allocation callbacks.
    void* p = nullptr;
    if (posix_memalign(&p, kMemoryAlignment, size_t(round_up(size, kMemoryAlignment))) != 0) {
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory: cannot allocate %llu bytes",
                    (unsigned long long)size);
    }
    mem.data = static_cast<uint8_t*>(p);
    mem.backing = DeviceMemory::Backing::Heap;
    return VK_SUCCESS;
}

}  // namespace

ExternalMemorySupport external_memory_support(VkExternalMemoryHandleTypeFlagBits type) {
    ExternalMemorySupport s;
    if (type == VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT) {
        s.supported = true;
        s.properties.externalMemoryFeatures =
            VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT | VK_EXTERNAL_MEMORY_FEATURE_IMPORTABLE_BIT;
        s.properties.exportFromImportedHandleTypes = type;
        s.properties.compatibleHandleTypes = type;
    } else if (type == VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT) {
        s.supported = true;
        s.properties.externalMemoryFeatures = VK_EXTERNAL_MEMORY_FEATURE_IMPORTABLE_BIT;
        s.properties.compatibleHandleTypes = type;
    }
    return s;
}

VkResult allocate_memory_backing(const VkMemoryAllocateInfo& info, DeviceMemory& mem) {
    const VkDeviceSize size = info.allocationSize;
    mem.size = size;
    if (const auto* host = find_in_chain<VkImportMemoryHostPointerInfoEXT>(
            info.pNext, VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT)) {
        return import_host_pointer(*host, size, mem);
    }
    if (const auto* file =
            find_in_chain<VkImportMemoryFdInfoKHR>(info.pNext, VK_STRUCTURE_TYPE_IMPORT_MEMORY_FD_INFO_KHR)) {
        return import_file(*file, size, mem);
    }
    const auto* exported =
        find_in_chain<VkExportMemoryAllocateInfo>(info.pNext, VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO);
    if (exported == nullptr || exported->handleTypes == 0) return allocate_heap(size, mem);
    if (exported->handleTypes != VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkAllocateMemory: VkExportMemoryAllocateInfo::handleTypes %#x: tilevk exports only "
                    "VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT",
                    unsigned(exported->handleTypes));
    }
    return export_new_file(size, mem);
}

void free_memory_backing(DeviceMemory& mem) {
    switch (mem.backing) {
        case DeviceMemory::Backing::Heap:
            free(mem.data);
            break;
        case DeviceMemory::Backing::HostPointer:  // the application's pages stay the application's
            break;
        case DeviceMemory::Backing::SharedFile:
            munmap(mem.data, mem.mapped_bytes);
            close(mem.fd);
            break;
    }
    mem.data = nullptr;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetMemoryFdKHR(VkDevice, const VkMemoryGetFdInfoKHR* pGetFdInfo, int* pFd) {
    const DeviceMemory* mem = from_handle<DeviceMemory>(pGetFdInfo->memory);
    if (pGetFdInfo->handleType != VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT || mem->fd < 0) {
        return fail(VK_ERROR_TOO_MANY_OBJECTS,
                    "vkGetMemoryFdKHR: the memory was not allocated with VkExportMemoryAllocateInfo::handleTypes "
                    "VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT (VUID-VkMemoryGetFdInfoKHR-handleType-00671)");
    }
    const int fd = fcntl(mem->fd, F_DUPFD_CLOEXEC, 0);
    if (fd < 0) return fail(VK_ERROR_TOO_MANY_OBJECTS, "vkGetMemoryFdKHR: no file descriptor left");
    *pFd = fd;
    return VK_SUCCESS;
}

// OPAQUE_FD, the one type tilevk imports from a file descriptor, is not one this query may ask about
// (VUID-vkGetMemoryFdPropertiesKHR-handleType-00674), so every call is answered with an invalid handle.
VKAPI_ATTR VkResult VKAPI_CALL tvk_GetMemoryFdPropertiesKHR(VkDevice, VkExternalMemoryHandleTypeFlagBits handleType,
                                                            int, VkMemoryFdPropertiesKHR*) {
    return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                "vkGetMemoryFdPropertiesKHR: handle type %#x: tilevk imports file descriptors only as "
                "VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT, which this query does not take",
                unsigned(handleType));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetMemoryHostPointerPropertiesEXT(VkDevice,
                                                                     VkExternalMemoryHandleTypeFlagBits handleType,
                                                                     const void* pHostPointer,
                                                                     VkMemoryHostPointerPropertiesEXT* pProperties) {
    if (handleType != VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkGetMemoryHostPointerPropertiesEXT: handle type %#x: tilevk imports host pointers only as "
                    "VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT",
                    unsigned(handleType));
    }
    if (reinterpret_cast<uintptr_t>(pHostPointer) % kMinImportedHostPointerAlignment != 0) {
        return fail(VK_ERROR_INVALID_EXTERNAL_HANDLE,
                    "vkGetMemoryHostPointerPropertiesEXT: pHostPointer is not aligned to "
                    "minImportedHostPointerAlignment (VUID-vkGetMemoryHostPointerPropertiesEXT-pHostPointer-01753)");
    }
    pProperties->memoryTypeBits = 1;  // the one memory type
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
