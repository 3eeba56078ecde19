#include "arena.h"

namespace tilevk::icd {

void* Arena::allocate(size_t size, size_t align) {
    if (head_ != nullptr) {
        size_t start = (head_->used + align - 1) & ~(align - 1);
        if (start + size <= head_->size) {
            head_->used = start + size;
            return head_->data + start;
        }
    }
    size_t capacity = size > kBlockSize ? size : kBlockSize;
    const VkAllocationCallbacks& a = callbacks_ != nullptr ? *callbacks_ : default_allocator();
    auto* block =
        static_cast<Block*>(host_alloc(a, offsetof(Block, data) + capacity, 16, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT));
    if (block == nullptr) return nullptr;
    block->next = head_;
    block->size = capacity;
    block->used = size;
    head_ = block;
    return block->data;
}

void Arena::release() {
    const VkAllocationCallbacks& a = callbacks_ != nullptr ? *callbacks_ : default_allocator();
    while (head_ != nullptr) {
        Block* next = head_->next;
        host_free(a, head_);
        head_ = next;
    }
}

}  // namespace tilevk::icd
