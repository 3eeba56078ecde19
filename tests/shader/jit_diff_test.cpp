// Differential test of the two tiers (shader/jit/README.md): every program of jit_diff_corpus.h, the bench shaders
// and every variant of the shader fuzz corpus that creates is built twice, compiled and interpreted, and run on the
// same random inputs (NaN, infinities, denormals, signed zeros, huge and small integers among them), the same
// resources and the same scratch history. Every byte of the batch or block, every storage-buffer byte and the
// loop-watchdog count must be the same.
#include <gtest/gtest.h>
#include <xmmintrin.h>

#include <spirv-tools/libspirv.hpp>

#include <array>
#include <atomic>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "bench/shader/bench_shaders.h"
#include "fuzz_corpus.h"
#include "glsl.h"
#include "jit_diff_corpus.h"
#include "shader/ir.h"
#include "shader/jit/analysis.h"
#include "shader/jit/jit.h"
#include "shader/jit/sample_rgba8.h"

using namespace tilevk::shader;
using tilevk::shader::test::compile_glsl;

namespace {

uint32_t fb(float f) {
    return std::bit_cast<uint32_t>(f);
}

// Inputs where the tiers could part: special floats, integers of every size, plain floats.
uint32_t random_word(std::mt19937& rng) {
    static const uint32_t kSpecial[] = {0u,
                                        0x80000000u,
                                        fb(1.0f),
                                        fb(-1.0f),
                                        fb(0.5f),
                                        fb(-0.5f),
                                        0x7f800000u,
                                        0xff800000u,
                                        0x7fc00000u,
                                        0xffc00001u,
                                        0x7f800001u,
                                        0x00000001u,
                                        0x807fffffu,
                                        0x00400000u,
                                        0x7f7fffffu,
                                        0x00800000u,
                                        fb(2147483648.0f),
                                        fb(4294967296.0f),
                                        fb(-2147483648.0f),
                                        fb(3.0e9f),
                                        1u,
                                        2u,
                                        3u,
                                        31u,
                                        32u,
                                        33u,
                                        0xffffffffu,
                                        0x7fffffffu,
                                        0xfffffffeu,
                                        fb(0.25f),
                                        fb(1.5f),
                                        fb(2.5f),
                                        fb(-2.5f),
                                        fb(8388608.5f),
                                        fb(0.49999997f)};
    switch (rng() % 8) {
        case 0:
        case 1:
            return kSpecial[rng() % std::size(kSpecial)];
        case 2:
            return uint32_t(int32_t(rng() % 41) - 20);
        case 3:
            return uint32_t(rng());
        default:
            return fb(std::uniform_real_distribution<float>(-4.0f, 4.0f)(rng));
    }
}

// Set 0, binding k: a buffer, an image and a sampler at once, so every declaration finds a resource. Storage
// buffers are per tier (both start from the same bytes); images and samplers are shared and read-only.
struct Resources {
    static constexpr int kBindings = 8;
    static constexpr size_t kBufferBytes = 512;
    std::vector<uint8_t> texels[5];
    ImageView images[5];
    SamplerState samplers[5];
    std::vector<uint8_t> initial[kBindings];
    std::vector<uint8_t> push;

    Resources() {
        std::mt19937 rng(1234);
        for (auto& b : initial) {
            b.resize(kBufferBytes);
            for (size_t i = 0; i < kBufferBytes; i += 4) {
                uint32_t w = random_word(rng);
                std::memcpy(&b[i], &w, 4);
            }
        }
        push.resize(128);
        for (auto& x : push) x = uint8_t(rng());
        // 0: RGBA8 32x32 with mips, trilinear repeat (the 8-bit path)
        make_image(0, Format::R8G8B8A8_UNORM, 4, 32, 32, 6, 1, rng);
        samplers[0].mag_filter = samplers[0].min_filter = Filter::Linear;
        samplers[0].mipmap_mode = MipmapMode::Linear;
        // 1: D32 16x16, compare LESS (shadow)
        make_image(1, Format::D32_SFLOAT, 4, 16, 16, 1, 1, rng, true);
        samplers[1].compare_enable = true;
        samplers[1].compare_op = CompareOp::Less;
        samplers[1].mag_filter = samplers[1].min_filter = Filter::Linear;
        // 2: RGBA16F 8x8, 3 layers, nearest clamp
        make_image(2, Format::R16G16B16A16_SFLOAT, 8, 8, 8, 1, 3, rng);
        samplers[2].address_u = samplers[2].address_v = AddressMode::ClampToEdge;
        // 3: R8 64x1 (1D), linear mirrored
        make_image(3, Format::R8_UNORM, 1, 64, 1, 1, 1, rng);
        samplers[3].mag_filter = samplers[3].min_filter = Filter::Linear;
        samplers[3].address_u = AddressMode::MirroredRepeat;
        // 4: RGBA32F 16x16 with 2 levels, linear border (the float path)
        make_image(4, Format::R32G32B32A32_SFLOAT, 16, 16, 16, 2, 1, rng, true);
        samplers[4].mag_filter = samplers[4].min_filter = Filter::Linear;
        samplers[4].mipmap_mode = MipmapMode::Linear;
        samplers[4].address_u = samplers[4].address_v = AddressMode::ClampToBorder;
        samplers[4].border = BorderColor::OpaqueWhite;
    }

    void make_image(int k, Format f, uint32_t bytes, uint32_t w, uint32_t h, uint32_t levels, uint32_t layers,
                    std::mt19937& rng, bool unit_floats = false) {
        ImageView& v = images[k];
        v.format = f;
        v.width = w, v.height = h, v.levels = levels, v.layers = layers;
        uint64_t off = 0;
        for (uint32_t l = 0; l < levels; ++l) {
            uint32_t lw = std::max(1u, w >> l), lh = std::max(1u, h >> l);
            v.level[l] = ImageLevel{off, uint64_t(lw) * bytes, uint64_t(lw) * lh * bytes};
            off += uint64_t(lw) * lh * bytes * layers;
        }
        texels[k].resize(off);
        if (unit_floats) {
            for (size_t i = 0; i + 4 <= off; i += 4) {
                float x = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
                std::memcpy(&texels[k][i], &x, 4);
            }
        } else {
            for (auto& x : texels[k]) x = uint8_t(rng());
        }
        v.base = texels[k].data();
    }
};

// One tier's view of the resources.
struct TierBindings {
    std::vector<uint8_t> buffers[Resources::kBindings];
    Bindings bindings;
    explicit TierBindings(const Resources& r) {
        for (int k = 0; k < Resources::kBindings; ++k) {
            buffers[k] = r.initial[k];
            Descriptor d;
            d.buffer = BufferView{buffers[k].data(), buffers[k].data(), buffers[k].size()};
            if (k >= 3) {
                d.image = &r.images[k - 3];
                d.sampler = &r.samplers[k - 3];
            } else {
                d.image = &r.images[0];
                d.sampler = &r.samplers[0];
            }
            bindings.set(0, uint32_t(k), 0, d);
        }
        bindings.push_constants = std::as_bytes(std::span(r.push));
    }
};

void random_block(std::mt19937& rng, FragmentBlock& b) {
    b = FragmentBlock{};
    const uint32_t pick = rng() % 4;
    b.cover_mask = pick == 0 ? kAllLanes : uint32_t(rng()) & kAllLanes;
    if (b.cover_mask == 0) b.cover_mask = 1;
    b.front_facing = rng() & 1;
    const float bx = float(4 * (rng() % 64)), by = float(4 * (rng() % 64));
    for (int l = 0; l < kLanes; ++l) {
        b.frag_coord[0][l] = fb(bx + float(lane_x(l)) + 0.5f);
        b.frag_coord[1][l] = fb(by + float(lane_y(l)) + 0.5f);
        b.frag_coord[2][l] = fb(std::uniform_real_distribution<float>(0.0f, 1.0f)(rng));
        b.frag_coord[3][l] = random_word(rng);
        b.sample_mask_in[l] = rng() & 15;
        b.point_coord[0][l] = random_word(rng);
        b.point_coord[1][l] = random_word(rng);
        for (int loc = 0; loc < 6; ++loc)
            for (int c = 0; c < 4; ++c) b.inputs[loc][c][l] = random_word(rng);
    }
}

void random_batch(std::mt19937& rng, VertexBatch& v) {
    v = VertexBatch{};
    v.count = rng() % 3 == 0 ? 1 + rng() % kLanes : kLanes;
    v.base_vertex = rng() % 100, v.base_instance = rng() % 10, v.draw_index = rng() % 4;
    for (int l = 0; l < kLanes; ++l) {
        v.vertex_index[l] = rng() % 1000;
        v.instance_index[l] = rng() % 8;
        for (int loc = 0; loc < 4; ++loc)
            for (int c = 0; c < 4; ++c) v.inputs[loc][c][l] = random_word(rng);
    }
}

// First differing 32-bit word of two equally sized objects, as "word N: x vs y", or empty.
std::string first_difference(const void* a, const void* b, size_t bytes) {
    const auto* x = static_cast<const uint8_t*>(a);
    const auto* y = static_cast<const uint8_t*>(b);
    for (size_t i = 0; i + 4 <= bytes; i += 4) {
        uint32_t p, q;
        std::memcpy(&p, x + i, 4), std::memcpy(&q, y + i, 4);
        if (p != q) {
            char s[96];
            std::snprintf(s, sizeof s, "byte offset %zu: compiled 0x%08x, interpreted 0x%08x", i, p, q);
            return s;
        }
    }
    return {};
}

struct Pair {
    std::shared_ptr<const Program> compiled, interpreted;
    std::string error;
};

Pair build(const std::vector<uint32_t>& spirv, Stage stage) {
    Pair p;
    set_jit_enabled(true);
    Result a = Program::create(spirv, stage);
    set_jit_enabled(false);
    Result b = Program::create(spirv, stage);
    set_jit_enabled(true);
    p.compiled = a.program, p.interpreted = b.program;
    p.error = a ? b.error : a.error;
    return p;
}

// Runs both programs `runs` times on the same random inputs; returns the first difference, or empty.
std::string compare_runs(const Pair& p, Stage stage, const Resources& res, uint32_t seed, int runs,
                         uint64_t* watchdog_cuts = nullptr) {
    TierBindings ta(res), tb(res);
    Scratch sa, sb;
    std::mt19937 rng(seed);
    for (int run = 0; run < runs; ++run) {
        std::string diff;
        if (stage == Stage::Fragment) {
            static FragmentBlock input, a, b;
            random_block(rng, input);
            a = input, b = input;
            p.compiled->run_fragment(ta.bindings, a, sa);
            p.interpreted->run_fragment(tb.bindings, b, sb);
            diff = first_difference(&a, &b, sizeof a);
        } else {
            static VertexBatch input, a, b;
            random_batch(rng, input);
            a = input, b = input;
            p.compiled->run_vertex(ta.bindings, a, sa);
            p.interpreted->run_vertex(tb.bindings, b, sb);
            diff = first_difference(&a, &b, sizeof a);
        }
        if (!diff.empty()) return "run " + std::to_string(run) + ", " + diff;
        for (int k = 0; k < Resources::kBindings; ++k) {
            diff = first_difference(ta.buffers[k].data(), tb.buffers[k].data(), ta.buffers[k].size());
            if (!diff.empty())
                return "run " + std::to_string(run) + ", storage buffer " + std::to_string(k) + " " + diff;
        }
        if (sa.loop_limit_hits() != sb.loop_limit_hits())
            return "run " + std::to_string(run) + ": loop watchdog " + std::to_string(sa.loop_limit_hits()) + " vs " +
                   std::to_string(sb.loop_limit_hits());
    }
    if (watchdog_cuts) *watchdog_cuts += sa.loop_limit_hits();
    return {};
}

std::vector<uint32_t> assemble(const std::string& text) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::string msg;
    tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { msg += m; });
    std::vector<uint32_t> words;
    EXPECT_TRUE(tools.Assemble(text, &words)) << msg;
    return words;
}

void note_ops(const Program& p, std::set<Op>& seen) {
    for (const Inst& in : p.internal().code) seen.insert(in.op);
}

class JitDiff : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!jit::host_supported()) GTEST_SKIP() << "the CPU lacks AVX2/FMA: there is no compiled tier to compare";
        if (!jit::enabled()) GTEST_SKIP() << "TILEVK_JIT=0: the compiled tier is off";
    }
    Resources res_;
};

constexpr int kRuns = 12;

}  // namespace

// The corpus and the bench shaders: compiled, identical to the interpreter, and together every op shader code
// can produce.
TEST_F(JitDiff, CorpusMatchesInterpreterBitForBit) {
    std::set<Op> seen;
    int programs = 0;
    auto check = [&](const std::string& name, const std::vector<uint32_t>& spirv, Stage stage, int seeds = 4,
                     int runs = kRuns) {
        ASSERT_FALSE(spirv.empty()) << name;
        Pair p = build(spirv, stage);
        ASSERT_TRUE(p.compiled && p.interpreted) << name << ": " << p.error;
        EXPECT_TRUE(p.compiled->compiled()) << name << " stayed in the interpreter";
        EXPECT_FALSE(p.interpreted->compiled()) << name;
        note_ops(*p.compiled, seen);
        for (uint32_t seed = 0; seed < uint32_t(seeds); ++seed) {
            std::string diff = compare_runs(p, stage, res_, seed * 7919 + uint32_t(programs), runs);
            EXPECT_TRUE(diff.empty()) << name << " seed " << seed << ": " << diff;
            if (!diff.empty()) break;
        }
        ++programs;
    };
    for (const auto& c : test::jit_corpus::kGlslCases) {
        const Stage stage = c.vertex ? Stage::Vertex : Stage::Fragment;
        check(c.name, compile_glsl(stage, c.glsl, true), stage);
    }
    for (const auto& c : test::jit_corpus::kAsmCases) {
        const bool endless = std::string(c.name) == "endless_loop";  // each run is 4M back edges until the watchdog
        check(c.name, assemble(std::string(test::jit_corpus::kAsmHeader) + c.body), Stage::Fragment, endless ? 1 : 4,
              endless ? 2 : kRuns);
    }
    using namespace tilevk::bench_shaders;
    check("bench passthrough_vs", compile_glsl(Stage::Vertex, kPassVs), Stage::Vertex);
    check("bench passthrough_fs", compile_glsl(Stage::Fragment, kPassFs), Stage::Fragment);
    check("bench phong_fs", compile_glsl(Stage::Fragment, kPhongFs), Stage::Fragment);
    check("bench textured_fs", compile_glsl(Stage::Fragment, kTexFs), Stage::Fragment);

    // Every op the translator emits must have been compared. It never emits Fma (shader/README.md), Jump, or the
    // greater-than comparisons (it swaps the operands of a less-than); OpsMatchInterpreterOneByOne covers those.
    const std::set<Op> never_emitted = {Op::Fma, Op::FOrdGt, Op::FOrdGe, Op::FUnordGt, Op::FUnordGe,
                                        Op::SGt, Op::SGe,    Op::UGt,    Op::UGe,      Op::Jump};
    std::string missing;
    for (uint32_t o = 0;; ++o) {
        const jit::OpInfo info = jit::op_info(Op(o));
        if (!info.name) break;
        if (Op(o) > Op::Halt) continue;  // compute and storage-image ops: jit_compute_diff_test.cpp
        if (!never_emitted.count(Op(o)) && !seen.count(Op(o))) missing += std::string(" ") + info.name;
    }
    EXPECT_TRUE(missing.empty()) << "ops no corpus program reaches:" << missing;
}

// Every fuzz variant that creates (fuzz_corpus.h, the same ones fuzz_test.cpp runs), endless loops included.
TEST_F(JitDiff, FuzzCorpusMatchesInterpreterBitForBit) {
    int created = 0, compiled = 0;
    uint64_t cuts = 0;
    for (size_t si = 0; si < std::size(test::fuzz::kSources); ++si) {
        const auto& src = test::fuzz::kSources[si];
        const auto spirv = compile_glsl(src.stage, src.glsl);
        test::fuzz::Variants variants(si);
        for (int iter = 0; iter < test::fuzz::kVariantsPerSource; ++iter) {
            const std::vector<uint32_t> m = variants.next(spirv);
            Pair p = build(m, src.stage);
            ASSERT_EQ(bool(p.compiled), bool(p.interpreted)) << "source " << si << " variant " << iter;
            if (!p.compiled) continue;
            ++created;
            compiled += p.compiled->compiled();
            std::string diff = compare_runs(p, src.stage, res_, uint32_t(si * 100003 + iter), 2, &cuts);
            EXPECT_TRUE(diff.empty()) << "source " << si << " variant " << iter << ": " << diff;
        }
    }
    std::printf("jit diff: %d fuzz variants ran in both tiers (%d compiled), %d runs cut by the watchdog\n", created,
                compiled, int(cuts));
    EXPECT_GT(created, 300);
    EXPECT_EQ(compiled, created);
}

// Every register op alone, on random register files (specials included), under lavapipe's FTZ/DAZ: the compiled
// instruction sequence against the interpreter's case. Memory, image and control ops need a program around them
// and are covered by the corpus (and Jump below).
TEST_F(JitDiff, OpsMatchInterpreterOneByOne) {
    const std::set<Op> needs_context = {Op::LoadLocal, Op::StoreLocal,     Op::LoadLocalFixed, Op::StoreLocalFixed,
                                        Op::LoadBuf,   Op::LoadBufUniform, Op::StoreBuf,       Op::BufArrayLength,
                                        Op::Sample,    Op::Fetch,          Op::QuerySize,      Op::QueryLevels,
                                        Op::Jump,      Op::JumpIfNone,     Op::JumpIfAny,      Op::Halt};
    const unsigned saved_csr = _mm_getcsr();
    _mm_setcsr((saved_csr & ~0x6000u) | 0x8040u);
    std::mt19937 rng(99);
    int ops = 0;
    for (uint32_t o = 0; jit::op_info(Op(o)).name; ++o) {
        const Op op = Op(o);
        if (needs_context.count(op) || op > Op::Halt) continue;  // compute: jit_compute_diff_test.cpp
        ProgramImpl p;
        p.num_regs = 8;
        p.local_words = 1;
        p.reg_live = 7;  // the host reads the live register: its home is always written
        // d = 7; sources 0..2 (Pack*x8 read 0..3); Bfi's count register is 4
        Inst in{op, 0, 7, 0, 1, 2, op == Op::Bfi ? 4u : 0u};
        for (uint32_t imm = 0; imm < (op == Op::Bfi ? 1u : 4u); ++imm) {
            if (op != Op::Bfi) in.imm = imm;
            p.code = {in, Inst{Op::Halt}};
            std::string why;
            auto code = jit::compile(p, &why);
            ASSERT_NE(code, nullptr) << jit::op_name(op) << ": " << why;
            for (int trial = 0; trial < 64; ++trial) {
                Scratch::Impl a, b;
                a.regs.resize(size_t(p.num_regs) * kLanes);
                for (auto& w : a.regs) w = random_word(rng);
                a.local.assign(kLanes, 0);
                b.regs = a.regs, b.local = a.local;
                jit::run(*code, a);
                execute(p, b);
                ASSERT_EQ(a.regs, b.regs) << jit::op_name(op) << " imm " << imm << " trial " << trial << ": "
                                          << first_difference(a.regs.data(), b.regs.data(), a.regs.size() * 4);
            }
        }
        ++ops;
    }
    _mm_setcsr(saved_csr);
    EXPECT_GT(ops, 100);
    // Jump: the skipped instruction leaves its register alone.
    ProgramImpl p;
    p.num_regs = 4;
    p.local_words = 1;
    p.reg_live = 2, p.reg_entry_mask = 3;
    p.code = {Inst{Op::Jump, 0, kNoReg, kNoReg, kNoReg, kNoReg, 2}, Inst{Op::Mov, 0, 2, 0}, Inst{Op::Mov, 0, 3, 1},
              Inst{Op::Halt}};
    std::string why;
    auto code = jit::compile(p, &why);
    ASSERT_NE(code, nullptr) << why;
    Scratch::Impl a, b;
    a.regs.resize(4 * kLanes);
    for (auto& w : a.regs) w = random_word(rng);
    a.local.assign(kLanes, 0);
    b.regs = a.regs, b.local = a.local;
    jit::run(*code, a);
    execute(p, b);
    EXPECT_EQ(a.regs, b.regs);
}

namespace {

// Edge values for the ops whose result depends on more than one IEEE rounding: NaNs of both signs and kinds with
// payloads, infinities, signed zeros, denormals, the smallest normal, the largest finite, negative bases with odd,
// even and fractional exponents (pow), exact integers past 2^23, values near 1, large trigonometric arguments.
const uint32_t kEdgeValues[] = {0u,
                                0x80000000u,
                                fb(1.0f),
                                fb(-1.0f),
                                fb(0.5f),
                                fb(-0.5f),
                                fb(2.0f),
                                fb(-2.0f),
                                fb(3.0f),
                                fb(-3.0f),
                                fb(16.0f),
                                fb(-16.0f),
                                fb(2.5f),
                                fb(-2.5f),
                                fb(0.1f),
                                fb(-8.0f),
                                fb(100.0f),
                                fb(-100.0f),
                                fb(1e10f),
                                fb(-1e10f),
                                fb(88.7f),
                                fb(-87.4f),
                                fb(1e-30f),
                                fb(-1e-30f),
                                0x7f7fffffu,
                                0xff7fffffu,
                                0x00800000u,
                                0x80800000u,
                                0x00000001u,
                                0x807fffffu,
                                0x00400000u,
                                0x7f800000u,
                                0xff800000u,
                                0x7fc00000u,
                                0xffc00001u,
                                0x7fc12345u,
                                0x7f800001u,
                                0xff812345u,
                                fb(3.14159265f),
                                fb(1e4f),
                                fb(0.99999994f),
                                fb(1.0000001f),
                                fb(8388609.0f),
                                fb(16777216.0f),
                                fb(-16777216.0f),
                                fb(0.75f),
                                fb(-0.99f),
                                fb(1e-5f)};

// The ops lowered into segments whose bits need more than one instruction to match the interpreter's: FAdd and FMul
// (the NaN operand order of each quarter, analysis.h nan_order) and the libm ops (FRem, Exp ... Atanh, and the rounding
// ops where the interpreter's are libm's: a call per half inside the segment, lanes.cpp lane_call, which must keep the
// values still to be read). `op` runs three times between native ops: on segment-local values that live only in YMM
// registers (one read for the last time, one read again later), on the inputs while a local value waits in a YMM
// register, and in place (d == a); four sync instructions (JumpIfNone) make the results visible in the register file.
// Every pair of edge values meets in every lane, under lavapipe's FTZ/DAZ and under the default MXCSR.
std::string compare_in_segment(Op op) {
    ProgramImpl p;
    p.num_regs = 12;
    p.local_words = 1;
    p.reg_live = 8, p.reg_entry_mask = 9;
    p.code = {Inst{Op::FSub, 0, 2, 0, 1},
              Inst{Op::FSub, 0, 3, 1, 0},
              Inst{Op::FSub, 0, 10, 3, 0},
              Inst{op, 0, 5, 10, 2},  // r10 only in a YMM register, read for the last time; r2 and r3 read later
              Inst{op, 0, 4, 0, 1},
              Inst{op, 0, 2, 2, 3},  // in place
              Inst{Op::FSub, 0, 6, 5, 2},
              Inst{Op::FSub, 0, 7, 3, 2},
              Inst{Op::JumpIfNone, 0, kNoReg, 4, kNoReg, kNoReg, 9},
              Inst{Op::JumpIfNone, 0, kNoReg, 5, kNoReg, kNoReg, 10},
              Inst{Op::JumpIfNone, 0, kNoReg, 6, kNoReg, kNoReg, 11},
              Inst{Op::JumpIfNone, 0, kNoReg, 7, kNoReg, kNoReg, 12},
              Inst{Op::Halt}};
    std::string why;
    auto code = jit::compile(p, &why);
    if (!code) return "not compiled: " + why;
    if (code->helper_ops != 0) return "runs through the interpreter";
    const jit::Analysis an = jit::analyze(p);
    if (!an.local[2] || !an.local[3] || !an.local[10]) return "the test's registers 2, 3, 10 are not segment-local";
    const unsigned saved_csr = _mm_getcsr();
    const size_t n = std::size(kEdgeValues);
    std::string diff;
    for (int ftz = 0; ftz < 2 && diff.empty(); ++ftz) {
        _mm_setcsr(ftz ? (saved_csr & ~0x6000u) | 0x8040u : saved_csr & ~0x8040u);
        for (size_t first = 0; first < n * n && diff.empty(); ++first) {
            Scratch::Impl a, b;
            a.regs.assign(size_t(p.num_regs) * kLanes, 0);
            for (int l = 0; l < kLanes; ++l) {
                const size_t pair = (first + size_t(l) * (n * n / kLanes + 1)) % (n * n);  // every pair in every lane
                a.regs[l] = kEdgeValues[pair / n];
                a.regs[kLanes + l] = kEdgeValues[pair % n];
            }
            a.local.assign(kLanes, 0);
            b.regs = a.regs, b.local = a.local;
            jit::run(*code, a);
            execute(p, b);
            for (uint32_t r = 0; r < p.num_regs && diff.empty(); ++r)
                if (!an.local[r])
                    diff = first_difference(&a.regs[r * kLanes], &b.regs[r * kLanes], kLanes * 4).empty()
                               ? ""
                               : "register " + std::to_string(r) + (ftz ? " (FTZ/DAZ)" : "") + ", inputs from " +
                                     std::to_string(first) + ": " +
                                     first_difference(&a.regs[r * kLanes], &b.regs[r * kLanes], kLanes * 4);
        }
    }
    _mm_setcsr(saved_csr);
    return diff;
}

}  // namespace

// LoadBuf from one buffer (a masked gather in the compiled tier, lanes.cpp load_buf) against the interpreter's loop
// at the bounds: element indices 0 and not, offsets inside, at the last word, straddling the end, past it and past
// 2^31, constant offsets that overflow 32 bits, a descriptor without data, a missing one, a slot past the table.
TEST_F(JitDiff, LoadBufMatchesInterpreterAtTheBounds) {
    std::vector<uint8_t> bytes(64);
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(i * 37 + 1);
    Descriptor full, no_data;
    full.buffer = BufferView{bytes.data(), bytes.data(), bytes.size()};
    no_data.buffer = BufferView{nullptr, nullptr, 64};
    const std::vector<const Descriptor*> slots = {&full, &no_data, nullptr, &full};
    const uint32_t offsets[] = {0, 1, 4, 56, 59, 60, 61, 64, 100, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFCu, 0xFFFFFFFFu};
    std::mt19937 rng(5);
    int compared = 0;
    for (uint32_t imm = 0; imm < 5; ++imm) {
        for (uint32_t extra : {0u, 8u, 60u, 61u, 0xFFFFFFF0u}) {
            ProgramImpl p;
            p.num_regs = 3;
            p.local_words = 1;
            p.reg_live = 2;  // the result: the host reads the live register, so its home is always written
            p.num_slots = uint32_t(slots.size());
            Inst in{Op::LoadBuf, 0, 2, 0, 1, kNoReg, imm};
            in.extra = extra;
            in.n = 1;
            p.code = {in, Inst{Op::Halt}};
            std::string why;
            auto code = jit::compile(p, &why);
            ASSERT_NE(code, nullptr) << why;
            for (int trial = 0; trial < 16; ++trial) {
                Scratch::Impl a, b;
                a.regs.resize(size_t(p.num_regs) * kLanes);
                for (auto& w : a.regs) w = random_word(rng);
                for (int l = 0; l < kLanes; ++l) {
                    a.regs[0 * kLanes + l] = rng() % 4 == 0 ? uint32_t(rng() % 3) : 0u;  // element index
                    a.regs[1 * kLanes + l] = rng() % 2 ? offsets[rng() % std::size(offsets)] : uint32_t(rng() % 72);
                }
                a.local.assign(kLanes, 0);
                a.slots = slots;
                b.regs = a.regs, b.local = a.local, b.slots = a.slots;
                jit::run(*code, a);
                execute(p, b);
                ASSERT_EQ(a.regs, b.regs) << "slot " << imm << " extra " << extra << " trial " << trial << ": "
                                          << first_difference(a.regs.data(), b.regs.data(), a.regs.size() * 4);
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, 5 * 5 * 16);
}

TEST_F(JitDiff, EdgeValuesMatchInterpreterInSegments) {
    for (Op op : {Op::FAdd,  Op::FMul, Op::FRem,  Op::Exp,   Op::Exp2,      Op::Log,   Op::Log2,
                  Op::Pow,   Op::Sin,  Op::Cos,   Op::Tan,   Op::Asin,      Op::Acos,  Op::Atan,
                  Op::Atan2, Op::Sinh, Op::Cosh,  Op::Tanh,  Op::Asinh,     Op::Acosh, Op::Atanh,
                  Op::Floor, Op::Ceil, Op::Trunc, Op::Round, Op::RoundEven, Op::Fract, Op::FMod})
        EXPECT_EQ(compare_in_segment(op), "") << jit::op_name(op);
}

// The compiled tier's RGBA8 sampler (shader/jit/sample_rgba8.cpp) against the interpreter's exec_image, on quads of
// finite coordinates whose LODs cover magnification, every level and beyond: whenever it takes the case, the four
// result registers are the same bits. Both address modes, both mip modes, LOD bias / min / max, RGBA and BGRA,
// implicit, biased and explicit LOD; a non-power-of-two REPEAT image must be left to exec_image.
TEST_F(JitDiff, Rgba8SamplerMatchesExecImage) {
    const unsigned saved_csr = _mm_getcsr();
    _mm_setcsr((saved_csr & ~0x6000u) | 0x8040u);
    std::mt19937 rng(77);
    struct Img {
        Format f;
        uint32_t w, h;
    };
    const Img imgs[] = {{Format::R8G8B8A8_UNORM, 64, 32},
                        {Format::B8G8R8A8_UNORM, 16, 16},
                        {Format::R8G8B8A8_UNORM, 24, 16},
                        {Format::R8G8B8A8_UNORM, 512, 4}};  // 10 levels: the level table's second half
    int taken = 0, refused = 0, npot_repeat_taken = 0;
    for (const Img& im : imgs) {
        std::vector<uint8_t> texels;
        ImageView view;
        view.format = im.f, view.width = im.w, view.height = im.h;
        uint64_t off = 0;
        for (uint32_t l = 0;; ++l) {
            const uint32_t lw = std::max(1u, im.w >> l), lh = std::max(1u, im.h >> l);
            view.level[l] = ImageLevel{off, uint64_t(lw) * 4, uint64_t(lw) * lh * 4};
            off += uint64_t(lw) * lh * 4;
            view.levels = l + 1;
            if (lw == 1 && lh == 1) break;
        }
        texels.resize(off);
        for (auto& x : texels) x = uint8_t(rng());
        view.base = texels.data();
        for (int trial = 0; trial < 400; ++trial) {
            SamplerState smp;
            smp.mag_filter = smp.min_filter = Filter::Linear;
            smp.mipmap_mode = rng() & 1 ? MipmapMode::Linear : MipmapMode::Nearest;
            smp.address_u = rng() & 1 ? AddressMode::Repeat : AddressMode::ClampToEdge;
            smp.address_v = rng() & 1 ? AddressMode::Repeat : AddressMode::ClampToEdge;
            if (rng() % 3 == 0) smp.mip_lod_bias = float(int(rng() % 9) - 4) * 0.37f;
            if (rng() % 3 == 0) smp.min_lod = float(rng() % 4) * 0.6f;
            if (rng() % 3 == 0) smp.max_lod = float(rng() % 6) * 0.9f;
            Descriptor desc{{}, &view, &smp};
            const Descriptor* slots[2] = {&desc, &desc};
            // registers: 0 handle, 1-2 coordinates, 3 lod/bias, 4-7 result
            std::vector<uint32_t> regs(8 * kLanes);
            for (int l = 0; l < kLanes; ++l) regs[l] = 1u | (1u << 16);
            for (int q = 0; q < 4; ++q) {
                const float cu = std::uniform_real_distribution<float>(-2.0f, 3.0f)(rng);
                const float cv = std::uniform_real_distribution<float>(-2.0f, 3.0f)(rng);
                const float scale = std::ldexp(1.0f, int(rng() % 15) - 12);
                const float du = scale * std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);
                const float dv = scale * std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);
                for (int k = 0; k < 4; ++k) {
                    const int l = q * 4 + k, x = k & 1, y = k >> 1;
                    regs[kLanes + l] = fb(cu + du * float(x) + dv * float(y) * 0.5f);
                    regs[2 * kLanes + l] = fb(cv + dv * float(y) - du * float(x) * 0.25f);
                    regs[3 * kLanes + l] = fb(std::uniform_real_distribution<float>(-3.0f, 8.0f)(rng));
                }
            }
            const uint32_t modes[] = {kSampleImplicitLod, kSampleImplicitLod | kSampleBias, kSampleExplicitLod};
            // a quarter of the calls write over their own coordinates (d = 1: results in 1-4), as SPIR-V
            // allows after register reuse: the kernel must read every source before it writes
            Inst in{Op::Sample, 0, trial % 4 == 3 ? 1u : 4u, 0, 1, 3, modes[rng() % 3], 2};
            std::vector<uint32_t> a = regs, b = regs;
            const bool fast = jit::sample_rgba8(in, a.data(), slots, 2);
            exec_image(in, b.data(), slots, 2);
            if (!fast) {
                EXPECT_EQ(a, regs) << "a refused case wrote registers";
                ++refused;
                continue;
            }
            ++taken;
            npot_repeat_taken += (im.w & (im.w - 1)) != 0 && smp.address_u == AddressMode::Repeat;
            ASSERT_EQ(a, b) << "image " << im.w << "x" << im.h << " trial " << trial << ": "
                            << first_difference(a.data(), b.data(), a.size() * 4);
        }
    }
    _mm_setcsr(saved_csr);
    std::printf("rgba8 sampler: %d calls taken, %d left to exec_image\n", taken, refused);
    EXPECT_GT(taken, 500);
    EXPECT_GT(refused, 100);  // NEAREST mips with implicit LOD, npot REPEAT
    EXPECT_EQ(npot_repeat_taken, 0);
}

namespace {

// A view of `w` x `h` RGBA8/BGRA8 texels over `levels` levels inside `mem`: rows `pad` bytes longer than the texels,
// level 0 at byte `first`, the levels stored smallest first when `reversed` (other offsets, same sizes).
ImageView laid_out(std::vector<uint8_t>& mem, Format f, uint32_t w, uint32_t h, uint32_t levels, uint32_t pad,
                   uint32_t first, bool reversed, std::mt19937& rng) {
    ImageView v;
    v.format = f, v.width = w, v.height = h, v.levels = levels;
    uint64_t off = first;
    for (uint32_t k = 0; k < levels; ++k) {
        const uint32_t l = reversed ? levels - 1 - k : k;
        const uint32_t lw = std::max(1u, w >> l), lh = std::max(1u, h >> l);
        v.level[l] = ImageLevel{off, uint64_t(lw) * 4 + pad, (uint64_t(lw) * 4 + pad) * lh};
        off += (uint64_t(lw) * 4 + pad) * lh;
    }
    mem.resize(off);
    for (auto& x : mem) x = uint8_t(rng());
    v.base = mem.data();
    return v;
}

// One Sample on random quads through both the kernel and exec_image; "" when the registers match (or the kernel
// refused without writing), else where they differ. `taken` counts the calls the kernel took.
std::string sample_once(const ImageView& view, const SamplerState& smp, std::mt19937& rng, int& taken) {
    Descriptor desc{{}, &view, &smp};
    const Descriptor* slots[2] = {&desc, &desc};
    std::vector<uint32_t> regs(8 * kLanes);
    for (int l = 0; l < kLanes; ++l) regs[l] = 1u | (1u << 16);
    for (int q = 0; q < 4; ++q) {
        const float cu = std::uniform_real_distribution<float>(-1.5f, 2.5f)(rng);
        const float cv = std::uniform_real_distribution<float>(-1.5f, 2.5f)(rng);
        const float d = std::ldexp(1.0f, int(rng() % 10) - 9);
        for (int k = 0; k < 4; ++k) {
            regs[kLanes + q * 4 + k] = fb(cu + d * float(k & 1));
            regs[2 * kLanes + q * 4 + k] = fb(cv + d * 0.7f * float(k >> 1));
        }
    }
    const Inst in{Op::Sample, 0, 4u, 0, 1, 3, kSampleImplicitLod, 2};
    std::vector<uint32_t> a = regs, b = regs;
    const bool fast = jit::sample_rgba8(in, a.data(), slots, 2);
    exec_image(in, b.data(), slots, 2);
    if (!fast) return a == regs ? "" : "a refused call wrote registers";
    ++taken;
    return first_difference(a.data(), b.data(), a.size() * 4);
}

}  // namespace

// Views prepared once (prepare_view, as icd/ does when a VkImageView is made) and sampled in alternation, as
// draws with different descriptor sets do: sizes, level counts, row pitches, level offsets (two views with the
// same sizes but other offsets), RGBA/BGRA, REPEAT/CLAMP; then views whose fields change after prepare_view (the
// table no longer matches the view: the kernel must rebuild it, or refuse a swizzle it does not cover). Every call
// must give exec_image's bits.
TEST_F(JitDiff, Rgba8SamplerPreparedViewsAlternate) {
    const unsigned saved_csr = _mm_getcsr();
    _mm_setcsr((saved_csr & ~0x6000u) | 0x8040u);
    std::mt19937 rng(2311);
    std::vector<uint8_t> mem[5];
    ImageView views[5] = {laid_out(mem[0], Format::R8G8B8A8_UNORM, 64, 32, 7, 0, 0, false, rng),
                          laid_out(mem[1], Format::B8G8R8A8_UNORM, 16, 16, 3, 16, 52, false, rng),
                          laid_out(mem[2], Format::R8G8B8A8_UNORM, 64, 32, 4, 0, 0, false, rng),
                          laid_out(mem[3], Format::R8G8B8A8_UNORM, 64, 32, 7, 8, 20, true, rng),
                          laid_out(mem[4], Format::R8G8B8A8_UNORM, 32, 16, 6, 4, 12, true, rng)};
    for (ImageView& v : views) prepare_view(v);
    SamplerState smp[2];
    for (SamplerState& s : smp) s.mag_filter = s.min_filter = Filter::Linear, s.mipmap_mode = MipmapMode::Linear;
    smp[1].address_u = smp[1].address_v = AddressMode::ClampToEdge;
    smp[1].mip_lod_bias = 0.6f;
    int taken[5] = {};
    for (int call = 0; call < 1000; ++call) {
        const int v = call % 5;
        ASSERT_EQ(sample_once(views[v], smp[(call / 5) % 2], rng, taken[v]), "") << "view " << v << " call " << call;
    }
    for (int v = 0; v < 5; ++v) EXPECT_EQ(taken[v], 200) << "view " << v;
    // view 0 becomes view 4's image (other sizes, levels and offsets) without prepare_view: its table is stale
    ImageView changed = views[0];
    const ViewLevelTable stale = changed.table;
    changed.width = views[4].width, changed.height = views[4].height, changed.levels = views[4].levels;
    changed.level = views[4].level, changed.base = views[4].base;
    ASSERT_EQ(std::memcmp(&changed.table, &stale, sizeof stale), 0);
    int changed_taken = 0;
    for (int call = 0; call < 200; ++call)
        ASSERT_EQ(sample_once(changed, smp[call % 2], rng, changed_taken), "") << "changed view, call " << call;
    EXPECT_EQ(changed_taken, 200);
    // a swizzle the kernel does not cover, set after prepare_view: refused, exec_image swizzles
    changed = views[0];
    changed.swizzle = {2, 1, 0, 3};
    int swizzled_taken = 0;
    for (int call = 0; call < 50; ++call)
        ASSERT_EQ(sample_once(changed, smp[0], rng, swizzled_taken), "") << "swizzled view, call " << call;
    EXPECT_EQ(swizzled_taken, 0);
    _mm_setcsr(saved_csr);
}

// The driver's time limit (Scratch::set_stop_flag): with the flag set, both tiers leave an endless loop at its first
// back edge, with the same outputs and one watchdog count each.
TEST_F(JitDiff, StopFlagEndsLoopsAlike) {
    const test::jit_corpus::AsmCase* endless = nullptr;
    for (const auto& c : test::jit_corpus::kAsmCases)
        if (std::string(c.name) == "endless_loop") endless = &c;
    ASSERT_NE(endless, nullptr);
    Pair p = build(assemble(std::string(test::jit_corpus::kAsmHeader) + endless->body), Stage::Fragment);
    ASSERT_TRUE(p.compiled && p.interpreted) << p.error;
    ASSERT_TRUE(p.compiled->compiled());
    std::atomic<bool> stop{true};
    TierBindings ta(res_), tb(res_);
    Scratch sa, sb;
    sa.set_stop_flag(&stop), sb.set_stop_flag(&stop);
    std::mt19937 rng(5);
    FragmentBlock input, a, b;
    random_block(rng, input);
    a = input, b = input;
    p.compiled->run_fragment(ta.bindings, a, sa);
    p.interpreted->run_fragment(tb.bindings, b, sb);
    EXPECT_EQ(first_difference(&a, &b, sizeof a), "");
    EXPECT_EQ(sa.loop_limit_hits(), 1u);
    EXPECT_EQ(sb.loop_limit_hits(), 1u);
}

// An op the compiled tier does not know keeps the whole program in the interpreter, with its name in the reason.
TEST_F(JitDiff, UnknownOpFallsBackToTheInterpreter) {
    ProgramImpl p;
    p.num_regs = 4;
    p.code = {Inst{Op::Mov, 0, 1, 2}, Inst{Op(4000), 0, 1, 2}, Inst{Op::Halt}};
    std::string why;
    EXPECT_EQ(jit::compile(p, &why), nullptr);
    EXPECT_NE(why.find("op #4000"), std::string::npos) << why;
    p.code.erase(p.code.begin() + 1);
    EXPECT_NE(jit::compile(p, &why), nullptr) << why;
}

// TILEVK_JIT=0 (the whole suite runs once that way in CI) and set_jit_enabled(false) keep programs interpreted.
TEST(JitSwitch, EnvironmentAndSwitchDecideTheTier) {
    const auto spirv = compile_glsl(Stage::Fragment, tilevk::bench_shaders::kPhongFs);
    const char* env = std::getenv("TILEVK_JIT");
    const bool env_off = env && std::string(env) == "0";
    Result r = Program::create(spirv, Stage::Fragment);
    ASSERT_TRUE(r) << r.error;
    EXPECT_EQ(r.program->compiled(), !env_off && jit::host_supported());
    set_jit_enabled(false);
    Result off = Program::create(spirv, Stage::Fragment);
    set_jit_enabled(!env_off);
    ASSERT_TRUE(off) << off.error;
    EXPECT_FALSE(off.program->compiled());
}
