// tilevk::shader — the program interface rast/ and icd/ code against.
//
// A Program is a SPIR-V vertex, fragment or compute entry point translated into an internal SIMD program that runs
// kLanes invocations at once, structure-of-arrays: every value is kLanes 32-bit words, one instruction covers all
// lanes, control flow is carried by per-lane execution masks. shader/ knows SPIR-V, never Vulkan.
//
// Fragment lanes cover a 4x4 pixel block with the four 2x2 quads kept together:
//   quad = (y >> 1) * 2 + (x >> 1)          x, y in 0..3 inside the block
//   lane = quad * 4 + (y & 1) * 2 + (x & 1)
// Derivatives are fine and per quad (like llvmpipe): dFdx = right - left within each row of the quad,
// dFdy = bottom - top within each column. The Coarse variants use the quad's top row / left column.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "format/format.h"

namespace tilevk::shader {

constexpr int kLanes = 16;
constexpr uint32_t kAllLanes = (1u << kLanes) - 1;
// Compute subgroups (SPIR-V GroupNonUniform*): kSubgroupSize consecutive lanes of a batch, so subgroup k of a
// workgroup is its invocations 8k .. 8k + 7 in LocalInvocationIndex order (batches start at multiples of kLanes).
// 8 is lavapipe's size on AVX2 hosts, where its subgroups are the same invocations whenever the workgroup's x size
// is a multiple of 8.
constexpr uint32_t kSubgroupSize = 8;
static_assert(kLanes % kSubgroupSize == 0, "a batch holds whole subgroups");
constexpr int kMaxLocations = 32;    // stage input/output locations (vec4 slots)
constexpr int kMaxColorOutputs = 8;  // fragment output locations
// The fragment output of Location 0, Index 1 (the second source of dual-source blending) is kept after them.
constexpr int kSecondColorOutput = kMaxColorOutputs;
constexpr int kColorOutputSlots = kMaxColorOutputs + 1;
constexpr int kMaxClipDistances = 8;
constexpr int kMaxMipLevels = 16;

// Lane index of pixel (x, y) of a 4x4 block, x, y in 0..3.
constexpr int lane_of(int x, int y) {
    return ((y >> 1) * 2 + (x >> 1)) * 4 + (y & 1) * 2 + (x & 1);
}
constexpr int lane_x(int lane) {
    return ((lane >> 2) & 1) * 2 + (lane & 1);
}
constexpr int lane_y(int lane) {
    return ((lane >> 3) & 1) * 2 + ((lane >> 1) & 1);
}

enum class Stage : uint8_t { Vertex, Fragment, Compute };

// ---------------------------------------------------------------------------------------------------------------
// Creation
// ---------------------------------------------------------------------------------------------------------------

// One specialization constant: SpecId and its raw value (1 word for 32-bit types and bool (0/1), 2 for 64-bit).
struct SpecConstant {
    uint32_t id = 0;
    std::vector<uint32_t> words;
};
using SpecConstants = std::vector<SpecConstant>;

class Program;

// Program::create's result: a program, or an error message naming what is wrong or unsupported
// (e.g. "unsupported opcode OpImageGather", "unsupported capability Geometry", "invalid SPIR-V: ...").
struct Result {
    std::shared_ptr<const Program> program;  // null on error
    std::string error;
    double create_ms = 0;  // wall time spent in Program::create
    explicit operator bool() const { return program != nullptr; }
};

// ---------------------------------------------------------------------------------------------------------------
// Reflection
// ---------------------------------------------------------------------------------------------------------------

enum class ScalarType : uint8_t { Float, Int, Uint };
enum class Interpolation : uint8_t { Smooth, Flat, NoPerspective };

// A user stage input or output, one per (location, component range). Arrays/matrices occupy consecutive
// locations and are reported one entry per location.
struct IoVariable {
    uint32_t location = 0;
    uint32_t component = 0;   // first component (Component decoration)
    uint32_t components = 4;  // 1..4
    ScalarType type = ScalarType::Float;
    Interpolation interpolation = Interpolation::Smooth;
    bool centroid = false;
    bool sample = false;
};

// Built-in variables, as bits of ProgramInterface::builtins_read / builtins_written.
enum class BuiltIn : uint32_t {
    Position = 1u << 0,
    PointSize = 1u << 1,
    ClipDistance = 1u << 2,
    CullDistance = 1u << 3,
    VertexIndex = 1u << 4,
    InstanceIndex = 1u << 5,
    BaseVertex = 1u << 6,
    BaseInstance = 1u << 7,
    DrawIndex = 1u << 8,
    FragCoord = 1u << 9,
    FrontFacing = 1u << 10,
    PointCoord = 1u << 11,
    FragDepth = 1u << 12,
    SampleMask = 1u << 13,
    SampleId = 1u << 14,
    SamplePosition = 1u << 15,
    HelperInvocation = 1u << 16,
    LocalInvocationId = 1u << 17,
    LocalInvocationIndex = 1u << 18,
    GlobalInvocationId = 1u << 19,
    WorkgroupId = 1u << 20,
    NumWorkgroups = 1u << 21,
    ViewIndex = 1u << 22,  // multiview: the view being rendered (vertex and fragment inputs)
};
constexpr uint32_t bit(BuiltIn b) {
    return static_cast<uint32_t>(b);
}

enum class DescriptorKind : uint8_t {
    UniformBuffer,
    StorageBuffer,
    CombinedImageSampler,
    SampledImage,
    Sampler,
    StorageImage,  // imageLoad / imageStore / imageSize (2D and 2D arrays)
};

struct DescriptorUse {
    uint32_t set = 0;
    uint32_t binding = 0;
    DescriptorKind kind = DescriptorKind::UniformBuffer;
    uint32_t array_size = 1;  // 1 for non-arrays
    bool written = false;     // storage buffer or storage image stored to
};

struct ProgramInterface {
    Stage stage = Stage::Vertex;
    std::string entry;
    std::vector<IoVariable> inputs;   // sorted by location, component
    std::vector<IoVariable> outputs;  // sorted by location, component
    uint32_t builtins_read = 0;       // BuiltIn bits
    uint32_t builtins_written = 0;    // BuiltIn bits
    uint32_t clip_distances = 0;      // array sizes of ClipDistance / CullDistance outputs (0: never stored to)
    uint32_t cull_distances = 0;
    uint32_t push_constant_size = 0;         // bytes the shader may read (highest offset + size)
    std::vector<DescriptorUse> descriptors;  // sorted by set, binding
    bool uses_discard = false;               // OpKill / OpDemoteToHelperInvocation
    bool writes_frag_depth = false;
    bool uses_derivatives = false;      // dFdx & co, or implicit-LOD sampling
    bool early_fragment_tests = false;  // ExecutionMode EarlyFragmentTests
    bool depth_replacing = false;
    bool origin_upper_left = true;
    // InterpolateAtCentroid / AtSample / AtOffset: the run reads FragmentBlock::input_planes (the renderer fills it)
    bool interpolates_at = false;
    // Compute: the workgroup size, from LocalSize / LocalSizeId or the WorkgroupSize built-in constant (which wins),
    // specialization constants applied.
    std::array<uint32_t, 3> local_size{1, 1, 1};
    uint32_t shared_memory_bytes = 0;  // compute: Workgroup variables, 4 bytes per 32-bit scalar, tightly packed
    bool uses_barriers = false;        // compute: OpControlBarrier (the workgroup's batches run in lock-step)
    bool uses_atomics = false;         // OpAtomic* on storage buffers or Workgroup memory
    bool writes_device_addresses = false;  // stores or atomics through PhysicalStorageBuffer pointers
};

// ---------------------------------------------------------------------------------------------------------------
// Device addresses (PhysicalStorageBuffer pointers, VK_KHR_buffer_device_address)
// ---------------------------------------------------------------------------------------------------------------

// A shader's PhysicalStorageBuffer pointer is a host address. The driver registers every allocation that buffer
// device addresses may point into (device_address.cpp); a load, store or atomic through a pointer whose bytes are not
// wholly inside one registered allocation reads 0 and writes nothing, so a wrong address in a shader (the
// application's bug) cannot touch the driver's or the application's other memory.
void register_device_memory(const void* data, uint64_t size);
void unregister_device_memory(const void* data);

// ---------------------------------------------------------------------------------------------------------------
// Resources the driver fills (plain data, no Vulkan types)
// ---------------------------------------------------------------------------------------------------------------

struct BufferView {
    const void* data = nullptr;  // readable bytes
    void* writable = nullptr;    // same bytes when the shader may write (storage buffers), else null
    uint64_t size = 0;           // bytes; accesses at or past size read 0 / are dropped
};

// Image formats are the format table's (format/format.h); the ones shader/ samples are those with a colour codec
// and the D16/D32F depth formats (sampled as (d, 0, 0, 1)).
using format::Format;

struct ImageLevel {
    uint64_t offset = 0;       // bytes from ImageView::base to texel (0,0) of layer 0
    uint64_t row_pitch = 0;    // bytes
    uint64_t layer_pitch = 0;  // bytes between array layers (or depth slices)
};

// A view's per-level sizes and 32-bit addressing as the compiled tier's RGBA8 sampler (shader/jit/sample_rgba8.cpp)
// looks them up per lane, with whether that sampler covers the view. Derived from the view's other fields once, by
// prepare_view(), instead of on every 16-lane Sample.
struct ViewLevelTable {
    int32_t w[kMaxMipLevels]{}, h[kMaxMipLevels]{};           // max(1, size >> level)
    int32_t offset[kMaxMipLevels]{}, pitch[kMaxMipLevels]{};  // bytes from base; 0 past the view's levels
    // What the table was derived from: the sampler compares these with the view on every call and rebuilds the
    // table on the stack when they differ (a view never prepared, or changed since). Level offsets and pitches are
    // not compared: change them only before prepare_view().
    Format format = Format::UNDEFINED;
    uint32_t width = 0, height = 0, levels = 0;
    std::array<uint8_t, 4> swizzle{};
    bool rgba8 = false;  // RGBA8/BGRA8 UNORM, identity swizzle, every level addressable with 32-bit offsets
    bool bgra = false;
};

struct ImageView {
    const uint8_t* base = nullptr;
    Format format = Format::UNDEFINED;
    uint32_t width = 0, height = 0, depth = 1;  // of level 0 of the view
    // The image's first level in the view and the image's own level-0 size (0: the view's): lavapipe's
    // anisotropic filter scales by them (texture_aniso.cpp)
    uint32_t base_level = 0, width0 = 0, height0 = 0;
    uint32_t levels = 1;                        // mip levels in the view
    uint32_t layers = 1;                        // array layers in the view
    uint32_t samples = 1;                       // 1, or 4 for a multisampled view (one level)
    uint64_t sample_pitch = 0;                  // bytes between the sample planes of a multisampled view
    std::array<ImageLevel, kMaxMipLevels> level{};
    // The view's component mapping, applied to every fetched/filtered result (not to depth comparisons): per
    // output channel, the source channel 0-3, or kSwizzleZero / kSwizzleOne.
    std::array<uint8_t, 4> swizzle{0, 1, 2, 3};
    ViewLevelTable table;  // derived from the fields above by prepare_view()
};
inline constexpr uint8_t kSwizzleZero = 4, kSwizzleOne = 5;

// Fills view.table from the view's other fields. Call it after the last change to them (icd/ does when it
// translates a VkImageView); an unprepared view samples the same bits, only slower.
void prepare_view(ImageView& view);
// The table prepare_view() would store (the sampler's fallback for a view whose table does not match it).
ViewLevelTable level_table(const ImageView& view);

enum class Filter : uint8_t { Nearest, Linear };
enum class MipmapMode : uint8_t { Nearest, Linear };
enum class AddressMode : uint8_t { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder, MirrorClampToEdge };
// Custom: VK_EXT_custom_border_color's colour, SamplerState::custom_border.
enum class BorderColor : uint8_t { TransparentBlack, OpaqueBlack, OpaqueWhite, Custom };
// VkSamplerReductionMode's values (shader/texture_reduce.h).
enum class Reduction : uint8_t { WeightedAverage, Min, Max };
// Same order as VkCompareOp. The one compare-op enum: depth/stencil tests (rast/fragment) and depth-compare
// sampling both use it.
enum class CompareOp : uint8_t { Never, Less, Equal, LessOrEqual, Greater, NotEqual, GreaterOrEqual, Always };

// a OP b as Vulkan defines the compare ops. NotEqual is !(a == b): with a NaN operand every op but Never,
// NotEqual and Always is false (IEEE ordered compares); callers with other NaN or denormal rules apply them first.
template <typename T>
constexpr bool compare_values(CompareOp op, T a, T b) {
    switch (op) {
        case CompareOp::Never:
            return false;
        case CompareOp::Less:
            return a < b;
        case CompareOp::Equal:
            return a == b;
        case CompareOp::LessOrEqual:
            return a <= b;
        case CompareOp::Greater:
            return a > b;
        case CompareOp::NotEqual:
            return !(a == b);
        case CompareOp::GreaterOrEqual:
            return a >= b;
        case CompareOp::Always:
            return true;
    }
    return false;
}

struct SamplerState {
    Filter mag_filter = Filter::Nearest;
    Filter min_filter = Filter::Nearest;
    MipmapMode mipmap_mode = MipmapMode::Nearest;
    AddressMode address_u = AddressMode::Repeat;
    AddressMode address_v = AddressMode::Repeat;
    AddressMode address_w = AddressMode::Repeat;
    float mip_lod_bias = 0.0f;
    float min_lod = 0.0f;
    float max_lod = 1000.0f;
    BorderColor border = BorderColor::TransparentBlack;
    bool integer_border = false;  // VK_BORDER_COLOR_INT_*: the opaque alpha is the integer 1, not 1.0f
    // BorderColor::Custom: VkClearColorValue's bits (float or integer alike: gallivm reads them as the texel type)
    std::array<uint32_t, 4> custom_border{};
    Reduction reduction = Reduction::WeightedAverage;  // how the linear filter combines its texels
    bool unnormalized = false;
    bool compare_enable = false;  // depth comparison for shadow samplers (texture(sampler2DShadow, ...))
    CompareOp compare_op = CompareOp::Never;
    // anisotropyEnable ? maxAnisotropy truncated : 1 (icd/render_state.cpp); above 1 the filter is anisotropic
    float max_anisotropy = 1.0f;
    // Cube maps filter across face edges and corners unless VK_SAMPLER_CREATE_NON_SEAMLESS_CUBE_MAP_BIT_EXT clears
    // this (shader/texture_cube.cpp).
    bool seamless_cube = true;
};

// One texture lookup outside a program (rast/'s blitter: lavapipe's u_blitter runs a TEX or TXF shader): what
// textureLod(img, vec2(s, t), 0.0) and texelFetch(img, ivec2(x, y), 0) on array layer `layer` return in a fragment
// shader, through the same sampler code. A view without a decodable format, or a fetch outside the level, gives
// (0, 0, 0, 0).
std::array<float, 4> sample_2d(const ImageView& img, const SamplerState& smp, float s, float t, uint32_t layer);
std::array<float, 4> fetch_2d(const ImageView& img, int32_t x, int32_t y, uint32_t layer);
// The same on a 3D view (its `depth` slices at level[0]): textureLod(img, vec3(s, t, r), 0.0) and
// texelFetch(img, ivec3(x, y, z), 0) of a sampler3D.
std::array<float, 4> sample_3d(const ImageView& img, const SamplerState& smp, float s, float t, float r);
std::array<float, 4> fetch_3d(const ImageView& img, int32_t x, int32_t y, int32_t z);

// What one (set, binding, array element) holds. Unused members stay null.
struct Descriptor {
    BufferView buffer;                      // uniform / storage buffers (offset and range already applied)
    const ImageView* image = nullptr;       // sampled images, combined image samplers and storage images
    const SamplerState* sampler = nullptr;  // samplers and combined image samplers
    uint8_t* image_writable = nullptr;      // storage images: image->base, which imageStore may write (else null)
};

// The resources one draw binds. The driver fills it; the program looks descriptors up once per run.
// A missing descriptor reads as zero (buffers) / transparent black (images), never crashes.
class Bindings {
  public:
    void set(uint32_t set, uint32_t binding, uint32_t element, const Descriptor& d);
    const Descriptor* find(uint32_t set, uint32_t binding, uint32_t element) const;
    void clear() { entries_.clear(); }
    std::span<const std::byte> push_constants;  // the push-constant bytes (reads past the end give 0)

  private:
    struct Entry {
        uint32_t set, binding, element;
        Descriptor d;
    };
    std::vector<Entry> entries_;
};

// ---------------------------------------------------------------------------------------------------------------
// Execution: structure-of-arrays batches. All values are 32-bit words (floats stored by bit pattern).
// ---------------------------------------------------------------------------------------------------------------

using Lanes = uint32_t[kLanes];

// Up to 16 vertices. Lanes >= count execute on garbage-free zeros and their results are to be ignored.
struct alignas(64) VertexBatch {
    uint32_t count = kLanes;
    uint32_t base_vertex = 0, base_instance = 0, draw_index = 0;
    uint32_t view_index = 0;             // ViewIndex: the multiview view this batch renders (0 outside multiview)
    alignas(64) Lanes vertex_index{};    // VertexIndex (already includes the vertex offset / base vertex)
    alignas(64) Lanes instance_index{};  // InstanceIndex (includes firstInstance)
    alignas(64) Lanes inputs[kMaxLocations][4]{};   // vertex attributes, [location][component][lane]
    alignas(64) Lanes outputs[kMaxLocations][4]{};  // varyings, [location][component][lane]
    alignas(64) Lanes position[4]{};                // gl_Position x, y, z, w (float bits)
    alignas(64) Lanes point_size{};                 // float bits; 1.0 when not written
    alignas(64) Lanes clip_distance[kMaxClipDistances]{};
    alignas(64) Lanes cull_distance[kMaxClipDistances]{};
};

// What InterpolateAtCentroid / AtSample / AtOffset re-evaluate (ProgramInterface::interpolates_at): each input's
// attribute planes a(x, y) = a0 + dadx*x + dady*y in the setup's frame (origin: pixel (0, 0)'s centre at 1x, its
// corner at 4x) and where the block and its samples are. shader/interpolate.cpp evaluates them as lavapipe does
// (lp_bld_interp.c lp_build_interp_soa).
struct InputPlanes {
    enum class Kind : uint8_t { None, Perspective, NoPerspective, Flat };  // None: the location has no plane (0.0)
    Kind kind[kMaxLocations]{};
    float a0[kMaxLocations][4]{}, dadx[kMaxLocations][4]{}, dady[kMaxLocations][4]{};
    float w[kLanes]{};         // the 1/w plane at the pixel centre: perspective inputs are multiplied by fl(1 / w)
    int32_t x = 0, y = 0;      // the block's top-left pixel
    int samples = 1;           // 1 or 4
    float sample_pos[4][2]{};  // the standard sample positions from the pixel corner (4x)
    uint16_t masks[4]{};       // per-sample lane masks when the run started (centroid at 4x)
    bool fused = false;        // fmuladd is one FMA (lavapipe on an FMA CPU), else mul then add
};

// One 4x4 pixel block (see the lane layout above). The rasterizer interpolates the inputs per lane.
struct alignas(64) FragmentBlock {
    uint32_t cover_mask = kAllLanes;               // in: covered lanes; the other lanes of the block are helper lanes
    uint32_t live_mask = 0;                        // out: cover_mask minus lanes that were discarded (demoted)
    uint32_t front_facing = 1;                     // in: 1 for a front-facing primitive (same for the whole block)
    uint32_t sample_id = 0;                        // in: SampleId, the sample a per-sample run shades (else 0)
    // in: SamplePosition x, y (float bits): the run's sample position within the pixel; (0.5, 0.5) at 1x
    uint32_t sample_position[2] = {0x3f000000u, 0x3f000000u};
    uint32_t view_index = 0;                       // in: ViewIndex, the multiview view (same for the whole block)
    const InputPlanes* input_planes = nullptr;     // in: for InterpolateAt* (interpolates_at); null reads 0.0
    alignas(64) Lanes frag_coord[4]{};             // in: x, y (pixel centre, e.g. 10.5), z, 1/w (float bits)
    alignas(64) Lanes sample_mask_in{};            // in: gl_SampleMaskIn[0]
    alignas(64) Lanes point_coord[2]{};            // in: gl_PointCoord
    alignas(64) Lanes inputs[kMaxLocations][4]{};  // in: interpolated varyings
    alignas(64) Lanes outputs[kColorOutputSlots][4]{};  // out: colour outputs, [location][component][lane]
    alignas(64) Lanes frag_depth{};                    // out: gl_FragDepth (float bits) when written
    alignas(64) Lanes sample_mask{};                   // out: gl_SampleMask[0] when written
};

// Up to 16 invocations of one compute workgroup (lanes >= count do not run: their stores are dropped). The
// program computes GlobalInvocationId = workgroup_id * local_size + local_id itself. Program::run_workgroup takes
// all of a workgroup's batches at once.
struct alignas(64) ComputeBatch {
    uint32_t count = kLanes;
    uint32_t workgroup_id[3] = {0, 0, 0};
    uint32_t num_workgroups[3] = {1, 1, 1};
    alignas(64) Lanes local_id[3]{};  // LocalInvocationId x, y, z
    alignas(64) Lanes local_index{};  // LocalInvocationIndex
};

// Per-thread working memory (registers, local variables). Reuse one per thread; it grows on demand.
class Scratch {
  public:
    Scratch();
    ~Scratch();
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    struct Impl;
    Impl* impl() { return impl_.get(); }
    // Runs cut short by the loop watchdog since this Scratch was made: a batch whose loops jumped back more than
    // kMaxLoopBackEdges times ends there (outputs as written so far) instead of hanging. Never happens for a
    // shader whose loops terminate in reasonable time; the driver may treat a non-zero count as a lost device.
    uint64_t loop_limit_hits() const;
    // The driver's time limit: once *stop is true, a run ends at its next loop back edge (counted in
    // loop_limit_hits) and the loop-count watchdog is off, so time, not iterations, bounds a run. Null (the
    // default): the loop-count watchdog only.
    void set_stop_flag(const std::atomic<bool>* stop);

  private:
    std::unique_ptr<Impl> impl_;
};
constexpr uint64_t kMaxLoopBackEdges = uint64_t(1) << 22;  // per run (batch of 16 lanes): ~4M iterations

struct ProgramImpl;  // internal: the translated SIMD program

// The compiled tier (shader/jit/README.md): Program::create also compiles the program to native AVX2/FMA code when
// the CPU has it, unless TILEVK_JIT=0 or this process-wide switch turned it off. Programs keep the tier they were
// created with (a ProgramCache may hand out a program created before a switch).
void set_jit_enabled(bool on);

class Program {
  public:
    // Validates (SPIRV-Tools), specializes, legalizes and translates `spirv`. Never crashes on bad input.
    static Result create(std::span<const uint32_t> spirv, Stage stage, std::string_view entry = "main",
                         const SpecConstants& spec = {});

    const ProgramInterface& interface() const { return interface_; }

    // Runs one batch. Thread-safe (the Program is immutable); each thread needs its own Scratch.
    void run_vertex(const Bindings& bindings, VertexBatch& batch, Scratch& scratch) const;
    void run_fragment(const Bindings& bindings, FragmentBlock& block, Scratch& scratch) const;

    // Direct fragment runs: run_fragment without the FragmentBlock's arrays, for the fragment stage, which shades
    // many blocks of one draw on one scratch. The caller binds (descriptors resolved and the scratch sized once per
    // bindings_key; a key names one Bindings content, 0 never matches, and any other run on the scratch unbinds it),
    // writes every input word of fragment_direct() (interpolated values, float bits) into the returned local memory,
    // runs, and reads the colour outputs from local memory. The same program state as run_fragment, so the same bits.
    struct FragmentDirect {
        bool ok = false;  // the program's only inputs are Input locations and FrontFacing, SampleId, ViewIndex or
                          // HelperInvocation, and its only outputs whole vec4 colour outputs
        // local word of each (location * 4 + component) the program reads, ~0u for the others
        uint32_t input_word[kMaxLocations * 4];
        uint32_t output_word[kColorOutputSlots];  // first of the four words of each colour output, ~0u: not written
    };
    const FragmentDirect& fragment_direct() const;
    uint32_t* bind_fragment(const Bindings& bindings, uint64_t bindings_key, Scratch& scratch) const;
    // Runs the bound program on its local memory; reads only the block's scalars (cover_mask, front_facing,
    // sample_id, view_index). Returns the live mask (cover_mask minus the discarded lanes).
    uint32_t run_bound_fragment(const FragmentBlock& scalars, Scratch& scratch) const;
    // Runs one whole compute workgroup: its batches (in LocalInvocationIndex order, all with the same workgroup
    // id) share one block of Workgroup memory, zeroed first, and run in lock-step phases between OpControlBarriers
    // (shader/README.md, "Compute"). A workgroup runs on one thread; storage-buffer atomics are real atomics, so
    // workgroups may run on several threads at once.
    void run_workgroup(const Bindings& bindings, std::span<const ComputeBatch> batches, Scratch& scratch) const;
    // Grows `scratch` to what a run of this program needs, so the runs themselves allocate nothing (the renderer
    // calls it for every worker before a scene, since which worker runs which program depends on timing).
    void reserve(Scratch& scratch) const;

    // Internal, for tests and benchmarks: number of SIMD instructions after translation.
    size_t instruction_count() const;
    // Internal, for tests and benchmarks: the program runs as native code (shader/jit/), not in the interpreter.
    // Both give the same bits; see set_jit_enabled.
    bool compiled() const;
    // Internal, for tests and the compiled tier: the translated program (shader/ir.h).
    const ProgramImpl& internal() const;

    // llvmpipe's linear shader class as far as tilevk reproduces it (shader/README.md, "Linear analysis"): colour
    // output location 0 whose every channel c is either component c of one float input, unchanged, or a constant
    // in [0, 1], and nothing else. ok = false for every other program.
    struct LinearShader {
        bool ok = false;
        int location = -1;      // the input read, or -1 (constants only)
        uint8_t usage = 0;      // components of that input the program reads (lavapipe's input_usage_mask)
        int8_t source[4] = {};  // per output channel: input component 0..3, or -1 for a constant
        float constant[4] = {};
    };
    LinearShader linear_shader() const { return linear_; }
    // The plain copy (channel c = component c of one input): its location, else -1.
    int linear_copy_input() const;

    ~Program();
    Program(std::unique_ptr<ProgramImpl> impl, ProgramInterface iface);

  private:
    LinearShader analyze_linear_shader() const;  // once, when the program is made (the renderer asks per draw)

    std::unique_ptr<ProgramImpl> impl_;
    ProgramInterface interface_;
    LinearShader linear_;
};

}  // namespace tilevk::shader
