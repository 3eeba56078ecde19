// A bump allocator for recorded commands: 64 KiB blocks from the command pool's allocation callbacks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "object.h"

namespace tilevk::icd {

class Arena {
  public:
    explicit Arena(const VkAllocationCallbacks* callbacks = nullptr) : callbacks_(callbacks) {}
    ~Arena() { release(); }
    Arena(const Arena&) = delete;
    Arena& operator=(const Arena&) = delete;

    void set_callbacks(const VkAllocationCallbacks* callbacks) { callbacks_ = callbacks; }
    // Returns `size` bytes aligned to `align` (a power of two <= 16), or nullptr when out of memory.
    void* allocate(size_t size, size_t align);
    // Frees every block.
    void release();
    // Forgets every allocation but keeps the blocks for the next ones (a command buffer re-recorded every frame
    // then allocates nothing); release() frees them.
    void rewind();
    // Frees the blocks rewind() kept.
    void trim();

    template <class T>
    T* copy_array(const T* src, size_t count) {
        if (count == 0 || src == nullptr) return nullptr;
        T* dst = static_cast<T*>(allocate(sizeof(T) * count, alignof(T)));
        if (dst != nullptr) std::memcpy(static_cast<void*>(dst), src, sizeof(T) * count);
        return dst;
    }

  private:
    struct Block {
        Block* next;
        size_t size;
        size_t used;
        alignas(16) unsigned char data[1];
    };
    static constexpr size_t kBlockSize = 64 * 1024;
    const VkAllocationCallbacks* callbacks_;
    Block* head_ = nullptr;
    Block* spare_ = nullptr;  // rewound blocks, reused before new ones are allocated
};

}  // namespace tilevk::icd
