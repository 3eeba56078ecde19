// LLVM ORC as the compiled tier's code generator, for the measurement that chose asmjit (llvm_probe.cpp).
#pragma once

#include <memory>
#include <string>

#include "shader/ir.h"
#include "shader/jit/jit.h"

namespace tilevk::bench_probe {

// Time to set LLVM's JIT up (targets, LLJIT): paid once per process.
double llvm_init_ms();

// Lowers and compiles `p` at LLVM optimisation level 1 or 2; null with *why for an op the probe does not lower.
std::shared_ptr<shader::jit::Code> llvm_compile(const shader::ProgramImpl& p, int opt_level, std::string* why);

}  // namespace tilevk::bench_probe
