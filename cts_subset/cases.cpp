#include "case.hpp"

namespace tilevk::cts {

void add_quirk_cases(CaseList& out);    // cases_quirks.cpp
void add_transcendental_cases(CaseList& out);  // cases_transcendental.cpp
void add_linear_cases(CaseList& out);   // cases_linear.cpp
void add_random_cases(CaseList& out);   // cases_random.cpp
void add_random_compute_cases(CaseList& out);  // cases_random_compute.cpp
void add_feature_cases(CaseList& out);  // cases_features.cpp
void add_pipeline_ext_cases(CaseList& out);  // cases_pipeline_ext.cpp
void add_extreme_cases(CaseList& out);  // cases_extreme.cpp
void add_format_cases(CaseList& out);   // cases_formats.cpp
void add_compute_cases(CaseList& out);  // cases_compute.cpp
void add_clipping_cases(CaseList& out);  // cases_clipping.cpp
void add_types_cases(CaseList& out);     // cases_types.cpp: 64-bit integers and doubles
void add_types_narrow_cases(CaseList& out);  // cases_types_narrow.cpp: 8- and 16-bit integers and storage

// dynamic.*: cases of the groups whose state extended dynamic state 1 and 2 can set, again with every such state
// set by vkCmdSet* on a pipeline made with other values (Draw::dynamic, render.cpp): culling, primitives (strips,
// fans, restart), depth, stencil, viewports and scissors, logic ops, list restart.
// dynamic.vertex_input_eds3.*: those groups and the ones whose state extended dynamic state 3 sets (blending and
// write masks, sample masks, alpha to coverage/one, polygon modes, provoking vertex, line modes, depth clamp and
// clip, [-w, w] depth), with the vertex input (VK_EXT_vertex_input_dynamic_state) and every extended dynamic
// state 3 state tilevk reports set by vkCmdSet* as well (Draw::dynamic3).
void add_dynamic_state_cases(CaseList& out) {
    const char* const groups[] = {
        "rasterization.culling.", "rasterization.primitives.", "depth.", "stencil.", "viewport.", "scissor.partial",
        "feature.logic_op.",      "feature.list_restart."};
    const char* const groups3[] = {"blend.",
                                   "overdraw.write_mask",
                                   "quirks.sample_mask.",
                                   "quirks.unfilled.",
                                   "feature.alpha_to_one.",
                                   "feature.depth_clip_control.",
                                   "rasterization.provoking_vertex.",
                                   "rasterization.line.",
                                   "clipping.depth_clip_enable.",
                                   "multisample.sample_shading.min"};
    auto in = [](const std::string& name, const auto& list) {
        for (const char* g : list)
            if (name.rfind(g, 0) == 0) return true;
        return false;
    };
    const size_t n = out.size();
    for (int level = 2; level <= 3; ++level)
        for (size_t i = 0; i < n; ++i) {
            const Case& c = out[i];
            if (!in(c.name, groups) && !(level == 3 && in(c.name, groups3))) continue;
            Case d = c;
            d.name = (level == 2 ? "dynamic." : "dynamic.vertex_input_eds3.") + c.name;
            d.scene = [make = c.scene, level] {
                Scene s = make();
                for (Draw& draw : s.draws) draw.dynamic = true, draw.dynamic3 = level == 3;
                return s;
            };
            out.push_back(std::move(d));
        }
}

CaseList all_cases() {
    CaseList out;
    // extreme.* first: its fragment results depend on subnormals, and lavapipe 22.3.6's rasterizer threads keep
    // denormals for good once a half-float target's blend meets an empty block (docs/lavapipe-rules.md §0.2). Before
    // any such case, they flush them as documented.
    add_extreme_cases(out);
    add_api_cases(out);
    add_primitive_cases(out);
    add_fill_rule_cases(out);
    add_culling_cases(out);
    add_clipping_cases(out);
    add_raster_ext_cases(out);
    add_interpolation_cases(out);
    add_interpolate_at_cases(out);
    add_multisample_cases(out);
    add_depth_cases(out);
    add_stencil_cases(out);
    add_blend_cases(out);
    add_overdraw_cases(out);
    add_viewport_cases(out);
    add_texture_cases(out);
    add_texture_3d_cases(out);
    add_texture_1d_cases(out);
    add_texture_cube_cases(out);
    add_texture_bc_cases(out);
    add_texture_aniso_cases(out);
    add_mesh_cases(out);
    add_quirk_cases(out);
    add_transcendental_cases(out);
    add_blit_cases(out);
    add_query_cases(out);
    add_statistics_cases(out);
    add_feature_cases(out);
    add_pipeline_ext_cases(out);
    add_format_cases(out);
    add_compute_cases(out);
    add_types_cases(out);
    add_types_narrow_cases(out);
    add_linear_cases(out);
    add_random_cases(out);
    add_random_compute_cases(out);
    add_dynamic_state_cases(out);
    return out;
}

}  // namespace tilevk::cts
