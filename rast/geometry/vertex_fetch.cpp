#include "rast/geometry/vertex_fetch.h"

#include <bit>
#include <cstring>

namespace tilevk::rast::geometry {

FetchedAttrib convert_element(VertexFormat f, const uint8_t* src) {
    FetchedAttrib out;
    format::fetch_words(format::format_info(f), src, out.w);
    return out;
}

ElementIndex element_index(const VertexBufferView& vb, uint32_t vertex_index, uint32_t instance_id,
                           uint32_t first_instance) {
    if (vb.rate == InputRate::kVertex) return {vertex_index, true};
    const uint32_t div = vb.divisor == 0 ? UINT32_MAX : vb.divisor;
    const uint64_t idx = static_cast<uint64_t>(first_instance) + instance_id / div;
    return {static_cast<uint32_t>(idx), idx <= 0xFFFFFFFFull};
}

FetchedAttrib fetch_attribute(const VertexAttribDesc& attrib, const VertexBufferView& vb, ElementIndex index) {
    const uint32_t elem = format::format_info(attrib.format).bytes;
    // size_adj = size - (elem - 1) - (offset + attrib.offset); any underflow (or offset overflow) -> 0
    const uint64_t base = static_cast<uint64_t>(vb.offset) + attrib.offset;
    uint64_t size_adj = 0;
    if (index.valid && base <= 0xFFFFFFFFull && vb.size >= elem - 1 && vb.size - (elem - 1) >= base)
        size_adj = vb.size - (elem - 1) - base;
    const uint32_t off32 = vb.stride * index.index;  // wraps like lavapipe's 32-bit mul
    if (static_cast<uint64_t>(off32) < size_adj && vb.data != nullptr) {
        // off32 + base + elem <= size: the read stays inside the buffer
        return convert_element(attrib.format, vb.data + base + off32);
    }
    if (vb.rate == InputRate::kInstance) return FetchedAttrib{{0, 0, 0, 0}};
    FetchedAttrib zero_src{};
    uint8_t zeros[16] = {};
    zero_src = convert_element(attrib.format, zeros);  // own components 0, missing ones (0,0,0,1)
    return zero_src;
}

namespace {

// fetch_lanes for R32..R32G32B32A32_SFLOAT (the bytes are the words; missing components (0, 0, 0, 1)), and for
// every other format through convert_element.
template <int kFloats>
void lanes_float(const AttribFetchPlan& plan, const uint32_t* element, const bool* valid, uint32_t n,
                 uint32_t (*out)[16]) {
    for (uint32_t lane = 0; lane < n; ++lane) {
        const uint32_t off32 = plan.stride * element[lane];  // wraps like lavapipe's 32-bit mul
        FetchedAttrib v = plan.out_of_bounds;
        if (valid[lane] && static_cast<uint64_t>(off32) < plan.size_adj) {
            v = FetchedAttrib{{0, 0, 0, std::bit_cast<uint32_t>(1.0f)}};
            std::memcpy(v.w, plan.base + off32, 4 * kFloats);
        }
        for (int c = 0; c < 4; ++c) out[c][lane] = v.w[c];
    }
}

void lanes_any(const AttribFetchPlan& plan, const uint32_t* element, const bool* valid, uint32_t n,
               uint32_t (*out)[16]) {
    for (uint32_t lane = 0; lane < n; ++lane) {
        const uint32_t off32 = plan.stride * element[lane];
        FetchedAttrib v = plan.out_of_bounds;
        if (valid[lane] && static_cast<uint64_t>(off32) < plan.size_adj)
            v = convert_element(plan.format, plan.base + off32);
        for (int c = 0; c < 4; ++c) out[c][lane] = v.w[c];
    }
}

}  // namespace

AttribFetchPlan make_attrib_fetch_plan(const VertexAttribDesc& attrib, const VertexBufferView& vb) {
    AttribFetchPlan p;
    p.format = attrib.format;
    switch (attrib.format) {
        case VertexFormat::R32G32B32A32_SFLOAT:
            p.lanes = lanes_float<4>;
            break;
        case VertexFormat::R32G32B32_SFLOAT:
            p.lanes = lanes_float<3>;
            break;
        case VertexFormat::R32G32_SFLOAT:
            p.lanes = lanes_float<2>;
            break;
        case VertexFormat::R32_SFLOAT:
            p.lanes = lanes_float<1>;
            break;
        default:
            p.lanes = lanes_any;
            break;
    }
    p.stride = vb.stride;
    p.per_instance = vb.rate == InputRate::kInstance;
    // As fetch_attribute: size_adj = size - (elem - 1) - (offset + attrib.offset); any underflow -> nothing fits.
    const uint32_t elem = format::format_info(attrib.format).bytes;
    const uint64_t base = static_cast<uint64_t>(vb.offset) + attrib.offset;
    if (vb.data != nullptr && base <= 0xFFFFFFFFull && vb.size >= elem - 1 && vb.size - (elem - 1) >= base) {
        p.size_adj = vb.size - (elem - 1) - base;
        p.base = vb.data + base;
    }
    const uint8_t zeros[16] = {};
    p.out_of_bounds = p.per_instance ? FetchedAttrib{{0, 0, 0, 0}} : convert_element(attrib.format, zeros);
    return p;
}

void fetch_vertex(const VertexAttribDesc* attribs, uint32_t count, const VertexBufferView* buffers,
                  uint32_t num_buffers, uint32_t vertex_index, uint32_t instance_id, uint32_t first_instance,
                  FetchedAttrib* out) {
    for (uint32_t i = 0; i < count; ++i) {
        if (attribs[i].binding >= num_buffers) {
            out[i] = FetchedAttrib{{0, 0, 0, 0}};
            continue;
        }
        const VertexBufferView& vb = buffers[attribs[i].binding];
        out[i] = fetch_attribute(attribs[i], vb, element_index(vb, vertex_index, instance_id, first_instance));
    }
}

}  // namespace tilevk::rast::geometry
