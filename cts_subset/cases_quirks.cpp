// quirks.*: lavapipe behaviours that no Vulkan rule asks for but real applications run into — a zero sample
// mask, llvmpipe's 9-vertex triangle-list analysis, draw's vertex batches (which decide the clipper/float-cull
// path), and draw's pipeline stages for polygonMode LINE/POINT (clipper edge flags, offset, flatshade, point size).
// Judged byte for byte against lavapipe; where an outcome is analytic (nothing drawn) it is also checked.
#include "case.hpp"

namespace tilevk::cts {
namespace {

const std::array<float, 4> kRed = {1, 0, 0, 1}, kGreen = {0, 1, 0, 1}, kBlue = {0, 0, 1, 1}, kWhite = {1, 1, 1, 1};

// Every colour pixel is the clear colour (transparent black).
Check nothing_drawn() {
    return palette_only({rgba8(0, 0, 0, 0)});
}

Draw triangle(std::array<float, 4> c = kWhite) {
    Draw d;
    d.vertices = {vtx(-0.8f, -0.7f, 0.5f, 1, kRed), vtx(0.9f, -0.5f, 0.5f, 1, kGreen), vtx(-0.2f, 0.8f, 0.5f, 1, c)};
    return d;
}

void add_sample_mask_cases(CaseList& out) {
    // lp_state_derived.c: sample_mask == 0 sets rasterizer_discard, at any sample count.
    out.push_back({"quirks.sample_mask.zero_1x",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0;
                       return one_draw(d);
                   },
                   nothing_drawn(), ""});
    out.push_back({"quirks.sample_mask.zero_1x_depth",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0;
                       d.depth_test = d.depth_write = true;
                       d.depth_op = VK_COMPARE_OP_ALWAYS;
                       Scene s = one_draw(d);
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       return s;
                   },
                   nothing_drawn(), ""});
    out.push_back({"quirks.sample_mask.zero_4x",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0;
                       Scene s = one_draw(d);
                       s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                       return s;
                   },
                   nothing_drawn(), ""});
    // Bits above the sample count: not zero, so no discard; at 1x the mask is not applied at all.
    out.push_back({"quirks.sample_mask.high_bits_1x",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0x10;
                       return one_draw(d);
                   },
                   Check(), ""});
}

}  // namespace

void add_quirk_cases(CaseList& out) {
    add_sample_mask_cases(out);
}

}  // namespace tilevk::cts
