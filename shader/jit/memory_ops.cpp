// Memory ops of the compiled tier: LoadBufUniform, LoadBuf from one buffer and compute's LoadShared inside segments
// (a load, a broadcast or a gather per 8-lane half), the sync ops StoreShared and AtomicShared, and StoreBuf to one
// buffer, the sync ops as the interpreter's lane loops (exec_atomic.h, exec_memory.h) written out for the 16 lanes: the
// same words in the same lane order, so the same memory and the same atomic results. Shared memory is one flat block
// per workgroup (not SoA), reached through Frame::shared; a workgroup runs on one thread, so the shared atomics are
// plain read-modify-writes, as in the interpreter.
#include <cstddef>
#include <cstdint>

#include "shader/jit/codegen.h"
#include "shader/jit/jit.h"

namespace tilevk::shader::jit {

using namespace asmjit;

namespace {

// A missing descriptor reads through kNoBuffer (no data, size 0); a failed uniform bounds check reads kZeroWord.
const Descriptor kNoBuffer{};
const uint32_t kZeroWord = 0;

// Word `lane` of IR register r in the register file.
x86::Mem lane_of(uint32_t r, int lane) {
    return x86::dword_ptr(kRegsBase, int32_t(size_t(r) * kLanes * 4 + size_t(lane) * 4));
}

// The operands a lane loop reads exist, and imm + index clamps into the variable (exec_atomic.h's min(imm + a,
// n - 1), which needs n >= 1).
bool lane_loop_ok(const ProgramImpl& p, const Inst& in, std::initializer_list<uint32_t> regs) {
    for (uint32_t r : regs)
        if (r >= p.num_regs) return false;
    return in.n != 0 && in.n <= p.shared_words;
}

// rax = min(imm + (uint64_t)eax, n - 1): the word index of exec_atomic.h, computed in 64 bits as it is there;
// r10 = n - 1 (set once per instruction by last_word).
void last_word(x86::Assembler& a, const Inst& in) {
    a.mov(x86::r10, uint64_t(in.n) - 1);
}
void clamp_index(x86::Assembler& a, const Inst& in) {
    if (in.imm != 0) a.add(x86::rax, int32_t(in.imm));
    a.cmp(x86::rax, x86::r10);
    a.cmova(x86::rax, x86::r10);
}

// r9d = atomic_result(op, old = ecx, v = r8d, cmp = the lane's d) (exec_atomic.h)
bool atomic_result(x86::Assembler& a, const Inst& in, int lane) {
    using namespace x86;
    a.mov(r9d, ecx);
    switch (AtomicOp(in.pad)) {
        case AtomicOp::Load:
            return true;
        case AtomicOp::Store:
        case AtomicOp::Exchange:
            a.mov(r9d, r8d);
            return true;
        case AtomicOp::CompareExchange:
            a.cmp(ecx, lane_of(in.d, lane));
            a.cmove(r9d, r8d);
            return true;
        case AtomicOp::IAdd:
            a.add(r9d, r8d);
            return true;
        case AtomicOp::SMin:  // int32(v) < int32(old) ? v : old
            a.cmp(r8d, ecx);
            a.cmovl(r9d, r8d);
            return true;
        case AtomicOp::SMax:
            a.cmp(r8d, ecx);
            a.cmovg(r9d, r8d);
            return true;
        case AtomicOp::UMin:
            a.cmp(r8d, ecx);
            a.cmovb(r9d, r8d);
            return true;
        case AtomicOp::UMax:
            a.cmp(r8d, ecx);
            a.cmova(r9d, r8d);
            return true;
        case AtomicOp::And:
            a.and_(r9d, r8d);
            return true;
        case AtomicOp::Or:
            a.or_(r9d, r8d);
            return true;
        case AtomicOp::Xor:
            a.xor_(r9d, r8d);
            return true;
        case AtomicOp::FAdd:  // float(old) + float(v), old first, under the run's MXCSR (xmm0/xmm1 are free here)
            a.vmovd(xmm0, ecx);
            a.vmovd(xmm1, r8d);
            a.vaddss(xmm0, xmm0, xmm1);
            a.vmovd(r9d, xmm0);
            return true;
        case AtomicOp::FMin:  // MINSS / MAXSS(v, old), then v when old is NaN (exec_atomic.h)
        case AtomicOp::FMax:
            a.vmovd(xmm0, r8d);
            a.vmovd(xmm1, ecx);
            if (AtomicOp(in.pad) == AtomicOp::FMin)
                a.vminss(xmm0, xmm0, xmm1);
            else
                a.vmaxss(xmm0, xmm0, xmm1);
            a.vmovd(r9d, xmm0);
            a.vucomiss(xmm1, xmm1);
            a.cmovp(r9d, r8d);
            return true;
    }
    return false;
}

}  // namespace

// exec_atomic.h op_store_shared: the lanes of mask c in lane order, each writing b to its clamped word.
bool emit_store_shared(x86::Assembler& a, const ProgramImpl& p, const Inst& in) {
    if (!lane_loop_ok(p, in, {in.a, in.b, in.c})) return false;
    using namespace x86;
    a.mov(rdx, qword_ptr(kFrameBase, int32_t(offsetof(Frame, shared))));
    last_word(a, in);
    for (int l = 0; l < kLanes; ++l) {
        Label skip = a.newLabel();
        a.cmp(lane_of(in.c, l), 0);
        a.je(skip);
        a.mov(eax, lane_of(in.a, l));  // zero-extends into rax
        clamp_index(a, in);
        a.mov(ecx, lane_of(in.b, l));
        a.mov(dword_ptr(rdx, rax, 2), ecx);
        a.bind(skip);
    }
    return true;
}

// exec_atomic.h op_atomic_shared: lane by lane, an inactive lane (index kNoReg) gets 0, an active one the old word
// after writing atomic_result to it; the comparator is read from d before the lane's result replaces it.
bool emit_atomic_shared(x86::Assembler& a, const ProgramImpl& p, const Inst& in) {
    if (!lane_loop_ok(p, in, {in.a, in.c, in.d})) return false;
    using namespace x86;
    a.mov(rdx, qword_ptr(kFrameBase, int32_t(offsetof(Frame, shared))));
    last_word(a, in);
    for (int l = 0; l < kLanes; ++l) {
        Label active = a.newLabel(), next = a.newLabel();
        a.mov(eax, lane_of(in.a, l));
        a.cmp(eax, int32_t(kNoReg));
        a.jne(active);
        a.mov(lane_of(in.d, l), 0);
        a.jmp(next);
        a.bind(active);
        clamp_index(a, in);
        a.lea(rsi, ptr(rdx, rax, 2));
        a.mov(ecx, dword_ptr(rsi));
        a.mov(r8d, lane_of(in.c, l));
        if (!atomic_result(a, in, l)) return false;
        a.mov(dword_ptr(rsi), r9d);
        a.mov(lane_of(in.d, l), ecx);
        a.bind(next);
    }
    return true;
}

// exec_memory.h op_store_buf for one buffer (in.n == 1, so only element 0 stores): the lanes of mask d in lane
// order, each storing c at byte b + extra when the descriptor is there and writable and the word lies inside it.
bool emit_store_buf(x86::Assembler& a, const ProgramImpl& p, const Inst& in) {
    for (uint32_t r : {in.a, in.b, in.c, in.d})
        if (r >= p.num_regs) return false;
    if (in.n != 1) return false;
    if (in.imm >= p.num_slots) return true;  // the slot is past the table: no lane stores (the interpreter's check)
    using namespace x86;
    Label done = a.newLabel();
    a.mov(rax, qword_ptr(kSlotsBase, int32_t(in.imm) * 8));
    a.test(rax, rax);
    a.jz(done);
    a.mov(rdx, qword_ptr(rax, int32_t(offsetof(Descriptor, buffer) + offsetof(BufferView, writable))));
    a.test(rdx, rdx);
    a.jz(done);
    a.mov(rsi, qword_ptr(rax, int32_t(offsetof(Descriptor, buffer) + offsetof(BufferView, size))));
    a.mov(rdi, uint64_t(in.extra) + 4);  // off + 4 <= size with off = b + extra, in 64 bits
    for (int l = 0; l < kLanes; ++l) {
        Label skip = a.newLabel();
        a.cmp(lane_of(in.d, l), 0);
        a.je(skip);
        a.cmp(lane_of(in.a, l), 0);  // a[l] >= n: another element of a one-element array
        a.jne(skip);
        a.mov(eax, lane_of(in.b, l));  // zero-extends
        a.add(rax, rdi);               // off + 4, no wrap in 64 bits
        a.cmp(rax, rsi);
        a.ja(skip);
        a.mov(ecx, lane_of(in.c, l));
        a.mov(dword_ptr(rdx, rax, 0, -4), ecx);
        a.bind(skip);
    }
    a.bind(done);
    return true;
}

// One bounds-checked read broadcast to every lane (exec.cpp LoadBufUniform), without branches. The descriptor's
// data pointer and size are resolved once per slot for the loads that follow in the segment (a shader reads its
// push constants and uniforms as runs of such loads: meshes_lit's tint took 14 instructions a word, now 4 after
// the resolution): r8 = the data, r9 = the size, 0 when there is no data (so every bound check fails, as the
// interpreter's `data &&`), r11 = the zero word. No lane-wise lowering touches r8-r11; a lane call (a C++
// call) clobbers them, so it forgets the resolution (uniform_slot_), and so does the end of the pass.
void LaneEmitter::load_buf_uniform(const Inst& in) {
    Ymm d = temp();
    if (in.imm >= p_.num_slots) {
        a_.vpxor(d, d, d);
        def(in.d, d);
        return;
    }
    using namespace x86;
    if (uniform_slot_ != in.imm) {
        a_.mov(rax, qword_ptr(kSlotsBase, int32_t(in.imm) * 8));
        a_.mov(rcx, reinterpret_cast<uint64_t>(&kNoBuffer));
        a_.test(rax, rax);
        a_.cmovz(rax, rcx);
        a_.mov(r8, qword_ptr(rax, int32_t(offsetof(Descriptor, buffer) + offsetof(BufferView, data))));
        a_.mov(r9, qword_ptr(rax, int32_t(offsetof(Descriptor, buffer) + offsetof(BufferView, size))));
        a_.xor_(ecx, ecx);
        a_.test(r8, r8);
        a_.cmovz(r9, rcx);  // no data: size 0
        a_.mov(r11, reinterpret_cast<uint64_t>(&kZeroWord));
        uniform_slot_ = in.imm;
    }
    // extra + 4 <= size, compared in 64 bits as the interpreter does (extra < 2^32: no overflow)
    const uint64_t end = uint64_t(in.extra) + 4;
    if (end <= uint64_t(INT32_MAX)) {
        a_.lea(rdi, qword_ptr(r8, int32_t(in.extra)));
        a_.cmp(r9, int32_t(end));
    } else {
        a_.mov(rdi, uint64_t(in.extra));
        a_.add(rdi, r8);
        a_.mov(rcx, end);
        a_.cmp(r9, rcx);
    }
    a_.cmovb(rdi, r11);  // size < extra + 4, or no data
    a_.vpbroadcastd(d, dword_ptr(rdi));
    def(in.d, d);
}

// exec_memory.h op_load_buf for a single buffer (in.n == 1) as one masked gather: a lane reads the word at byte
// b + extra when its element index a is 0, the buffer has data and b + extra + 4 <= size; every other lane gets 0
// (a masked-off lane of vpgatherdd keeps the zeroed destination and touches no memory). The bound is computed in
// 64 bits and capped at 2^31 (gather indices are signed dwords), which changes nothing for a valid descriptor: its
// range is at most maxStorageBufferRange = 2^27 (maxUniformBufferRange 16384). Past the cap (invalid usage) a lane
// reads 0 where the interpreter reads the word; every lane that reads stays inside the buffer either way.
void LaneEmitter::load_buf(const Inst& in) {
    if (in.imm >= p_.num_slots) {
        Ymm d = temp();
        a_.vpxor(d, d, d);
        def(in.d, d);
        return;
    }
    using namespace x86;
    // The sources first: a temp is only reserved from the moment it is taken, so a later use() could reuse it.
    Ymm a = use(in.a), b = use(in.b), d = temp(), lim = temp(), bad = temp(), mask = temp();
    a_.vpxor(d, d, d);
    a_.mov(rax, qword_ptr(kSlotsBase, int32_t(in.imm) * 8));
    a_.mov(rcx, reinterpret_cast<uint64_t>(&kNoBuffer));
    a_.test(rax, rax);
    a_.cmovz(rax, rcx);
    a_.mov(rdx, qword_ptr(rax, int32_t(offsetof(Descriptor, buffer) + offsetof(BufferView, data))));
    a_.mov(rcx, qword_ptr(rax, int32_t(offsetof(Descriptor, buffer) + offsetof(BufferView, size))));
    a_.mov(rsi, uint64_t(1) << 31);
    a_.cmp(rcx, rsi);
    a_.cmovb(rsi, rcx);  // rsi = min(size, 2^31)
    a_.xor_(ecx, ecx);
    a_.test(rdx, rdx);
    a_.cmovz(rsi, rcx);  // no data: nothing is inside
    a_.mov(rcx, uint64_t(in.extra) + 4);
    a_.sub(rsi, rcx);  // the largest b that is inside; negative: none
    a_.mov(rcx, uint64_t(int64_t(-1)));
    a_.cmovl(rsi, rcx);
    a_.vmovd(lim.xmm(), esi);
    a_.vpbroadcastd(lim, lim.xmm());
    a_.vpcmpgtd(bad, b, lim);  // b > bound (signed: the bound is below 2^31)
    a_.vpcmpgtd(mask, d, b);   // b >= 2^31 (negative as a signed dword); d is zero here
    a_.vpor(bad, bad, mask);
    a_.vpcmpeqd(mask, a, d);  // element index 0
    a_.vpandn(mask, bad, mask);
    a_.mov(rdi, uint64_t(in.extra));
    a_.add(rdi, rdx);
    // Every lane inside and the offsets 4 bytes apart (a row of a buffer, as x[gl_GlobalInvocationID.x] reads):
    // one plain load of the same 32 bytes; gathers are slow here (load_shared).
    static const uint32_t kSteps[8] = {0, 4, 8, 12, 16, 20, 24, 28};
    Label gather = a_.newLabel(), done = a_.newLabel();
    a_.vmovmskps(ecx, mask);
    a_.cmp(ecx, 0xFF);
    a_.jne(gather);
    a_.vpbroadcastd(bad, b.xmm());
    a_.vpsubd(bad, b, bad);
    a_.vpcmpeqd(bad, bad, pool_.vector(kSteps));
    a_.vmovmskps(ecx, bad);
    a_.cmp(ecx, 0xFF);
    a_.jne(gather);
    a_.vmovd(ecx, b.xmm());  // zero-extends: the offset is below 2^31 here
    a_.vmovdqu(d, ptr(rdi, rcx));
    a_.jmp(done);
    a_.bind(gather);
    a_.vpgatherdd(d, ptr(rdi, b, 0), mask);
    a_.bind(done);
    def(in.d, d);
}

// exec_atomic.h op_load_shared for one half: d = shared[min(imm + a, n - 1)] per lane, with the index clamped to
// n - 1 - imm first (the same word: imm <= n - 1, and the sum cannot wrap then). Gathers are slow on the machines
// this runs on (README "The RGBA8 sampler's loads"), and a workgroup's lanes mostly read one row of a tile (x
// consecutive words) or one word (a value every lane of the row needs): those two are a plain load and a
// broadcast, checked per half at run time; any other pattern is a gather. The same words either way.
bool LaneEmitter::load_shared(const Inst& in) {
    if (in.n == 0 || in.n > p_.shared_words) return false;
    using namespace x86;
    a_.mov(rax, qword_ptr(kFrameBase, int32_t(offsetof(Frame, shared))));
    if (in.imm >= in.n - 1) {  // every index clamps to the last word
        Ymm d = temp();
        a_.vpbroadcastd(d, dword_ptr(rax, int32_t(in.n - 1) * 4));
        def(in.d, d);
        return true;
    }
    static const uint32_t kSteps[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    Ymm a = use(in.a), idx = temp(), t = temp(), d = temp();
    Label not_row = a_.newLabel(), gather = a_.newLabel(), done = a_.newLabel();
    const int32_t base = int32_t(in.imm) * 4;
    a_.vpminud(idx, a, pool_.splat(in.n - 1 - in.imm));
    a_.vpbroadcastd(t, idx.xmm());
    a_.vpsubd(t, idx, t);  // each lane's index minus lane 0's
    a_.vmovd(ecx, idx.xmm());
    a_.vpcmpeqd(d, t, pool_.vector(kSteps));
    a_.vmovmskps(edx, d);
    a_.cmp(edx, 0xFF);
    a_.jne(not_row);
    a_.vmovdqu(d, ptr(rax, rcx, 2, base));  // consecutive words
    a_.jmp(done);
    a_.bind(not_row);
    a_.vptest(t, t);
    a_.jnz(gather);
    a_.vpbroadcastd(d, dword_ptr(rax, rcx, 2, base));  // one word
    a_.jmp(done);
    a_.bind(gather);
    a_.vpcmpeqd(t, t, t);
    a_.vpxor(d, d, d);
    a_.vpgatherdd(d, ptr(rax, idx, 2, base), t);
    a_.bind(done);
    def(in.d, d);
    return true;
}

}  // namespace tilevk::shader::jit
