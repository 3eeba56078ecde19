// Counts the process's heap allocations: this executable's malloc family wraps glibc's own entry points, and the
// dynamic linker binds every library's malloc calls (the Vulkan loader, the driver it dlopens, libstdc++'s
// operator new) to the executable's definitions first. Not built with sanitizers (they interpose malloc
// themselves); alloc_count.h then reports that counting is off.
#include "alloc_count.h"

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdint>

extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void __libc_free(void*);
}

namespace {
std::atomic<uint64_t> g_allocations{0};
inline void count() {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

namespace tilevk::bench {
bool allocations_counted() {
    return true;
}
uint64_t allocations() {
    return g_allocations.load(std::memory_order_relaxed);
}
}  // namespace tilevk::bench

extern "C" {
void* malloc(size_t n) {
    count();
    return __libc_malloc(n);
}
void* calloc(size_t a, size_t b) {
    count();
    return __libc_calloc(a, b);
}
void* realloc(void* p, size_t n) {
    count();
    return __libc_realloc(p, n);
}
void free(void* p) {
    __libc_free(p);
}
void* memalign(size_t align, size_t n) {
    count();
    return __libc_memalign(align, n);
}
void* aligned_alloc(size_t align, size_t n) {
    count();
    return __libc_memalign(align, n);
}
int posix_memalign(void** out, size_t align, size_t n) {
    if (align < sizeof(void*) || (align & (align - 1)) != 0) return EINVAL;
    count();
    void* p = __libc_memalign(align, n);
    if (p == nullptr && n != 0) return ENOMEM;
    *out = p;
    return 0;
}
void* valloc(size_t n) {
    count();
    return __libc_memalign(4096, n);
}
}
