// Compute's synchronisation and atomics: OpControlBarrier and the OpAtomic* family (32-bit integers; 32-bit floats:
// Load, Store, Exchange, OpAtomicFAddEXT, OpAtomicFMinEXT / FMaxEXT) on storage buffers, storage images and
// Workgroup memory, and 64-bit integers on storage buffers and Workgroup memory (the kernels: exec_atomic.h,
// exec_pointer.h).
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

namespace {

// The IR atomic of an OpAtomic* (IIncrement / IDecrement / ISub are additions of 1, -1, -value).
bool atomic_kind(spv::Op op, AtomicOp& out) {
    switch (op) {
        case spv::Op::OpAtomicLoad:
            out = AtomicOp::Load;
            return true;
        case spv::Op::OpAtomicStore:
            out = AtomicOp::Store;
            return true;
        case spv::Op::OpAtomicExchange:
            out = AtomicOp::Exchange;
            return true;
        case spv::Op::OpAtomicCompareExchange:
            out = AtomicOp::CompareExchange;
            return true;
        case spv::Op::OpAtomicIIncrement:
        case spv::Op::OpAtomicIDecrement:
        case spv::Op::OpAtomicIAdd:
        case spv::Op::OpAtomicISub:
            out = AtomicOp::IAdd;
            return true;
        case spv::Op::OpAtomicSMin:
            out = AtomicOp::SMin;
            return true;
        case spv::Op::OpAtomicSMax:
            out = AtomicOp::SMax;
            return true;
        case spv::Op::OpAtomicUMin:
            out = AtomicOp::UMin;
            return true;
        case spv::Op::OpAtomicUMax:
            out = AtomicOp::UMax;
            return true;
        case spv::Op::OpAtomicAnd:
            out = AtomicOp::And;
            return true;
        case spv::Op::OpAtomicOr:
            out = AtomicOp::Or;
            return true;
        case spv::Op::OpAtomicXor:
            out = AtomicOp::Xor;
            return true;
        case spv::Op::OpAtomicFAddEXT:
            out = AtomicOp::FAdd;
            return true;
        case spv::Op::OpAtomicFMinEXT:
            out = AtomicOp::FMin;
            return true;
        case spv::Op::OpAtomicFMaxEXT:
            out = AtomicOp::FMax;
            return true;
        default:
            return false;  // OpAtomicFlag*, OpAtomicCompareExchangeWeak (Kernel): refused by name
    }
}

bool is_float_op(AtomicOp kind) {
    return kind == AtomicOp::FAdd || kind == AtomicOp::FMin || kind == AtomicOp::FMax;
}

// The message refusing atomic `kind` on type t in `space`, or empty. 32-bit integers take every atomic; 64-bit
// integers every integer atomic on storage buffers (through PhysicalStorageBuffer pointers too) and Workgroup memory
// (VK_KHR_shader_atomic_int64's shaderBufferInt64Atomics and shaderSharedInt64Atomics, as lavapipe reports them; no
// image form).
// 32-bit floats (VK_EXT_shader_atomic_float's shader*Float32Atomics and *Float32AtomicAdd, and
// VK_EXT_shader_atomic_float2's shader*Float32AtomicMinMax, as lavapipe 22.3 with LLVM 15 reports them) take Load,
// Store, Exchange, OpAtomicFAddEXT and OpAtomicFMinEXT / FMaxEXT. The 16- and 64-bit float features are VK_FALSE
// in lavapipe and tilevk.
std::string atomic_type_error(spv::Op op, AtomicOp kind, const Type& t, Space space) {
    const bool float_op =
        kind == AtomicOp::Load || kind == AtomicOp::Store || kind == AtomicOp::Exchange || is_float_op(kind);
    const std::string what = "unsupported " + opname(op);
    if (t.kind == Type::Int && t.wide && is_float_op(kind)) return what + " on a 64-bit integer";
    if (t.kind == Type::Int && t.wide && space == Space::Texel)
        return what + " on a 64-bit integer image texel (VK_EXT_shader_image_atomic_int64 is not offered)";
    if (t.kind == Type::Int && t.wide) return {};
    if (t.kind == Type::Int && t.bits != 32) return what + " on a " + std::to_string(t.bits) + "-bit integer";
    if (t.kind == Type::Int && !is_float_op(kind)) return {};
    if (t.kind != Type::Float) return what + " on a non-integer, non-float type";
    if (t.wide)
        return what +
               " on a 64-bit float (VkPhysicalDeviceShaderAtomicFloatFeaturesEXT::shaderBufferFloat64Atomics and "
               "shaderSharedFloat64Atomics are VK_FALSE)";
    if (t.bits != 32)
        return what +
               " on a 16-bit float (VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT::shaderBufferFloat16Atomics "
               "and shaderSharedFloat16Atomics are VK_FALSE)";
    if (!float_op)
        return what +
               " on a float (32-bit floats: OpAtomicLoad, Store, Exchange, OpAtomicFAddEXT, OpAtomicFMinEXT "
               "and OpAtomicFMaxEXT)";
    return {};
}

}  // namespace

bool Translator::op_atomic(const Instr& in) {
    if (in.op == spv::Op::OpControlBarrier) {
        uint32_t scope = 0;
        if (!const_of(in[1], scope)) fail("OpControlBarrier with a non-constant execution scope");
        if (scope == uint32_t(spv::Scope::Subgroup) || scope == uint32_t(spv::Scope::Invocation))
            return true;  // subgroups are one invocation (subgroupSize 1): nothing to wait for
        if (stage_ != Stage::Compute || scope != uint32_t(spv::Scope::Workgroup))
            fail(std::string("unsupported OpControlBarrier with execution scope ") + std::to_string(scope) + " in a " +
                 stage_name(stage_) + " shader");
        emit(SOp::Barrier, kNoReg);
        p_.has_barrier = true;
        iface_.uses_barriers = true;
        return true;
    }
    AtomicOp kind{};
    if (!atomic_kind(in.op, kind)) return false;
    // Any stage: buffer atomics take effect under side_effect_mask() (fragment: live, covered lanes only, so
    // helper lanes and discarded fragments change nothing and get 0), as stores do.
    const bool store = in.op == spv::Op::OpAtomicStore;
    const uint32_t ptr_id = store ? in[1] : in[3];
    const Value& pv = val(ptr_id);
    const bool phys = pv.type != 0 && is_phys_pointer(pv.type);
    if (pv.ptr < 0 && !phys) fail(opname(in.op) + " on a non-pointer");
    const Pointer p = phys ? phys_pointer(ptr_id) : pointers_[size_t(pv.ptr)];
    if (std::string why = atomic_type_error(in.op, kind, type(p.type), p.space); !why.empty()) fail(why);
    const bool is64 = type(p.type).wide;  // 64-bit integers: register pairs (value, comparator, result)
    uint32_t value = zero_;
    switch (in.op) {
        case spv::Op::OpAtomicStore:
            value = reg(in[4]);
            break;
        case spv::Op::OpAtomicIIncrement:
            value = is64 ? konst64(1) : konst(1);
            break;
        case spv::Op::OpAtomicIDecrement:
            value = is64 ? konst64(~uint64_t(0)) : konst(~0u);
            break;
        case spv::Op::OpAtomicISub:
            value = is64 ? wide(WideOp::INeg, kNoReg, reg(in[6])) : emit1(SOp::INeg, reg(in[6]));
            break;
        case spv::Op::OpAtomicLoad:
            break;
        case spv::Op::OpAtomicCompareExchange:
            value = reg(in[7]);
            break;
        default:
            value = reg(in[6]);
            break;
    }
    const uint32_t comparator = in.op == spv::Op::OpAtomicCompareExchange ? reg(in[8]) : kNoReg;
    const uint32_t dyn = p.dyn == kNoReg ? zero_ : p.dyn;
    iface_.uses_atomics = true;
    // Inactive lanes get an element / word index of kNoReg: the kernel skips them (their result is 0).
    const uint16_t pad = uint16_t(uint16_t(kind) | (is64 ? kAtomicWide : 0));
    auto gen = [&](uint32_t d) {
        if (comparator != kNoReg) emit(SOp::Mov, d, comparator);
        if (comparator != kNoReg && is64) emit(SOp::Mov, d + 1, comparator + 1);
        if (p.space == Space::Phys) {  // lanes outside the side-effect mask do nothing and get 0
            iface_.writes_device_addresses = true;
            Inst& a = emit(SOp::AtomicPtr, d, p.base, p.base + 1, value, 0, p.offset);
            a.n = side_effect_mask();
            a.pad = pad;
            return;
        }
        if (p.space == Space::Texel) {  // the handle is kNoReg in lanes without effect: the kernel skips them
            image_written_ = true;
            const uint32_t handle = emit1(SOp::Select, p.base, konst(kNoReg), side_effect_mask());
            emit(SOp::AtomicImage, d, handle, p.dyn, value, p.offset).pad = uint16_t(kind);
            return;
        }
        if (p.space == Space::Shared) {
            const uint32_t idx = emit1(SOp::Select, dyn, konst(kNoReg), cur_mask_);
            Inst& a = emit(SOp::AtomicShared, d, idx, kNoReg, value, p.base + p.offset);
            a.n = p.limit;
            a.pad = pad;
            return;
        }
        if (p.space != Space::Buffer || p.base == 0 || !p.writable)
            fail("unsupported " + opname(in.op) + " outside a storage buffer, a storage image or Workgroup memory");
        buffer_written_ = true;
        const uint32_t elem = p.elem == kNoReg ? konst(p.elem_const) : p.elem;
        const uint32_t e = emit1(SOp::Select, elem, konst(kNoReg), side_effect_mask());
        Inst& a = emit(SOp::AtomicBuf, d, e, dyn, value, p.base, p.offset);
        a.n = p.limit;
        a.pad = pad;
    };
    const uint32_t words = is64 ? 2 : 1;
    if (store) {
        gen(alloc(words));
        return true;
    }
    // the result depends on other lanes' atomics: in a loop, lanes that left it keep what they got
    keep_active(def(in), words, gen);
    return true;
}

}  // namespace tilevk::shader
