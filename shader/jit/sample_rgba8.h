// The compiled tier's 8-lane Sample for 2D RGBA8/BGRA8 UNORM images with bilinear filtering (sample_rgba8.cpp).
#pragma once

#include "shader/ir.h"

namespace tilevk::shader::jit {

// Computes a Sample instruction exactly as exec_image would, when it is one of the cases this kernel covers (one
// image and sampler for all lanes; see the .cpp). False, with no register written, otherwise. Resolves and checks
// the descriptors on every call: bind_sample + sample_bound in one.
bool sample_rgba8(const Inst& in, uint32_t* regs, const Descriptor* const* slots, uint32_t num_slots);

// Binds `in` to the image and sampler that `handle` names in `slots` (BoundSample, ir.h): every check that depends
// on the instruction, the descriptors, the view and the sampler, made once. True (state Kernel) when the kernel
// covers the case, else false (state Interpreter).
bool bind_sample(const Inst& in, uint32_t handle, const Descriptor* const* slots, uint32_t num_slots, BoundSample& b);

// The instruction through its binding: true with the result registers written when `b` is bound to the kernel and
// every lane's handle is b.handle, and the implicit LOD meets no NaN; false, with no register written, otherwise.
bool sample_bound(const Inst& in, uint32_t* regs, const BoundSample& b);

}  // namespace tilevk::shader::jit
