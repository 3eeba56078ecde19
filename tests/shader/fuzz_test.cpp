// Fuzz-style robustness (issue #4): thousands of seeded mutations of real shaders' SPIR-V through
// Program::create. Every variant must give either a clear error or a valid program that runs; never a crash,
// never a hang. Mutations: truncation, word garbling, instruction deletion/duplication/swap, operand id
// replacement, opcode replacement, header damage.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::compile_glsl;

namespace {

struct Source {
    Stage stage;
    const char* glsl;
};

const Source kSources[] = {
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

// Instruction start offsets of a module (stops at the first malformed word count).
std::vector<size_t> instruction_starts(const std::vector<uint32_t>& m) {
    std::vector<size_t> at;
    for (size_t i = 5; i < m.size();) {
        uint32_t n = m[i] >> 16;
        if (n == 0 || i + n > m.size()) break;
        at.push_back(i);
        i += n;
    }
    return at;
}

std::vector<uint32_t> mutate(const std::vector<uint32_t>& src, std::mt19937& rng) {
    std::vector<uint32_t> m = src;
    auto starts = instruction_starts(m);
    auto pick = [&](size_t n) { return size_t(rng() % n); };
    int kind = int(rng() % 9);
    switch (kind) {
        case 0:  // truncate anywhere
            m.resize(pick(m.size()));
            break;
        case 1:  // garble 1-3 words
            for (int e = 1 + int(rng() % 3); e > 0; --e) {
                size_t at = 5 + pick(m.size() - 5);
                m[at] = (rng() & 1) ? uint32_t(rng()) : m[at] ^ (1u << (rng() % 32));
            }
            break;
        case 2: {  // delete an instruction
            size_t i = pick(starts.size());
            size_t b = starts[i], n = m[b] >> 16;
            m.erase(m.begin() + long(b), m.begin() + long(b + n));
            break;
        }
        case 3: {  // duplicate an instruction
            size_t i = pick(starts.size());
            size_t b = starts[i], n = m[b] >> 16;
            std::vector<uint32_t> copy(m.begin() + long(b), m.begin() + long(b + n));
            size_t to = starts[pick(starts.size())];
            m.insert(m.begin() + long(to), copy.begin(), copy.end());
            break;
        }
        case 4: {  // swap two instructions
            size_t i = pick(starts.size()), j = pick(starts.size());
            if (i > j) std::swap(i, j);
            if (i == j) break;
            size_t bi = starts[i], ni = m[bi] >> 16, bj = starts[j], nj = m[bj] >> 16;
            std::vector<uint32_t> a(m.begin() + long(bi), m.begin() + long(bi + ni));
            std::vector<uint32_t> b(m.begin() + long(bj), m.begin() + long(bj + nj));
            std::vector<uint32_t> out(m.begin(), m.begin() + long(bi));
            out.insert(out.end(), b.begin(), b.end());
            out.insert(out.end(), m.begin() + long(bi + ni), m.begin() + long(bj));
            out.insert(out.end(), a.begin(), a.end());
            out.insert(out.end(), m.begin() + long(bj + nj), m.end());
            m = out;
            break;
        }
        case 5: {  // replace an operand word by another id below the bound (type confusion, wrong targets)
            size_t i = pick(starts.size());
            size_t b = starts[i], n = m[b] >> 16;
            if (n > 1) m[b + 1 + pick(n - 1)] = 1 + uint32_t(rng() % std::max(1u, m[3] - 1));
            break;
        }
        case 6: {  // replace an opcode, keeping the word count
            size_t b = starts[pick(starts.size())];
            m[b] = (m[b] & 0xffff0000u) | (rng() % 420);
            break;
        }
        case 7: {  // small values into operands: literals, indices, storage classes, dims
            size_t i = pick(starts.size());
            size_t b = starts[i], n = m[b] >> 16;
            if (n > 1) m[b + 1 + pick(n - 1)] = uint32_t(rng() % 8);
            break;
        }
        default:  // header damage: version, bound, schema
            m[1 + pick(4)] = (rng() & 1) ? uint32_t(rng()) : uint32_t(rng() % 0x20000);
            break;
    }
    return m;
}

}  // namespace

TEST(ShaderFuzz, MutatedModulesFailCleanlyOrRun) {
    const int kPerSource = 1000;
    int created = 0, total = 0;
    uint64_t cut = 0;  // runs stopped by the loop watchdog (a mutation made a loop infinite)
    for (size_t si = 0; si < std::size(kSources); ++si) {
        const Source& src = kSources[si];
        auto spirv = compile_glsl(src.stage, src.glsl);
        ASSERT_FALSE(spirv.empty()) << si;
        Result base = Program::create(spirv, src.stage);
        ASSERT_TRUE(base) << si << ": " << base.error;
        std::mt19937 rng(uint32_t(0xC0FFEE + si));
        for (int iter = 0; iter < kPerSource; ++iter) {
            std::vector<uint32_t> m = mutate(spirv, rng);
            // a second mutation now and then
            if (rng() % 4 == 0) m = m.size() > 6 ? mutate(m, rng) : m;
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
    EXPECT_EQ(total, int(std::size(kSources)) * kPerSource);
}
