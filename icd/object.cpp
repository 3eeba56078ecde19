#include "object.h"

#include <malloc.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace tilevk::icd {
namespace {

void* VKAPI_CALL default_alloc(void*, size_t size, size_t align, VkSystemAllocationScope) {
    if (align < sizeof(void*)) align = sizeof(void*);
    void* p = nullptr;
    if (posix_memalign(&p, align, size == 0 ? 1 : size) != 0) return nullptr;
    return p;
}

// The spec's pfnReallocation contract: null old -> allocate; size 0 -> free and return null; otherwise a block of
// `size` bytes aligned to `align` holding the old contents up to the smaller size (the old block is freed only on
// success). tilevk itself never reallocates through the callbacks.
void* VKAPI_CALL default_realloc(void* user, void* old, size_t size, size_t align, VkSystemAllocationScope s) {
    if (old == nullptr) return default_alloc(user, size, align, s);
    if (size == 0) {
        free(old);
        return nullptr;
    }
    void* p = default_alloc(user, size, align, s);
    if (p == nullptr) return nullptr;
    std::memcpy(p, old, std::min(size, malloc_usable_size(old)));
    free(old);
    return p;
}

void VKAPI_CALL default_free(void*, void* p) {
    free(p);
}

void vlog(const char* fmt, va_list ap) {
    char buf[512];
    vsnprintf(buf, sizeof buf, fmt, ap);
    fprintf(stderr, "tilevk: %s\n", buf);
}

}  // namespace

const VkAllocationCallbacks& default_allocator() {
    static const VkAllocationCallbacks kDefault = {nullptr,      default_alloc, default_realloc,
                                                   default_free, nullptr,       nullptr};
    return kDefault;
}

const VkAllocationCallbacks& pick_allocator(const VkAllocationCallbacks* app, const VkAllocationCallbacks* parent) {
    if (app != nullptr) return *app;
    if (parent != nullptr) return *parent;
    return default_allocator();
}

void* host_alloc(const VkAllocationCallbacks& a, size_t size, size_t align, VkSystemAllocationScope scope) {
    return a.pfnAllocation(a.pUserData, size, align, scope);
}

void host_free(const VkAllocationCallbacks& a, void* p) {
    if (p != nullptr) a.pfnFree(a.pUserData, p);
}

VkResult fail(VkResult result, const char* fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vlog(fmt, ap);
    va_end(ap);
    return result;
}

void log_error(const char* fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vlog(fmt, ap);
    va_end(ap);
}

}  // namespace tilevk::icd
