// The rasterization extensions (suite RasterExtensions): VK_EXT_provoking_vertex, VK_EXT_depth_clip_enable and
// VK_EXT_line_rasterization (rectangular and Bresenham lines), enabled on tilevk and lavapipe with
// the validation layer on, drawn and compared byte for byte and against the colours the rule gives; what tilevk
// reports for it; and, on a device without the validation layer, the pipeline states tilevk refuses by name.
// (Every feature member is also requested exactly when reported by honest_reports_test.cpp.)
#include <optional>

#include "api_breadth.h"
// after api_breadth.h, which includes <cstdint> for the generated arrays
#include "ab_flat_frag.h"
#include "ab_flat_vert.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

class RasterExtensions : public ApiBreadth {};

uint32_t pixel(const Bytes& img, uint32_t x, uint32_t y, uint32_t w = 32) {
    uint32_t p;
    std::memcpy(&p, img.data() + (size_t(y) * w + x) * 4, 4);
    return p;
}
constexpr uint32_t kRed = 0xff0000ffu, kGreen = 0xff00ff00u, kBlue = 0xffff0000u, kWhite = 0xffffffffu;

// One draw of `verts` with pipeline `p` (its render pass set here) into a 32x32 RGBA8 target cleared to black.
Bytes draw_into_target(Kit& k, Pipe p, const std::vector<Vertex>& verts) {
    Target t = target(k);
    p.rp = t.rp;
    VkPipeline pipe = k.pipeline(p);
    Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        VkDeviceSize off = 0;
        vkCmdBindVertexBuffers(c, 0, 1, &vb.buffer, &off);
        vkCmdDraw(c, uint32_t(verts.size()), 1, 0, 0);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 4);
}

// One draw of `verts` as `topology` with ab_flat's flat colour into a 32x32 RGBA8 target cleared to black.
Bytes flat_draw(Kit& k, VkPrimitiveTopology topology, const std::vector<Vertex>& verts, const void* rs_chain,
                float line_width = 1.0f) {
    Pipe p;
    p.vs = SPV(ab_flat_vert);
    p.fs = SPV(ab_flat_frag);
    p.topology = topology;
    p.rasterization_pnext = rs_chain;
    p.line_width = line_width;
    return draw_into_target(k, p, verts);
}

// A strip of four corners coloured red, green, blue, white (pixel (4, 16) in its first triangle, (27, 16) in its
// second), a 5-vertex fan around the centre, and a line strip: the provoking vertex decides every colour.
TEST_F(RasterExtensions, ProvokingVertexLastOnStripsFansAndLines) {
    VkPhysicalDeviceProvokingVertexFeaturesEXT feature{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT};
    feature.provokingVertexLast = VK_TRUE;
    auto dev = device_pair({VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME}, &feature);
    ASSERT_TRUE(dev->ok());
    const std::vector<Vertex> strip = {v(-1, -1, 0, 1, 0, 0), v(-1, 1, 0, 0, 1, 0), v(1, -1, 0, 0, 0, 1),
                                       v(1, 1, 0, 1, 1, 1)};
    // Fan: centre white, then red, green, blue corners: triangles (c, r, g) and (c, g, b).
    const std::vector<Vertex> fan = {v(0, 0, 0, 1, 1, 1), v(-1, -1, 0, 1, 0, 0), v(1, -1, 0, 0, 1, 0),
                                     v(1, 1, 0, 0, 0, 1)};
    // Line strip along row 8 then down column 24: red -> green -> blue.
    const std::vector<Vertex> lines = {v(-0.75f, -0.46875f, 0, 1, 0, 0), v(0.5f, -0.46875f, 0, 0, 1, 0),
                                       v(0.53125f, 0.75f, 0, 0, 0, 1)};
    for (VkProvokingVertexModeEXT mode :
         {VK_PROVOKING_VERTEX_MODE_FIRST_VERTEX_EXT, VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT}) {
        VkPipelineRasterizationProvokingVertexStateCreateInfoEXT pv{
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_PROVOKING_VERTEX_STATE_CREATE_INFO_EXT};
        pv.provokingVertexMode = mode;
        const bool last = mode == VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT;
        const Bytes s = both_on(dev->tilevk, dev->lavapipe,
                                [&](Kit& k) { return flat_draw(k, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, strip, &pv); });
        EXPECT_EQ(pixel(s, 4, 16), last ? kBlue : kRed) << mode;
        EXPECT_EQ(pixel(s, 27, 16), last ? kWhite : kGreen) << mode;
        const Bytes f = both_on(dev->tilevk, dev->lavapipe,
                                [&](Kit& k) { return flat_draw(k, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, fan, &pv); });
        EXPECT_EQ(pixel(f, 16, 4), last ? kGreen : kRed) << mode;    // (c, r, g): first is r (the fan's order)
        EXPECT_EQ(pixel(f, 27, 16), last ? kBlue : kGreen) << mode;  // (c, g, b)
        const Bytes l = both_on(dev->tilevk, dev->lavapipe,
                                [&](Kit& k) { return flat_draw(k, VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, lines, &pv); });
        EXPECT_EQ(pixel(l, 10, 8), last ? kGreen : kRed) << mode;
        EXPECT_EQ(pixel(l, 24, 20), last ? kBlue : kGreen) << mode;
    }
}

// What tilevk reports: the last vertex may provoke, per pipeline; no transform feedback to preserve it in.
TEST_F(RasterExtensions, ProvokingVertexReports) {
    VkPhysicalDeviceProvokingVertexFeaturesEXT f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f};
    vkGetPhysicalDeviceFeatures2(tilevk_->physical(), &f2);
    EXPECT_EQ(f.provokingVertexLast, VK_TRUE);
    EXPECT_EQ(f.transformFeedbackPreservesProvokingVertex, VK_FALSE);
    VkPhysicalDeviceProvokingVertexPropertiesEXT p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p};
    vkGetPhysicalDeviceProperties2(tilevk_->physical(), &p2);
    EXPECT_EQ(p.provokingVertexModePerPipeline, VK_TRUE);
    EXPECT_EQ(p.transformFeedbackPreservesTriangleFanProvokingVertex, VK_FALSE);
}

// VK_EXT_depth_clip_enable: a quad beyond the far plane (z = 1.5) over the left half, one before the near plane
// (z = -0.5) over the right half. depthClipEnable decides alone whether they are clipped, with or without
// depthClampEnable (lavapipe's depth_clip_near/far); without the struct, depthClampEnable does.
TEST_F(RasterExtensions, DepthClipEnableWithAndWithoutClamp) {
    VkPhysicalDeviceDepthClipEnableFeaturesEXT feature{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_ENABLE_FEATURES_EXT};
    feature.depthClipEnable = VK_TRUE;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &feature};
    f2.features.depthClamp = VK_TRUE;
    auto dev = device_pair({VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME}, &f2);
    ASSERT_TRUE(dev->ok());
    std::vector<Vertex> quads;
    for (float x0 : {-1.0f, 0.0f}) {
        const float z = x0 < 0 ? 1.5f : -0.5f;
        const float g = x0 < 0 ? 0.0f : 1.0f;
        for (auto [x, y] :
             {std::pair{x0, -1.0f}, {x0 + 1, -1.0f}, {x0, 1.0f}, {x0 + 1, -1.0f}, {x0 + 1, 1.0f}, {x0, 1.0f}})
            quads.push_back(v(x, y, z, 1 - g, g, 0));
    }
    for (int with_struct = 0; with_struct < 2; ++with_struct)
        for (bool clip : {false, true})
            for (bool clamp : {false, true}) {
                if (!with_struct && clip) continue;  // without the struct only depthClampEnable matters
                VkPipelineRasterizationDepthClipStateCreateInfoEXT dc{
                    VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_DEPTH_CLIP_STATE_CREATE_INFO_EXT};
                dc.depthClipEnable = clip;
                const Bytes img = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
                    Pipe p;
                    p.rasterization_pnext = with_struct ? &dc : nullptr;
                    p.depth_clamp = clamp;
                    return draw_into_target(k, p, quads);
                });
                const bool clipped = with_struct ? clip : !clamp;
                EXPECT_EQ(pixel(img, 8, 16), clipped ? 0xff000000u : kRed) << with_struct << clip << clamp;
                EXPECT_EQ(pixel(img, 24, 16), clipped ? 0xff000000u : kGreen) << with_struct << clip << clamp;
            }
}

// A line strip in `mode` (nullopt: no VkPipelineRasterizationLineStateCreateInfoEXT) with draw.vert's smooth
// colours, `width` wide, into a 32x32 RGBA8 target cleared to black.
Bytes line_draw(Kit& k, std::optional<VkLineRasterizationModeEXT> mode, float width, const std::vector<Vertex>& verts) {
    VkPipelineRasterizationLineStateCreateInfoEXT ls{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
    ls.lineRasterizationMode = mode.value_or(VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT);
    Pipe p;
    p.topology = VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
    p.rasterization_pnext = mode ? &ls : nullptr;
    p.line_width = width;
    return draw_into_target(k, p, verts);
}

// VK_EXT_line_rasterization: DEFAULT, RECTANGULAR and BRESENHAM line strips, 1 and 3 pixels wide, against lavapipe.
// The rules checked here: DEFAULT is RECTANGULAR; a 1-pixel Bresenham x-major line lights exactly one pixel in
// each column strictly between its ends (a rectangular one of the same slope lights two in some).
TEST_F(RasterExtensions, LineRasterizationModes) {
    VkPhysicalDeviceLineRasterizationFeaturesEXT feature{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
    feature.rectangularLines = feature.bresenhamLines = VK_TRUE;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &feature};
    f2.features.wideLines = VK_TRUE;
    auto dev = device_pair({VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME}, &f2);
    ASSERT_TRUE(dev->ok());
    // x-major from pixel (2.5, 4.5) to (29.5, 20.5), then back along a steeper y-major segment.
    auto ndc = [](float px) { return px / 16.0f - 1.0f; };
    const std::vector<Vertex> strip = {v(ndc(2.5f), ndc(4.5f), 0, 1, 0, 0), v(ndc(29.5f), ndc(20.5f), 0, 0, 1, 0)};
    const std::vector<Vertex> both_axes = {v(ndc(2.5f), ndc(4.5f), 0, 1, 0, 0), v(ndc(29.5f), ndc(20.5f), 0, 0, 1, 0),
                                           v(ndc(20.25f), ndc(30.75f), 0, 0, 0, 1)};
    auto lit_in_column = [](const Bytes& img, uint32_t x) {
        int n = 0;
        for (uint32_t y = 0; y < 32; ++y) n += (pixel(img, x, y) & 0xffffffu) != 0;
        return n;
    };
    for (float width : {1.0f, 3.0f}) {
        Bytes by_mode[3];
        int m = 0;
        for (VkLineRasterizationModeEXT mode :
             {VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT, VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT,
              VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT}) {
            by_mode[m++] =
                both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) { return line_draw(k, mode, width, both_axes); });
        }
        EXPECT_EQ(by_mode[0], by_mode[1]) << width;
        EXPECT_NE(by_mode[1], by_mode[2]) << width;
        Kit k(dev->tilevk);
        EXPECT_EQ(line_draw(k, std::nullopt, width, both_axes), by_mode[0]) << "no struct vs DEFAULT";
    }
    Kit k(dev->tilevk);
    const Bytes bres = line_draw(k, VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT, 1.0f, strip);
    const Bytes rect = line_draw(k, VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT, 1.0f, strip);
    int rect_doubles = 0;
    for (uint32_t x = 3; x <= 28; ++x) {
        EXPECT_EQ(lit_in_column(bres, x), 1) << "Bresenham column " << x;
        rect_doubles += lit_in_column(rect, x) > 1;
    }
    EXPECT_GT(rect_doubles, 0);
}

// Pipeline states tilevk refuses by name (VK_ERROR_INITIALIZATION_FAILED and one stderr line), on a device without
// the validation layer since they need features tilevk does not report: smooth and stippled lines, the line
// stipple dynamic state, and Bresenham lines in a multisampled pass.
TEST_F(RasterExtensions, UnsupportedLineStatesAreRefusedByName) {
    Harness h(false);
    VkPhysicalDeviceLineRasterizationFeaturesEXT feature{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
    feature.rectangularLines = feature.bresenhamLines = VK_TRUE;
    Device dev(h.find_device("tilevk"), nullptr, {VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME}, &feature);
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    Target t = target(k);
    struct Row {
        VkLineRasterizationModeEXT mode;
        bool stipple;
        VkSampleCountFlagBits samples;
        bool dynamic_stipple;
        const char* named;
    };
    const Row rows[] = {
        {VK_LINE_RASTERIZATION_MODE_RECTANGULAR_SMOOTH_EXT, false, VK_SAMPLE_COUNT_1_BIT, false,
         "VK_LINE_RASTERIZATION_MODE_RECTANGULAR_SMOOTH_EXT"},
        {VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT, true, VK_SAMPLE_COUNT_1_BIT, false, "stippledLineEnable"},
        {VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT, false, VK_SAMPLE_COUNT_4_BIT, false, "VK_SAMPLE_COUNT_4_BIT"},
        {VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT, false, VK_SAMPLE_COUNT_1_BIT, true,
         "VK_DYNAMIC_STATE_LINE_STIPPLE_EXT"},
    };
    for (const Row& r : rows) {
        VkPipelineRasterizationLineStateCreateInfoEXT ls{
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
        ls.lineRasterizationMode = r.mode;
        ls.stippledLineEnable = r.stipple;
        ls.lineStippleFactor = 1;
        ls.lineStipplePattern = 0xf0f0;
        Pipe p;
        p.rp = t.rp;
        p.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        p.rasterization_pnext = &ls;
        p.samples = r.samples;
        if (r.dynamic_stipple) p.dynamic = {VK_DYNAMIC_STATE_LINE_STIPPLE_EXT};
        VkResult result = VK_SUCCESS;
        StderrCapture capture;
        EXPECT_EQ(k.pipeline(p, &result), VkPipeline(VK_NULL_HANDLE)) << r.named;
        EXPECT_EQ(result, VK_ERROR_INITIALIZATION_FAILED) << r.named;
        EXPECT_NE(capture.text().find(r.named), std::string::npos) << capture.text();
    }
    // The same pipeline without what is refused is made.
    Pipe ok;
    ok.rp = t.rp;
    ok.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    EXPECT_NE(k.pipeline(ok), VkPipeline(VK_NULL_HANDLE));
}

}  // namespace
}  // namespace tilevk::test::breadth
