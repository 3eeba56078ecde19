// Code generator internals shared by compile.cpp (the function, control flow, helper calls) and lanes.cpp (lane-wise
// ops, register allocation within a segment).
//
// Machine state. rbx = register file, r12 = local memory, r13 = resolved descriptors, r14 = the Frame; all four are
// callee-saved, so helper calls keep them. Every IR register has its home in the register file and every local word
// in local memory, exactly where the interpreter keeps them, so helpers (the interpreter's own code for one
// instruction) and the host see the same state. YMM registers cache values inside one segment only.
#pragma once

#include <asmjit/x86.h>

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "shader/jit/analysis.h"

namespace tilevk::shader::jit {

inline const asmjit::x86::Gp kRegsBase = asmjit::x86::rbx;
inline const asmjit::x86::Gp kLocalBase = asmjit::x86::r12;
inline const asmjit::x86::Gp kSlotsBase = asmjit::x86::r13;
inline const asmjit::x86::Gp kFrameBase = asmjit::x86::r14;

constexpr uint32_t kNever = UINT32_MAX;

// 32-byte constants after the code, addressed RIP-relative.
class ConstantPool {
  public:
    explicit ConstantPool(const asmjit::Label& label) : label_(label) {}
    asmjit::x86::Mem splat(uint32_t bits);         // eight copies of bits
    asmjit::x86::Mem vector(const uint32_t v[8]);  // eight words
    void emit(asmjit::x86::Assembler& a) const;    // at the end of the function

  private:
    asmjit::Label label_;
    std::vector<uint32_t> words_;
    std::unordered_map<uint32_t, uint32_t> splats_;  // bits -> byte offset
};

// Which value a machine register holds: an IR register or a local word.
constexpr uint64_t reg_key(uint32_t r) {
    return (uint64_t(1) << 32) | r;
}
constexpr uint64_t word_key(uint32_t w) {
    return (uint64_t(2) << 32) | w;
}

// For one instruction of a segment: the values it reads and writes, each with the position of its next read in the
// segment (kNever: not read again before it is overwritten or the segment ends).
struct Uses {
    static constexpr int kMax = 6;
    uint64_t key[kMax];
    uint32_t next[kMax];
    bool write[kMax];
    int n = 0;
};
// Fills uses[i - first] for the instructions [first, end) of one segment.
void segment_uses(const ProgramImpl& p, size_t first, size_t end, std::vector<Uses>& uses);

// Emits the lane-wise instructions of one segment for one 8-lane half (lanes 0-7 or 8-15), allocating the 16 YMM
// registers by farthest next use; values leave machine registers at the end of the pass (non-local registers and
// local words are written through to their homes at once, local registers are dead there by definition).
class LaneEmitter {
  public:
    LaneEmitter(const ProgramImpl& p, const Analysis& an, asmjit::x86::Assembler& a, ConstantPool& pool);
    // Emits code[first, end) for half h. False when an instruction cannot be emitted.
    bool pass(size_t first, size_t end, const std::vector<Uses>& uses, int h);
    uint32_t folded() const { return folded_; }  // instructions fold() took, per half, so far

  private:
    using Ymm = asmjit::x86::Ymm;
    struct Phys {
        uint64_t key = 0;  // 0: holds nothing
        uint32_t next = kNever;
        bool pinned = false;
    };
    asmjit::x86::Mem home(uint64_t key) const;
    int8_t& where(uint64_t key);
    uint32_t next_use(uint64_t key, bool write) const;
    int alloc();
    Ymm use(uint64_t key);  // the value in a machine register, pinned for this instruction
    Ymm use(uint32_t r) { return use(reg_key(r)); }
    Ymm take(uint64_t key);  // use() that may hand over the register (last read) for the result
    Ymm temp();
    void def(uint64_t key, Ymm y);
    void def(uint32_t r, const Ymm& y) { def(reg_key(r), y); }
    void end_instruction();
    bool dead(const Inst& in) const;  // nothing reads its results: not emitted
    bool fold(const Inst& in);        // a lane-uniform result known here: not emitted (fold.cpp)
    bool value_of(uint32_t r, uint32_t& bits) const;
    void forget_value(uint32_t r);
    bool op(const Inst& in);
    // op() by family (lanes.cpp): nullopt when in.op is not of the family, else op()'s answer
    std::optional<bool> float_op(const Inst& in);
    std::optional<bool> compare_op(const Inst& in);
    std::optional<bool> int_op(const Inst& in);
    std::optional<bool> convert_op(const Inst& in);
    std::optional<bool> memory_op(const Inst& in);
    std::optional<bool> gallivm_op(const Inst& in);  // gallivm_ops.cpp: exp2, log2, pow, exp, log inline

    // lowerings used by several ops
    template <typename F>
    void unary(const Inst& in, F f);
    template <typename F>
    void binary(const Inst& in, F f);
    void fcmp(const Inst& in, uint32_t predicate);
    Ymm select(Ymm m, Ymm x, Ymm y);
    Ymm fmin(Ymm a, Ymm b);
    Ymm fmax(Ymm a, Ymm b);
    Ymm round(Ymm a, uint32_t mode);
    void add_mul(const Inst& in);
    bool nan_order_free(const Inst& in) const;  // no lane can meet two NaNs in in.a and in.b
    void int_compare(const Inst& in);
    void f2u(const Inst& in);
    void u2f(const Inst& in);
    void fsign(const Inst& in);
    void smooth_step(const Inst& in);
    void derivative(const Inst& in, uint32_t right, uint32_t left);
    bool load_local(const Inst& in);
    void lane_call(const Inst& in, const void* fn);
    void load_buf_uniform(const Inst& in);
    void load_buf(const Inst& in);
    bool load_shared(const Inst& in);  // memory_ops.cpp

    const ProgramImpl& p_;
    const Analysis& an_;
    asmjit::x86::Assembler& a_;
    ConstantPool& pool_;
    Phys phys_[16];
    std::vector<int8_t> reg_where_, word_where_;
    const Uses* uses_ = nullptr;  // of the instruction being emitted
    int half_ = 0;
    bool overflow_ = false;
    uint32_t uniform_slot_ = kNoReg;  // the slot whose data and size r8, r9 hold (load_buf_uniform)
    bool inline_gallivm_ = false;     // gallivm_op may emit (gallivm::avx2_build_runs)
    // Segment-local registers whose value fold() computed in this pass (the same in every lane), with their bits:
    // they reach a machine register from the constant pool when an emitted instruction reads them (use()).
    std::vector<uint8_t> known_;
    std::vector<uint32_t> known_bits_, known_list_;
    uint32_t folded_ = 0;
};

// The memory sync ops as the interpreter's lane loops (memory_ops.cpp), at a sync point (every value in its home,
// rax, rcx, rdx, rsi, rdi, r8, r9, r10 and the vector registers free: YMM caches end at sync points). False when
// the instruction's operands are out of range.
bool emit_store_shared(asmjit::x86::Assembler& a, const ProgramImpl& p, const Inst& in);
bool emit_atomic_shared(asmjit::x86::Assembler& a, const ProgramImpl& p, const Inst& in);
bool emit_store_buf(asmjit::x86::Assembler& a, const ProgramImpl& p, const Inst& in);  // in.n == 1 only

}  // namespace tilevk::shader::jit
