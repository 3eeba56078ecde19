// Common base of every tilevk Vulkan object: loader data for dispatchable handles, type-checked handle casts,
// allocation through VkAllocationCallbacks, and the one-line error log.
#pragma once
#include <vulkan/vk_icd.h>
#include <vulkan/vulkan.h>

#include <cassert>
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace tilevk::icd {

// Logs "tilevk: <what>" to stderr once per call site message and returns `result` (so call sites read
// `return fail(VK_ERROR_..., "why")`).
VkResult fail(VkResult result, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
void log_error(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

// Dispatchable objects: the loader overwrites the first pointer-sized field, so it must be VK_LOADER_DATA at
// offset 0 (no virtual functions anywhere in these types).
struct DispatchableObject {
    VK_LOADER_DATA loader_data;
    VkObjectType object_type;
    VkAllocationCallbacks allocator;  // the callbacks this object was allocated with (defaults when none given)

    explicit DispatchableObject(VkObjectType t) : object_type(t) { loader_data.loaderMagic = ICD_LOADER_MAGIC; }
};

struct NonDispatchableObject {
    VkObjectType object_type;
    VkAllocationCallbacks allocator;
    explicit NonDispatchableObject(VkObjectType t) : object_type(t) {}
};

// The struct of type `t` in a const pNext chain, or nullptr.
template <class T>
const T* find_in_chain(const void* chain, VkStructureType t) {
    for (auto* s = static_cast<const VkBaseInStructure*>(chain); s != nullptr; s = s->pNext)
        if (s->sType == t) return reinterpret_cast<const T*>(s);
    return nullptr;
}

// ---- host allocation ------------------------------------------------------------------------------------------
const VkAllocationCallbacks& default_allocator();
// The callbacks to use: the application's if given, else the parent's, else the defaults.
const VkAllocationCallbacks& pick_allocator(const VkAllocationCallbacks* app, const VkAllocationCallbacks* parent);
void* host_alloc(const VkAllocationCallbacks& a, size_t size, size_t align, VkSystemAllocationScope scope);
void host_free(const VkAllocationCallbacks& a, void* p);

// Allocates and constructs T (whose constructor takes the remaining args); nullptr on allocation failure.
template <class T, class... Args>
T* create_object(const VkAllocationCallbacks& a, VkSystemAllocationScope scope, Args&&... args) {
    void* mem = host_alloc(a, sizeof(T), alignof(T) < 16 ? 16 : alignof(T), scope);
    if (mem == nullptr) return nullptr;
    T* obj = new (mem) T(std::forward<Args>(args)...);
    obj->allocator = a;
    return obj;
}

// Drops the private data (private_data.cpp) attached to the object at `handle`, if any has ever been set.
void forget_private_data(const void* handle);

template <class T>
void destroy_object(T* obj) {
    if (obj == nullptr) return;
    forget_private_data(obj);
    VkAllocationCallbacks a = obj->allocator;
    obj->~T();
    host_free(a, obj);
}

// ---- handle casts ---------------------------------------------------------------------------------------------
// Each object type declares `using Handle = VkXxx; static constexpr VkObjectType kType = ...;`.
template <class T>
T* from_handle(typename T::Handle h) {
    T* obj = reinterpret_cast<T*>(h);
    assert(obj == nullptr || obj->object_type == T::kType);
    return obj;
}

template <class T>
typename T::Handle to_handle(T* obj) {
    return reinterpret_cast<typename T::Handle>(obj);
}

// Checks at compile time that the loader's data sits at offset 0 of a dispatchable object: it is the first field
// of DispatchableObject (standard layout), which is the first and only base of T (no virtual functions, so no
// vtable pointer ahead of it; the Itanium C++ ABI puts a non-virtual first base at offset 0).
static_assert(std::is_standard_layout_v<VK_LOADER_DATA> && sizeof(VK_LOADER_DATA) == sizeof(void*));
static_assert(offsetof(DispatchableObject, loader_data) == 0);
#define TILEVK_ASSERT_DISPATCHABLE(T)                                                    \
    static_assert(std::is_base_of_v<DispatchableObject, T> && !std::is_polymorphic_v<T>, \
                  #T ": must derive from DispatchableObject and have no virtual functions")

}  // namespace tilevk::icd
