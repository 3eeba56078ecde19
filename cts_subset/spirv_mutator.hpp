// The SPIR-V mutator of the fuzzers (tests/shader/fuzz_test.cpp through Program::create, tilevk-cts --fuzz
// through vkCreateShaderModule/vkCreateGraphicsPipelines): one seeded structural mutation of a module — truncation,
// word garbling, instruction deletion/duplication/swap, operand id replacement, opcode replacement, small operand
// values, header damage.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace tilevk::fuzz {

// Instruction start offsets of a module (stops at the first malformed word count).
inline std::vector<size_t> instruction_starts(const std::vector<uint32_t>& m) {
    std::vector<size_t> at;
    for (size_t i = 5; i < m.size();) {
        uint32_t n = m[i] >> 16;
        if (n == 0 || i + n > m.size()) break;
        at.push_back(i);
        i += n;
    }
    return at;
}

inline std::vector<uint32_t> mutate(const std::vector<uint32_t>& src, std::mt19937& rng) {
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

}  // namespace tilevk::fuzz
