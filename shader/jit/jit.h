// The compiled tier: an IR program (shader/ir.h) compiled with asmjit to one native function of 16-lane AVX2/FMA
// code. It computes exactly what the interpreter (exec.cpp, the first tier and the reference) computes: same
// registers, same local memory, same float operations in the same order, the interpreter's own code for every op
// this tier does not emit natively. shader/jit/README.md has the design and the figures.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "shader/ir.h"

namespace tilevk::shader::jit {

// What the generated function receives: the interpreter's working memory for this run.
struct Frame {
    uint32_t* regs;                  // register r = regs + r * kLanes
    uint32_t* local;                 // local word w = local + w * kLanes
    const Descriptor* const* slots;  // resolved descriptors (slot 0: push constants)
    Scratch::Impl* scratch;
    const std::atomic<bool>* stop;  // the driver's time limit (Scratch::set_stop_flag), or null
    uint64_t back_edges;            // loop watchdog without a stop flag: back edges taken in this run (all phases)
    uint32_t* shared;               // compute: the workgroup's shared memory (Scratch::Impl::shared)
    uint64_t resume;                // where the run starts: 0, or the pc after a Barrier an earlier run stopped at
};
// Returns kRunDone after Halt or the watchdog, else the pc after the Barrier the run stopped at.
using Entry = size_t (*)(Frame*);

// A compiled program. Owns the executable memory and the instructions the generated code hands back to the
// interpreter one at a time.
struct Code {
    Entry entry = nullptr;
    std::unique_ptr<Inst[]> helper_code;  // per helper op: the instruction, then Halt
    uint32_t native_ops = 0, helper_ops = 0;
    uint32_t sample_ops = 0;  // Sample instructions, numbered in code order: Scratch::Impl::samples[k]
    uint32_t folded = 0;      // lane-wise instructions computed while compiling, once per 8-lane half (fold.cpp)
    size_t code_bytes = 0;
    double compile_ms = 0;
    ~Code();
};

// Compiles `p`. Returns null with *why_not set when this tier is off (TILEVK_JIT=0, set_jit_enabled(false)), the
// host lacks AVX2/FMA, the program contains an op this tier does not know, or code generation fails: the program
// then runs in the interpreter, never with a wrong result.
std::shared_ptr<const Code> compile(const ProgramImpl& p, std::string* why_not);

// Runs the compiled program on `s` (prepared by Program::run_*, floating-point environment already set) from pc 0
// or, in a workgroup's lock-step phases, from the pc after a Barrier; returns as execute_code does (kRunDone, or the
// pc after the Barrier the run stopped at).
size_t run(const Code& code, Scratch::Impl& s, size_t pc = 0);

// CPUID (and the OS's saved register state) says the host runs AVX2 and FMA code.
bool host_supported();

// Process-wide switch read by compile(): on unless TILEVK_JIT=0.
bool enabled();

// Debug output under TILEVK_LOG_PIPELINES: why a program stays in the interpreter, compile figures.
bool log_enabled();

// The IR op's name ("FAdd", "Sample", ...), or "op #N" for an op this tier does not know.
std::string op_name(Op op);

}  // namespace tilevk::shader::jit
