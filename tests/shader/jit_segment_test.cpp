// The compiled tier's segment-level shortcuts against the interpreter (shader/jit/lanes.cpp): runs of LoadBufUniform
// sharing one resolution of their descriptor (load_buf_uniform), and instructions whose results nothing reads left
// out (LaneEmitter::dead), FAdd / FMul without the NaN operand-order blends where no lane can meet two NaNs
// (LaneEmitter::nan_order_free), lane-uniform arithmetic on constants computed while compiling (fold.cpp). All
// must leave every register the host or a later segment can see as the interpreter
// leaves it.
#include <gtest/gtest.h>
#include <xmmintrin.h>

#include <bit>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "shader/ir.h"
#include "shader/jit/analysis.h"
#include "shader/jit/jit.h"

using namespace tilevk::shader;

namespace {

class JitSegment : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!jit::host_supported()) GTEST_SKIP() << "the CPU lacks AVX2/FMA: there is no compiled tier to compare";
        if (!jit::enabled()) GTEST_SKIP() << "TILEVK_JIT=0: the compiled tier is off";
    }
};

// Runs `p` on both tiers from the same registers; "" when every register that is not segment-local (the ones the
// host or a later segment reads) has the same bits, else the first difference.
// `fill` (when given) then rewrites the random registers.
std::string compare_tiers(const ProgramImpl& p, const std::vector<const Descriptor*>& slots, std::mt19937& rng,
                          const std::function<void(std::vector<uint32_t>&)>& fill = nullptr) {
    std::string why;
    auto code = jit::compile(p, &why);
    if (!code) return "not compiled: " + why;
    const jit::Analysis an = jit::analyze(p);
    Scratch::Impl a, b;
    a.regs.resize(size_t(p.num_regs) * kLanes);
    for (auto& w : a.regs) w = uint32_t(rng());
    if (fill) fill(a.regs);
    a.local.assign(size_t(p.local_words) * kLanes, 0);
    a.slots = slots;
    b.regs = a.regs, b.local = a.local, b.slots = a.slots;
    jit::run(*code, a);
    execute(p, b);
    for (uint32_t r = 0; r < p.num_regs; ++r) {
        if (an.local[r]) continue;
        for (int l = 0; l < kLanes; ++l)
            if (a.regs[r * kLanes + l] != b.regs[r * kLanes + l])
                return "register " + std::to_string(r) + " lane " + std::to_string(l) + ": compiled " +
                       std::to_string(a.regs[r * kLanes + l]) + ", interpreter " +
                       std::to_string(b.regs[r * kLanes + l]);
    }
    return "";
}

// registers 0..9: the loads' results, 10: the lane call's, all read after a sync point (so not segment-local)
constexpr uint32_t kCount = 10;
// lane calls (lanes.cpp lane_call): gallivm's pow and sin, libm's atan2, fmod and asinh lane by lane
constexpr Op kCalls[] = {Op::Pow, Op::Sin, Op::Atan2, Op::FRem, Op::Asinh};

// A run of uniform loads in one segment: slots alternating between two buffers of different sizes, a descriptor
// without data, a missing one and one past the table, at offsets inside, at the last word, straddling the end and
// past it (also past 2^31), with a lane call among them (a C++ call: gallivm's or libm's code, which may use the
// registers holding the resolution).
// Then a sync point (JumpIfNone) and reads of every result from the next segment.
TEST_F(JitSegment, UniformLoadsSharingADescriptorMatchTheInterpreter) {
    std::vector<uint8_t> big(64), small(24);
    for (size_t i = 0; i < big.size(); ++i) big[i] = uint8_t(i * 37 + 1);
    for (size_t i = 0; i < small.size(); ++i) small[i] = uint8_t(i * 91 + 7);
    Descriptor full, part, no_data;
    full.buffer = BufferView{big.data(), big.data(), big.size()};
    part.buffer = BufferView{small.data(), small.data(), small.size()};
    no_data.buffer = BufferView{nullptr, nullptr, 64};
    const std::vector<const Descriptor*> slots = {&full, &part, &no_data, nullptr};
    const uint32_t offsets[] = {0, 4, 16, 20, 21, 24, 56, 60, 61, 64, 0x7FFFFFF8u, 0x7FFFFFFCu, 0xFFFFFFFCu};
    std::mt19937 rng(11);
    int programs = 0;
    for (int trial = 0; trial < 200; ++trial) {
        ProgramImpl p;
        p.num_regs = kCount + 4;
        p.local_words = 1;
        p.reg_live = kCount + 2, p.reg_entry_mask = kCount + 3;
        p.num_slots = uint32_t(slots.size());
        // mostly runs on one slot (the resolution reused), sometimes another slot or a slot past the table
        uint32_t slot = uint32_t(rng() % 2);
        const uint32_t call_at = uint32_t(rng() % (kCount + 1));  // kCount: no call
        const Op call = kCalls[rng() % std::size(kCalls)];
        for (uint32_t r = 0; r < kCount; ++r) {
            if (rng() % 4 == 0) slot = uint32_t(rng() % (slots.size() + 1));
            if (r == call_at) p.code.push_back(Inst{call, 0, kCount, kCount + 1, kCount + 1});
            Inst in{Op::LoadBufUniform, 0, r, kNoReg, kNoReg, kNoReg, slot};
            in.extra = offsets[rng() % std::size(offsets)];
            p.code.push_back(in);
        }
        const uint32_t after = uint32_t(p.code.size()) + 1;
        p.code.push_back(Inst{Op::JumpIfNone, 0, kNoReg, kCount + 2, kNoReg, kNoReg, after});
        for (uint32_t r = 0; r <= kCount; ++r) p.code.push_back(Inst{Op::Mov, 0, kCount + 1, r});  // and Pow's
        p.code.push_back(Inst{Op::Halt});
        const std::string diff = compare_tiers(p, slots, rng);
        ASSERT_EQ(diff, "") << "program " << trial;
        ++programs;
    }
    EXPECT_EQ(programs, 200);
}

// Results nothing reads (a segment-local register written twice, a dead load, a dead libm call) are not emitted,
// and the live ones around them still come out right: the registers read after the sync point equal the
// interpreter's, and the code is byte for byte as long as the same program's without the dead instructions.
TEST_F(JitSegment, DeadResultsAreLeftOutAndLiveOnesKept) {
    std::vector<uint8_t> bytes(32);
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(i * 13 + 5);
    Descriptor buf;
    buf.buffer = BufferView{bytes.data(), bytes.data(), bytes.size()};
    const std::vector<const Descriptor*> slots = {&buf};
    enum Variant { kDead, kWithout, kRead };
    auto program = [](Variant v) {
        ProgramImpl p;
        p.num_regs = 12;
        p.local_words = 1;
        p.reg_live = 10, p.reg_entry_mask = 11;
        p.num_slots = 1;
        Inst load{Op::LoadBufUniform, 0, 5, kNoReg, kNoReg, kNoReg, 0};
        load.extra = 8;
        if (v != kWithout) p.code.push_back(Inst{Op::FMul, 0, 4, 0, 1});  // dead: overwritten before any read
        p.code.push_back(Inst{Op::FAdd, 0, 4, 0, 0});                     // live: read by the FSub
        if (v != kWithout) {
            p.code.push_back(load);                       // dead unless read (kRead)
            p.code.push_back(Inst{Op::Pow, 0, 6, 0, 1});  // dead unless read (kRead)
        }
        p.code.push_back(Inst{Op::FSub, 0, 2, 4, 1});  // r2, r3 read after the sync point
        p.code.push_back(Inst{Op::FMul, 0, 3, 4, 0});
        if (v == kRead) {
            p.code.push_back(Inst{Op::FAdd, 0, 7, 5, 6});
            p.code.push_back(Inst{Op::FAdd, 0, 3, 3, 7});
        }
        const uint32_t after = uint32_t(p.code.size()) + 1;
        p.code.push_back(Inst{Op::JumpIfNone, 0, kNoReg, 10, kNoReg, kNoReg, after});
        p.code.push_back(Inst{Op::FAdd, 0, 8, 2, 3});
        p.code.push_back(Inst{Op::Halt});
        return p;
    };
    const unsigned saved_csr = _mm_getcsr();
    _mm_setcsr((saved_csr & ~0x6000u) | 0x8040u);
    std::mt19937 rng(3);
    for (Variant v : {kDead, kRead})
        for (int trial = 0; trial < 64; ++trial)
            ASSERT_EQ(compare_tiers(program(v), slots, rng), "") << "variant " << int(v);
    _mm_setcsr(saved_csr);
    const jit::Analysis an = jit::analyze(program(kDead));
    ASSERT_TRUE(an.local[4] && an.local[5] && an.local[6]) << "the test's dead registers are not segment-local";
    size_t bytes_of[3] = {};
    for (Variant v : {kDead, kWithout, kRead}) {
        std::string why;
        auto code = jit::compile(program(v), &why);
        ASSERT_NE(code, nullptr) << why;
        bytes_of[v] = code->code_bytes;
    }
    EXPECT_EQ(bytes_of[kDead], bytes_of[kWithout]);
    EXPECT_GT(bytes_of[kRead], bytes_of[kDead]);  // read, they are emitted
}

// FAdd / FMul whose operands are one register, or one a constant that is not a NaN, skip the blends that give each
// quarter the interpreter's operand order (no lane can meet two NaNs); with a NaN constant they keep them. Lanes
// hold NaNs of many payloads and both signs (so two NaNs meet wherever the order matters), numbers, infinities,
// zeros; every result is read after a sync point.
TEST_F(JitSegment, NanOrderFreeOperandsSkipTheBlendsAndMatchTheInterpreter) {
    constexpr uint32_t kNumber = 2, kNan = 3;  // constant registers: 0.8f and a quiet NaN with a payload
    constexpr uint32_t kNumberBits = 0x3f4ccccdu, kNanBits = 0xffc0beefu;
    auto program = [&](uint32_t constant, bool same) {
        ProgramImpl p;
        p.num_regs = 16;
        p.reg_live = 14, p.reg_entry_mask = 15;
        p.const_regs = {kNumber, kNumberBits, kNan, kNanBits};
        const uint32_t other = same ? 0 : 1;
        p.code = {Inst{Op::FMul, 0, 4, 0, other},    Inst{Op::FAdd, 0, 5, 0, other},
                  Inst{Op::FMul, 0, 6, 0, constant}, Inst{Op::FAdd, 0, 7, constant, 1},
                  Inst{Op::FMul, 0, 8, constant, 1}, Inst{Op::FAdd, 0, 9, 1, constant}};
        p.code.push_back(Inst{Op::JumpIfNone, 0, kNoReg, 14, kNoReg, kNoReg, uint32_t(p.code.size()) + 1});
        for (uint32_t r = 4; r < 10; ++r) p.code.push_back(Inst{Op::FAdd, 0, 10, r, 10});
        p.code.push_back(Inst{Op::Halt});
        return p;
    };
    const auto fill = [&](std::vector<uint32_t>& regs) {
        static constexpr uint32_t kSpecial[] = {0x7fc00000u, 0xffc00000u, 0x7f800001u, 0xff812345u, 0x7fc0abcdu,
                                                0x7f800000u, 0xff800000u, 0x00000000u, 0x80000000u, 0x3f800000u};
        for (uint32_t r : {0u, 1u})
            for (int l = 0; l < kLanes; ++l) {
                uint32_t& w = regs[r * kLanes + l];
                if (w % 4 != 0) w = kSpecial[w % std::size(kSpecial)] ^ (w % 3 == 0 ? 0x1234u & (w >> 8) : 0u);
            }
        for (int l = 0; l < kLanes; ++l) {
            regs[kNumber * kLanes + l] = kNumberBits;
            regs[kNan * kLanes + l] = kNanBits;
            regs[14 * kLanes + l] = regs[15 * kLanes + l] = ~0u;
        }
    };
    const unsigned saved_csr = _mm_getcsr();
    _mm_setcsr((saved_csr & ~0x6000u) | 0x8040u);
    std::mt19937 rng(11);
    for (uint32_t constant : {kNumber, kNan})
        for (bool same : {false, true})
            for (int trial = 0; trial < 64; ++trial)
                ASSERT_EQ(compare_tiers(program(constant, same), {}, rng, fill), "")
                    << "constant " << constant << " same " << same;
    _mm_setcsr(saved_csr);
    // the blends are there to skip only when some half's two quarters take the operands in different orders
    bool blends = false;
    for (Op op : {Op::FAdd, Op::FMul})
        for (int h = 0; h < 2; ++h) blends |= jit::nan_order(op, 2 * h) != jit::nan_order(op, 2 * h + 1);
    auto bytes = [&](uint32_t constant, bool same) {
        std::string why;
        auto code = jit::compile(program(constant, same), &why);
        EXPECT_NE(code, nullptr) << why;
        return code ? code->code_bytes : 0;
    };
    if (!blends) GTEST_SKIP() << "every half's quarters take FAdd's and FMul's operands in one order: no blends";
    EXPECT_LT(bytes(kNumber, false), bytes(kNan, false));  // the constant's four ops
    EXPECT_LT(bytes(kNan, true), bytes(kNan, false));      // x * x and x + x
}

// Arithmetic on constants into segment-local registers is computed while compiling and not emitted (fold.cpp): a
// chain (x * x + y, its square root, a quotient, a difference, a division by zero) read by emitted ops, by a lane
// call (libm's atan2 reads its operands from their homes) and redefined by an emitted op; beside it the cases that
// must stay emitted: a NaN result (sqrt of -2), results FTZ would flush (1e-20 squared, FLT_MIN halved), a denormal
// operand (DAZ) and a NaN operand. Under FTZ + DAZ (vertex, fragment) and without (compute), every register read
// after the sync point equals the interpreter's, and exactly the chain is folded (none of it when it starts from
// registers that are not constants).
TEST_F(JitSegment, ConstantArithmeticIsFoldedWhileCompilingAndMatchesTheInterpreter) {
    // 2: 3.0, 3: 0.5, 4: -2.0, 5: 1e-20, 6: a NaN with a payload, 7: FLT_MIN, 8: a denormal, 9: 0.0
    const std::vector<uint32_t> constants = {2, 0x40400000u, 3, 0x3f000000u, 4, 0xc0000000u, 5, 0x1e3ce508u,
                                             6, 0x7fc0beefu, 7, 0x00800000u, 8, 0x00000123u, 9, 0u};
    auto program = [&](bool chain_constant) {
        ProgramImpl p;
        p.num_regs = 34;
        p.reg_live = 32, p.reg_entry_mask = 33;
        p.const_regs = constants;
        if (!chain_constant) p.const_regs.erase(p.const_regs.begin(), p.const_regs.begin() + 4);  // 2 and 3
        p.code = {Inst{Op::FMul, 0, 10, 2, 2},  Inst{Op::FAdd, 0, 11, 10, 3}, Inst{Op::Sqrt, 0, 12, 11},
                  Inst{Op::FDiv, 0, 13, 3, 12}, Inst{Op::Sqrt, 0, 14, 4},     Inst{Op::FMul, 0, 15, 5, 5},
                  Inst{Op::FMul, 0, 16, 7, 3},  Inst{Op::FAdd, 0, 17, 8, 2},  Inst{Op::FMul, 0, 18, 6, 2},
                  Inst{Op::FDiv, 0, 19, 2, 9},  Inst{Op::FSub, 0, 20, 13, 12}};
        const uint32_t read[] = {13, 14, 15, 16, 17, 18, 19, 20};
        // the would-be flushed results copied bit for bit (a float op would read them through DAZ), the rest used
        for (uint32_t k = 0; k < std::size(read); ++k)
            p.code.push_back(read[k] == 15 || read[k] == 16 ? Inst{Op::Mov, 0, 21 + k, read[k]}
                                                            : Inst{Op::FMul, 0, 21 + k, 0, read[k]});
        p.code.push_back(Inst{Op::Atan2, 0, 29, 12, 1});  // a lane call on a folded operand
        p.code.push_back(Inst{Op::FMul, 0, 10, 0, 1});    // a folded register redefined, then read
        p.code.push_back(Inst{Op::FAdd, 0, 30, 10, 11});
        p.code.push_back(Inst{Op::JumpIfNone, 0, kNoReg, 32, kNoReg, kNoReg, uint32_t(p.code.size()) + 1});
        for (uint32_t r = 21; r <= 30; ++r) p.code.push_back(Inst{Op::FAdd, 0, 31, r, 31});
        p.code.push_back(Inst{Op::Halt});
        return p;
    };
    const auto fill = [&](std::vector<uint32_t>& regs) {
        for (size_t i = 0; i + 1 < constants.size(); i += 2)
            for (int l = 0; l < kLanes; ++l) regs[constants[i] * kLanes + l] = constants[i + 1];
        for (uint32_t r : {0u, 1u})  // small floats, so that the products keep the folded values' bits visible
            for (int l = 0; l < kLanes; ++l) regs[r * kLanes + l] = 0x3f800000u + (regs[r * kLanes + l] & 0x7fffffu);
        for (int l = 0; l < kLanes; ++l) regs[32 * kLanes + l] = regs[33 * kLanes + l] = ~0u;
    };
    const jit::Analysis an = jit::analyze(program(true));
    for (uint32_t r = 10; r <= 20; ++r) ASSERT_TRUE(an.local[r]) << "register " << r << " is not segment-local";
    const unsigned saved_csr = _mm_getcsr();
    std::mt19937 rng(5);
    for (unsigned flush : {0x8040u, 0u}) {
        _mm_setcsr((saved_csr & ~0xE040u) | flush);
        for (int trial = 0; trial < 16; ++trial)
            ASSERT_EQ(compare_tiers(program(true), {}, rng, fill), "") << "MXCSR flush bits " << flush;
    }
    _mm_setcsr(saved_csr);
    std::string why;
    auto folded = jit::compile(program(true), &why);
    ASSERT_NE(folded, nullptr) << why;
    auto emitted = jit::compile(program(false), &why);
    ASSERT_NE(emitted, nullptr) << why;
    // registers 10, 11, 12, 13, 19 and 20 in each half; none without the constants (the code counts its pool)
    EXPECT_EQ(folded->folded, 2u * 6u);
    EXPECT_EQ(emitted->folded, 0u);
}

}  // namespace
