// Op table (name, how it is compiled), register footprints, segments and segment-local registers.
#include "shader/jit/analysis.h"

#include <algorithm>
#include <array>

namespace tilevk::shader::jit {

namespace {

constexpr Lowering N = Lowering::Native, H = Lowering::Helper, U = Lowering::Unknown;

struct OpEntry {
    Op op;
    const char* name;
    Lowering lowering;
};

// Every op of ir.h this tier knows, in enum order. Ops appended to ir.h later are not listed: op_info reports them
// as Unknown and the program stays in the interpreter until someone decides how to compile them.
constexpr OpEntry kOps[] = {
    {Op::Mov, "Mov", N},
    {Op::Select, "Select", N},
    {Op::MaskedMov, "MaskedMov", N},
    {Op::FAdd, "FAdd", N},
    {Op::FSub, "FSub", N},
    {Op::FMul, "FMul", N},
    {Op::FDiv, "FDiv", N},
    {Op::FNeg, "FNeg", N},
    {Op::FAbs, "FAbs", N},
    {Op::FMin, "FMin", N},
    {Op::FMax, "FMax", N},
    {Op::FMod, "FMod", N},
    {Op::FRem, "FRem", N},
    {Op::Fma, "Fma", N},
    {Op::FOrdEq, "FOrdEq", N},
    {Op::FOrdNe, "FOrdNe", N},
    {Op::FOrdLt, "FOrdLt", N},
    {Op::FOrdLe, "FOrdLe", N},
    {Op::FOrdGt, "FOrdGt", N},
    {Op::FOrdGe, "FOrdGe", N},
    {Op::FUnordEq, "FUnordEq", N},
    {Op::FUnordNe, "FUnordNe", N},
    {Op::FUnordLt, "FUnordLt", N},
    {Op::FUnordLe, "FUnordLe", N},
    {Op::FUnordGt, "FUnordGt", N},
    {Op::FUnordGe, "FUnordGe", N},
    {Op::IsNan, "IsNan", N},
    {Op::IsInf, "IsInf", N},
    {Op::IAdd, "IAdd", N},
    {Op::ISub, "ISub", N},
    {Op::IMul, "IMul", N},
    {Op::SDiv, "SDiv", H},
    {Op::UDiv, "UDiv", H},
    {Op::SRem, "SRem", H},
    {Op::SMod, "SMod", H},
    {Op::UMod, "UMod", H},
    {Op::INeg, "INeg", N},
    {Op::And, "And", N},
    {Op::Or, "Or", N},
    {Op::Xor, "Xor", N},
    {Op::Not, "Not", N},
    {Op::Shl, "Shl", N},
    {Op::ShrL, "ShrL", N},
    {Op::ShrA, "ShrA", N},
    {Op::IEq, "IEq", N},
    {Op::INe, "INe", N},
    {Op::SLt, "SLt", N},
    {Op::SLe, "SLe", N},
    {Op::SGt, "SGt", N},
    {Op::SGe, "SGe", N},
    {Op::ULt, "ULt", N},
    {Op::ULe, "ULe", N},
    {Op::UGt, "UGt", N},
    {Op::UGe, "UGe", N},
    {Op::SMin, "SMin", N},
    {Op::SMax, "SMax", N},
    {Op::UMin, "UMin", N},
    {Op::UMax, "UMax", N},
    {Op::SAbs, "SAbs", N},
    {Op::SSign, "SSign", H},
    {Op::BitCount, "BitCount", H},
    {Op::BitReverse, "BitReverse", H},
    {Op::FindLsb, "FindLsb", H},
    {Op::FindSMsb, "FindSMsb", H},
    {Op::FindUMsb, "FindUMsb", H},
    {Op::BfeS, "BfeS", H},
    {Op::BfeU, "BfeU", H},
    {Op::Bfi, "Bfi", H},
    {Op::F2S, "F2S", N},
    {Op::F2U, "F2U", N},
    {Op::S2F, "S2F", N},
    {Op::U2F, "U2F", N},
    {Op::Floor, "Floor", N},
    {Op::Ceil, "Ceil", N},
    {Op::Trunc, "Trunc", N},
    {Op::Round, "Round", N},
    {Op::RoundEven, "RoundEven", N},
    {Op::Fract, "Fract", N},
    {Op::FSign, "FSign", N},
    {Op::Sqrt, "Sqrt", N},
    {Op::InvSqrt, "InvSqrt", N},
    {Op::Exp, "Exp", N},
    {Op::Exp2, "Exp2", N},
    {Op::Log, "Log", N},
    {Op::Log2, "Log2", N},
    {Op::Pow, "Pow", N},
    {Op::Sin, "Sin", N},
    {Op::Cos, "Cos", N},
    {Op::Tan, "Tan", N},
    {Op::Asin, "Asin", N},
    {Op::Acos, "Acos", N},
    {Op::Atan, "Atan", N},
    {Op::Atan2, "Atan2", N},
    {Op::Sinh, "Sinh", N},
    {Op::Cosh, "Cosh", N},
    {Op::Tanh, "Tanh", N},
    {Op::Asinh, "Asinh", N},
    {Op::Acosh, "Acosh", N},
    {Op::Atanh, "Atanh", N},
    {Op::FClamp, "FClamp", N},
    {Op::Step, "Step", N},
    {Op::SmoothStep, "SmoothStep", N},
    {Op::Ldexp, "Ldexp", H},
    {Op::FrexpSig, "FrexpSig", H},
    {Op::FrexpExp, "FrexpExp", H},
    {Op::MulHiU, "MulHiU", H},
    {Op::MulHiS, "MulHiS", H},
    {Op::PackHalf2x16, "PackHalf2x16", H},
    {Op::UnpackHalf2x16Lo, "UnpackHalf2x16Lo", H},
    {Op::UnpackHalf2x16Hi, "UnpackHalf2x16Hi", H},
    {Op::PackUnorm4x8, "PackUnorm4x8", H},
    {Op::UnpackUnorm4x8, "UnpackUnorm4x8", H},
    {Op::PackSnorm4x8, "PackSnorm4x8", H},
    {Op::UnpackSnorm4x8, "UnpackSnorm4x8", H},
    {Op::PackUnorm2x16, "PackUnorm2x16", H},
    {Op::UnpackUnorm2x16, "UnpackUnorm2x16", H},
    {Op::PackSnorm2x16, "PackSnorm2x16", H},
    {Op::UnpackSnorm2x16, "UnpackSnorm2x16", H},
    {Op::DdxFine, "DdxFine", N},
    {Op::DdyFine, "DdyFine", N},
    {Op::DdxCoarse, "DdxCoarse", N},
    {Op::DdyCoarse, "DdyCoarse", N},
    {Op::LoadLocal, "LoadLocal", N},
    {Op::StoreLocal, "StoreLocal", H},
    {Op::LoadLocalFixed, "LoadLocalFixed", N},
    {Op::StoreLocalFixed, "StoreLocalFixed", N},
    {Op::LoadBuf, "LoadBuf", H},
    {Op::LoadBufUniform, "LoadBufUniform", N},
    {Op::StoreBuf, "StoreBuf", H},
    {Op::BufArrayLength, "BufArrayLength", H},
    {Op::Sample, "Sample", H},
    {Op::Fetch, "Fetch", H},
    {Op::QuerySize, "QuerySize", H},
    {Op::QueryLevels, "QueryLevels", H},
    {Op::Jump, "Jump", N},
    {Op::JumpIfNone, "JumpIfNone", N},
    {Op::JumpIfAny, "JumpIfAny", N},
    {Op::Kill, "Kill", N},
    {Op::Halt, "Halt", N},
    // Compute and storage images. LoadShared is a gather inside segments (memory_ops.cpp); StoreShared and the
    // atomics are sync points whose lanes apply in lane order, as the interpreter's loops do: StoreShared and
    // AtomicShared are emitted as that loop (memory_ops.cpp), the rest are the interpreter's code for the one
    // instruction. Barrier ends the run with its pc (compile.cpp), the next run resumes after it.
    {Op::LoadShared, "LoadShared", N},
    {Op::StoreShared, "StoreShared", N},
    {Op::AtomicBuf, "AtomicBuf", H},
    {Op::AtomicShared, "AtomicShared", N},
    {Op::Barrier, "Barrier", N},
    {Op::SgLaneId, "SgLaneId", H},
    {Op::SgElect, "SgElect", H},
    {Op::SgAll, "SgAll", H},
    {Op::SgAny, "SgAny", H},
    {Op::SgAllEqual, "SgAllEqual", H},
    {Op::SgBroadcast, "SgBroadcast", H},
    {Op::SgBroadcastFirst, "SgBroadcastFirst", H},
    {Op::SgBallot, "SgBallot", H},
    {Op::ImageLoad, "ImageLoad", H},
    {Op::ImageStore, "ImageStore", H},
    {Op::AtomicImage, "AtomicImage", H},
    // Pointers, 64-bit and narrow types: not compiled (a program with them stays in the interpreter; op_name in
    // compile.cpp names them).
    {Op::LoadPtr, nullptr, U},
    {Op::StorePtr, nullptr, U},
    {Op::AtomicPtr, nullptr, U},
    {Op::Wide, nullptr, U},
    {Op::LoadBufN, nullptr, U},
    {Op::StoreBufN, nullptr, U},
    {Op::HalfToFloat, nullptr, U},
    {Op::FloatToHalf, nullptr, U},
    // InterpolateAt* reads the block's planes through the scratch: the interpreter's code (interpolate.cpp).
    {Op::InterpolateAt, "InterpolateAt", H},
};

constexpr bool table_in_enum_order() {
    for (size_t i = 0; i < std::size(kOps); ++i)
        if (size_t(kOps[i].op) != i) return false;
    return true;
}
static_assert(table_in_enum_order(), "kOps must list ir.h's ops in enum order");

bool is_image(Op op) {
    return op == Op::Sample || op == Op::Fetch || op == Op::QuerySize || op == Op::QueryLevels;
}

// When both operands of an x86 addition or multiplication are NaN, the result is the first source operand's NaN
// (quieted). For the commutative FAdd and FMul, which operand comes first in the interpreter is the C++
// compiler's choice, made per machine instruction: the baseline x86-64 build computes the 16 lanes as four SSE
// operations of four lanes, and GCC orders each one as its register allocation likes (this build's FAdd has a first
// in lanes 0-3 and b first in lanes 4-15). So the order is measured once per process and four-lane quarter: the
// interpreter adds and multiplies two different NaNs.
NanOrder measure_nan_order(Op op, int quarter) {
    Scratch::Impl s;
    s.regs.assign(3 * kLanes, 0);
    s.local.assign(kLanes, 0);
    for (int l = 0; l < kLanes; ++l) {
        s.regs[l] = 0x7fa00000u | uint32_t(l);                // a: signalling NaNs with per-lane payloads
        s.regs[kLanes + l] = 0xffc00000u | uint32_t(l << 8);  // b: quiet NaNs, other payloads
    }
    const Inst code[2] = {Inst{op, 0, 2, 0, 1}, Inst{Op::Halt}};
    execute_code(code, s);
    int a_first = 0, b_first = 0;
    for (int l = 4 * quarter; l < 4 * quarter + 4; ++l) {
        a_first += s.regs[2 * kLanes + l] == (s.regs[l] | 0x00400000u);
        b_first += s.regs[2 * kLanes + l] == s.regs[kLanes + l];
    }
    return a_first == 4 ? NanOrder::AFirst : b_first == 4 ? NanOrder::BFirst : NanOrder::Unknown;
}

struct NanOrders {
    NanOrder order[2][4];  // [FAdd, FMul][quarter]
    NanOrders() {
        for (int q = 0; q < 4; ++q) {
            order[0][q] = measure_nan_order(Op::FAdd, q);
            order[1][q] = measure_nan_order(Op::FMul, q);
        }
    }
};

}  // namespace

NanOrder nan_order(Op op, int quarter) {
    static const NanOrders orders;
    return orders.order[op == Op::FMul][quarter];
}

Lowering lowering(const Inst& in) {
    // 64-bit integer atomics (register pairs, two-word memory): a program with one stays in the interpreter, as
    // programs with Op::Wide do.
    if ((in.op == Op::AtomicBuf || in.op == Op::AtomicShared) && (in.pad & kAtomicWide)) return Lowering::Unknown;
    if (in.op == Op::FAdd || in.op == Op::FMul)
        for (int q = 0; q < 4; ++q)
            if (nan_order(in.op, q) == NanOrder::Unknown) return Lowering::Helper;
#if !TILEVK_SIMD_AVX2
    // shader/ is built for baseline x86-64 (no SSE4.1 / FMA): fmaf is a libm call in the interpreter, whose NaN
    // results are libm's (another payload than vfmadd's), and only the translator's never-emitted Fma uses it. The
    // generated code hands it to the interpreter. (Floor ... FMod, libm calls too, run as lane calls: lanes.cpp.)
    if (in.op == Op::Fma) return Lowering::Helper;
#endif
    // A load from one buffer (not an array of descriptors) is a masked gather (lanes.cpp load_buf); from a
    // descriptor array, each lane may read another buffer: the interpreter's loop.
    if (in.op == Op::LoadBuf) return in.n == 1 ? Lowering::Native : Lowering::Helper;
    // A store to one buffer is the interpreter's lane loop written out (memory_ops.cpp), a sync op.
    if (in.op == Op::StoreBuf) return in.n == 1 ? Lowering::Native : Lowering::Helper;
    return op_info(in.op).lowering;
}

bool is_sync(const Inst& in) {
    switch (in.op) {
        case Op::Jump:
        case Op::JumpIfNone:
        case Op::JumpIfAny:
        case Op::Halt:
        case Op::Barrier:
        case Op::StoreBuf:      // lanes in order, like StoreShared
        case Op::StoreShared:   // lanes in order over all 16 lanes: the last lane writing a word wins
        case Op::AtomicShared:  // the same, and each lane sees the lanes before it
            return true;
        default:
            return lowering(in) != Lowering::Native;
    }
}

OpInfo op_info(Op op) {
    size_t i = size_t(op);
    if (i >= std::size(kOps)) return {nullptr, Lowering::Unknown};
    return {kOps[i].name, kOps[i].lowering};
}

Footprint footprint(const Inst& in) {
    Footprint f;
    switch (in.op) {
        case Op::Jump:
        case Op::Halt:
            break;
        case Op::JumpIfNone:
        case Op::JumpIfAny:
            f.read(in.a);
            break;
        case Op::MaskedMov:
            f.read(in.a), f.read(in.c), f.read(in.d), f.write(in.d);
            f.reads_dest = true;
            break;
        case Op::Kill:
            f.read(in.a), f.read(in.d), f.write(in.d);
            f.reads_dest = true;
            break;
        case Op::LoadLocalFixed:
        case Op::LoadBufUniform:
            f.write(in.d);
            break;
        case Op::StoreLocalFixed:
            f.read(in.b), f.read(in.c);
            break;
        case Op::StoreLocal:
            f.read(in.a), f.read(in.b), f.read(in.c);
            break;
        case Op::StoreBuf:
            f.read(in.d), f.read(in.a), f.read(in.b), f.read(in.c);  // d is the store mask
            break;
        case Op::AtomicBuf:
        case Op::AtomicShared:  // d is the comparator as well as the result
            f.read(in.a), f.read(in.b), f.read(in.c), f.read(in.d), f.write(in.d);
            f.reads_dest = true;
            break;
        case Op::ImageLoad:  // handle, x, y, layer; four results
            f.read(in.a);
            for (uint32_t i = 0; i < 3 && in.b != kNoReg; ++i) f.read(in.b + i);
            for (uint32_t i = 0; i < 4 && in.d != kNoReg; ++i) f.write(in.d + i);
            break;
        case Op::ImageStore:  // handle, x, y, layer, four values, the mask d
            f.read(in.a), f.read(in.d);
            for (uint32_t i = 0; i < 3 && in.b != kNoReg; ++i) f.read(in.b + i);
            for (uint32_t i = 0; i < 4 && in.c != kNoReg; ++i) f.read(in.c + i);
            break;
        case Op::AtomicImage:  // handle, x, y, layer, value; d the comparator and the result
            f.read(in.a), f.read(in.c), f.read(in.d), f.write(in.d);
            for (uint32_t i = 0; i < 3 && in.b != kNoReg; ++i) f.read(in.b + i);
            f.reads_dest = true;
            break;
        case Op::Bfi:
            f.read(in.a), f.read(in.b), f.read(in.c), f.read(in.imm), f.write(in.d);
            break;
        case Op::PackUnorm4x8:
        case Op::PackSnorm4x8:
            for (uint32_t i = 0; i < 4 && in.a != kNoReg; ++i) f.read(in.a + i);
            f.write(in.d);
            break;
        case Op::PackUnorm2x16:
        case Op::PackSnorm2x16:
            for (uint32_t i = 0; i < 2 && in.a != kNoReg; ++i) f.read(in.a + i);
            f.write(in.d);
            break;
        default:
            if (is_image(in.op)) {
                // handle, lod/bias, the coordinate run (at least x, y, layer), the gradients; four results
                f.read(in.a), f.read(in.c);
                if (in.b != kNoReg)
                    for (uint32_t i = 0; i < std::max<uint32_t>(in.extra, 3) && f.complete(); ++i) f.read(in.b + i);
                if (in.op == Op::Sample && (in.imm & kSampleGrad))  // 3D and cube: dx.xyz, dy.xyz
                    for (uint32_t i = 0; i < ((in.imm & (kSample3D | kSampleCube)) ? 6u : 4u); ++i) f.read(in.n + i);
                for (uint32_t i = 0; i < 4 && in.d != kNoReg; ++i) f.write(in.d + i);
                break;
            }
            // plain ops: up to three sources, one result
            f.read(in.a), f.read(in.b), f.read(in.c), f.write(in.d);
            break;
    }
    return f;
}

Analysis analyze(const ProgramImpl& p) {
    Analysis an;
    const size_t n = p.code.size();
    const uint32_t regs = p.num_regs;
    an.label.assign(n + 1, 0);
    an.label[0] = 1;
    for (size_t i = 0; i < n; ++i) {
        const Inst& in = p.code[i];
        if (lowering(in) == Lowering::Unknown) {
            if (an.unknown_at < 0) an.unknown_at = int64_t(i);
            continue;
        }
        if (in.op == Op::Jump || in.op == Op::JumpIfNone || in.op == Op::JumpIfAny) {
            if (in.imm > n) {
                if (an.unknown_at < 0) an.unknown_at = int64_t(i);
                continue;
            }
            an.label[in.imm] = 1;
        }
        if (in.op == Op::Barrier) an.label[i + 1] = 1;  // a run resumes there (compile.cpp's resume table)
    }

    an.is_const.assign(regs, 0);
    an.const_value.assign(regs, 0);
    for (size_t i = 0; i + 1 < p.const_regs.size(); i += 2) {
        if (p.const_regs[i] >= regs) continue;
        an.is_const[p.const_regs[i]] = 1;
        an.const_value[p.const_regs[i]] = p.const_regs[i + 1];
    }

    // Segments: a new one at every label and around every sync instruction.
    an.segment.assign(n, 0);
    uint32_t segment = 0;
    for (size_t i = 0; i < n; ++i) {
        const bool sync = is_sync(p.code[i]);
        if (i > 0 && (an.label[i] || sync || is_sync(p.code[i - 1]))) ++segment;
        an.segment[i] = segment;
    }

    // Per register: segment of its first access (-1: none yet), whether that access wrote it, whether it is
    // accessed from a second segment or by a sync instruction.
    std::vector<int64_t> first_segment(regs, -1);
    std::vector<uint8_t> first_write(regs, 0), shared(regs, 0);
    for (size_t i = 0; i < n; ++i) {
        const Inst& in = p.code[i];
        if (lowering(in) == Lowering::Unknown) continue;
        const bool sync = is_sync(in);
        const Footprint f = footprint(in);
        auto touch = [&](uint32_t r, bool write) {
            if (r >= regs) return false;
            if (first_segment[r] < 0) {
                first_segment[r] = an.segment[i];
                first_write[r] = write;
            } else if (first_segment[r] != int64_t(an.segment[i])) {
                shared[r] = 1;
            }
            if (sync) shared[r] = 1;
            return true;
        };
        bool ok = f.complete();
        for (int k = 0; ok && k < f.num_reads; ++k) ok = touch(f.reads[k], false);
        for (int k = 0; ok && k < f.num_writes; ++k) ok = touch(f.writes[k], true);
        if (!ok && an.unknown_at < 0) an.unknown_at = int64_t(i);  // a register past the file: do not compile
    }
    an.local.assign(regs, 0);
    for (uint32_t r = 0; r < regs; ++r)
        an.local[r] = first_segment[r] >= 0 && first_write[r] && !shared[r] && !an.is_const[r] &&
                      r != p.reg_entry_mask && r != p.reg_live;
    // A constant some instruction writes is an ordinary register.
    for (size_t i = 0; i < n; ++i) {
        const Inst& in = p.code[i];
        if (lowering(in) == Lowering::Unknown) continue;
        const Footprint f = footprint(in);
        for (int k = 0; k < f.num_writes && k < Footprint::kMax; ++k)
            if (f.writes[k] < regs) an.is_const[f.writes[k]] = 0;
    }
    return an;
}

}  // namespace tilevk::shader::jit
