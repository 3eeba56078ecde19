// Sanitizer builds: ASan/TSan interpose malloc themselves, so allocations are not counted (alloc_count.cpp).
#include "alloc_count.h"

namespace tilevk::bench {
bool allocations_counted() {
    return false;
}
uint64_t allocations() {
    return 0;
}
}  // namespace tilevk::bench
