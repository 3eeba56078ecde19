// Vertex attribute fetch from raw buffers, with lavapipe's conversions (draw_llvm.c fetch_vector /
// fetch_instanced -> gallivm lp_build_fetch_rgba_soa/aos -> lp_bld_format_soa.c lp_build_extract_soa_chan).
#pragma once

#include <cstddef>
#include <cstdint>

#include "format/texel_codec.h"

namespace tilevk::rast::geometry {

// A vertex attribute's format: a row of the format table (format/format.h) with VERTEX_BUFFER support. Its
// channels say where each component sits; format::fetch_words converts them as lavapipe's fetch does.
using VertexFormat = format::Format;

enum class InputRate : uint8_t { kVertex, kInstance };

// A bound vertex buffer: `data` holds `size` bytes (the whole VkBuffer range from the binding offset onwards may
// be given; `offset` is the binding offset inside it).
struct VertexBufferView {
    const uint8_t* data = nullptr;
    uint32_t size = 0;
    uint32_t offset = 0;
    uint32_t stride = 0;  // 0 is legal: every vertex reads the same element
    InputRate rate = InputRate::kVertex;
    // Instance rate: the element is firstInstance + instance / divisor; 0 reads firstInstance's element for every
    // instance (lavapipe turns divisor 0 into UINT32_MAX, lvp_execute.c).
    uint32_t divisor = 1;
};

struct VertexAttribDesc {
    VertexFormat format = VertexFormat::R32G32B32A32_SFLOAT;
    uint32_t binding = 0;
    uint32_t offset = 0;  // attribute offset inside the element
};

// One fetched attribute as four 32-bit words: float bits for float/norm formats, integer bits for uint/sint.
struct FetchedAttrib {
    uint32_t w[4];
};

// The element index that lavapipe fetches for a vertex (draw_llvm.c): per-vertex rate uses `vertex_index`
// (the index value + vertexOffset, or firstVertex + i, wrapped to 32 bits); per-instance rate uses
// firstInstance + instance_id / divisor. `valid` is false when that sum overflows 32 bits.
struct ElementIndex {
    uint32_t index;
    bool valid;
};
ElementIndex element_index(const VertexBufferView& vb, uint32_t vertex_index, uint32_t instance_id,
                           uint32_t first_instance);

// Robustness rule (lavapipe's, draw_llvm.c): with off32 = (uint32)(stride * index) (wrapping), the element is in
// bounds iff off32 < size - (offset + attrib.offset) - (elem_size - 1) computed without underflow (underflow makes
// everything out of bounds). Out of bounds:
//   per-vertex rate   -> the format's own components read as 0, missing components still (0,0,0,1);
//   per-instance rate -> all four words 0 (the AoS fetch result is masked as a whole).
// Never reads outside [data, data + size).
FetchedAttrib fetch_attribute(const VertexAttribDesc& attrib, const VertexBufferView& vb, ElementIndex index);

// Conversion of one element from memory (exposed for tests): reads format_info(f).bytes bytes at `src`.
FetchedAttrib convert_element(VertexFormat f, const uint8_t* src);

// One attribute of up to 16 vertices at a time, prepared once per draw: the bounds rule of fetch_attribute hoisted
// (size_adj), the conversion specialised for the format. fetch_lanes(plan, indices, n, out) gives, for every lane,
// exactly fetch_attribute(attrib, vb, element_index(vb, indices[lane], ...)) as SoA words out[component][lane].
struct AttribFetchPlan {
    using LanesFn = void (*)(const AttribFetchPlan& plan, const uint32_t* element, const bool* valid, uint32_t n,
                             uint32_t (*out)[16]);
    LanesFn lanes = nullptr;
    VertexFormat format = VertexFormat::R32G32B32A32_SFLOAT;
    const uint8_t* base = nullptr;  // vb.data + vb.offset + attrib.offset (null: every element out of bounds)
    uint64_t size_adj = 0;          // element in bounds iff (uint32)(stride * index) < size_adj
    uint32_t stride = 0;
    bool per_instance = false;
    FetchedAttrib out_of_bounds{};  // the result for an element out of bounds (per the rate)
};
AttribFetchPlan make_attrib_fetch_plan(const VertexAttribDesc& attrib, const VertexBufferView& vb);

// Element indices (element_index) of `n` <= 16 vertices for one attribute, then the SoA fetch.
inline void fetch_lanes(const AttribFetchPlan& plan, const uint32_t* element, const bool* valid, uint32_t n,
                        uint32_t (*out)[16]) {
    plan.lanes(plan, element, valid, n, out);
}

// Fetches `count` attributes for one vertex into out[count] (plain loop over fetch_attribute).
void fetch_vertex(const VertexAttribDesc* attribs, uint32_t count, const VertexBufferView* buffers,
                  uint32_t num_buffers, uint32_t vertex_index, uint32_t instance_id, uint32_t first_instance,
                  FetchedAttrib* out);

}  // namespace tilevk::rast::geometry
