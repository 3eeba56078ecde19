// PhysicalStorageBuffer pointers (SPV_KHR_physical_storage_buffer, GL_EXT_buffer_reference): the pointer is a value
// of two registers, its 64-bit address as low and high word (the address is a host address, icd/buffer.cpp
// vkGetBufferDeviceAddress). Access chains add their byte offset to it; loads, stores and atomics through it become
// LoadPtr / StorePtr / AtomicPtr (exec_pointer.h), which look every word up in the device-address registry. Those ops
// come after Halt, so jit::compile leaves such programs to the interpreter, by name.
//
// 64-bit integers exist for the arithmetic glslang writes around such pointers (buffer_reference2 indexing:
// OpConvertPtrToU, OpUConvert / OpSConvert from 32 bits, OpIMul, OpIAdd, OpConvertUToPtr) and nothing more:
// scalar OpIAdd, OpISub, OpIMul, OpIEqual, OpINotEqual, the conversions to and from 32 bits and to and from
// pointers, copies, selects and bit casts. Any other instruction on a 64-bit integer is refused by name
// (shaderInt64 is not reported).
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

bool Translator::is_phys_pointer(uint32_t type_id) const {
    const Type& t = type(type_id);
    return t.kind == Type::Pointer && t.storage == spv::StorageClass::PhysicalStorageBuffer;
}

Pointer Translator::phys_pointer(uint32_t id) {
    const Value& v = val(id);
    if (v.reg == kNoReg || !is_phys_pointer(v.type)) fail("invalid PhysicalStorageBuffer pointer operand");
    const uint32_t pointee = type(v.type).elem;
    // an access chain's result keeps the layout it walked (matrix stride, row major) while its registers are these
    if (v.ptr >= 0) {
        const Pointer& known = pointers_[size_t(v.ptr)];
        if (known.space == Space::Phys && known.base == v.reg && known.type == pointee) return known;
    }
    Pointer p;
    p.space = Space::Phys;
    p.type = pointee;
    p.base = v.reg;
    p.writable = true;
    return p;
}

uint32_t Translator::address_add(uint32_t addr, uint32_t off) {
    const uint32_t d = alloc(2);
    emit(SOp::IAdd, d, addr, off);
    const uint32_t carry = emit1(SOp::ULt, d, addr);         // ~0 where the low word wrapped
    const uint32_t sign = emit1(SOp::ShrA, off, konst(31));  // the offset is signed (SPIR-V indices are)
    emit(SOp::ISub, d + 1, emit1(SOp::IAdd, addr + 1, sign), carry);
    return d;
}

// OpAccessChain (first_index 4, elem kNoReg) or OpPtrAccessChain (elem = its Element operand, first_index 5) on a
// PhysicalStorageBuffer pointer: the result is a new address, base + the chain's byte offset.
void Translator::phys_access_chain(const Instr& in, uint32_t base_id, uint32_t elem, size_t first_index) {
    Pointer p = phys_pointer(base_id);
    if (elem != kNoReg) {  // OpPtrAccessChain: whole pointees, by the pointer type's ArrayStride
        const int stride = deco_[val(base_id).type].array_stride;
        uint32_t cv = 0;
        const bool zero = const_of(elem, cv) && cv == 0 && !type(val(elem).type).wide;
        if (!zero) {
            if (stride <= 0) fail("OpPtrAccessChain on a pointer type without ArrayStride");
            p.dyn = emit1(SOp::IMul, reg(elem), konst(uint32_t(stride)));
        }
    }
    p = access_chain(p, in.w + first_index, in.n - first_index);
    uint32_t off = p.offset == 0 ? kNoReg : konst(p.offset);
    if (p.dyn != kNoReg) off = off == kNoReg ? p.dyn : emit1(SOp::IAdd, p.dyn, off);
    p.base = off == kNoReg ? p.base : address_add(p.base, off);
    p.dyn = kNoReg;
    p.offset = 0;
    pointers_.push_back(p);
    vals_[in[2]] = Value{p.base, in[1], int(pointers_.size() - 1)};
}

bool Translator::op_pointer(const Instr& in) {
    switch (in.op) {
        case spv::Op::OpAccessChain:
        case spv::Op::OpInBoundsAccessChain:
            if (!is_phys_pointer(val(in[3]).type)) return false;
            phys_access_chain(in, in[3], kNoReg, 4);
            return true;
        case spv::Op::OpPtrAccessChain:
        case spv::Op::OpInBoundsPtrAccessChain:
            if (!is_phys_pointer(val(in[3]).type))
                fail(opname(in.op) + " is supported on PhysicalStorageBuffer pointers only");
            phys_access_chain(in, in[3], in[4], 5);
            return true;
        case spv::Op::OpLoad: {
            if (!is_phys_pointer(val(in[3]).type)) return false;
            const Pointer p = phys_pointer(in[3]);
            const uint32_t d = def(in);
            // memory other lanes may change while this one waits (in a loop it has left)
            keep_active(d, std::max(1u, type(in[1]).flat), [&](uint32_t t) { load_phys(p, in[1], t); });
            return true;
        }
        case spv::Op::OpStore:
            if (!is_phys_pointer(val(in[1]).type)) return false;
            store_phys(phys_pointer(in[1]), type(val(in[1]).type).elem, reg(in[2]));
            return true;
        case spv::Op::OpConvertUToPtr:
        case spv::Op::OpConvertPtrToU:
            if (flat_of(in[3]) != 2 || type(in[1]).flat != 2)
                fail(opname(in.op) + " needs a 64-bit integer and a PhysicalStorageBuffer pointer");
            if (val(in[3]).is_phi)
                unary(in, SOp::Mov);
            else
                alias(in, reg(in[3]));
            return true;
        default:  // (64-bit integer arithmetic on addresses: translate_wide.cpp)
            return false;
    }
}

}  // namespace tilevk::shader
