// Memory: access chains into local memory and buffer layouts (std140/std430/scalar as decorated), loads and
// stores, and the memory instructions.
#include <algorithm>

#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

uint32_t Translator::enter_member(Pointer& p, uint32_t struct_type, uint32_t m) {
    auto it = member_deco_.find({struct_type, m});
    if (it == member_deco_.end() || it->second.offset < 0) fail("buffer struct member without Offset");
    p.matrix_stride = uint32_t(it->second.matrix_stride);
    p.row_major = it->second.row_major;
    p.vec_stride = 0;
    return uint32_t(it->second.offset);
}

uint32_t Translator::buffer_array_stride(uint32_t array_type) {
    const uint32_t stride = uint32_t(deco_[array_type].array_stride);
    if (stride == 0) fail("buffer array without ArrayStride");
    return stride;
}

uint32_t Translator::vector_stride(const Pointer& p, uint32_t vector_type) const {
    return p.vec_stride ? p.vec_stride : scalar_bytes(type(vector_type).elem);
}

// Column-major: a column is a vector at MatrixStride steps; row-major: a row is (Vulkan's RowMajor decoration).
Translator::MatrixSteps Translator::matrix_steps(const Pointer& p, uint32_t matrix_type) const {
    const uint32_t size = scalar_bytes(type(type(matrix_type).elem).elem);
    return p.row_major ? MatrixSteps{size, p.matrix_stride} : MatrixSteps{p.matrix_stride, size};
}

Pointer Translator::access_chain(const Pointer& base, const uint32_t* idx, size_t n) {
    Pointer p = base;
    for (size_t i = 0; i < n; ++i) {
        uint32_t id = idx[i];
        uint32_t cv = 0;
        bool is_const = const_of(id, cv);
        if (!is_const && val(id).reg == kNoReg) fail("invalid access chain index");
        if (p.in_array) {  // descriptor array element
            if (is_const)
                p.elem_const = cv;
            else
                p.elem = reg(id);
            p.in_array = false;
            p.type = type(p.type).elem;
            continue;
        }
        const Type& t = type(p.type);
        auto add_dyn = [&](uint32_t stride) {
            uint32_t scaled = stride == 1 ? reg(id) : emit1(SOp::IMul, reg(id), konst(stride));
            p.dyn = p.dyn == kNoReg ? scaled : emit1(SOp::IAdd, p.dyn, scaled);
        };
        if (p.space == Space::Local || p.space == Space::Shared) {
            if (t.kind == Type::Struct) {
                if (!is_const || cv >= t.members.size()) fail("invalid struct index");
                for (uint32_t m = 0; m < cv; ++m) p.offset += type(t.members[m]).flat;
                p.type = t.members[cv];
            } else if (t.kind == Type::Array || t.kind == Type::Vector || t.kind == Type::Matrix) {
                uint32_t stride = type(t.elem).flat;
                if (is_const)
                    p.offset += std::min(cv, t.count - 1) * stride;
                else
                    add_dyn(stride);
                p.type = t.elem;
            } else {
                fail("access chain into a non-composite");
            }
            continue;
        }
        // Buffer layout (std140/std430 as decorated).
        if (t.kind == Type::Struct) {
            if (!is_const || cv >= t.members.size()) fail("invalid struct index");
            p.offset += enter_member(p, p.type, cv);
            p.type = t.members[cv];
        } else if (t.kind == Type::Array || t.kind == Type::RuntimeArray) {
            const uint32_t stride = buffer_array_stride(p.type);
            // a huge constant index stays in bounds of uint32 arithmetic; the executor rejects it
            if (is_const)
                p.offset = uint32_t(std::min<uint64_t>(p.offset + uint64_t(cv) * stride, 0x7fffffffu));
            else
                add_dyn(stride);
            p.type = t.elem;
        } else if (t.kind == Type::Matrix) {
            const MatrixSteps steps = matrix_steps(p, p.type);
            if (is_const)
                p.offset += std::min(cv, t.count) * steps.column;
            else
                add_dyn(steps.column);
            p.vec_stride = p.row_major ? steps.row : 0;
            p.type = t.elem;
        } else if (t.kind == Type::Vector) {
            const uint32_t stride = vector_stride(p, p.type);
            if (is_const)
                p.offset += std::min(cv, t.count) * stride;
            else
                add_dyn(stride);
            p.type = t.elem;
        } else {
            fail("access chain into a non-composite");
        }
    }
    return p;
}

template <typename Scalar>
void Translator::walk_buffer_layout(const Pointer& p, uint32_t ty, uint32_t reg, uint32_t off, const Scalar& scalar) {
    const Type& t = type(ty);
    switch (t.kind) {
        case Type::Bool:
        case Type::Int:
        case Type::Float:
        case Type::Pointer:  // (a PhysicalStorageBuffer pointer or a 64-bit integer: two words, low first)
            scalar(reg, off, ty);
            if (t.flat == 2) scalar(reg + 1, off + 4, ty);
            break;
        case Type::Vector: {  // (64-bit components: two registers and two words each)
            const uint32_t words = type(t.elem).flat, stride = vector_stride(p, ty);
            for (uint32_t i = 0; i < t.count; ++i)
                for (uint32_t w = 0; w < words; ++w) scalar(reg + i * words + w, off + i * stride + w * 4, t.elem);
            break;
        }
        case Type::Matrix: {
            const Type& col = type(t.elem);
            const uint32_t words = type(col.elem).flat;
            const MatrixSteps steps = matrix_steps(p, ty);
            for (uint32_t c = 0; c < t.count; ++c)
                for (uint32_t r = 0; r < col.count; ++r) {
                    const uint32_t o = c * steps.column + r * steps.row;
                    for (uint32_t w = 0; w < words; ++w)
                        scalar(reg + (c * col.count + r) * words + w, off + o + w * 4, col.elem);
                }
            break;
        }
        case Type::Array: {
            const uint32_t stride = buffer_array_stride(ty);
            Pointer q = p;
            q.vec_stride = 0;
            for (uint32_t i = 0; i < t.count; ++i)
                walk_buffer_layout(q, t.elem, reg + i * type(t.elem).flat, off + i * stride, scalar);
            break;
        }
        case Type::Struct: {
            uint32_t at = 0;
            for (uint32_t m = 0; m < t.members.size(); ++m) {
                Pointer q = p;
                const uint32_t member_off = enter_member(q, ty, m);
                walk_buffer_layout(q, t.members[m], reg + at, off + member_off, scalar);
                at += type(t.members[m]).flat;
            }
            break;
        }
        default:
            fail("unsupported buffer load or store type");
    }
}

// Marks the clip / cull distance outputs as written when a local access of `words` words at `off` may reach them
// (a dynamic offset may land anywhere in the variable). Loads count too, as they always have: conservative.
void Translator::touch_distance_words(const Pointer& p, uint32_t off, uint32_t words) {
    const uint32_t first = p.dyn == kNoReg ? p.base + p.offset + off : p.base;
    const uint32_t end = p.dyn == kNoReg ? first + words : p.limit;
    for (int k = 0; k < 2; ++k) distance_written_[k] |= first < distance_words_[k][1] && distance_words_[k][0] < end;
}

void Translator::load(const Pointer& p, uint32_t ty, uint32_t dst, uint32_t off) {
    if (p.space == Space::Phys) {  // (OpCopyMemory; loads through such pointers come from op_pointer)
        Pointer q = p;
        q.offset += off;
        return load_phys(q, ty, dst);
    }
    const Type& t = type(ty);
    uint32_t dyn = p.dyn == kNoReg ? zero_ : p.dyn;
    if (p.space == Space::Shared) {
        for (uint32_t i = 0; i < t.flat; ++i)
            emit(SOp::LoadShared, dst + i, dyn, kNoReg, kNoReg, p.base + p.offset + off + i).n = p.limit;
        return;
    }
    if (p.space == Space::Local) {
        touch_distance_words(p, off, t.flat);
        for (uint32_t i = 0; i < t.flat; ++i) {
            uint32_t w = p.base + p.offset + off + i;
            if (p.dyn == kNoReg && w < p.limit)
                emit(SOp::LoadLocalFixed, dst + i, kNoReg, kNoReg, kNoReg, w);
            else
                emit(SOp::LoadLocal, dst + i, dyn, kNoReg, kNoReg, w).n = p.limit;
        }
        return;
    }
    if (p.space == Space::Handle) {
        if (p.in_array) fail("load of a whole descriptor array");
        uint32_t shift = t.kind == Type::Sampler ? 16 : 0;
        bool both = t.kind == Type::SampledImage;
        if (p.elem == kNoReg) {
            uint32_t s = std::min(p.base + p.elem_const, p.base + p.limit - 1);
            emit(SOp::Mov, dst, konst(both ? (s | s << 16) : s << shift));
        } else {
            // clamp the element to the array (robust indexing)
            uint32_t e = emit1(SOp::UMin, p.elem, konst(p.limit - 1));
            uint32_t s = emit1(SOp::IAdd, e, konst(p.base));
            if (both)
                emit(SOp::Or, dst, s, emit1(SOp::Shl, s, konst(16)));
            else if (shift)
                emit(SOp::Shl, dst, s, konst(16));
            else
                emit(SOp::Mov, dst, s);
        }
        return;
    }
    uint32_t elem = p.elem == kNoReg ? konst(p.elem_const) : p.elem;
    auto scalar = [&](uint32_t d, uint32_t byte_off, uint32_t sty) {
        if (const uint32_t bytes = scalar_bytes(sty); bytes < 4) {  // 8- and 16-bit values (translate_narrow.cpp)
            emit(SOp::LoadBufN, d, elem, dyn, kNoReg, p.base, p.offset + byte_off).n = p.limit;
            p_.code.back().pad = uint16_t(bytes);
            return;
        }
        if (p.dyn == kNoReg && p.elem == kNoReg) {
            if (p.elem_const < p.limit)
                emit(SOp::LoadBufUniform, d, kNoReg, kNoReg, kNoReg, p.base + p.elem_const, p.offset + byte_off);
            else
                emit(SOp::Mov, d, zero_);
        } else {
            emit(SOp::LoadBuf, d, elem, dyn, kNoReg, p.base, p.offset + byte_off).n = p.limit;
        }
        if (type(sty).kind == Type::Bool) emit(SOp::INe, d, d, zero_);
    };
    walk_buffer_layout(p, ty, dst, off, scalar);
}

void Translator::store(const Pointer& p, uint32_t ty, uint32_t src, uint32_t off) {
    if (p.space == Space::Phys) {
        Pointer q = p;
        q.offset += off;
        return store_phys(q, ty, src);
    }
    const Type& t = type(ty);
    uint32_t dyn = p.dyn == kNoReg ? zero_ : p.dyn;
    if (p.space == Space::Shared) {
        for (uint32_t i = 0; i < t.flat; ++i)
            emit(SOp::StoreShared, kNoReg, dyn, src + i, cur_mask_, p.base + p.offset + off + i).n = p.limit;
        return;
    }
    if (p.space == Space::Local) {
        touch_distance_words(p, off, t.flat);
        for (uint32_t i = 0; i < t.flat; ++i) {
            uint32_t w = p.base + p.offset + off + i;
            if (p.dyn == kNoReg && w < p.limit)
                emit(SOp::StoreLocalFixed, kNoReg, kNoReg, src + i, cur_mask_, w);
            else
                emit(SOp::StoreLocal, kNoReg, dyn, src + i, cur_mask_, w).n = p.limit;
        }
        return;
    }
    if (p.space == Space::Handle) fail("store to an image or sampler variable");
    if (!p.writable) fail("store to a read-only buffer");
    buffer_written_ = true;
    uint32_t mask = side_effect_mask();
    uint32_t elem = p.elem == kNoReg ? konst(p.elem_const) : p.elem;
    auto scalar = [&](uint32_t s, uint32_t byte_off, uint32_t sty) {
        uint32_t v = s;
        if (type(sty).kind == Type::Bool) v = emit1(SOp::And, s, konst(1));
        const uint32_t bytes = scalar_bytes(sty);
        emit(bytes < 4 ? SOp::StoreBufN : SOp::StoreBuf, mask, elem, dyn, v, p.base, p.offset + byte_off).n = p.limit;
        if (bytes < 4) p_.code.back().pad = uint16_t(bytes);
    };
    walk_buffer_layout(p, ty, src, off, scalar);
}

// Through a PhysicalStorageBuffer pointer (translate_pointer.cpp), the buffer layout as above.
void Translator::load_phys(const Pointer& p, uint32_t ty, uint32_t dst) {
    // only the block's lanes: other lanes' pointers may be anything (the registry would catch them; this keeps
    // their results 0 and deterministic)
    walk_buffer_layout(p, ty, dst, p.offset, [&](uint32_t d, uint32_t byte_off, uint32_t sty) {
        if (scalar_bytes(sty) < 4) fail("8- or 16-bit load through a PhysicalStorageBuffer pointer is not supported");
        emit(SOp::LoadPtr, d, p.base, p.base + 1, cur_mask_, 0, byte_off);
        if (type(sty).kind == Type::Bool) emit(SOp::INe, d, d, zero_);
    });
}

void Translator::store_phys(const Pointer& p, uint32_t ty, uint32_t src) {
    iface_.writes_device_addresses = true;
    const uint32_t mask = side_effect_mask();
    walk_buffer_layout(p, ty, src, p.offset, [&](uint32_t s, uint32_t byte_off, uint32_t sty) {
        if (scalar_bytes(sty) < 4) fail("8- or 16-bit store through a PhysicalStorageBuffer pointer is not supported");
        const uint32_t v = type(sty).kind == Type::Bool ? emit1(SOp::And, s, konst(1)) : s;
        emit(SOp::StorePtr, mask, p.base, p.base + 1, v, 0, byte_off);
    });
}

uint32_t Translator::side_effect_mask() {
    if (store_mask_ == kNoReg)
        store_mask_ = stage_ == Stage::Fragment ? emit1(SOp::And, cur_mask_, p_.reg_live) : cur_mask_;
    return store_mask_;
}

// Variables, access chains, loads, stores, array lengths, copies.
bool Translator::op_memory(const Instr& in) {
    switch (in.op) {
        // memory
        case spv::Op::OpUndef: {  // undefined value: zeros (deterministic)
            uint32_t d = def(in);
            for (uint32_t i = 0; i < std::max(1u, type(in[1]).flat); ++i) emit(SOp::Mov, d + i, zero_);
            return true;
        }
        case spv::Op::OpVariable: {  // function variable (memory assigned in translate.cpp); initializer
            const Value& v = val(in[2]);
            if (in.n > 4) store(pointers_[size_t(v.ptr)], pointers_[size_t(v.ptr)].type, reg(in[4]), 0);
            return true;
        }
        case spv::Op::OpAccessChain:
        case spv::Op::OpInBoundsAccessChain: {
            const Value& b = val(in[3]);
            if (b.ptr < 0) fail("access chain base is not a pointer");
            Pointer p = access_chain(pointers_[size_t(b.ptr)], in.w + 4, in.n - 4);
            pointers_.push_back(p);
            vals_[in[2]] = Value{kNoReg, in[1], int(pointers_.size() - 1)};
            return true;
        }
        case spv::Op::OpLoad: {
            const Value& pv = val(in[3]);
            if (pv.ptr < 0) fail("load from a non-pointer");
            Pointer p = pointers_[size_t(pv.ptr)];
            if (p.space == Space::Buffer && p.base == 0) {
                iface_.push_constant_size = std::max(iface_.push_constant_size, p.offset + 4 * type(in[1]).flat);
            }
            uint32_t d = def(in);
            // memory other lanes may change while this one waits (in a loop it has left)
            if (p.space == Space::Buffer || p.space == Space::Shared)
                keep_active(d, std::max(1u, type(in[1]).flat), [&](uint32_t t) { load(p, in[1], t, 0); });
            else
                load(p, in[1], d, 0);
            return true;
        }
        case spv::Op::OpStore: {
            const Value& pv = val(in[1]);
            if (pv.ptr < 0) fail("store to a non-pointer");
            Pointer p = pointers_[size_t(pv.ptr)];
            store(p, p.type, reg(in[2]), 0);
            return true;
        }
        case spv::Op::OpArrayLength: {
            // length of the runtime array that ends a storage buffer block: (size - member offset) / stride
            const Value& sv = val(in[3]);
            if (sv.ptr < 0) fail("OpArrayLength of a non-pointer");
            const Pointer& p = pointers_[size_t(sv.ptr)];
            const Type& st = type(p.type);
            uint32_t m = in[4];
            if (p.space != Space::Buffer || p.in_array || st.kind != Type::Struct || m >= st.members.size() ||
                type(st.members[m]).kind != Type::RuntimeArray)
                fail("OpArrayLength needs a buffer block ending in a runtime array");
            auto it = member_deco_.find({p.type, m});
            uint32_t stride = uint32_t(deco_[st.members[m]].array_stride);
            if (it == member_deco_.end() || it->second.offset < 0 || stride == 0)
                fail("runtime array without Offset/ArrayStride");
            uint32_t elem = p.elem == kNoReg ? konst(p.elem_const) : p.elem;
            emit(SOp::BufArrayLength, def(in), elem, konst(stride), kNoReg, p.base,
                 p.offset + uint32_t(it->second.offset))
                .n = p.limit;
            return true;
        }
        case spv::Op::OpCopyMemory: {
            const Value& dv = val(in[1]);
            const Value& sv = val(in[2]);
            if (dv.ptr < 0 || sv.ptr < 0) fail("OpCopyMemory on non-pointers");
            Pointer dp = pointers_[size_t(dv.ptr)], sp = pointers_[size_t(sv.ptr)];
            uint32_t tmp = alloc(std::max(1u, type(sp.type).flat));
            load(sp, sp.type, tmp, 0);
            store(dp, dp.type, tmp, 0);
            return true;
        }
        default:
            return false;
    }
}

}  // namespace tilevk::shader
