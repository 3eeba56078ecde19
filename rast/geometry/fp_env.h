// lavapipe runs draw (vertex shader, clipping, viewport, setup) and its rasterizer threads with denormals flushed:
// FTZ and DAZ set in MXCSR, round to nearest even (notes §0.2). Wrap the geometry stage in this guard so the same
// float operations give the same results, e.g. a subnormal clip distance or plane term becomes 0 as in lavapipe.
#pragma once

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace tilevk::rast::geometry {

class ScopedFlushDenormals {
  public:
#if defined(__x86_64__) || defined(__i386__)
    static constexpr unsigned kFtz = 0x8000u;  // MXCSR flush-to-zero
    static constexpr unsigned kDaz = 0x0040u;  // MXCSR denormals-are-zero
    static constexpr unsigned kRoundMask = 0x6000u;
    ScopedFlushDenormals() : saved_(_mm_getcsr()) {
        _mm_setcsr((saved_ | kFtz | kDaz) & ~kRoundMask);
    }
    ~ScopedFlushDenormals() {
        _mm_setcsr(saved_);
    }

  private:
    unsigned saved_;
#else
    ScopedFlushDenormals() = default;  // other hosts: no MXCSR; results may differ on subnormals
#endif
  public:
    ScopedFlushDenormals(const ScopedFlushDenormals&) = delete;
    ScopedFlushDenormals& operator=(const ScopedFlushDenormals&) = delete;
};

}  // namespace tilevk::rast::geometry
