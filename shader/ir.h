// Internal SIMD program: pre-decoded instructions over SoA registers (each register = kLanes 32-bit words).
// Booleans and execution masks are 0 / 0xFFFFFFFF per lane, so masks, bools and select share one representation.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "shader/program.h"

namespace tilevk::shader {

namespace jit {
struct Code;  // shader/jit/jit.h
}

enum class Op : uint16_t {
    // moves and selects
    Mov,        // d = a
    Select,     // d = c ? a : b  (c is a mask register)
    MaskedMov,  // d = c ? a : d
    // float
    FAdd,
    FSub,
    FMul,
    FDiv,
    FNeg,
    FAbs,
    FMin,
    FMax,
    FMod,
    FRem,
    Fma,
    FOrdEq,
    FOrdNe,
    FOrdLt,
    FOrdLe,
    FOrdGt,
    FOrdGe,
    FUnordEq,
    FUnordNe,
    FUnordLt,
    FUnordLe,
    FUnordGt,
    FUnordGe,
    IsNan,
    IsInf,
    // integer
    IAdd,
    ISub,
    IMul,
    SDiv,
    UDiv,
    SRem,
    SMod,
    UMod,
    INeg,
    And,
    Or,
    Xor,
    Not,
    Shl,
    ShrL,
    ShrA,
    IEq,
    INe,
    SLt,
    SLe,
    SGt,
    SGe,
    ULt,
    ULe,
    UGt,
    UGe,
    SMin,
    SMax,
    UMin,
    UMax,
    SAbs,
    SSign,
    BitCount,
    BitReverse,
    FindLsb,
    FindSMsb,
    FindUMsb,
    BfeS,
    BfeU,
    Bfi,  // bitfield extract (a, offset b, count c) / insert (imm = index of count register)
    // conversions
    F2S,
    F2U,
    S2F,
    U2F,
    // GLSL.std.450 (scalar lanes)
    Floor,
    Ceil,
    Trunc,
    Round,
    RoundEven,
    Fract,
    FSign,
    Sqrt,
    InvSqrt,
    Exp,
    Exp2,
    Log,
    Log2,
    Pow,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Sinh,
    Cosh,
    Tanh,
    Asinh,
    Acosh,
    Atanh,
    FClamp,
    Step,
    SmoothStep,
    Ldexp,
    FrexpSig,  // nir_lower_frexp: (0 < |x| finite) ? (x & 0x807fffff) | 0x3f000000 : x
    FrexpExp,  // (|x| >> 23) - (|x| != 0 ? 126 : 0)
    MulHiU,    // high 32 bits of the 64-bit product (umulExtended / imulExtended)
    MulHiS,
    PackHalf2x16,
    UnpackHalf2x16Lo,
    UnpackHalf2x16Hi,
    PackUnorm4x8,
    UnpackUnorm4x8,
    PackSnorm4x8,
    UnpackSnorm4x8,
    PackUnorm2x16,
    UnpackUnorm2x16,
    PackSnorm2x16,
    UnpackSnorm2x16,
    // derivatives (fine per quad / coarse per quad)
    DdxFine,
    DdyFine,
    DdxCoarse,
    DdyCoarse,
    // memory
    LoadLocal,        // d = local[(imm + clamp(a)) lane]; b = size limit (words) of the variable
    StoreLocal,       // local[(imm + clamp(a))] = b under mask c; size limit in extra
    LoadLocalFixed,   // d = local[imm] (constant word: a plain 16-lane copy)
    StoreLocalFixed,  // local[imm] = b under mask c
    LoadBuf,          // d = buffer(slot imm + elem a)[byte offset b]; out of bounds -> 0
    LoadBufUniform,   // d = buffer(slot imm)[byte offset extra] for every lane
    StoreBuf,         // buffer(slot imm + elem a)[byte offset b] = c under mask extra
    BufArrayLength,   // d = max(size(buffer(slot imm + elem a)) - extra, 0) / b (stride register); n: array size
    // images: d..d+3 = result; a = handle, b = first coordinate register, c = lod/bias register or kNoReg
    Sample,     // imm: SampleFlags; extra: dref/offset unused
    Fetch,      // texelFetch: integer coords at b, lod at c
    QuerySize,  // textureSize: d.. = size at lod a (imm = components)
    QueryLevels,
    // control
    Jump,        // pc = imm
    JumpIfNone,  // if no lane of a is set: pc = imm
    JumpIfAny,   // if any lane of a is set: pc = imm
    Kill,        // live &= ~a (OpKill / demote); the kill register is d
    Halt,
    // Appended after Halt; the compiled tier's op table (jit/analysis.cpp) lists them too (shader/jit/README.md,
    // "Compute"), and an op appended after these stays Unknown there until someone decides how to compile it.
    // Workgroup memory, barriers and subgroups are compute only; atomics and storage images work in every stage.
    LoadShared,    // d = shared[min(imm + a, n - 1)] (one word of the workgroup's memory, same for every lane)
    StoreShared,   // shared[min(imm + a, n - 1)] = b under mask c, lanes in order (the last lane wins)
    AtomicBuf,     // d = atomic pad:AtomicOp on buffer(slot imm + elem a)[byte b + extra], value c, comparator d;
                   // n: array size; lanes in order; a lane whose elem is >= n (inactive: kNoReg) does nothing
    AtomicShared,  // d = atomic pad:AtomicOp on shared[min(imm + a, n - 1)], value c, comparator d; a = kNoReg
                   // in a lane: inactive, nothing done, d = 0
    Barrier,       // OpControlBarrier: the run stops here; the workgroup's other batches run up to it, then all resume
    // Subgroup operations (compute only): a subgroup is kSubgroupSize consecutive lanes of a batch; c is the mask of
    // the lanes taking part (the block's), and every result is the same for all lanes of a subgroup unless said.
    SgLaneId,          // d = lane % kSubgroupSize (SubgroupLocalInvocationId, per lane)
    SgElect,           // d = lane is the lowest active one of its subgroup
    SgAll,             // d = every active lane's a is true
    SgAny,             // d = some active lane's a is true
    SgAllEqual,        // d = every active lane's a equals the others' (imm 1: as floats, ordered ==)
    SgBroadcast,       // d = a of lane b (b read from the lowest active lane; taken modulo kSubgroupSize)
    SgBroadcastFirst,  // d = a of the lowest active lane
    SgBallot,          // d = the bits (1 << lane id) of the active lanes whose a is true
    // Storage images (any stage): a = handle, b = first integer coordinate (x, y[, layer]), imm = kSampleArray or 0.
    // A coordinate outside the view's level 0 or layers loads (0, 0, 0, 1 if the format has no alpha) and stores
    // nothing.
    ImageLoad,   // d..d+3 = the texel decoded (format/texel_codec.h decode_color)
    ImageStore,  // texel = c..c+3 encoded (store_image_texel) under mask d, lanes in order
    // d = atomic pad:AtomicOp on the 32-bit texel of an R32_UINT / R32_SINT / R32_SFLOAT view at the coordinates b,
    // value c, comparator d, lanes in order (std::atomic_ref); a lane whose handle a is kNoReg (inactive), a
    // coordinate outside the view or another format: nothing done, d = 0 (storage_image_word)
    AtomicImage,
    // PhysicalStorageBuffer pointers (buffer device addresses, any stage; exec_pointer.h): a = the address's low
    // word, b = its high word, extra = a constant byte offset. A word outside the memory the driver registered
    // (program.h register_device_memory) loads 0 and stores nothing.
    LoadPtr,    // d = the word, in the lanes of mask c (0 elsewhere)
    StorePtr,   // the word = c in the lanes of mask d, lanes in order
    AtomicPtr,  // d = atomic pad:AtomicOp on the word, value c, comparator d, in the lanes of mask register n
    // 64-bit integers and doubles (exec_wide.h): pad = WideOp. A 64-bit operand or result is two registers, low word
    // then high word (r, r + 1); which of d, a, b, c are 64-bit is WideOp's shape (wide_shape).
    Wide,
    // 8- and 16-bit values (exec_narrow.h; shader/README.md "8- and 16-bit types"): a register holds the value
    // zero-extended. LoadBufN / StoreBufN are LoadBuf / StoreBuf of pad bytes (1 or 2): the element is in bounds
    // when all its bytes are; loads zero-extend, stores write the low pad bytes of c.
    LoadBufN,
    StoreBufN,
    HalfToFloat,  // d = float(the IEEE half in a's low 16 bits), exact (F16C's VCVTPH2PS, LLVM's fpext)
    FloatToHalf,  // d = the IEEE half nearest to a, ties to even; NaN: 0x7E00 with a's sign (exec_narrow.h)
    // GLSL.std.450 InterpolateAt* (fragment; shader/interpolate.cpp): d = input component imm (location * 4 +
    // component) re-evaluated from Scratch::Impl::input_planes at pad: InterpAt; Offset: a, b = the x, y offsets;
    // Sample: a = the sample index. The compiled tier runs it as the interpreter's code (a Helper op).
    InterpolateAt,
};

enum class InterpAt : uint16_t { Centroid, Sample, Offset };

// Inst::pad of Op::Wide (translate_wide.cpp, exec_wide.h). Shapes: see wide_shape.
enum class WideOp : uint16_t {
    // 64-bit integer: d, a, b 64-bit (shifts: b is a 32-bit count, masked to 0..63 as llvmpipe)
    IAdd,
    ISub,
    IMul,
    SDiv,
    UDiv,
    SRem,
    SMod,
    UMod,
    And,
    Or,
    Xor,
    SMin,
    SMax,
    UMin,
    UMax,
    Shl,
    ShrL,
    ShrA,
    INeg,
    Not,
    SAbs,
    SSign,
    // double: d, a, b, c 64-bit
    FAdd,
    FSub,
    FMul,
    FDiv,
    FMod,
    FRem,
    FMin,
    FMax,
    Step,
    FNeg,
    FAbs,
    Floor,
    Ceil,
    Trunc,
    RoundEven,
    Fract,
    FSign,
    Sqrt,
    InvSqrt,
    FClamp,
    FFma,
    SmoothStep,  // FFma: fused (a * b + c rounded once)
    // comparisons: d a 32-bit mask, a and b 64-bit
    IEq,
    INe,
    SLt,
    SLe,
    ULt,
    ULe,
    FOrdEq,
    FOrdNe,
    FOrdLt,
    FOrdLe,
    FUnordEq,
    FUnordNe,
    FUnordLt,
    FUnordLe,
    IsNan,
    IsInf,
    BitCount,
    // conversions (the name says which side is 32-bit)
    F32ToF64,
    S32ToF64,
    U32ToF64,
    F32ToS64,
    F32ToU64,  // a 32-bit, d 64-bit
    F64ToF32,
    F64ToS32,
    F64ToU32,
    S64ToF32,
    U64ToF32,  // a 64-bit, d 32-bit
    S64ToF64,
    U64ToF64,
    F64ToS64,
    F64ToU64,  // both 64-bit
};
// Which operands of a WideOp are 64-bit: bit 0 d, bit 1 a, bit 2 b, bit 3 c.
constexpr uint32_t wide_shape(WideOp o) {
    if (o >= WideOp::Shl && o <= WideOp::ShrA) return 0b0011;
    if (o <= WideOp::SmoothStep) return 0b1111;
    if (o <= WideOp::BitCount) return 0b0110;
    if (o <= WideOp::F32ToU64) return 0b0001;
    if (o <= WideOp::U64ToF32) return 0b0010;
    return 0b0011;
}

// Inst::pad of AtomicBuf / AtomicShared: which OpAtomic*. IIncrement / IDecrement / ISub become IAdd of 1, -1, -v.
// FAdd is OpAtomicFAddEXT (VK_EXT_shader_atomic_float): the word read as a float plus the operand, old value first;
// FMin / FMax are OpAtomicFMinEXT / OpAtomicFMaxEXT (VK_EXT_shader_atomic_float2) as LLVM 15 lowers atomicrmw
// fmin / fmax on x86 (docs/lavapipe-rules.md "Float atomics"). kAtomicWide or'ed into pad: a 64-bit integer atomic
// (VK_KHR_shader_atomic_int64) on AtomicBuf / AtomicShared, whose d, c and comparator are register pairs (low word,
// high word) and whose memory is two words (interpreter only: jit/analysis.cpp leaves such programs there).
constexpr uint16_t kAtomicWide = 0x100;
enum class AtomicOp : uint16_t {
    Load,
    Store,
    Exchange,
    CompareExchange,
    IAdd,
    SMin,
    SMax,
    UMin,
    UMax,
    And,
    Or,
    Xor,
    FAdd,
    FMin,
    FMax
};

enum SampleFlags : uint32_t {
    kSampleImplicitLod = 1,  // derivative-based LOD (fragment only)
    kSampleExplicitLod = 2,  // c holds the LOD
    kSampleBias = 4,         // c holds a bias added to the implicit LOD
    kSampleArray = 8,        // coordinates have a layer component
    kSampleProj = 16,        // divide by the last coordinate
    kSampleGrad = 32,        // n..n+3: dx.xy, dy.xy registers (3D: n..n+5, dx.xyz, dy.xyz)
    kSample1D = 64,          // 1D image: one coordinate (plus layer)
    kSampleDref = 128,       // depth compare: the reference is the last coordinate register (b + extra - 1)
    kSampleOffset = 256,     // constant texel offset: x in bits 16..23, y in bits 24..31 (signed)
    kSampleGather = 512,     // OpImageGather / OpImageDrefGather: level 0's 2x2 footprint, component in bits 10..11
    kSampleCube = 32768,     // cube / cube-array view: coordinates are a direction (x, y, z[, layer]), gradients
                             // n..n+5 (dx.xyz, dy.xyz); shader/texture_cube.cpp
    kSampleMs = 4096,        // Fetch: c holds the sample index (level 0 of a multisampled view); QueryLevels: the
                             // view's sample count instead of its levels (OpImageQuerySamples)
    kSample3D = 8192,        // 3D image: coordinates (s, t, r), sizes (w, h, d); texture_3d.cpp
};
constexpr uint32_t kSampleGatherCompShift = 10;

constexpr uint32_t kNoReg = 0xFFFFFFFFu;

struct Inst {
    Op op;
    uint16_t pad = 0;
    uint32_t d = kNoReg, a = kNoReg, b = kNoReg, c = kNoReg;
    uint32_t imm = 0;
    uint32_t extra = 0;
    uint32_t n = 0;  // LoadLocal/StoreLocal: end word of the variable; LoadBuf/StoreBuf: descriptor array size
};

// Where an input/output variable's words are copied from/to at the start/end of a run.
enum class IoSlot : uint8_t {
    Input,
    Output,
    Position,
    PointSize,
    ClipDistance,
    CullDistance,
    VertexIndex,
    InstanceIndex,
    BaseVertex,
    BaseInstance,
    DrawIndex,
    FragCoord,
    FrontFacing,
    PointCoord,
    FragDepth,
    SampleMask,
    SampleMaskIn,
    SampleId,
    HelperInvocation,
    LocalInvocationId,
    LocalInvocationIndex,
    GlobalInvocationId,
    WorkgroupId,
    NumWorkgroups,
    ViewIndex,
    // compute: the subgroup built-ins (program.h kSubgroupSize; the Eq..Lt masks are uvec4s, index = component)
    SubgroupSize,
    SubgroupLocalInvocationId,
    SubgroupId,
    NumSubgroups,
    SubgroupEqMask,
    SubgroupGeMask,
    SubgroupGtMask,
    SubgroupLeMask,
    SubgroupLtMask,
    SamplePosition,  // fragment: vec2, index = component
};
struct IoCopy {
    IoSlot slot;
    uint32_t index;  // location*4+component, or builtin component
    uint32_t word;   // local memory word
};

// The fragment stage's copies between local memory and a FragmentBlock, planned once per program (exec.cpp
// plan_fragment_io): `count` consecutive words from local word `word` on, to or from the block's bytes at `bytes`
// on (64 per word). count 0: io_in[bytes] is a value the run computes (FrontFacing, SampleId, ...).
struct IoRun {
    uint32_t word, bytes, count;
};

// A descriptor binding the program reads: resolved once per run into the scratch table.
struct SlotBinding {
    uint32_t set, binding, count;
};

struct ProgramImpl {
    uint64_t serial = 0;  // unique per program (scratch re-initializes its constants when it changes)
    Stage stage = Stage::Vertex;
    std::vector<Inst> code;
    uint32_t num_regs = 0;
    std::vector<uint32_t> const_regs;  // register index, value pairs... stored as (reg, value)
    uint32_t local_words = 0;          // SoA local memory words (each kLanes wide)
    std::vector<IoCopy> io_in, io_out;
    // Fragment programs: io_in and io_out as runs of whole-word copies, in their order, and the local words no input
    // writes (word, count), the only ones each run zeroes (plan_fragment_io).
    std::vector<IoRun> frag_in, frag_out;
    std::vector<std::pair<uint32_t, uint32_t>> frag_zero;
    Program::FragmentDirect frag_direct;  // what direct runs write and read (plan_fragment_io)
    std::vector<SlotBinding> slots;  // slot 0 is the push-constant block
    uint32_t num_slots = 1;          // total resolved descriptors
    uint32_t shared_words = 0;       // compute: 32-bit words of Workgroup storage (one block per workgroup)
    bool has_barrier = false;        // compute: contains Barrier (a workgroup's batches run in lock-step)
    // registers with fixed meaning
    uint32_t reg_entry_mask = 0;  // lanes that run (vertex: lanes < count; fragment: all 16)
    uint32_t reg_live = 0;        // lanes not killed (fragment: covered and not discarded)
    // The compiled tier's native code for this program (shader/jit/), or null: the interpreter runs it.
    std::shared_ptr<const jit::Code> jit;
};

// One Sample instruction of a compiled program bound to the image and sampler its handle names in the current
// bindings (shader/jit/sample_rgba8.cpp bind_sample): resolved and checked at the instruction's first run after
// prepare() (which unbinds every entry), then reused by every later run with the same handle; so a draw's
// per-texture checks (format, swizzle, filters, wraps, level table) are made once per draw and worker, not per call.
struct BoundSample {
    enum class State : uint8_t {
        Unbound,      // not resolved since prepare()
        Kernel,       // the RGBA8 kernel covers it: img, smp and table hold what it reads
        Interpreter,  // exec_image (a case the kernel does not cover)
    };
    State state = State::Unbound;
    uint32_t handle = 0;  // the handle (every lane's) it was resolved for
    const ImageView* img = nullptr;
    const SamplerState* smp = nullptr;
    ViewLevelTable table;  // the view's level table (prepare_view's, or rebuilt when the view changed since)
};

// Per-thread working memory.
struct Scratch::Impl {
    // Room for the Sample instructions of ordinary programs, taken when the worker's scratch is made: a worker that
    // first meets a sampling shader after an application's first frames then does not allocate mid-frame
    // (bench/frame steady_frame_test.py).
    static constexpr size_t kSampleOpsReserved = 32;
    Impl() { samples.reserve(kSampleOpsReserved); }
    std::vector<uint32_t> regs;
    std::vector<uint32_t> local;
    std::vector<const Descriptor*> slots;
    uint64_t last = 0;  // serial of the program the registers were prepared for
    // Program::bind_fragment: the bindings key the slots were resolved for (0 after any other run), and the
    // push-constant descriptor slot 0 points to while bound
    uint64_t bound_key = 0;
    Descriptor bound_push;
    uint64_t loop_limit_hits = 0;
    const std::atomic<bool>* stop = nullptr;  // Scratch::set_stop_flag
    const InputPlanes* input_planes = nullptr;  // run_fragment: the block's (Op::InterpolateAt), else null
    std::vector<BoundSample> samples;           // per Sample instruction of the compiled code (jit::Code::sample_ops)
    uint64_t back_edges = 0;                  // loop watchdog: back edges taken in this run (all its phases)
    // Compute: the workgroup's shared memory (Program::run_workgroup) and, for programs with barriers, one frame
    // (registers, local memory, where it stopped) per batch of the workgroup beyond this one.
    uint32_t* shared = nullptr;
    uint32_t shared_words = 0;
    std::vector<uint32_t> shared_storage;
    size_t resume_pc = 0;  // where this frame's run continues after a barrier
    bool done = false;     // this frame's run reached Halt (or the watchdog)
    std::vector<std::unique_ptr<Impl>> frames;
};

// Fills frag_in, frag_out, frag_zero and frag_direct from io_in, io_out and local_words (exec.cpp).
void plan_fragment_io(ProgramImpl& p);

// Interpret the program (exec.cpp).
void execute(const ProgramImpl& p, Scratch::Impl& s);
// Interpret from code[pc] until Halt (the compiled tier runs single instructions this way) or a Barrier. Returns
// kRunDone after Halt or the watchdog, else the pc after the Barrier.
constexpr size_t kRunDone = ~size_t(0);
size_t execute_code(const Inst* code, Scratch::Impl& s, size_t pc = 0);

// Translate optimized, valid SPIR-V into `out`. Returns an empty string or an error message.
std::string translate(const std::vector<uint32_t>& spirv, Stage stage, std::string_view entry, ProgramImpl& out,
                      ProgramInterface& iface);

// Run one Op::InterpolateAt (interpolate.cpp). regs = register file base; planes may be null (the result is 0.0).
void exec_interpolate_at(const Inst& in, uint32_t* regs, const InputPlanes* planes);

// Run one image instruction (texture.cpp). regs = register file base (register r = regs + r * kLanes).
void exec_image(const Inst& in, uint32_t* regs, const Descriptor* const* slots, uint32_t num_slots);
// The writable word of an image atomic (texture.cpp): the texel (x, y, layer) of the R32_UINT / R32_SINT storage
// image behind descriptor slot `handle`, or null (no such storage image, another format, outside level 0 of the
// view or its layers, misaligned).
uint32_t* storage_image_word(const Descriptor* const* slots, uint32_t num_slots, uint32_t handle, uint32_t x,
                             uint32_t y, uint32_t layer);

}  // namespace tilevk::shader
