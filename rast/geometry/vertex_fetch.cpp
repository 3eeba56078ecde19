#include "rast/geometry/vertex_fetch.h"

#include <bit>
#include <cstring>
#include <iterator>

namespace tilevk::rast::geometry {
namespace {

constexpr VertexFormatInfo kInfo[] = {
    {ComponentKind::kFloat, 1, 4, false}, {ComponentKind::kFloat, 2, 4, false}, {ComponentKind::kFloat, 3, 4, false},
    {ComponentKind::kFloat, 4, 4, false}, {ComponentKind::kHalf, 1, 2, false},  {ComponentKind::kHalf, 2, 2, false},
    {ComponentKind::kHalf, 3, 2, false},  {ComponentKind::kHalf, 4, 2, false},  {ComponentKind::kUnorm, 1, 1, false},
    {ComponentKind::kUnorm, 2, 1, false}, {ComponentKind::kUnorm, 3, 1, false}, {ComponentKind::kUnorm, 4, 1, false},
    {ComponentKind::kUnorm, 4, 1, true},  {ComponentKind::kSnorm, 1, 1, false}, {ComponentKind::kSnorm, 2, 1, false},
    {ComponentKind::kSnorm, 3, 1, false}, {ComponentKind::kSnorm, 4, 1, false}, {ComponentKind::kUnorm, 1, 2, false},
    {ComponentKind::kUnorm, 2, 2, false}, {ComponentKind::kUnorm, 3, 2, false}, {ComponentKind::kUnorm, 4, 2, false},
    {ComponentKind::kSnorm, 1, 2, false}, {ComponentKind::kSnorm, 2, 2, false}, {ComponentKind::kSnorm, 3, 2, false},
    {ComponentKind::kSnorm, 4, 2, false}, {ComponentKind::kUint, 1, 1, false},  {ComponentKind::kUint, 2, 1, false},
    {ComponentKind::kUint, 3, 1, false},  {ComponentKind::kUint, 4, 1, false},  {ComponentKind::kSint, 1, 1, false},
    {ComponentKind::kSint, 2, 1, false},  {ComponentKind::kSint, 3, 1, false},  {ComponentKind::kSint, 4, 1, false},
    {ComponentKind::kUint, 1, 2, false},  {ComponentKind::kUint, 2, 2, false},  {ComponentKind::kUint, 3, 2, false},
    {ComponentKind::kUint, 4, 2, false},  {ComponentKind::kSint, 1, 2, false},  {ComponentKind::kSint, 2, 2, false},
    {ComponentKind::kSint, 3, 2, false},  {ComponentKind::kSint, 4, 2, false},  {ComponentKind::kUint, 1, 4, false},
    {ComponentKind::kUint, 2, 4, false},  {ComponentKind::kUint, 3, 4, false},  {ComponentKind::kUint, 4, 4, false},
    {ComponentKind::kSint, 1, 4, false},  {ComponentKind::kSint, 2, 4, false},  {ComponentKind::kSint, 3, 4, false},
    {ComponentKind::kSint, 4, 4, false},
};
// The A2B10G10R10 formats (one 32-bit word), after the array formats in VertexFormat.
constexpr VertexFormatInfo kPackedInfo[] = {
    {ComponentKind::kUnorm, 4, 1, false, true},
    {ComponentKind::kSnorm, 4, 1, false, true},
    {ComponentKind::kUint, 4, 1, false, true},
    {ComponentKind::kSint, 4, 1, false, true},
};
static_assert(std::size(kInfo) + std::size(kPackedInfo) == static_cast<size_t>(VertexFormat::kCount));

uint32_t read_le(const uint8_t* p, int bytes) {
    uint32_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}

// IEEE half -> float, exact (every half is representable; F16C or gallivm's software path give the same).
float half_to_float(uint16_t h) {
    const uint32_t sign = static_cast<uint32_t>(h & 0x8000u) << 16;
    const uint32_t exp = (h >> 10) & 0x1Fu;
    const uint32_t man = h & 0x3FFu;
    if (exp == 0x1F) return std::bit_cast<float>(sign | 0x7F800000u | (man << 13));  // Inf / NaN (payload kept)
    if (exp != 0) return std::bit_cast<float>(sign | ((exp + 112u) << 23) | (man << 13));
    // zero or subnormal half: man * 2^-24, exact in float
    const float mag = static_cast<float>(man) * 0x1p-24f;
    return sign ? -mag : mag;
}

uint32_t fbits(float f) {
    return std::bit_cast<uint32_t>(f);
}

}  // namespace

VertexFormatInfo vertex_format_info(VertexFormat f) {
    const size_t i = static_cast<size_t>(f);
    return i < std::size(kInfo) ? kInfo[i] : kPackedInfo[i - std::size(kInfo)];
}

uint32_t vertex_format_size(VertexFormat f) {
    const VertexFormatInfo i = vertex_format_info(f);
    return static_cast<uint32_t>(i.components) * i.component_bytes;
}

bool vertex_format_is_integer(VertexFormat f) {
    const ComponentKind k = vertex_format_info(f).kind;
    return k == ComponentKind::kUint || k == ComponentKind::kSint;
}

FetchedAttrib convert_element(VertexFormat f, const uint8_t* src) {
    const VertexFormatInfo info = vertex_format_info(f);
    const bool integer = info.kind == ComponentKind::kUint || info.kind == ComponentKind::kSint;
    // Missing components: (0, 0, 0, 1), 1 being integer 1 for pure-integer formats.
    FetchedAttrib out{{0, 0, 0, integer ? 1u : fbits(1.0f)}};
    const uint32_t word = info.packed_2_10_10_10 ? read_le(src, 4) : 0;
    for (int c = 0; c < info.components; ++c) {
        // Packed formats go through the same per-channel rules with their own widths (lp_build_extract_soa_chan
        // shifts each channel out of the word, then converts it like any other channel of that width).
        const int bits = info.packed_2_10_10_10 ? (c == 3 ? 2 : 10) : info.component_bytes * 8;
        const int mem_c = info.bgra ? (c == 3 ? 3 : 2 - c) : c;
        const uint32_t raw = info.packed_2_10_10_10 ? (word >> (10 * c)) & ((1u << bits) - 1u)
                                                    : read_le(src + mem_c * info.component_bytes, info.component_bytes);
        switch (info.kind) {
            case ComponentKind::kFloat:
                out.w[c] = raw;
                break;
            case ComponentKind::kHalf:
                out.w[c] = fbits(half_to_float(static_cast<uint16_t>(raw)));
                break;
            case ComponentKind::kUnorm: {
                // lp_build_unsigned_norm_to_float: fl((float)c * fl(1/(2^n-1))), a multiply, not a divide
                const float scale = static_cast<float>(1.0 / static_cast<double>((1u << bits) - 1u));
                out.w[c] = fbits(static_cast<float>(raw) * scale);
                break;
            }
            case ComponentKind::kSnorm: {
                // lp_build_extract_soa_chan: max(fl((float)c * fl(1/(2^(n-1)-1))), -1)
                const int32_t s = static_cast<int32_t>(raw << (32 - bits)) >> (32 - bits);
                const float scale = static_cast<float>(1.0 / static_cast<double>((1u << (bits - 1)) - 1u));
                const float v = static_cast<float>(s) * scale;
                out.w[c] = fbits(v < -1.0f ? -1.0f : v);
                break;
            }
            case ComponentKind::kUint:
                out.w[c] = raw;
                break;
            case ComponentKind::kSint:
                out.w[c] =
                    bits == 32 ? raw : static_cast<uint32_t>(static_cast<int32_t>(raw << (32 - bits)) >> (32 - bits));
                break;
        }
    }
    return out;
}

ElementIndex element_index(const VertexBufferView& vb, uint32_t vertex_index, uint32_t instance_id,
                           uint32_t first_instance) {
    if (vb.rate == InputRate::kVertex) return {vertex_index, true};
    const uint32_t div = vb.divisor == 0 ? 1 : vb.divisor;
    const uint64_t idx = static_cast<uint64_t>(first_instance) + instance_id / div;
    return {static_cast<uint32_t>(idx), idx <= 0xFFFFFFFFull};
}

FetchedAttrib fetch_attribute(const VertexAttribDesc& attrib, const VertexBufferView& vb, ElementIndex index) {
    const uint32_t elem = vertex_format_size(attrib.format);
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
