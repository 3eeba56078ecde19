// What a binned scene remembers about each draw and each primitive until its tiles are rendered.
// The primitive stage (renderer.cpp) writes these; the fragment stage (fragment_stage.cpp) reads them.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "rast/core/huge_page_allocator.h"
#include "rast/core/recycled_list.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/fragment/linear.h"
#include "rast/geometry/planes.h"
#include "rast/render/draw_state.h"
#include "rast/render/vertex_stage.h"
#include "shader/program.h"

namespace tilevk::rast::render {

struct DrawRecord {
    const PipelineState* pipe = nullptr;
    uint32_t id = 0;                            // DrawCall::id
    shader::Bindings bindings;                  // copy: the draw's descriptors (pointers stay valid until end())
    std::vector<std::byte> push_constants;      // copy; bindings.push_constants points here
    VaryingMap varyings;                        // record slot -> fragment input location
    fragment::DepthStencilState depth_stencil;  // with the viewport depth range applied
    uint8_t depth_mode = 0;                     // fragment::DepthModeBits
    uint64_t* samples_passed = nullptr;         // DrawCall::samples_passed
    RasterStatistics* statistics = nullptr;     // DrawCall::statistics
    // llvmpipe's linear shading for this draw's rectangles (fragment/linear.h): the varying slot the shader copies
    // to colour 0, or -1 when tilevk does not shade this draw linearly (shader class, blending, write mask, ...).
    bool linear = false;
    int linear_slot = -1;  // -1 with `linear`: the shader writes constants only
    bool linear_perspective = true;
    fragment::LinearChannels linear_channels;

    // Back to a fresh record, keeping the storage of its vectors (RecycledList).
    void reset() {
        pipe = nullptr;
        id = 0;
        bindings.clear();
        bindings.push_constants = {};
        push_constants.clear();
        varyings.slot_location.clear();
        varyings.slot_interp.clear();
        varyings.carry_point_size = false;
        varyings.point_coord_slot = -1;
        varyings.distance_slot = -1;
        varyings.num_clip_distances = varyings.num_cull_distances = 0;
        depth_stencil = {};
        depth_mode = 0;
        samples_passed = nullptr;
        statistics = nullptr;
        linear = false;
        linear_slot = -1;
        linear_perspective = true;
        linear_channels = {};
    }
};

// The draws of a scene, reused from scene to scene.
using DrawRecords = RecycledList<DrawRecord>;

// What the driver's stop flag (Renderer::set_stop_flag) interrupted: the DrawCall::id of a draw whose shader run was
// cut short, and of one whose work was skipped. Written by whichever thread saw it first.
struct Interruption {
    static constexpr uint32_t kNone = ~0u;
    std::atomic<uint32_t> cut{kNone}, skipped{kNone};
    void note(bool was_cut, uint32_t id) {
        uint32_t none = kNone;
        (was_cut ? cut : skipped).compare_exchange_strong(none, id, std::memory_order_relaxed);
    }
    void reset() {
        cut.store(kNone, std::memory_order_relaxed);
        skipped.store(kNone, std::memory_order_relaxed);
    }
};

// kRect: llvmpipe's rectangle (lp_setup_rect.c): box coverage, planes from three corners.
enum class PrimKind : uint8_t { kTriangle, kLine, kPoint, kRect };

// One primitive's record in the scene's record store (PrimStore), the fragment stage's per-primitive head:
//   [pos plane (12 floats)][depth offset][draw][kind][rect][attrib planes (12 floats each)]
// draw, kind and rect are 32-bit integers kept in float slots (bit copies): one record, so the tile loop fetches a
// primitive's draw and its planes from the same cache lines instead of a separate array first.
inline constexpr uint32_t kPlaneFloats = 12;
inline constexpr uint32_t kPrimHeaderFloats = kPlaneFloats + 4;
inline constexpr uint32_t kRecordDrawSlot = kPlaneFloats + 1, kRecordKindSlot = kPlaneFloats + 2,
                          kRecordRectSlot = kPlaneFloats + 3;
// Records start at multiples of kRecordAlign floats (every record's length is one: 16 + 12 * attribs), and a
// primitive's payload is its start / kRecordAlign, so 2^32 payloads reach 2^34 floats.
inline constexpr uint32_t kRecordAlign = 4;
static_assert(kPrimHeaderFloats % kRecordAlign == 0 && kPlaneFloats % kRecordAlign == 0);

inline uint32_t record_floats(uint32_t num_attribs) {
    return kPrimHeaderFloats + kPlaneFloats * num_attribs;
}

// A decoded record header: what the fragment stage reads of a primitive besides its planes.
struct PrimRecord {
    uint32_t draw = 0;                    // index into the draw records
    PrimKind kind = PrimKind::kTriangle;  // linear mode shades rectangles and triangles differently
    uint32_t rect = 0;                    // kRect: index of its pixel box (Renderer's rect boxes, linear mode only)
    const float* planes = nullptr;        // the record: position plane, depth offset, ..., attribute planes
};

// The scene's primitive records in one arena, reused from scene to scene. Grown without zero-fill (a steady frame
// writes each record once, in setup): a slot that setup leaves unwritten (a rejected triangle of a parallel draw) is
// never binned, so never read. Large arenas get transparent huge pages: the tile loop reads records in API order
// with gaps.
class PrimStore {
  public:
    void clear() {
        used_ = 0;
        count_ = 0;
    }
    bool empty() const { return count_ == 0; }
    size_t count() const { return count_; }  // records appended (including unwritten slots), for scene limits
    uint32_t next_payload() const { return static_cast<uint32_t>(used_ / kRecordAlign); }
    // Appends `n` records of `floats` floats each (a multiple of kRecordAlign); returns the first one's payload.
    uint32_t append(size_t n, uint32_t floats) {
        const uint32_t first = next_payload();
        used_ += n * floats;
        count_ += n;
        if (floats_.size() < used_ + kSlackFloats) floats_.resize(std::max(used_ + kSlackFloats, floats_.size() * 2));
        return first;
    }
    float* record(uint32_t payload) { return floats_.data() + size_t(payload) * kRecordAlign; }
    const float* record(uint32_t payload) const { return floats_.data() + size_t(payload) * kRecordAlign; }
    bool contains(uint32_t payload) const { return size_t(payload) * kRecordAlign < used_; }
    // Floats past the last record that stay inside the arena: a prefetch of a record's first 192 bytes never
    // leaves it.
    static constexpr size_t kSlackFloats = 48;
    // Writes the header of the record at `payload`.
    void set_header(uint32_t payload, const geometry::AttribPlane& pos, float depth_offset, uint32_t draw,
                    PrimKind kind, uint32_t rect) {
        static_assert(sizeof(pos) == sizeof(float) * kPlaneFloats);
        float* dst = record(payload);
        std::memcpy(dst, &pos, sizeof(float) * kPlaneFloats);
        dst[kPlaneFloats] = depth_offset;
        const uint32_t k = static_cast<uint32_t>(kind);
        std::memcpy(dst + kRecordDrawSlot, &draw, 4);
        std::memcpy(dst + kRecordKindSlot, &k, 4);
        std::memcpy(dst + kRecordRectSlot, &rect, 4);
    }
    void set_rect(uint32_t payload, uint32_t rect) { std::memcpy(record(payload) + kRecordRectSlot, &rect, 4); }
    PrimRecord header(uint32_t payload) const {
        PrimRecord r;
        r.planes = record(payload);
        uint32_t k = 0;
        std::memcpy(&r.draw, r.planes + kRecordDrawSlot, 4);
        std::memcpy(&k, r.planes + kRecordKindSlot, 4);
        std::memcpy(&r.rect, r.planes + kRecordRectSlot, 4);
        r.kind = static_cast<PrimKind>(k);
        return r;
    }

  private:
    // std::allocator_traits construct() default-initialises here: resize() leaves the new floats unwritten.
    template <class T>
    struct UninitAllocator : HugePageAllocator<T> {
        template <class U>
        struct rebind {
            using other = UninitAllocator<U>;
        };
        UninitAllocator() = default;
        template <class U>
        UninitAllocator(const UninitAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor)
        template <class U>
        void construct(U* p) noexcept {
            ::new (static_cast<void*>(p)) U;
        }
        template <class U, class... A>
        void construct(U* p, A&&... a) {
            ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
        }
    };
    std::vector<float, UninitAllocator<float>> floats_;
    size_t used_ = 0;   // floats in use
    size_t count_ = 0;  // records appended
};

}  // namespace tilevk::rast::render
