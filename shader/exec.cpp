// The interpreter: a loop over pre-decoded instructions, each a whole-register operation or a 16-lane loop that
// the compiler vectorizes (-mavx2), dispatched by one switch. The kernels live with their family (exec_arith.h,
// exec_math.h, exec_memory.h; images in texture.cpp), each family listing its opcodes in one X-macro; control flow
// and the hottest moves are here. Runs with FTZ/DAZ like lavapipe.
#include <emmintrin.h>
#include <pmmintrin.h>
#include <xmmintrin.h>
#include <algorithm>
#include <cstddef>
#include <iterator>

#include "shader/exec_arith.h"
#include "shader/exec_atomic.h"
#include "shader/exec_math.h"
#include "shader/exec_memory.h"
#include "shader/exec_narrow.h"
#include "shader/exec_pointer.h"
#include "shader/exec_subgroup.h"
#include "shader/exec_wide.h"
#include "shader/jit/jit.h"

namespace tilevk::shader {

using namespace exec;

void execute(const ProgramImpl& p, Scratch::Impl& s) {
    execute_code(p.code.data(), s);
}

size_t execute_code(const Inst* code, Scratch::Impl& s, size_t pc) {
    Machine mc{s.regs.data(), s.local.data(), s.slots.data(), uint32_t(s.slots.size()), s.shared};
    // s.back_edges: the loop watchdog (a valid shader may loop forever; never hang the caller), over all the
    // phases of a run that stops at barriers.
    for (;;) {
        const Inst& in = code[pc++];
        switch (in.op) {
#define TILEVK_EXEC_EXPR(op, body) \
    case Op::op:                   \
        body /* NOLINT(bugprone-macro-parentheses): the argument is a statement */ break;
#define TILEVK_EXEC_CALL(op, fn) \
    case Op::op:                 \
        fn(in, mc);              \
        break;
            TILEVK_EXEC_VECTOR_OPS(TILEVK_EXEC_EXPR)
            TILEVK_EXEC_FLOAT_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_INT_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_MATH_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_PACK_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_MEMORY_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_SHARED_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_POINTER_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_SUBGROUP_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_WIDE_OPS(TILEVK_EXEC_CALL)
            TILEVK_EXEC_NARROW_OPS(TILEVK_EXEC_CALL)
#define TILEVK_EXEC_LIBM(op, expr) TILEVK_EXEC_CALL(op, op_libm_##op)
            TILEVK_LIBM_OPS(TILEVK_EXEC_LIBM, TILEVK_EXEC_LIBM)
#undef TILEVK_EXEC_LIBM
#define TILEVK_EXEC_GALLIVM(op, fn) TILEVK_EXEC_CALL(op, op_gallivm_##op)
            TILEVK_GALLIVM_OPS(TILEVK_EXEC_GALLIVM)
#undef TILEVK_EXEC_GALLIVM
#undef TILEVK_EXEC_EXPR
#undef TILEVK_EXEC_CALL
            case Op::Select: {
                VU a = vload<VU>(A), b = vload<VU>(B), c = vload<VU>(C);
                vstore(D, (c & a) | (~c & b));
                break;
            }
            case Op::MaskedMov: {
                VU a = vload<VU>(A), c = vload<VU>(C), d = vload<VU>(D);
                vstore(D, (c & a) | (~c & d));
                break;
            }
            case Op::LoadLocalFixed:
                vstore(D, vload<VU>(mc.M + size_t(in.imm) * kLanes));
                break;
            case Op::StoreLocalFixed: {
                uint32_t* w = mc.M + size_t(in.imm) * kLanes;
                VU b = vload<VU>(B), c = vload<VU>(C), old = vload<VU>(w);
                vstore(w, (c & b) | (~c & old));
                break;
            }
            case Op::Sample:
            case Op::Fetch:
            case Op::QuerySize:
            case Op::QueryLevels:
            case Op::ImageLoad:
            case Op::ImageStore:
                exec_image(in, mc.R, mc.slots, mc.num_slots);
                break;
            case Op::InterpolateAt:
                exec_interpolate_at(in, mc.R, s.input_planes);
                break;
            case Op::Jump:
                pc = in.imm;
                break;
            case Op::JumpIfNone: {
                const uint32_t* __restrict a = A;
                uint32_t any = 0;
                LANES any |= a[l];
                if (!any) pc = in.imm;
                break;
            }
            case Op::JumpIfAny: {
                const uint32_t* __restrict a = A;
                uint32_t any = 0;
                LANES any |= a[l];
                if (any) {
                    if (s.stop != nullptr ? s.stop->load(std::memory_order_relaxed)
                                          : ++s.back_edges > kMaxLoopBackEdges) {
                        ++s.loop_limit_hits;
                        return kRunDone;
                    }
                    pc = in.imm;
                }
                break;
            }
            case Op::Kill: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A;
                LANES d[l] &= ~a[l];
                break;
            }
            case Op::Halt:
                return kRunDone;
            case Op::Barrier:
                return pc;
        }
    }
}

namespace {

// Set up the scratch for a program: sizes, constants, resolved descriptors.
// zero_local false: the caller zeroes the local words itself (run_fragment: only those no input writes).
// resolve false: s.slots already holds these bindings' descriptors and &push (the workgroup's earlier batch on this
// scratch): the look-ups were a third of a small compute batch's set-up.
void prepare(const ProgramImpl& p, const Bindings& bindings, Scratch::Impl& s, Descriptor& push, bool zero_local = true,
             bool resolve = true) {
    if (s.last != p.serial) {
        s.regs.assign(size_t(p.num_regs) * kLanes, 0);
        for (size_t i = 0; i + 1 < p.const_regs.size(); i += 2)
            for (int l = 0; l < kLanes; ++l) s.regs[size_t(p.const_regs[i]) * kLanes + l] = p.const_regs[i + 1];
        s.last = p.serial;
    }
    s.back_edges = 0;
    s.bound_key = 0;  // the slots below are this run's (bind_fragment sets the key after)
    // Sample instructions are bound again at their first run with these bindings (BoundSample)
    const uint32_t sample_ops = p.jit ? p.jit->sample_ops : 0;
    if (s.samples.size() != sample_ops) s.samples.resize(sample_ops);
    for (BoundSample& b : s.samples) b.state = BoundSample::State::Unbound;
    size_t words = size_t(std::max(1u, p.local_words)) * kLanes;
    if (s.local.size() < words) s.local.resize(words);
    // variables start at zero, so results never depend on history
    if (zero_local) std::memset(s.local.data(), 0, words * 4);
    if (!resolve && s.slots.size() == p.num_slots) return;
    if (s.slots.size() != p.num_slots) s.slots.resize(p.num_slots);
    push.buffer.data = bindings.push_constants.data();
    push.buffer.size = bindings.push_constants.size();
    s.slots[0] = &push;
    uint32_t at = 1;
    for (const SlotBinding& b : p.slots)
        for (uint32_t e = 0; e < b.count; ++e) s.slots[at++] = bindings.find(b.set, b.binding, e);
}

struct FloatEnv {
    // lavapipe runs vertex and fragment shaders with denormals flushed (FTZ) and treated as zero (DAZ), rounding to
    // nearest. The fragment stage's tiles already run that way: MXCSR is then left alone (a write costs more than the
    // compare). Compute shaders run on llvmpipe's compute thread pool (lp_cs_tpool.c), which never sets the denormal
    // modes: denormals are kept there (cts types.float64.*: float(x) of a double below FLT_MIN stays a denormal).
    unsigned saved = _mm_getcsr();
    unsigned wanted;
    explicit FloatEnv(bool flush = true) : wanted((saved & ~0xE040u) | (flush ? 0x8040u : 0u)) {
        if (wanted != saved) _mm_setcsr(wanted);
    }
    ~FloatEnv() {
        if (wanted != saved) _mm_setcsr(saved);
    }
};

// The compiled code when the program has it, else the interpreter: the same results either way.
inline void run_program(const ProgramImpl& p, Scratch::Impl& s) {
    if (p.jit)
        jit::run(*p.jit, s);
    else
        execute(p, s);
}

// Batch b's working memory in a lock-step run: the scratch itself for batch 0, its frames for the others.
Scratch::Impl& frame_of(Scratch::Impl& s, size_t b) {
    return b == 0 ? s : *s.frames[b - 1];
}

void ensure_frames(Scratch::Impl& s, size_t batches) {
    while (s.frames.size() + 1 < batches) s.frames.push_back(std::make_unique<Scratch::Impl>());
}

inline void copy_lanes(uint32_t* dst, const uint32_t* src) {
    std::memcpy(dst, src, kLanes * 4);
}

// Lane l of w = bit l of mask ? ~0 : 0 (SSE2, 4 lanes at a time: the fragment stage does this per 4x4 block, and
// the per-lane loop cost ~60 instructions).
inline void lanes_from_mask(uint32_t mask, uint32_t* w) {
    const __m128i bits = _mm_setr_epi32(1, 2, 4, 8);
    for (int q = 0; q < kLanes / 4; ++q) {
        const __m128i m = _mm_and_si128(_mm_set1_epi32(int(mask >> (4 * q))), bits);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(w + 4 * q), _mm_cmpeq_epi32(m, bits));
    }
}

// Bit l = bit 0 of lane l of w.
inline uint32_t mask_from_lanes(const uint32_t* w) {
    uint32_t mask = 0;
    for (int q = 0; q < kLanes / 4; ++q) {
        const __m128i v = _mm_slli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(w + 4 * q)), 31);
        mask |= uint32_t(_mm_movemask_ps(_mm_castsi128_ps(v))) << (4 * q);
    }
    return mask;
}

}  // namespace

void Program::reserve(Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    s.regs.reserve(size_t(p.num_regs) * kLanes);
    s.local.reserve(size_t(std::max(1u, p.local_words)) * kLanes);
    s.slots.reserve(p.num_slots);
    if (p.stage != Stage::Compute) return;
    s.shared_storage.reserve(p.shared_words);
    if (!p.has_barrier) return;
    const std::array<uint32_t, 3>& size = interface_.local_size;
    const size_t batches = (size_t(size[0]) * size[1] * size[2] + kLanes - 1) / kLanes;
    ensure_frames(s, batches);
    for (const auto& f : s.frames) {
        f->regs.reserve(size_t(p.num_regs) * kLanes);
        f->local.reserve(size_t(std::max(1u, p.local_words)) * kLanes);
        f->slots.reserve(p.num_slots);
    }
}

void Program::run_vertex(const Bindings& bindings, VertexBatch& vb, Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    Descriptor push;
    prepare(p, bindings, s, push);
    uint32_t* M = s.local.data();
    for (const IoCopy& c : p.io_in) {
        uint32_t* w = M + size_t(c.word) * kLanes;
        switch (c.slot) {
            case IoSlot::Input:
                copy_lanes(w, vb.inputs[c.index / 4][c.index % 4]);
                break;
            case IoSlot::VertexIndex:
                copy_lanes(w, vb.vertex_index);
                break;
            case IoSlot::InstanceIndex:
                copy_lanes(w, vb.instance_index);
                break;
            case IoSlot::BaseVertex:
                LANES w[l] = vb.base_vertex;
                break;
            case IoSlot::BaseInstance:
                LANES w[l] = vb.base_instance;
                break;
            case IoSlot::DrawIndex:
                LANES w[l] = vb.draw_index;
                break;
            case IoSlot::ViewIndex:
                LANES w[l] = vb.view_index;
                break;
            default:
                break;
        }
    }
    uint32_t* entry = s.regs.data() + size_t(p.reg_entry_mask) * kLanes;
    LANES entry[l] = uint32_t(l) < vb.count ? ~0u : 0u;
    {
        FloatEnv env;
        run_program(p, s);
    }
    for (const IoCopy& c : p.io_out) {
        const uint32_t* w = M + size_t(c.word) * kLanes;
        switch (c.slot) {
            case IoSlot::Output:
                copy_lanes(vb.outputs[c.index / 4][c.index % 4], w);
                break;
            case IoSlot::Position:
                copy_lanes(vb.position[c.index], w);
                break;
            case IoSlot::PointSize:
                copy_lanes(vb.point_size, w);
                break;
            case IoSlot::ClipDistance:
                copy_lanes(vb.clip_distance[c.index], w);
                break;
            case IoSlot::CullDistance:
                copy_lanes(vb.cull_distance[c.index], w);
                break;
            default:
                break;
        }
    }
}

namespace {

// Where an IoCopy of a fragment program lives in a FragmentBlock: its byte offset, or ~0u for a value computed per
// run (or, for outputs, nothing written).
uint32_t block_bytes(const IoCopy& c, bool out) {
    const auto lanes = [](size_t at, uint32_t i) { return uint32_t(at + size_t(i) * sizeof(Lanes)); };
    if (out) {
        switch (c.slot) {
            case IoSlot::Output:
                return lanes(offsetof(FragmentBlock, outputs), c.index);
            case IoSlot::FragDepth:
                return lanes(offsetof(FragmentBlock, frag_depth), 0);
            case IoSlot::SampleMask:
                return lanes(offsetof(FragmentBlock, sample_mask), 0);
            default:
                return ~0u;
        }
    }
    switch (c.slot) {
        case IoSlot::Input:
            return lanes(offsetof(FragmentBlock, inputs), c.index);
        case IoSlot::FragCoord:
            return lanes(offsetof(FragmentBlock, frag_coord), c.index);
        case IoSlot::PointCoord:
            return lanes(offsetof(FragmentBlock, point_coord), c.index);
        case IoSlot::SampleMaskIn:
            return lanes(offsetof(FragmentBlock, sample_mask_in), 0);
        default:
            return ~0u;
    }
}

// io as runs: a copy extends the previous run when both its word and its bytes follow on.
std::vector<IoRun> plan_runs(const std::vector<IoCopy>& io, bool out) {
    std::vector<IoRun> runs;
    for (size_t i = 0; i < io.size(); ++i) {
        const uint32_t bytes = block_bytes(io[i], out);
        if (bytes == ~0u) {
            if (!out) runs.push_back({io[i].word, uint32_t(i), 0});
            continue;
        }
        IoRun* last = runs.empty() ? nullptr : &runs.back();
        if (last && last->count && last->word + last->count == io[i].word &&
            last->bytes + last->count * sizeof(Lanes) == bytes)
            ++last->count;
        else
            runs.push_back({io[i].word, bytes, 1});
    }
    return runs;
}

// A fragment input no copy covers: the block's values for it.
void write_fragment_builtin(const IoCopy& c, const FragmentBlock& fb, uint32_t* w) {
    switch (c.slot) {
        case IoSlot::FrontFacing:
            LANES w[l] = fb.front_facing ? ~0u : 0u;
            break;
        case IoSlot::SampleId:
            LANES w[l] = fb.sample_id;
            break;
        case IoSlot::SamplePosition:
            LANES w[l] = fb.sample_position[c.index & 1];
            break;
        case IoSlot::ViewIndex:
            LANES w[l] = fb.view_index;
            break;
        case IoSlot::HelperInvocation:
            LANES w[l] = (fb.cover_mask >> l) & 1 ? 0u : ~0u;
            break;
        default:  // a slot no fragment input has: the word stays zero, as if never written (plan_fragment_io)
            LANES w[l] = 0;
            break;
    }
}

}  // namespace

namespace {

// Program::FragmentDirect from io_in and io_out: ok when every input is an Input location or a built-in the run
// computes, each read once, and every output a component of a colour output whose four components are four
// consecutive local words.
Program::FragmentDirect plan_direct(const ProgramImpl& p) {
    Program::FragmentDirect d;
    std::fill(std::begin(d.input_word), std::end(d.input_word), ~0u);
    std::fill(std::begin(d.output_word), std::end(d.output_word), ~0u);
    for (const IoCopy& c : p.io_in) {
        if (c.slot == IoSlot::FrontFacing || c.slot == IoSlot::SampleId || c.slot == IoSlot::SamplePosition ||
            c.slot == IoSlot::ViewIndex || c.slot == IoSlot::HelperInvocation)
            continue;
        if (c.slot != IoSlot::Input || c.index >= std::size(d.input_word) || d.input_word[c.index] != ~0u) return d;
        d.input_word[c.index] = c.word;
    }
    uint32_t seen[kColorOutputSlots] = {};  // components written, one bit each
    for (const IoCopy& c : p.io_out) {
        const uint32_t loc = c.index / 4, comp = c.index % 4;
        if (c.slot != IoSlot::Output || loc >= uint32_t(kColorOutputSlots) || (seen[loc] >> comp) & 1) return d;
        if (!seen[loc]) d.output_word[loc] = c.word - comp;
        if (c.word < comp || d.output_word[loc] != c.word - comp) return d;
        seen[loc] |= 1u << comp;
    }
    for (int loc = 0; loc < kColorOutputSlots; ++loc)
        if (seen[loc] && seen[loc] != 0xfu) return d;
    d.ok = true;
    return d;
}

}  // namespace

void plan_fragment_io(ProgramImpl& p) {
    p.frag_in = plan_runs(p.io_in, false);
    p.frag_out = plan_runs(p.io_out, true);
    p.frag_direct = plan_direct(p);
    // every input writes all 16 lanes of its word: the rest start at zero
    std::vector<bool> written(std::max(1u, p.local_words), false);
    for (const IoCopy& c : p.io_in)
        if (c.word < written.size()) written[c.word] = true;
    p.frag_zero.clear();
    for (uint32_t w = 0; w < written.size(); ++w) {
        if (written[w]) continue;
        if (!p.frag_zero.empty() && p.frag_zero.back().first + p.frag_zero.back().second == w)
            ++p.frag_zero.back().second;
        else
            p.frag_zero.emplace_back(w, 1);
    }
}

namespace {

// A fragment program's run on its prepared scratch: every lane enters (helper lanes too, for derivatives), the
// covered ones live. Returns the live mask.
uint32_t run_fragment_lanes(const ProgramImpl& p, Scratch::Impl& s, uint32_t cover_mask) {
    uint32_t* entry = s.regs.data() + size_t(p.reg_entry_mask) * kLanes;
    uint32_t* live = s.regs.data() + size_t(p.reg_live) * kLanes;
    LANES entry[l] = ~0u;
    lanes_from_mask(cover_mask, live);
    {
        FloatEnv env;
        run_program(p, s);
    }
    return mask_from_lanes(live) & cover_mask;
}

}  // namespace

void Program::run_fragment(const Bindings& bindings, FragmentBlock& fb, Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    Descriptor push;
    prepare(p, bindings, s, push, false);
    uint32_t* M = s.local.data();
    for (const auto& [word, count] : p.frag_zero) std::memset(M + size_t(word) * kLanes, 0, size_t(count) * kLanes * 4);
    const auto* block = reinterpret_cast<std::byte*>(&fb);
    for (const IoRun& r : p.frag_in) {
        uint32_t* w = M + size_t(r.word) * kLanes;
        if (!r.count) write_fragment_builtin(p.io_in[r.bytes], fb, w);
        for (uint32_t k = 0; k < r.count; ++k)
            std::memcpy(w + size_t(k) * kLanes, block + r.bytes + size_t(k) * sizeof(Lanes), sizeof(Lanes));
    }
    s.input_planes = fb.input_planes;
    fb.live_mask = run_fragment_lanes(p, s, fb.cover_mask);
    s.input_planes = nullptr;
    auto* out = reinterpret_cast<std::byte*>(&fb);
    for (const IoRun& r : p.frag_out)
        for (uint32_t k = 0; k < r.count; ++k)
            std::memcpy(out + r.bytes + size_t(k) * sizeof(Lanes), M + size_t(r.word + k) * kLanes, sizeof(Lanes));
}

const Program::FragmentDirect& Program::fragment_direct() const {
    return impl_->frag_direct;
}

uint32_t* Program::bind_fragment(const Bindings& bindings, uint64_t bindings_key, Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    if (bindings_key == 0 || s.bound_key != bindings_key || s.last != p.serial) {
        prepare(p, bindings, s, s.bound_push, false);
        s.bound_key = bindings_key;
    }
    return s.local.data();
}

// run_fragment's steps between its input and output copies, on the bound scratch.
uint32_t Program::run_bound_fragment(const FragmentBlock& fb, Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    s.back_edges = 0;
    uint32_t* M = s.local.data();
    for (const auto& [word, count] : p.frag_zero) std::memset(M + size_t(word) * kLanes, 0, size_t(count) * kLanes * 4);
    for (const IoRun& r : p.frag_in)
        if (!r.count) write_fragment_builtin(p.io_in[r.bytes], fb, M + size_t(r.word) * kLanes);
    return run_fragment_lanes(p, s, fb.cover_mask);
}

namespace {

// The subgroup built-ins of a compute batch (program.h kSubgroupSize: batches start at multiples of kLanes in
// LocalInvocationIndex order, so subgroup k holds invocations k * kSubgroupSize ...). The Eq..Lt masks are uvec4s
// whose components past the first are 0 (a subgroup has fewer than 32 lanes).
void write_subgroup_builtin(const IoCopy& c, const std::array<uint32_t, 3>& size, const ComputeBatch& cb, uint32_t* w) {
    const uint32_t all = (1u << kSubgroupSize) - 1;
    const auto mask = [&](auto bits_of_id) { LANES w[l] = c.index == 0 ? bits_of_id(uint32_t(l) % kSubgroupSize) : 0; };
    switch (c.slot) {
        case IoSlot::SubgroupSize:
            LANES w[l] = kSubgroupSize;
            break;
        case IoSlot::SubgroupLocalInvocationId:
            LANES w[l] = uint32_t(l) % kSubgroupSize;
            break;
        case IoSlot::SubgroupId:
            LANES w[l] = cb.local_index[l] / kSubgroupSize;
            break;
        case IoSlot::NumSubgroups:
            LANES w[l] = (size[0] * size[1] * size[2] + kSubgroupSize - 1) / kSubgroupSize;
            break;
        case IoSlot::SubgroupEqMask:
            mask([](uint32_t id) { return 1u << id; });
            break;
        case IoSlot::SubgroupGeMask:
            mask([all](uint32_t id) { return all & ~((1u << id) - 1); });
            break;
        case IoSlot::SubgroupGtMask:
            mask([all](uint32_t id) { return all & ~((2u << id) - 1); });
            break;
        case IoSlot::SubgroupLeMask:
            mask([](uint32_t id) { return (2u << id) - 1; });
            break;
        case IoSlot::SubgroupLtMask:
            mask([](uint32_t id) { return (1u << id) - 1; });
            break;
        default:
            break;
    }
}

// A compute batch's start: the scratch prepared, the built-ins copied into local memory, the entry mask.
void start_compute(const ProgramImpl& p, const std::array<uint32_t, 3>& size, const Bindings& bindings,
                   const ComputeBatch& cb, Scratch::Impl& s, Descriptor& push, bool resolve = true) {
    prepare(p, bindings, s, push, true, resolve);
    uint32_t* M = s.local.data();
    for (const IoCopy& c : p.io_in) {
        uint32_t* w = M + size_t(c.word) * kLanes;
        const uint32_t i = c.index < 3 ? c.index : 0;
        switch (c.slot) {
            case IoSlot::LocalInvocationId:
                copy_lanes(w, cb.local_id[i]);
                break;
            case IoSlot::LocalInvocationIndex:
                copy_lanes(w, cb.local_index);
                break;
            case IoSlot::GlobalInvocationId: {  // wraps in 32 bits as the SPIR-V arithmetic would
                // SSE2 by hand: GCC kept the multiply in the per-lane loop (w might alias cb)
                const __m128i base = _mm_set1_epi32(int(cb.workgroup_id[i] * size[i]));
                for (int q = 0; q < kLanes; q += 4) {
                    const __m128i id = _mm_loadu_si128(reinterpret_cast<const __m128i*>(cb.local_id[i] + q));
                    _mm_storeu_si128(reinterpret_cast<__m128i*>(w + q), _mm_add_epi32(base, id));
                }
                break;
            }
            case IoSlot::WorkgroupId:
                LANES w[l] = cb.workgroup_id[i];
                break;
            case IoSlot::NumWorkgroups:
                LANES w[l] = cb.num_workgroups[i];
                break;
            default:
                write_subgroup_builtin(c, size, cb, w);
                break;
        }
    }
    uint32_t* entry = s.regs.data() + size_t(p.reg_entry_mask) * kLanes;
    LANES entry[l] = uint32_t(l) < cb.count ? ~0u : 0u;
}

}  // namespace

// A workgroup: shared memory zeroed (lavapipe leaves it undefined; zero keeps every run deterministic), then its
// batches. Without barriers they run one after the other, each to the end. With barriers they run in lock-step
// phases: batch 0 up to its next Barrier (or the end), then batch 1 up to its next one, ..., then the next phase
// resumes each where it stopped, until every batch has ended. SPIR-V requires a workgroup's invocations to reach
// each OpControlBarrier together (uniform control flow); if they do not, a batch's barrier still only ends its
// phase, so a wrong shader gets some deterministic result and never hangs (the watchdog bounds its loops).
void Program::run_workgroup(const Bindings& bindings, std::span<const ComputeBatch> batches, Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    uint32_t* shared = nullptr;
    if (p.shared_words != 0) {
        if (s.shared_storage.size() < p.shared_words) s.shared_storage.resize(p.shared_words);
        shared = s.shared_storage.data();
        std::memset(shared, 0, size_t(p.shared_words) * 4);
    }
    Descriptor push;
    FloatEnv env(false);
    if (!p.has_barrier) {
        for (const ComputeBatch& cb : batches) {
            start_compute(p, interface_.local_size, bindings, cb, s, push, &cb == batches.data());
            s.shared = shared;
            run_program(p, s);
        }
        return;
    }
    ensure_frames(s, batches.size());
    for (size_t b = 0; b < batches.size(); ++b) {
        Scratch::Impl& f = frame_of(s, b);
        f.stop = s.stop;
        start_compute(p, interface_.local_size, bindings, batches[b], f, push);
        f.shared = shared;
        f.resume_pc = 0;
        f.done = false;
    }
    for (bool running = true; running;) {
        running = false;
        for (size_t b = 0; b < batches.size(); ++b) {
            Scratch::Impl& f = frame_of(s, b);
            if (f.done) continue;
            const size_t pc = p.jit ? jit::run(*p.jit, f, f.resume_pc) : execute_code(p.code.data(), f, f.resume_pc);
            f.done = pc == kRunDone;
            f.resume_pc = pc;
            running |= !f.done;
        }
    }
    for (size_t b = 1; b < batches.size(); ++b) {
        s.loop_limit_hits += frame_of(s, b).loop_limit_hits;
        frame_of(s, b).loop_limit_hits = 0;
    }
}

}  // namespace tilevk::shader
