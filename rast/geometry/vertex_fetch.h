// Vertex attribute fetch from raw buffers, with lavapipe's conversions (draw_llvm.c fetch_vector /
// fetch_instanced -> gallivm lp_build_fetch_rgba_soa/aos -> lp_bld_format_soa.c lp_build_extract_soa_chan).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tilevk::rast::geometry {

// Vertex formats as a plain enum (the icd maps VkFormat onto these). Components are little-endian, tightly packed.
enum class VertexFormat : uint8_t {
    kR32Float,
    kR32G32Float,
    kR32G32B32Float,
    kR32G32B32A32Float,
    kR16Float,
    kR16G16Float,
    kR16G16B16Float,
    kR16G16B16A16Float,
    kR8Unorm,
    kR8G8Unorm,
    kR8G8B8Unorm,
    kR8G8B8A8Unorm,
    kB8G8R8A8Unorm,
    kR8Snorm,
    kR8G8Snorm,
    kR8G8B8Snorm,
    kR8G8B8A8Snorm,
    kR16Unorm,
    kR16G16Unorm,
    kR16G16B16Unorm,
    kR16G16B16A16Unorm,
    kR16Snorm,
    kR16G16Snorm,
    kR16G16B16Snorm,
    kR16G16B16A16Snorm,
    kR8Uint,
    kR8G8Uint,
    kR8G8B8Uint,
    kR8G8B8A8Uint,
    kR8Sint,
    kR8G8Sint,
    kR8G8B8Sint,
    kR8G8B8A8Sint,
    kR16Uint,
    kR16G16Uint,
    kR16G16B16Uint,
    kR16G16B16A16Uint,
    kR16Sint,
    kR16G16Sint,
    kR16G16B16Sint,
    kR16G16B16A16Sint,
    kR32Uint,
    kR32G32Uint,
    kR32G32B32Uint,
    kR32G32B32A32Uint,
    kR32Sint,
    kR32G32Sint,
    kR32G32B32Sint,
    kR32G32B32A32Sint,
    kA2B10G10R10Unorm,  // one 32-bit word: R bits 0-9, G 10-19, B 20-29, A 30-31
    kA2B10G10R10Snorm,
    kA2B10G10R10Uint,
    kA2B10G10R10Sint,
    kCount
};

enum class ComponentKind : uint8_t { kFloat, kHalf, kUnorm, kSnorm, kUint, kSint };

struct VertexFormatInfo {
    ComponentKind kind;
    uint8_t components;              // 1..4
    uint8_t component_bytes;         // 1, 2 or 4 (packed formats: element bytes / components)
    bool bgra;                       // B8G8R8A8: memory order B,G,R,A
    bool packed_2_10_10_10 = false;  // A2B10G10R10: 10-bit R, G, B and 2-bit A in one little-endian word
};

VertexFormatInfo vertex_format_info(VertexFormat f);
uint32_t vertex_format_size(VertexFormat f);  // bytes of one element
// True for uint/sint formats: the fetched words are integers (missing components filled with integer 0,0,0,1).
bool vertex_format_is_integer(VertexFormat f);

enum class InputRate : uint8_t { kVertex, kInstance };

// A bound vertex buffer: `data` holds `size` bytes (the whole VkBuffer range from the binding offset onwards may
// be given; `offset` is the binding offset inside it).
struct VertexBufferView {
    const uint8_t* data = nullptr;
    uint32_t size = 0;
    uint32_t offset = 0;
    uint32_t stride = 0;  // 0 is legal: every vertex reads the same element
    InputRate rate = InputRate::kVertex;
    uint32_t divisor = 1;  // instance divisor (0 treated as 1; lavapipe only advertises divisor 1 without the ext)
};

struct VertexAttribDesc {
    VertexFormat format = VertexFormat::kR32G32B32A32Float;
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

// Conversion of one element from memory (exposed for tests): reads vertex_format_size(f) bytes at `src`.
FetchedAttrib convert_element(VertexFormat f, const uint8_t* src);

// Fetches `count` attributes for one vertex into out[count] (plain loop over fetch_attribute).
void fetch_vertex(const VertexAttribDesc* attribs, uint32_t count, const VertexBufferView* buffers,
                  uint32_t num_buffers, uint32_t vertex_index, uint32_t instance_id, uint32_t first_instance,
                  FetchedAttrib* out);

}  // namespace tilevk::rast::geometry
