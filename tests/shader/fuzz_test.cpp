// Fuzz-style robustness: thousands of seeded mutations of real shaders' SPIR-V (fuzz_corpus.h) through
// Program::create. Every variant must give either a clear error or a valid program that runs; never a crash,
// never a hang.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "fuzz_corpus.h"
#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::compile_glsl;
using namespace tilevk::shader::test::fuzz;

TEST(ShaderFuzz, MutatedModulesFailCleanlyOrRun) {
    std::printf("fuzz: TILEVK_FUZZ_SPIRV_SEED=%u\n", base_seed());
    int created = 0, total = 0;
    uint64_t cut = 0;  // runs stopped by the loop watchdog (a mutation made a loop infinite)
    for (size_t si = 0; si < std::size(kSources); ++si) {
        const Source& src = kSources[si];
        auto spirv = compile_glsl(src.stage, src.glsl);
        ASSERT_FALSE(spirv.empty()) << si;
        Result base = Program::create(spirv, src.stage);
        ASSERT_TRUE(base) << si << ": " << base.error;
        Variants variants(si);
        for (int iter = 0; iter < kVariantsPerSource; ++iter) {
            std::vector<uint32_t> m = variants.next(spirv);
            ++total;
            Result r = Program::create(m, src.stage);
            if (!r) {
                EXPECT_FALSE(r.error.empty()) << "source " << si << " iteration " << iter;
                continue;
            }
            ++created;
            // A module that still validates and translates must run safely (bounds-checked, no traps).
            Scratch s;
            if (src.stage == Stage::Fragment) {
                FragmentBlock fb;
                for (int l = 0; l < kLanes; ++l) fb.inputs[0][0][l] = uint32_t(l);
                r.program->run_fragment(Bindings{}, fb, s);
            } else {
                VertexBatch vb;
                r.program->run_vertex(Bindings{}, vb, s);
            }
            cut += s.loop_limit_hits();
        }
    }
    std::printf("fuzz: %d variants, %d still valid and ran (%d cut by the loop watchdog), %d rejected with a message\n",
                total, created, int(cut), total - created);
    EXPECT_EQ(total, int(std::size(kSources)) * kVariantsPerSource);
}
