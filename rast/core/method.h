// Coverage methods, chosen at run time (TILEVK_RAST=reference|bbox|hier|float).
#pragma once

#include <optional>
#include <string_view>

namespace tilevk::rast {

enum class Method {
    kReference,  // brute force per sample over the bbox, 64-bit: the oracle
    kBBox,       // Giesen-style bounding-box scan in 4x4 blocks, incremental 32-bit edges, SIMD
    kHier,       // Larrabee hierarchy 64->16->4 with trivial accept/reject (default)
    kFloat,      // unsnapped float edge functions: the naive baseline (expected to mismatch sometimes)
};

const char* to_string(Method m);
std::optional<Method> parse_method(std::string_view name);
// TILEVK_RAST if set and valid (an invalid value logs once to stderr), else kHier.
Method method_from_env();

}  // namespace tilevk::rast
