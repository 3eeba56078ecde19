// Which fragment programs tilevk can shade like llvmpipe's linear path: plain copies of one vec4 float input to
// colour output 0, decided on tilevk's own program (ir.h) by tracking where every register and local word
// comes from through the straight-line code the translator emits for such a shader.
#include <bit>
#include <cstddef>
#include <vector>

#include "shader/ir.h"
#include "shader/program.h"

namespace tilevk::shader {

Program::LinearShader Program::analyze_linear_shader() const {
    LinearShader out;
    const ProgramImpl& p = *impl_;
    if (p.stage != Stage::Fragment) return out;
    // Provenance of every register and local word: kUnknown, an input component (location*4 + component), or a
    // constant (kConstant | bits).
    constexpr int64_t kUnknown = -1;
    constexpr int64_t kConstant = int64_t{1} << 40;
    std::vector<int64_t> word(p.local_words, kUnknown), reg(p.num_regs, kUnknown);
    for (size_t i = 0; i + 1 < p.const_regs.size(); i += 2)
        if (p.const_regs[i] < reg.size()) reg[p.const_regs[i]] = kConstant | p.const_regs[i + 1];
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
                if (in.d >= reg.size() || in.a >= reg.size()) return out;
                reg[in.d] = reg[in.a];
                break;
            case Op::LoadLocalFixed:
                if (in.d >= reg.size() || in.imm >= word.size()) return out;
                reg[in.d] = word[in.imm];
                break;
            case Op::StoreLocalFixed:
                // under the live mask: every lane that reaches the output writes it
                if (in.b >= reg.size() || in.imm >= word.size()) return out;
                word[in.imm] = reg[in.b];
                break;
            case Op::JumpIfNone:
            case Op::JumpIfAny:
            case Op::Jump:
                if (in.imm <= last_store) return out;
                break;
            case Op::Halt:
                break;
            default:
                return out;  // arithmetic, memory, images, discard, ...: not the class
        }
    }
    uint32_t seen = 0;
    for (const IoCopy& c : p.io_out) {
        if (c.slot != IoSlot::Output || c.index >= 4 || c.word >= word.size()) return out;  // one vec4 output only
        const int64_t src = word[c.word];
        if (src == kUnknown) return out;
        if (src & kConstant) {
            const float v = std::bit_cast<float>(static_cast<uint32_t>(src));
            if (!(v >= 0.0f && v <= 1.0f)) return out;  // lavapipe: load_const outside [0, 1] is not linear
            out.source[c.index] = -1;
            out.constant[c.index] = v;
        } else {
            const int loc = static_cast<int>(src / 4);
            if (out.location >= 0 && loc != out.location) return out;  // one input only (tilevk's limit)
            // Swizzles are refused: lavapipe's linear variant renders v.bgra as v.rgba (found by experiment), a
            // rule tilevk does not know for other swizzles (shader/README.md).
            if (src % 4 != c.index) return out;
            out.location = loc;
            out.source[c.index] = static_cast<int8_t>(src % 4);
            out.usage |= uint8_t(1u << (src % 4));
        }
        seen |= 1u << c.index;
    }
    if (seen != 0xF) return out;
    for (const IoVariable& v : interface_.inputs)
        if (static_cast<int>(v.location) == out.location && v.type != ScalarType::Float) return out;
    out.ok = true;
    return out;
}

int Program::linear_copy_input() const {
    const LinearShader l = linear_shader();
    if (!l.ok || l.location < 0) return -1;
    for (int c = 0; c < 4; ++c)
        if (l.source[c] != c) return -1;
    return l.location;
}

}  // namespace tilevk::shader
