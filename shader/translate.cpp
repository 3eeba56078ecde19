// SPIR-V module -> SIMD program: the translator's phases (declarations, blocks, emission), its value and type
// helpers, and the entry point translate(). The phases live in translate_module.cpp (types, constants,
// decorations), translate_interface.cpp (variables), translate_control.cpp (control flow) and translate_ops.cpp
// with its families (one instruction at a time).
#include <algorithm>
#include <bit>
#include <cstring>
#include <functional>

#include <spirv/unified1/GLSL.std.450.h>

#include "shader/spirv_names.h"
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

uint32_t Translator::konst(uint32_t v) {
    auto it = const_regs_.find(v);
    if (it != const_regs_.end()) return it->second;
    uint32_t r = alloc();
    set_const(r, v);
    const_regs_[v] = r;
    return r;
}
uint32_t Translator::konstf(float f) {
    return konst(std::bit_cast<uint32_t>(f));
}

const Type& Translator::type(uint32_t id) const {
    if (id >= bound_ || !is_type_[id]) fail("invalid type id " + std::to_string(id));
    return types_[id];
}
Value& Translator::val(uint32_t id) {
    if (id >= bound_ || (vals_[id].reg == kNoReg && vals_[id].ptr < 0))
        fail("use of unsupported or undefined value %" + std::to_string(id));
    return vals_[id];
}
uint32_t Translator::component_type(uint32_t t) const {
    while (types_[t].kind == Type::Vector || types_[t].kind == Type::Matrix) t = types_[t].elem;
    return t;
}

// Flat register offset of a composite index path (OpCompositeExtract/Insert literals).
uint32_t Translator::flat_index(uint32_t t, const uint32_t* idx, size_t n, uint32_t* out_type) const {
    uint32_t off = 0;
    for (size_t i = 0; i < n; ++i) {
        const Type& ty = type(t);
        uint32_t k = idx[i];
        switch (ty.kind) {
            case Type::Vector:
            case Type::Matrix:
            case Type::Array:
                if (k >= ty.count) fail("composite index out of range");
                off += k * type(ty.elem).flat;
                t = ty.elem;
                break;
            case Type::Struct:
                if (k >= ty.members.size()) fail("composite index out of range");
                for (uint32_t m = 0; m < k; ++m) off += type(ty.members[m]).flat;
                t = ty.members[k];
                break;
            default:
                fail("composite index into a non-composite");
        }
    }
    *out_type = t;
    return off;
}

void Translator::run(const std::vector<uint32_t>& words, std::string_view entry_name) {
    if (words.size() < 5) fail("invalid SPIR-V: no header");
    bound_ = words[3];
    if (bound_ > (1u << 22)) fail("SPIR-V id bound too large");
    types_.resize(bound_);
    is_type_.assign(bound_, 0);
    deco_.resize(bound_);
    vals_.resize(bound_);
    iface_.stage = stage_;
    iface_.entry = std::string(entry_name);
    p_.stage = stage_;
    for (size_t i = 5; i < words.size();) {
        uint32_t n = words[i] >> 16;
        if (n == 0 || i + n > words.size()) fail("invalid SPIR-V: truncated instruction");
        ins_.push_back(Instr{spv::Op(words[i] & 0xffff), &words[i], n});
        i += n;
    }

    // Fixed registers: constant zero, the entry mask and the live mask (filled by the executor).
    zero_ = konst(0);
    p_.reg_entry_mask = alloc();
    p_.reg_live = alloc();

    find_entry_point(entry_name);
    // Module-level declarations, up to the first function.
    size_t fn_begin = ins_.size();
    for (size_t k = 0; k < ins_.size(); ++k) {
        if (ins_[k].op == spv::Op::OpFunction) {
            fn_begin = k;
            break;
        }
        declare(ins_[k]);
    }
    p_.num_slots = next_slot_;
    if (stage_ == Stage::Compute) resolve_local_size();
    if (local_words_ > (1u << 20)) fail("too much variable memory");

    collect_blocks(fn_begin);
    p_.local_words = local_words_;
    order_blocks();
    init_masks_and_phis();
    // Module-scope initializers run first, for every lane.
    cur_mask_ = konst(~0u);
    for (auto& [ptr, init] : private_inits_) store(pointers_[ptr], pointers_[ptr].type, reg(init), 0);
    emit_blocks();
    finish_interface();
}

void Translator::find_entry_point(std::string_view entry_name) {
    spv::ExecutionModel want = stage_ == Stage::Vertex     ? spv::ExecutionModel::Vertex
                               : stage_ == Stage::Fragment ? spv::ExecutionModel::Fragment
                                                           : spv::ExecutionModel::GLCompute;
    for (const Instr& in : ins_) {
        if (in.op == spv::Op::OpEntryPoint && spv::ExecutionModel(in[1]) == want &&
            literal_string(in, 3) == entry_name) {
            entry_fn_ = in[2];
            size_t name_words = (literal_string(in, 3).size() + 4) / 4;
            for (size_t k = 3 + name_words; k < in.n; ++k) entry_iface_.push_back(in[k]);
        }
    }
    if (!entry_fn_)
        fail("no " + std::string(stage_name(stage_)) + " entry point named '" + std::string(entry_name) + "'");
}

// Reflection in a stable order; which storage buffers the program writes.
void Translator::finish_interface() {
    std::sort(iface_.inputs.begin(), iface_.inputs.end(), [](const IoVariable& a, const IoVariable& b) {
        return a.location * 4 + a.component < b.location * 4 + b.component;
    });
    std::sort(iface_.outputs.begin(), iface_.outputs.end(), [](const IoVariable& a, const IoVariable& b) {
        return a.location * 4 + a.component < b.location * 4 + b.component;
    });
    for (auto& d : iface_.descriptors)
        if (d.kind == DescriptorKind::StorageBuffer)
            d.written = buffer_written_;
        else if (d.kind == DescriptorKind::StorageImage)
            d.written = image_written_;
    if (!distance_written_[0]) iface_.clip_distances = 0;
    if (!distance_written_[1]) iface_.cull_distances = 0;
    p_.shared_words = shared_words_;
    iface_.shared_memory_bytes = shared_words_ * 4;
    std::sort(iface_.descriptors.begin(), iface_.descriptors.end(), [](const DescriptorUse& a, const DescriptorUse& b) {
        return a.set != b.set ? a.set < b.set : a.binding < b.binding;
    });
}

std::string translate(const std::vector<uint32_t>& spirv, Stage stage, std::string_view entry, ProgramImpl& out,
                      ProgramInterface& iface) {
    Translator t(stage, out, iface);
    try {
        t.run(spirv, entry);
    } catch (const TranslateError& e) {
        return e.message;
    } catch (const std::exception& e) {
        return std::string("translation failed: ") + e.what();
    }
    return {};
}

}  // namespace tilevk::shader
