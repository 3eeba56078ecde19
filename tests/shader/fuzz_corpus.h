// The shader fuzz corpus: four real shaders and seeded mutations of their SPIR-V (cts_subset/spirv_mutator.hpp:
// truncation, word garbling, instruction deletion/duplication/swap, operand id replacement, opcode replacement,
// header damage). Shared by fuzz_test.cpp (every variant fails cleanly or runs) and jit_diff_test.cpp (every variant
// that runs gives the same bits in both tiers).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "shader/program.h"
#include "spirv_mutator.hpp"

namespace tilevk::shader::test::fuzz {

struct Source {
    Stage stage;
    const char* glsl;
};

inline const Source kSources[] = {
    {Stage::Fragment, R"(#version 450
        layout(location=0) in vec4 v;
        layout(location=0) out vec4 color;
        layout(set=0, binding=0) uniform sampler2D tex;
        void main() {
            vec4 c = texture(tex, v.xy);
            for (int i = 0; i < 4; ++i) { if (c.x > v.z) break; c += v; }
            color = c;
        })"},
    {Stage::Vertex, R"(#version 450
        layout(set=0, binding=0, std140) uniform U { mat4 mvp; mat3 nrm; vec4 light; } u;
        layout(location=0) in vec3 pos;
        layout(location=1) in vec3 normal;
        layout(location=0) out vec3 n;
        layout(location=1) out float d;
        void main() {
            gl_Position = u.mvp * vec4(pos, 1.0);
            n = normalize(u.nrm * normal);
            d = max(dot(n, normalize(u.light.xyz)), 0.0);
        })"},
    {Stage::Fragment, R"(#version 450
        layout(location=0) flat in int idx;
        layout(location=1) in vec4 v;
        layout(location=0) out vec4 color;
        layout(set=0, binding=0, std430) buffer S { uint data[]; } s;
        void main() {
            uint acc = 0u;
            for (int i = 0; i < idx; ++i) {
                switch (i % 3) { case 0: acc += s.data[i]; break; case 1: acc ^= uint(i); default: acc += 1u; }
                if (acc > 100u) discard;
                s.data[idx] = acc;
            }
            color = vec4(float(acc), dFdx(v.x), fwidth(v.y), float(s.data.length()));
        })"},
    {Stage::Fragment, R"(#version 450
        layout(location=0) in vec4 v;
        layout(location=0) out vec4 color;
        layout(push_constant) uniform P { vec4 k; int n; } p;
        float f(float x) { return x < 0.0 ? -x : sqrt(x); }
        void main() {
            mat3 m = mat3(v.xyz, v.yzw, v.zwx);
            vec3 w; vec3 fr = modf(v.xyz * 3.7, w);
            ivec3 e; vec3 sg = frexp(v.xyz, e);
            float acc = determinant(m) + inverse(m)[1].y;
            int i = 0;
            do { acc += f(v[i & 3]) * p.k[i & 3]; i++; } while (i < p.n && i < 16);
            color = vec4(acc, fr.x + w.y, sg.z + float(e.x), pow(abs(v.w), 2.2));
        })"},
};

// The mutator is the fuzzers' one (cts_subset/spirv_mutator.hpp, also used by tilevk-cts --fuzz).
using tilevk::fuzz::mutate;

// The seeds: 0xC0FFEE + source by default (CI's fixed window); TILEVK_FUZZ_SPIRV_SEED=N starts the window at
// N + source instead (the main job passes the date, tools/run_main.sh), printed by fuzz_test so a failure can be
// reproduced.
inline uint32_t base_seed() {
    const char* env = std::getenv("TILEVK_FUZZ_SPIRV_SEED");
    return env ? uint32_t(std::strtoul(env, nullptr, 0)) : 0xC0FFEEu;
}

struct Variants {
    explicit Variants(size_t si) : rng(uint32_t(base_seed() + si)) {}
    std::vector<uint32_t> next(const std::vector<uint32_t>& spirv) {
        std::vector<uint32_t> m = mutate(spirv, rng);
        if (rng() % 4 == 0) m = m.size() > 6 ? mutate(m, rng) : m;
        return m;
    }
    std::mt19937 rng;
};
constexpr int kVariantsPerSource = 1000;

}  // namespace tilevk::shader::test::fuzz
