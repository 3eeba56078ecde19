#include "case.hpp"

namespace tilevk::cts {

void add_quirk_cases(CaseList& out);   // cases_quirks.cpp
void add_linear_cases(CaseList& out);  // cases_linear.cpp
void add_random_cases(CaseList& out);  // cases_random.cpp

CaseList all_cases() {
    CaseList out;
    add_api_cases(out);
    add_primitive_cases(out);
    add_fill_rule_cases(out);
    add_culling_cases(out);
    add_interpolation_cases(out);
    add_multisample_cases(out);
    add_depth_cases(out);
    add_stencil_cases(out);
    add_blend_cases(out);
    add_viewport_cases(out);
    add_texture_cases(out);
    add_mesh_cases(out);
    add_quirk_cases(out);
    add_blit_cases(out);
    add_query_cases(out);
    add_linear_cases(out);
    add_random_cases(out);
    return out;
}

}  // namespace tilevk::cts
