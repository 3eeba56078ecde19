// What the code generator needs to know about an IR program before emitting it: how each op is compiled, which
// registers each instruction touches, where the jump targets and segments are, and which registers never need
// their memory home.
#pragma once

#include <cstdint>
#include <vector>

#include "shader/ir.h"

namespace tilevk::shader::jit {

enum class Lowering : uint8_t {
    Unknown,  // an op this tier does not know (e.g. added to ir.h later): the whole program stays interpreted
    Native,   // emitted as AVX2/FMA instructions; libm ops as a call per 8-lane half inside the segment
    Helper,   // the interpreter's own code runs this one instruction (images, buffers, rare integer ops)
};

struct OpInfo {
    const char* name;
    Lowering lowering;
};
// Name and lowering of an op; {nullptr, Unknown} for an op this tier does not know.
OpInfo op_info(Op op);

// Which operand's NaN the interpreter's FAdd / FMul returns in lanes 4q to 4q + 3 (quarter q, 0-3) when both are
// NaN (measured on the interpreter, whose compiler picks the order per 4-lane SSE instruction).
enum class NanOrder : uint8_t { AFirst, BFirst, Unknown };
NanOrder nan_order(Op op, int quarter);

// How this instruction is compiled: op_info's lowering, except that FAdd / FMul run through the interpreter when
// nan_order cannot say for some quarter.
Lowering lowering(const Inst& in);

// Registers an instruction reads and writes. For helper ops this is a superset of what the interpreter touches
// (image ops read runs of coordinate registers); that only costs speed, never correctness.
struct Footprint {
    static constexpr int kMax = 16;
    uint32_t reads[kMax];
    uint32_t writes[kMax];
    int num_reads = 0, num_writes = 0;  // may exceed kMax: then the instruction is not compiled
    bool reads_dest = false;            // the old value of a written register is read (MaskedMov, Kill)
    void read(uint32_t r) {
        if (r == kNoReg) return;
        if (num_reads < kMax) reads[num_reads] = r;
        ++num_reads;
    }
    void write(uint32_t r) {
        if (r == kNoReg) return;
        if (num_writes < kMax) writes[num_writes] = r;
        ++num_writes;
    }
    bool complete() const { return num_reads <= kMax && num_writes <= kMax; }
};
Footprint footprint(const Inst& in);

// An instruction the generated code cannot run lane-wise, half by half: it reads whole registers (control flow
// tests masks across all 16 lanes) or hands them to the interpreter through memory.
bool is_sync(const Inst& in);

struct Analysis {
    // Instruction i is a jump target.
    std::vector<uint8_t> label;  // code.size() + 1 entries
    // Segment of each instruction: straight-line lane-wise code, split at labels and around sync instructions
    // (each sync instruction is a segment of its own). Within a segment lanes 0-7 and 8-15 are independent, so the
    // code generator emits each segment twice, once per 8-lane half.
    std::vector<uint32_t> segment;
    // Register r is segment-local: every access lies in one segment, the first one writes it without reading it,
    // it is not a sync instruction's operand and the host never reads it. Its value lives in machine registers
    // (spilled to its home only under register pressure).
    std::vector<uint8_t> local;
    // Register r holds a constant (const_regs) that no instruction writes.
    std::vector<uint8_t> is_const;
    std::vector<uint32_t> const_value;
    // Instruction index of the first op the tier does not know, or -1.
    int64_t unknown_at = -1;
};
Analysis analyze(const ProgramImpl& p);

}  // namespace tilevk::shader::jit
