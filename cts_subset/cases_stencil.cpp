// stencil.*: every stencil op on the pass, fail and depth-fail paths, every compare op, and the masks.
// The stencil aspect is read back and compared byte for byte, as is the colour.
#include "case.hpp"

namespace tilevk::cts {
namespace {

VkStencilOpState state(VkCompareOp cmp, VkStencilOp pass, VkStencilOp fail, VkStencilOp dfail, uint32_t ref,
                       uint32_t cmask = 0xFF, uint32_t wmask = 0xFF) {
    return {fail, pass, dfail, cmp, cmask, wmask, ref};
}

// Stencil starts at 5; a first triangle REPLACEs 0xFE (so clamping and wrapping both show); then `under_test`
// is drawn over a quad that overlaps both regions, with depth at 0.5 against a cleared 1.0 (or 0.0 to force
// depth failure).
Scene stencil_scene(VkFormat format, VkStencilOpState front, VkStencilOpState back, bool depth_fail) {
    Draw seed;
    seed.stencil_test = true;
    seed.stencil_front = seed.stencil_back =
        state(VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_REPLACE, VK_STENCIL_OP_KEEP, VK_STENCIL_OP_KEEP, 0xFE);
    seed.vertices = {vtx(-1, -1, 0.5f, 1, {0.2f, 0.2f, 0.2f, 1}), vtx(0.5f, -1, 0.5f, 1, {0.2f, 0.2f, 0.2f, 1}),
                     vtx(-1, 0.6f, 0.5f, 1, {0.2f, 0.2f, 0.2f, 1})};
    seed.depth_test = true;
    seed.depth_op = VK_COMPARE_OP_ALWAYS;
    Draw test;
    test.stencil_test = true;
    test.depth_test = true;
    test.depth_op = depth_fail ? VK_COMPARE_OP_NEVER : VK_COMPARE_OP_ALWAYS;
    test.stencil_front = front;
    test.stencil_back = back;
    // One front-facing and one back-facing triangle (CCW is front by default).
    std::array<float, 4> c = {0, 1, 0, 1};
    test.vertices = {vtx(-0.8f, -0.8f, 0.5f, 1, c), vtx(0.9f, -0.8f, 0.5f, 1, c), vtx(-0.8f, 0.9f, 0.5f, 1, c),
                     vtx(0.9f, -0.7f, 0.5f, 1, c),  vtx(0.9f, 0.9f, 0.5f, 1, c),  vtx(-0.7f, 0.9f, 0.5f, 1, c)};
    Scene s = one_draw(seed);
    s.draws.push_back(test);
    s.target.depth = format;
    s.target.clear_stencil = 5;
    return s;
}

}  // namespace

void add_stencil_cases(CaseList& out) {
    struct Op {
        const char* name;
        VkStencilOp op;
    };
    const Op ops[] = {{"keep", VK_STENCIL_OP_KEEP},
                      {"zero", VK_STENCIL_OP_ZERO},
                      {"replace", VK_STENCIL_OP_REPLACE},
                      {"incr_clamp", VK_STENCIL_OP_INCREMENT_AND_CLAMP},
                      {"decr_clamp", VK_STENCIL_OP_DECREMENT_AND_CLAMP},
                      {"invert", VK_STENCIL_OP_INVERT},
                      {"incr_wrap", VK_STENCIL_OP_INCREMENT_AND_WRAP},
                      {"decr_wrap", VK_STENCIL_OP_DECREMENT_AND_WRAP}};
    const VkFormat fmt = VK_FORMAT_D24_UNORM_S8_UINT;
    const VkStencilOp K = VK_STENCIL_OP_KEEP;
    for (const Op& o : ops) {
        auto pass = state(VK_COMPARE_OP_ALWAYS, o.op, K, K, 0x3C);
        out.push_back({std::string("stencil.op.pass_") + o.name, [=] { return stencil_scene(fmt, pass, pass, false); },
                       nullptr, ""});
    }
    for (const Op& o : {ops[2], ops[4], ops[6]}) {
        auto fail = state(VK_COMPARE_OP_NEVER, K, o.op, K, 0x3C);
        out.push_back({std::string("stencil.op.fail_") + o.name, [=] { return stencil_scene(fmt, fail, fail, false); },
                       nullptr, ""});
        auto dfail = state(VK_COMPARE_OP_ALWAYS, K, K, o.op, 0x3C);
        out.push_back({std::string("stencil.op.depth_fail_") + o.name,
                       [=] { return stencil_scene(fmt, dfail, dfail, true); }, nullptr, ""});
    }
    struct Cmp {
        const char* name;
        VkCompareOp op;
    };
    const Cmp cmps[] = {{"never", VK_COMPARE_OP_NEVER},
                        {"less", VK_COMPARE_OP_LESS},
                        {"equal", VK_COMPARE_OP_EQUAL},
                        {"less_or_equal", VK_COMPARE_OP_LESS_OR_EQUAL},
                        {"greater", VK_COMPARE_OP_GREATER},
                        {"not_equal", VK_COMPARE_OP_NOT_EQUAL},
                        {"greater_or_equal", VK_COMPARE_OP_GREATER_OR_EQUAL},
                        {"always", VK_COMPARE_OP_ALWAYS}};
    for (const Cmp& c : cmps) {
        // Reference 0x80 lies between the cleared 5 and the seeded 0xFE, so each op splits the quad differently.
        auto st = state(c.op, VK_STENCIL_OP_INCREMENT_AND_WRAP, VK_STENCIL_OP_INVERT, K, 0x80);
        out.push_back({std::string("stencil.compare.") + c.name, [=] { return stencil_scene(fmt, st, st, false); },
                       // NEVER: only the clear and the seed triangle (0.2 -> unorm8 51) may show.
                       c.op == VK_COMPARE_OP_NEVER ? palette_only({0, rgba8(51, 51, 51, 255)}) : Check(), ""});
    }
    auto masked = [&](const char* name, uint32_t cmask, uint32_t wmask) {
        auto st =
            state(VK_COMPARE_OP_EQUAL, VK_STENCIL_OP_INVERT, VK_STENCIL_OP_INCREMENT_AND_WRAP, K, 0x04, cmask, wmask);
        out.push_back(
            {std::string("stencil.mask.") + name, [=] { return stencil_scene(fmt, st, st, false); }, nullptr, ""});
    };
    masked("compare_mask_0x0c", 0x0C, 0xFF);
    masked("write_mask_0x0f", 0xFF, 0x0F);
    masked("both_masks", 0x06, 0xF0);
    auto front = state(VK_COMPARE_OP_ALWAYS, VK_STENCIL_OP_REPLACE, K, K, 0x11);
    auto back = state(VK_COMPARE_OP_GREATER, VK_STENCIL_OP_INCREMENT_AND_CLAMP, VK_STENCIL_OP_ZERO, K, 0x40);
    out.push_back({"stencil.two_sided", [=] { return stencil_scene(fmt, front, back, false); }, nullptr, ""});
    out.push_back({"stencil.two_sided_d32s8",
                   [=] { return stencil_scene(VK_FORMAT_D32_SFLOAT_S8_UINT, front, back, false); }, nullptr, ""});
    // S8_UINT: stencil without depth (the scene's depth test has nothing to test), at 1x and 4x.
    for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT})
        out.push_back({std::string("stencil.two_sided_s8") + (samples == VK_SAMPLE_COUNT_4_BIT ? "_4x" : ""),
                       [=] {
                           Scene s = stencil_scene(VK_FORMAT_S8_UINT, front, back, false);
                           s.target.samples = samples;
                           return s;
                       },
                       nullptr, ""});
    // Polygon modes LINE/POINT: lavapipe's edges and corners are front facing (front stencil state) unless the
    // fragment shader reads gl_FrontFacing, which makes draw inject the triangle's facing (found by the random
    // scene fuzzer, seeds 429/508/730/770 of 49..848: tilevk used the triangle's facing always).
    for (VkPolygonMode mode : {VK_POLYGON_MODE_LINE, VK_POLYGON_MODE_POINT})
        for (bool reads_facing : {false, true}) {
            const std::string name = std::string("stencil.two_sided_polygon_mode_") +
                                     (mode == VK_POLYGON_MODE_LINE ? "line" : "point") +
                                     (reads_facing ? "_reads_facing" : "");
            out.push_back({name,
                           [=] {
                               Scene s = stencil_scene(fmt, front, back, false);
                               s.draws[1].polygon_mode = mode;
                               if (reads_facing) s.draws[1].frag = Frag::kFacing;
                               return s;
                           },
                           nullptr, ""});
        }
}

}  // namespace tilevk::cts
