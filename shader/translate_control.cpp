// Structured control flow as lane masks.
//
// Blocks are laid out in a structured reverse post-order (a loop's or selection's merge block is visited first, so
// it lands after the construct's body). Every block has a mask register of the lanes that reached it; a branch ORs
// (mask & condition) into its targets' masks and a phi is a masked move on each edge. A block whose mask is empty
// is skipped. A loop's back edge ORs into the header mask and jumps back while any lane is set. Return and kill
// simply send lanes nowhere.
#include <algorithm>

#include "shader/spirv_names.h"
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

// The entry point's blocks (after inlining only the entry point remains) and its function-scope variables.
void Translator::collect_blocks(size_t fn_begin) {
    size_t fb = fn_begin;
    if (fb >= ins_.size() || ins_[fb][2] != entry_fn_) {
        for (; fb < ins_.size(); ++fb)
            if (ins_[fb].op == spv::Op::OpFunction && ins_[fb][2] == entry_fn_) break;
    }
    if (fb >= ins_.size()) fail("entry point function not found");
    for (size_t k = fb + 1; k < ins_.size() && ins_[k].op != spv::Op::OpFunctionEnd; ++k) {
        const Instr& in = ins_[k];
        if (in.op == spv::Op::OpLabel) {
            block_of_[in[1]] = uint32_t(blocks_.size());
            Block nb;
            nb.label = in[1];
            nb.first = nb.end = k + 1;
            blocks_.push_back(nb);
        } else if (in.op == spv::Op::OpVariable) {
            // Function-scope variable: local SoA memory.
            if (blocks_.empty()) fail("variable outside a block");
            const Type& pt = type(in[1]);
            Pointer p;
            p.space = Space::Local;
            p.type = pt.elem;
            p.base = local_words_;
            p.limit = local_words_ + type(pt.elem).flat;
            local_words_ += type(pt.elem).flat;
            if (local_words_ > (1u << 20)) fail("too much variable memory");
            pointers_.push_back(p);
            vals_[in[2]] = Value{kNoReg, in[1], int(pointers_.size() - 1)};
        } else if (in.op == spv::Op::OpExtInst && in.n > 3 && in[3] != glsl_ext_) {
            // Any set but GLSL.std.450 is a NonSemantic.* one (declare() refuses the others): its instructions have
            // no effect, as in lavapipe's spirv_to_nir, and may even follow a block's terminator (DebugNoScope after
            // OpReturn), so they are never part of a block (SPV_KHR_non_semantic_info).
            continue;
        } else if (!blocks_.empty()) {
            Block& b = blocks_.back();
            b.end = k + 1;
            if (in.op == spv::Op::OpSelectionMerge) b.merge = in[1];
            if (in.op == spv::Op::OpLoopMerge) {
                b.merge = in[1];
                b.cont = in[2];
            }
            if (in.op == spv::Op::OpBranch) b.succ = {in[1]};
            if (in.op == spv::Op::OpBranchConditional) b.succ = {in[2], in[3]};
            if (in.op == spv::Op::OpSwitch) {
                b.succ.push_back(in[2]);
                for (size_t j = 4; j < in.n; j += 2) b.succ.push_back(in[j]);
            }
        } else if (in.op != spv::Op::OpFunctionParameter) {
            fail("instruction outside a block");
        }
    }
    if (blocks_.empty()) fail("entry point has no body");
    for (auto& b : blocks_)
        for (uint32_t s : b.succ)
            if (!block_of_.count(s)) fail("branch to unknown block");
}

// Structured reverse post-order: merge (and continue) targets are visited first so they end up last. Also marks
// the blocks that lie inside a loop construct.
void Translator::order_blocks() {
    std::vector<uint32_t> post;
    std::vector<uint8_t> state(blocks_.size(), 0);
    std::vector<std::pair<uint32_t, size_t>> stack{{0, 0}};
    state[0] = 1;
    std::vector<std::vector<uint32_t>> succs(blocks_.size());
    for (uint32_t i = 0; i < blocks_.size(); ++i) {
        const Block& b = blocks_[i];
        if (b.merge) succs[i].push_back(block_of_.at(b.merge));
        if (b.cont) succs[i].push_back(block_of_.at(b.cont));
        for (auto it = b.succ.rbegin(); it != b.succ.rend(); ++it) succs[i].push_back(block_of_.at(*it));
    }
    while (!stack.empty()) {
        auto& [bi, next] = stack.back();
        if (next < succs[bi].size()) {
            uint32_t s = succs[bi][next++];
            if (!state[s]) {
                state[s] = 1;
                stack.push_back({s, 0});
            }
        } else {
            post.push_back(bi);
            stack.pop_back();
        }
    }
    order_.assign(post.rbegin(), post.rend());
    for (uint32_t i = 0; i < order_.size(); ++i) blocks_[order_[i]].order = int(i);

    // Blocks inside a loop construct: between the header and its merge block in this layout (the merge is visited
    // first, so every block of the loop lands before it). Over-approximating only costs a masked move.
    block_in_loop_.assign(blocks_.size(), 0);
    for (const Block& h : blocks_) {
        if (!h.cont || h.order < 0) continue;
        int lo = h.order, hi = blocks_[block_of_.at(h.merge)].order;
        if (hi <= lo) hi = int(order_.size());
        for (int o = lo; o < hi; ++o) block_in_loop_[order_[size_t(o)]] = 1;
    }
}

// Masks: the entry block starts with the entry mask, the others empty. Phi registers are allocated up front so
// edges can write them before their block is translated.
void Translator::init_masks_and_phis() {
    for (uint32_t i = 0; i < blocks_.size(); ++i) {
        blocks_[i].mask = alloc();
        emit(SOp::Mov, blocks_[i].mask, i == 0 ? p_.reg_entry_mask : zero_);
    }
    for (auto& b : blocks_) {
        for (size_t j = b.first; j < b.end; ++j) {
            const Instr& in = ins_[j];
            if (in.op != spv::Op::OpPhi) continue;
            uint32_t n = std::max(1u, type(in[1]).flat);
            uint32_t r = alloc(n);
            vals_[in[2]] = Value{r, in[1], -1, true};
            // Lanes that never reach this block would otherwise keep a previous run's value, which a derivative
            // in non-uniform control flow (undefined, but must be deterministic) could read from a neighbour.
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Mov, r + i, zero_);
        }
    }
}

void Translator::emit_blocks() {
    for (uint32_t oi = 0; oi < order_.size(); ++oi) {
        Block& b = blocks_[order_[oi]];
        size_t skip_at = p_.code.size();
        b.code = skip_at;
        emit(SOp::JumpIfNone, kNoReg, b.mask);
        cur_mask_ = b.mask;
        store_mask_ = kNoReg;
        in_loop_ = block_in_loop_[order_[oi]] != 0;
        for (size_t j = b.first; j + 1 < b.end; ++j) {
            const Instr& in = ins_[j];
            if (in.op == spv::Op::OpPhi || in.op == spv::Op::OpSelectionMerge || in.op == spv::Op::OpLoopMerge)
                continue;
            op(in);
        }
        emit_terminator(b, ins_[b.end - 1]);
        p_.code[skip_at].imm = uint32_t(p_.code.size());
    }
    emit(SOp::Halt, kNoReg);
}

// The edge masks of a block's terminator: (target block, mask register) pairs.
std::vector<std::pair<uint32_t, uint32_t>> Translator::edges_of(const Block& b, const Instr& term) {
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    switch (term.op) {
        case spv::Op::OpBranch:
            edges.push_back({block_of_.at(term[1]), b.mask});
            break;
        case spv::Op::OpBranchConditional: {
            uint32_t c = reg(term[1]);
            if (term[2] == term[3]) {
                edges.push_back({block_of_.at(term[2]), b.mask});
            } else {
                edges.push_back({block_of_.at(term[2]), emit1(SOp::And, b.mask, c)});
                edges.push_back({block_of_.at(term[3]), emit1(SOp::Select, zero_, b.mask, c)});
            }
            break;
        }
        case spv::Op::OpSwitch: {
            uint32_t sel = reg(term[1]);
            uint32_t rest = b.mask;
            std::map<uint32_t, uint32_t> per_target;
            for (size_t q = 3; q + 1 < term.n; q += 2) {
                uint32_t eq = emit1(SOp::IEq, sel, konst(term[q]));
                uint32_t e = emit1(SOp::And, rest, eq);
                rest = emit1(SOp::Select, zero_, rest, eq);
                uint32_t t = block_of_.at(term[q + 1]);
                per_target[t] = per_target.count(t) ? emit1(SOp::Or, per_target[t], e) : e;
            }
            uint32_t t = block_of_.at(term[2]);
            per_target[t] = per_target.count(t) ? emit1(SOp::Or, per_target[t], rest) : rest;
            for (auto& [tb, m] : per_target) edges.push_back({tb, m});
            break;
        }
        case spv::Op::OpReturn:
        case spv::Op::OpUnreachable:
            break;
        case spv::Op::OpKill:
        case spv::Op::OpTerminateInvocation:
            if (stage_ != Stage::Fragment) fail("OpKill outside a fragment shader");
            iface_.uses_discard = true;
            emit(SOp::Kill, p_.reg_live, b.mask);
            break;
        default:
            fail(std::string("unsupported block terminator ") + names::opcode(uint32_t(term.op)));
    }
    return edges;
}

// Sends the block's lanes along its edges (phi moves, target masks) and loops back where an edge goes backwards.
void Translator::emit_terminator(Block& b, const Instr& term) {
    std::vector<std::pair<uint32_t, uint32_t>> edges = edges_of(b, term);
    // If this block's mask register is used as an edge mask, copy it before clearing.
    for (auto& e : edges)
        if (e.second == b.mask) e.second = emit1(SOp::Mov, b.mask);
    emit(SOp::Mov, b.mask, zero_);
    int back_target = -1;
    for (auto& [tb, m] : edges) {
        Block& t = blocks_[tb];
        // phis of the target: read all incoming values first (a phi may read another phi of the same block)
        std::vector<std::pair<uint32_t, uint32_t>> moves;  // (dst reg, src reg)
        for (size_t q = t.first; q < t.end && ins_[q].op == spv::Op::OpPhi; ++q) {
            const Instr& phi = ins_[q];
            for (size_t a = 3; a + 1 < phi.n; a += 2) {
                if (phi[a + 1] != b.label) continue;
                const Value& dst = vals_[phi[2]];
                const Value& src = val(phi[a]);
                uint32_t n = std::max(1u, type(phi[1]).flat);
                for (uint32_t r = 0; r < n; ++r) moves.push_back({dst.reg + r, src.reg + r});
            }
        }
        std::vector<uint32_t> tmp;
        tmp.reserve(moves.size());
        for (auto& mv : moves) tmp.push_back(emit1(SOp::Mov, mv.second));
        for (size_t q = 0; q < moves.size(); ++q) emit(SOp::MaskedMov, moves[q].first, tmp[q], kNoReg, m);
        emit(SOp::Or, t.mask, t.mask, m);
        if (t.order <= b.order) {
            if (back_target >= 0) fail("block with two back edges");
            back_target = int(tb);
        }
    }
    if (back_target >= 0) {
        // loop back while any lane continues; the blocks after this one must lie outside the loop
        emit(SOp::JumpIfAny, kNoReg, blocks_[back_target].mask, kNoReg, kNoReg, uint32_t(blocks_[back_target].code));
    }
}

}  // namespace tilevk::shader
