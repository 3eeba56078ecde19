// The compiled tier's 8-lane Sample for 2D RGBA8/BGRA8 UNORM images with bilinear filtering (sample_rgba8.cpp).
#pragma once

#include "shader/ir.h"

namespace tilevk::shader::jit {

// Computes a Sample instruction exactly as exec_image would, when it is one of the cases this kernel covers (one
// image and sampler for all lanes; see the .cpp). False, with no register written, otherwise.
bool sample_rgba8(const Inst& in, uint32_t* regs, const Descriptor* const* slots, uint32_t num_slots);

}  // namespace tilevk::shader::jit
