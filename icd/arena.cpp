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
    // A rewound block large enough (blocks are kBlockSize unless one allocation was larger).
    for (Block** link = &spare_; *link != nullptr; link = &(*link)->next) {
        Block* b = *link;
        if (b->size < size) continue;
        *link = b->next;
        b->next = head_;
        b->used = size;
        head_ = b;
        return b->data;
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
    rewind();
    trim();
}

void Arena::trim() {
    const VkAllocationCallbacks& a = callbacks_ != nullptr ? *callbacks_ : default_allocator();
    while (spare_ != nullptr) {
        Block* next = spare_->next;
        host_free(a, spare_);
        spare_ = next;
    }
}

void Arena::rewind() {
    while (head_ != nullptr) {
        Block* next = head_->next;
        head_->used = 0;
        head_->next = spare_;
        spare_ = head_;
        head_ = next;
    }
}

}  // namespace tilevk::icd
