// The compiled tier's RGBA8 sampler bound once per draw (shader/jit/sample_rgba8.h bind_sample / sample_bound,
// BoundSample in shader/ir.h) against the interpreter's exec_image and against the per-call kernel sample_rgba8:
// one binding per view and sampler, then many calls with coordinates at and near texel edges, over formats
// (RGBA8, BGRA8, formats the kernel refuses), filters, address modes, mip modes, level counts and LOD modes. Every
// call that the binding takes must give exec_image's bits, the binding must take exactly the calls the per-call
// kernel takes, and a call whose handle is not the bound one must be refused without writing a register.
#include <gtest/gtest.h>
#include <xmmintrin.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "shader/ir.h"
#include "shader/jit/jit.h"
#include "shader/jit/sample_rgba8.h"

using namespace tilevk::shader;

namespace {

uint32_t fb(float f) {
    return std::bit_cast<uint32_t>(f);
}

std::string first_difference(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) {
            char s[96];
            std::snprintf(s, sizeof s, "register %zu lane %zu: bound 0x%08x, exec_image 0x%08x", i / kLanes, i % kLanes,
                          a[i], b[i]);
            return s;
        }
    return {};
}

// A w x h view of `levels` levels (rows `pad` bytes longer than the texels) over random bytes in `mem`.
ImageView make_view(std::vector<uint8_t>& mem, Format f, uint32_t w, uint32_t h, uint32_t levels, uint32_t pad,
                    std::mt19937& rng) {
    ImageView v;
    v.format = f, v.width = w, v.height = h, v.levels = levels;
    uint64_t off = 0;
    for (uint32_t l = 0; l < levels; ++l) {
        const uint32_t lw = std::max(1u, w >> l), lh = std::max(1u, h >> l);
        v.level[l] = ImageLevel{off, uint64_t(lw) * 4 + pad, (uint64_t(lw) * 4 + pad) * lh};
        off += (uint64_t(lw) * 4 + pad) * lh;
    }
    mem.resize(off);
    for (auto& x : mem) x = uint8_t(rng());
    v.base = mem.data();
    return v;
}

// A coordinate on an axis of n texels: texel edges and centres (exact k/n and (k + 0.5)/n, one ulp either side),
// 0, 1, -0, far outside, and plain values.
float edge_coordinate(uint32_t n, std::mt19937& rng) {
    const float k = float(int(rng() % (2 * n + 3)) - int(n) - 1);
    switch (rng() % 6) {
        case 0:
            return k / float(n);
        case 1:
            return (k + 0.5f) / float(n);
        case 2:
            return std::nextafter(k / float(n), rng() & 1 ? 10.0f : -10.0f);
        case 3: {
            const float special[] = {0.0f, -0.0f, 1.0f, std::nextafter(1.0f, 0.0f), 0.5f, -1.0f, 1000.3f, -517.77f};
            return special[rng() % std::size(special)];
        }
        default:
            return std::uniform_real_distribution<float>(-2.0f, 3.0f)(rng);
    }
}

struct Case {
    ImageView view;
    SamplerState smp;
};

class BoundSampler : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!jit::host_supported()) GTEST_SKIP() << "the CPU lacks AVX2/FMA: there is no compiled tier";
        saved_csr_ = _mm_getcsr();
        _mm_setcsr((saved_csr_ & ~0x6000u) | 0x8040u);  // the fragment stage's FTZ/DAZ, round to nearest
    }
    void TearDown() override { _mm_setcsr(saved_csr_); }
    unsigned saved_csr_ = 0;
};

}  // namespace

TEST_F(BoundSampler, MatchesExecImageAndThePerCallKernel) {
    std::mt19937 rng(4242);
    struct Img {
        Format f;
        uint32_t w, h, levels, pad;
        bool prepared;
    };
    const Img imgs[] = {
        {Format::R8G8B8A8_UNORM, 64, 32, 7, 0, true},  {Format::B8G8R8A8_UNORM, 16, 16, 5, 12, true},
        {Format::R8G8B8A8_UNORM, 24, 16, 5, 0, true},   // not a power of two: REPEAT refused
        {Format::R8G8B8A8_UNORM, 512, 4, 10, 4, true},  // 10 levels: the table's second half
        {Format::R8G8B8A8_UNORM, 8, 8, 1, 0, true},    {Format::R8G8B8A8_UNORM, 32, 32, 6, 8, false},  // no table
        {Format::R8G8B8A8_SRGB, 16, 16, 5, 0, true},  // the float filter: refused
    };
    const Filter filters[] = {Filter::Linear, Filter::Linear, Filter::Linear, Filter::Nearest};
    const AddressMode wraps[] = {AddressMode::Repeat,      AddressMode::ClampToEdge,    AddressMode::Repeat,
                                 AddressMode::ClampToEdge, AddressMode::Repeat,         AddressMode::ClampToEdge,
                                 AddressMode::ClampToEdge, AddressMode::MirroredRepeat, AddressMode::ClampToBorder};
    const uint32_t modes[] = {kSampleImplicitLod, kSampleImplicitLod | kSampleBias, kSampleExplicitLod};
    int taken = 0, refused = 0, other_handle = 0;
    for (const Img& im : imgs) {
        std::vector<uint8_t> mem;
        ImageView view = make_view(mem, im.f, im.w, im.h, im.levels, im.pad, rng);
        if (im.prepared) prepare_view(view);
        for (int binding = 0; binding < 100; ++binding) {
            SamplerState smp;
            smp.mag_filter = filters[rng() % std::size(filters)];
            smp.min_filter = filters[rng() % std::size(filters)];
            smp.mipmap_mode = rng() & 1 ? MipmapMode::Linear : MipmapMode::Nearest;
            smp.address_u = wraps[rng() % std::size(wraps)];
            smp.address_v = wraps[rng() % std::size(wraps)];
            if (rng() % 3 == 0) smp.mip_lod_bias = float(int(rng() % 9) - 4) * 0.37f;
            if (rng() % 3 == 0) smp.min_lod = float(rng() % 4) * 0.6f;
            if (rng() % 3 == 0) smp.max_lod = float(rng() % 6) * 0.9f;
            Descriptor desc{{}, &view, &smp}, other{{}, &view, &smp};
            const Descriptor* slots[3] = {&desc, &desc, &other};
            // registers: 0 handle, 1-2 coordinates, 3 lod/bias, 4-7 result; a quarter of the instructions write
            // over their own coordinates
            const uint32_t handle = 1u | (1u << 16);
            const Inst in{Op::Sample, 0, binding % 4 == 3 ? 1u : 4u, 0, 1, 3, modes[rng() % 3], 2};
            std::vector<uint32_t> regs(8 * kLanes);
            for (int l = 0; l < kLanes; ++l) regs[l] = handle;
            BoundSample b;
            const bool bound = jit::bind_sample(in, handle, slots, 3, b);
            ASSERT_EQ(bound, b.state == BoundSample::State::Kernel);
            for (int call = 0; call < 12; ++call) {
                const uint32_t lw = std::max(1u, im.w >> (rng() % im.levels));
                const uint32_t lh = std::max(1u, im.h >> (rng() % im.levels));
                for (int q = 0; q < 4; ++q) {
                    const float cu = edge_coordinate(lw, rng), cv = edge_coordinate(lh, rng);
                    const float d = rng() % 4 == 0 ? 0.0f : std::ldexp(1.0f, int(rng() % 15) - 12);
                    for (int k = 0; k < 4; ++k) {
                        const int l = q * 4 + k;
                        regs[kLanes + l] = fb(cu + d * float(k & 1));
                        regs[2 * kLanes + l] = fb(cv + d * 0.7f * float(k >> 1));
                        regs[3 * kLanes + l] = fb(float(int(rng() % 45) - 12) * 0.25f);
                    }
                }
                // every fourth call names another descriptor (slot 2) in one lane or in all: not the bound handle
                const int other_lanes = call % 4 == 1 ? 1 : call % 4 == 3 ? kLanes : 0;
                for (int l = 0; l < kLanes; ++l) regs[l] = l < other_lanes ? 2u | (2u << 16) : handle;
                std::vector<uint32_t> a = regs, g = regs, ref = regs;
                const bool fast = jit::sample_bound(in, a.data(), b);
                const bool generic = jit::sample_rgba8(in, g.data(), slots, 3);
                exec_image(in, ref.data(), slots, 3);
                if (other_lanes) {
                    ASSERT_FALSE(fast) << "a call with a handle it was not bound to was taken";
                    ASSERT_EQ(a, regs) << "a refused call wrote registers";
                    ++other_handle;
                    continue;
                }
                ASSERT_EQ(fast, generic) << "image " << im.w << "x" << im.h << " binding " << binding << " call "
                                         << call << ": the binding and the per-call kernel disagree";
                if (!fast) {
                    ASSERT_EQ(a, regs) << "a refused call wrote registers";
                    ++refused;
                    continue;
                }
                ++taken;
                ASSERT_EQ(a, ref) << "image " << im.w << "x" << im.h << " binding " << binding << " call " << call
                                  << ": " << first_difference(a, ref);
                ASSERT_EQ(g, ref) << "the per-call kernel: " << first_difference(g, ref);
            }
        }
    }
    std::printf("bound rgba8 sampler: %d calls taken, %d refused, %d with another handle\n", taken, refused,
                other_handle);
    EXPECT_GT(taken, 500);
    EXPECT_GT(refused, 2000);
    EXPECT_GT(other_handle, 3000);
}

// A binding stays what it was bound to: rebinding the same entry to another view (another draw's bindings) takes
// that view's table, and a view that changed after prepare_view is bound with the table rebuilt from it.
TEST_F(BoundSampler, RebindingFollowsTheBindings) {
    std::mt19937 rng(99);
    std::vector<uint8_t> mem[2];
    ImageView v0 = make_view(mem[0], Format::R8G8B8A8_UNORM, 64, 64, 7, 0, rng);
    ImageView v1 = make_view(mem[1], Format::B8G8R8A8_UNORM, 32, 16, 4, 20, rng);
    prepare_view(v0), prepare_view(v1);
    SamplerState smp;
    smp.mag_filter = smp.min_filter = Filter::Linear, smp.mipmap_mode = MipmapMode::Linear;
    const uint32_t handle = 1u | (1u << 16);
    const Inst in{Op::Sample, 0, 4u, 0, 1, 3, kSampleImplicitLod, 2};
    BoundSample b;
    int taken = 0;
    for (int round = 0; round < 40; ++round) {
        ImageView* view = round % 2 ? &v1 : &v0;
        ImageView stale;
        if (round % 5 == 4) {  // v0's fields become v1's without prepare_view: its table is stale
            stale = v0;
            stale.width = v1.width, stale.height = v1.height, stale.levels = v1.levels, stale.level = v1.level;
            stale.base = v1.base;
            view = &stale;
        }
        Descriptor desc{{}, view, &smp};
        const Descriptor* slots[2] = {&desc, &desc};
        ASSERT_TRUE(jit::bind_sample(in, handle, slots, 2, b));
        for (int call = 0; call < 8; ++call) {
            std::vector<uint32_t> regs(8 * kLanes);
            for (int l = 0; l < kLanes; ++l) {
                regs[l] = handle;
                regs[kLanes + l] = fb(edge_coordinate(view->width, rng) + 0.01f * float(l & 1));
                regs[2 * kLanes + l] = fb(edge_coordinate(view->height, rng) + 0.013f * float(l >> 1 & 1));
            }
            std::vector<uint32_t> a = regs, ref = regs;
            const bool fast = jit::sample_bound(in, a.data(), b);
            exec_image(in, ref.data(), slots, 2);
            if (!fast) continue;  // a NaN or infinite LOD: exec_image's
            ++taken;
            ASSERT_EQ(a, ref) << "round " << round << " call " << call << ": " << first_difference(a, ref);
        }
    }
    EXPECT_GT(taken, 250);
}
