// Which fragment programs tilevk can shade like llvmpipe's linear path: plain copies of one vec4 float input to
// colour output 0, decided on tilevk's own program (ir.h) by tracking where every register and local word
// comes from through the straight-line code the translator emits for such a shader.
#include <cstddef>
#include <vector>

#include "shader/ir.h"
#include "shader/program.h"

namespace tilevk::shader {

int Program::linear_copy_input() const {
    const ProgramImpl& p = *impl_;
    if (p.stage != Stage::Fragment) return -1;
    constexpr int64_t kUnknown = -1;
    // Provenance: the input component (location*4 + component) a value is an unmodified copy of, or kUnknown.
    std::vector<int64_t> word(p.local_words, kUnknown), reg(p.num_regs, kUnknown);
    for (const IoCopy& c : p.io_in)
        if (c.slot == IoSlot::Input && c.word < word.size()) word[c.word] = c.index;
    // The last store; jumps may only skip to after it (the translator's "no live lane" early exit).
    size_t last_store = 0;
    for (size_t i = 0; i < p.code.size(); ++i)
        if (p.code[i].op == Op::StoreLocalFixed || p.code[i].op == Op::StoreLocal) last_store = i;
    for (size_t i = 0; i < p.code.size(); ++i) {
        const Inst& in = p.code[i];
        switch (in.op) {
            case Op::Mov:
                if (in.d >= reg.size() || in.a >= reg.size()) return -1;
                reg[in.d] = reg[in.a];
                break;
            case Op::LoadLocalFixed:
                if (in.d >= reg.size() || in.imm >= word.size()) return -1;
                reg[in.d] = word[in.imm];
                break;
            case Op::StoreLocalFixed:
                // under the live mask: every lane that reaches the output writes it
                if (in.b >= reg.size() || in.imm >= word.size()) return -1;
                word[in.imm] = reg[in.b];
                break;
            case Op::JumpIfNone:
            case Op::JumpIfAny:
            case Op::Jump:
                if (in.imm <= last_store) return -1;
                break;
            case Op::Halt:
                break;
            default:
                return -1;  // arithmetic, memory, images, discard, ...: not the copy class
        }
    }
    int location = -1;
    uint32_t seen = 0;
    for (const IoCopy& c : p.io_out) {
        if (c.slot != IoSlot::Output || c.index >= 4 || c.word >= word.size()) return -1;  // one vec4 output only
        const int64_t src = word[c.word];
        if (src < 0 || src % 4 != c.index) return -1;  // component c must be input component c
        const int loc = static_cast<int>(src / 4);
        if (location >= 0 && loc != location) return -1;
        location = loc;
        seen |= 1u << c.index;
    }
    if (seen != 0xF) return -1;
    for (const IoVariable& v : interface_.inputs)
        if (static_cast<int>(v.location) == location && v.type != ScalarType::Float) return -1;
    return location;
}

}  // namespace tilevk::shader
