// HugePageAllocator<T>: a std::allocator for the scene's large stores (primitives, plane records), which a tile
// reads in API order with gaps: a block of 2 MB or more is 2 MB aligned and asks Linux for transparent huge pages
// (madvise; the system's default is "madvise" here), so a random read costs a cache miss but no page walk (a
// 56 MB store in 4 KB pages is ~14 000 pages, far more than the TLB holds). Smaller blocks, and other systems,
// get plain operator new.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tilevk::rast {

template <class T>
struct HugePageAllocator {
    using value_type = T;
    static constexpr size_t kHugePage = size_t{2} << 20;

    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor)

    T* allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        const size_t bytes = n * sizeof(T);
        if (bytes < kHugePage) return static_cast<T*>(::operator new(bytes));
        const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* p = std::aligned_alloc(kHugePage, rounded);
        if (!p) throw std::bad_alloc();
#if defined(__linux__)
        madvise(p, rounded, MADV_HUGEPAGE);  // a hint: without huge pages the store works the same
#endif
        return static_cast<T*>(p);
    }
    void deallocate(T* p, size_t n) noexcept {
        if (n * sizeof(T) < kHugePage)
            ::operator delete(p);
        else
            std::free(p);
    }
    template <class U>
    bool operator==(const HugePageAllocator<U>&) const noexcept {
        return true;
    }
};

}  // namespace tilevk::rast
