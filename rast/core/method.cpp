#include "rast/core/method.h"

#include <cstdio>
#include <cstdlib>

namespace tilevk::rast {

const char* to_string(Method m) {
    switch (m) {
        case Method::kReference:
            return "reference";
        case Method::kBBox:
            return "bbox";
        case Method::kHier:
            return "hier";
        case Method::kFloat:
            return "float";
    }
    return "?";
}

std::optional<Method> parse_method(std::string_view name) {
    for (Method m : {Method::kReference, Method::kBBox, Method::kHier, Method::kFloat})
        if (name == to_string(m)) return m;
    return std::nullopt;
}

Method method_from_env() {
    const char* env = std::getenv("TILEVK_RAST");
    if (!env || !*env) return Method::kHier;
    if (auto m = parse_method(env)) return *m;
    static bool logged = false;
    if (!logged) {
        logged = true;
        std::fprintf(stderr, "tilevk: TILEVK_RAST=%s is not one of reference|bbox|hier|float; using hier\n", env);
    }
    return Method::kHier;
}

}  // namespace tilevk::rast
