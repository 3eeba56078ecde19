#include "rast/render/linear_mode.h"

#include <cstring>

namespace tilevk::rast::render {

bool lavapipe_linear_mode(const BoundFramebuffer& fb) {
    if (fb.color_buffers != 1 || fb.depth_stencil_bound || !fb.color0_bound) return false;
    return fb.color0_format == format::Format::B8G8R8A8_UNORM && fb.color0_samples == 1 && fb.color0_array_layers == 1;
}

void choose_linear_shading(bool linear_mode, const PipelineState& pipe, DrawRecord& rec) {
    rec.linear_slot = -1;
    // lp_fs_linear_run: every float of constant buffer 0 (the fragment push constants) must lie in [0, 1].
    bool constants_in_range = true;
    for (uint32_t off = 0; off + 4 <= pipe.fragment_push_constant_bytes; off += 4) {
        float v = 0.0f;
        if (off + 4 <= rec.push_constants.size()) std::memcpy(&v, rec.push_constants.data() + off, 4);
        constants_in_range = constants_in_range && !(v < 0.0f || v > 1.0f);
    }
    rec.linear = false;
    // lp_state_fs.c linear_pipeline: a logic op keeps the draw off the linear path. Alpha to one is kept off it
    // too (tilevk's linear shading has no alpha override).
    const bool linear_state = !pipe.blend[0].logic_op_enable && !pipe.alpha_to_one;
    if (!linear_mode || !pipe.fragment || !constants_in_range || !linear_state) return;
    // llvmpipe's linear variant (lp_state_fs.c, lp_linear.c) for the class shader/ recognises.
    const shader::Program::LinearShader ls = pipe.fragment->linear_shader();
    int slot = -1;
    bool perspective = true, found = ls.location < 0;
    for (size_t k = 0; ls.ok && ls.location >= 0 && k < rec.varyings.slot_location.size(); ++k)
        if (int(rec.varyings.slot_location[k]) == ls.location &&
            rec.varyings.slot_interp[k] != geometry::Interp::kFlat) {
            slot = static_cast<int>(k);
            perspective = rec.varyings.slot_interp[k] == geometry::Interp::kPerspective;
            found = true;
        }
    if (!ls.ok || !found) return;
    rec.linear = true;
    rec.linear_slot = slot;
    rec.linear_perspective = perspective;
    for (int c = 0; c < 4; ++c) {
        rec.linear_channels.source[c] = ls.source[c];
        rec.linear_channels.constant[c] = ls.constant[c];
    }
    rec.linear_channels.usage = ls.usage;
}

}  // namespace tilevk::rast::render
