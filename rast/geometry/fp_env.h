// lavapipe runs draw (vertex shader, clipping, viewport, setup) and its rasterizer threads with denormals flushed:
// FTZ and DAZ set in MXCSR, round to nearest even (lavapipe-rules §0.2). Wrap the geometry stage in this guard so the
// same float operations give the same results, e.g. a subnormal clip distance or plane term becomes 0 as in lavapipe.
#pragma once

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace tilevk::rast::geometry {

// The same for a span that is not one scope (a worker's tile, from begin_tile to end_tile): returns the state that
// flush_denormals_end restores.
inline unsigned flush_denormals_begin() {
#if defined(__x86_64__) || defined(__i386__)
    const unsigned saved = _mm_getcsr();
    _mm_setcsr((saved | 0x8000u | 0x0040u) & ~0x6000u);  // FTZ | DAZ, round to nearest even
    return saved;
#else
    return 0;
#endif
}
inline void flush_denormals_end(unsigned saved) {
#if defined(__x86_64__) || defined(__i386__)
    _mm_setcsr(saved);
#else
    (void)saved;
#endif
}

class ScopedFlushDenormals {
  public:
#if defined(__x86_64__) || defined(__i386__)
    ScopedFlushDenormals() : saved_(flush_denormals_begin()) {}
    ~ScopedFlushDenormals() { flush_denormals_end(saved_); }

  private:
    unsigned saved_;
#else
    ScopedFlushDenormals() = default;  // other hosts: no MXCSR; results may differ on subnormals
#endif
  public:
    ScopedFlushDenormals(const ScopedFlushDenormals&) = delete;
    ScopedFlushDenormals& operator=(const ScopedFlushDenormals&) = delete;
};

// The opposite, for setup that lavapipe runs after draw_vbo has restored its thread's float state (denormals kept,
// round to nearest even): the triangles draw's vbuf still holds when llvmpipe_draw_vbo calls draw_flush.
class ScopedKeepDenormals {
  public:
#if defined(__x86_64__) || defined(__i386__)
    ScopedKeepDenormals() : saved_(_mm_getcsr()) {
        _mm_setcsr(saved_ & ~(0x8000u | 0x0040u | 0x6000u));
    }
    ~ScopedKeepDenormals() {
        _mm_setcsr(saved_);
    }

  private:
    unsigned saved_;
#else
    ScopedKeepDenormals() = default;
#endif
  public:
    ScopedKeepDenormals(const ScopedKeepDenormals&) = delete;
    ScopedKeepDenormals& operator=(const ScopedKeepDenormals&) = delete;
};

}  // namespace tilevk::rast::geometry
