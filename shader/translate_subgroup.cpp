// Compute's subgroup operations: SPIR-V GroupNonUniform (basic), GroupNonUniformVote and GroupNonUniformBallot.
// A subgroup is kSubgroupSize consecutive lanes of a batch (program.h); the kernels are in exec_subgroup.h. The
// lanes taking part are the block's (cur_mask_); results depend on other lanes, so in loops the lanes that left
// keep what they had (keep_active). The ballot helpers are per-lane arithmetic on the ballot's first word: a
// subgroup has fewer than 32 lanes, and the bits of lanes past it are ignored, as the spec says.
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

namespace {

bool is_subgroup_op(spv::Op op) {
    switch (op) {
        case spv::Op::OpGroupNonUniformElect:
        case spv::Op::OpGroupNonUniformAll:
        case spv::Op::OpGroupNonUniformAny:
        case spv::Op::OpGroupNonUniformAllEqual:
        case spv::Op::OpGroupNonUniformBroadcast:
        case spv::Op::OpGroupNonUniformBroadcastFirst:
        case spv::Op::OpGroupNonUniformBallot:
        case spv::Op::OpGroupNonUniformInverseBallot:
        case spv::Op::OpGroupNonUniformBallotBitExtract:
        case spv::Op::OpGroupNonUniformBallotBitCount:
        case spv::Op::OpGroupNonUniformBallotFindLSB:
        case spv::Op::OpGroupNonUniformBallotFindMSB:
            return true;
        default:
            return false;
    }
}

}  // namespace

// The ops whose result depends on the other lanes of the subgroup: one kernel each (exec_subgroup.h).
bool Translator::subgroup_collective(const Instr& in) {
    // One kernel per component of the value at in[4] (b: a second operand register, or kNoReg).
    const auto per_component = [&](SOp o, uint32_t b = kNoReg) {
        const uint32_t a = reg(in[4]), n = flat_of(in[4]);
        keep_active(def(in), n, [&](uint32_t d) {
            for (uint32_t i = 0; i < n; ++i) emit(o, d + i, a + i, b, cur_mask_);
        });
        return true;
    };
    switch (in.op) {
        case spv::Op::OpGroupNonUniformElect:
            keep_active(def(in), 1, [&](uint32_t d) { emit(SOp::SgElect, d, kNoReg, kNoReg, cur_mask_); });
            return true;
        case spv::Op::OpGroupNonUniformAll:
            return per_component(SOp::SgAll);
        case spv::Op::OpGroupNonUniformAny:
            return per_component(SOp::SgAny);
        case spv::Op::OpGroupNonUniformAllEqual: {
            const uint32_t a = reg(in[4]), n = flat_of(in[4]);
            const uint32_t as_float = type(component_type(val(in[4]).type)).kind == Type::Float ? 1 : 0;
            keep_active(def(in), 1, [&](uint32_t d) {
                emit(SOp::SgAllEqual, d, a, kNoReg, cur_mask_, as_float);
                for (uint32_t i = 1; i < n; ++i) {  // a vector: every component equal
                    const uint32_t t = alloc();
                    emit(SOp::SgAllEqual, t, a + i, kNoReg, cur_mask_, as_float);
                    emit(SOp::And, d, d, t);
                }
            });
            return true;
        }
        case spv::Op::OpGroupNonUniformBroadcast:
            return per_component(SOp::SgBroadcast, reg(in[5]));
        case spv::Op::OpGroupNonUniformBroadcastFirst:
            return per_component(SOp::SgBroadcastFirst);
        case spv::Op::OpGroupNonUniformBallot: {
            const uint32_t pred = reg(in[4]);
            keep_active(def(in), 4, [&](uint32_t d) {
                emit(SOp::SgBallot, d, pred, kNoReg, cur_mask_);
                for (uint32_t i = 1; i < 4; ++i) emit(SOp::Mov, d + i, zero_);
            });
            return true;
        }
        default:
            return false;
    }
}

// The ballot helpers: per lane, on the ballot's first word (in[4], or in[5] for BitCount).
void Translator::subgroup_ballot_helper(const Instr& in) {
    const uint32_t lane = emit1(SOp::SgLaneId);
    const uint32_t one = konst(1), all_lanes = konst((1u << kSubgroupSize) - 1);
    switch (in.op) {
        case spv::Op::OpGroupNonUniformInverseBallot: {  // bit (lane id) of x
            const uint32_t bit = emit1(SOp::And, emit1(SOp::ShrL, reg(in[4]), lane), one);
            emit(SOp::INe, def(in), bit, zero_);
            return;
        }
        case spv::Op::OpGroupNonUniformBallotBitExtract: {  // bit `index` of the uvec4
            const uint32_t x = reg(in[4]), index = reg(in[5]);
            const uint32_t word = emit1(SOp::ShrL, index, konst(5));
            uint32_t w = x + 3;
            for (uint32_t i = 3; i-- > 0;) w = emit1(SOp::Select, x + i, w, emit1(SOp::IEq, word, konst(i)));
            const uint32_t bit = emit1(SOp::And, emit1(SOp::ShrL, w, emit1(SOp::And, index, konst(31))), one);
            emit(SOp::INe, def(in), bit, zero_);
            return;
        }
        case spv::Op::OpGroupNonUniformBallotBitCount: {
            // in[4]: Reduce (every lane's bit), InclusiveScan (lanes <= this one), ExclusiveScan (lanes < this one)
            uint32_t bits = all_lanes;
            if (in[4] == uint32_t(spv::GroupOperation::InclusiveScan))
                bits = emit1(SOp::ISub, emit1(SOp::Shl, konst(2), lane), one);
            else if (in[4] == uint32_t(spv::GroupOperation::ExclusiveScan))
                bits = emit1(SOp::ISub, emit1(SOp::Shl, one, lane), one);
            else if (in[4] != uint32_t(spv::GroupOperation::Reduce))
                fail("unsupported OpGroupNonUniformBallotBitCount group operation " + std::to_string(in[4]));
            emit(SOp::BitCount, def(in), emit1(SOp::And, reg(in[5]), bits));
            return;
        }
        case spv::Op::OpGroupNonUniformBallotFindLSB:
            emit(SOp::FindLsb, def(in), emit1(SOp::And, reg(in[4]), all_lanes));
            return;
        case spv::Op::OpGroupNonUniformBallotFindMSB:
            emit(SOp::FindUMsb, def(in), emit1(SOp::And, reg(in[4]), all_lanes));
            return;
        default:
            fail("unsupported opcode " + opname(in.op));
    }
}

bool Translator::op_subgroup(const Instr& in) {
    if (!is_subgroup_op(in.op)) return false;
    if (stage_ != Stage::Compute)
        fail("unsupported " + opname(in.op) + " in a " + stage_name(stage_) +
             " shader (subgroup operations: compute only)");
    uint32_t scope = 0;
    if (!const_of(in[3], scope) || scope != uint32_t(spv::Scope::Subgroup))
        fail("unsupported " + opname(in.op) + " with an execution scope other than Subgroup");
    if (!subgroup_collective(in)) subgroup_ballot_helper(in);
    return true;
}

}  // namespace tilevk::shader
