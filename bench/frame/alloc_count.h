// Heap allocations of the whole process (every thread, every library), for the frame benchmark's
// "allocations per steady frame" (alloc_count.cpp; absent from sanitizer builds, which interpose malloc).
#pragma once

#include <cstdint>

namespace tilevk::bench {

// Whether allocations are counted in this build.
bool allocations_counted();
// Calls of malloc, calloc, realloc and the aligned variants so far (operator new included).
uint64_t allocations();

}  // namespace tilevk::bench
