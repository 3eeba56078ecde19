// Queries through the loader with validation on, on tilevk and lavapipe: occlusion counts of the same command
// buffers must be equal on both drivers and equal to counts computed by hand (pixel-aligned rectangles, so every
// sample is either inside or outside); vkGetQueryPoolResults and vkCmdCopyQueryPoolResults with every flag; queries
// spanning render passes; reset; timestamps. The last test drives the commands without validation (invalid on
// purpose): buffer views, dispatches, sparse binding.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "vk_harness.h"
#include "vk_pipeline.h"

namespace {

#include "color_frag.h"
#include "discard_frag.h"
#include "draw_vert.h"

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::PipelineStates;
using tilevk::test::shader_stage;
using tilevk::test::TwoDriverSuite;

constexpr uint32_t kW = 40, kH = 24;

struct Vertex {
    float pos[4];
    float color[4];
};

// One draw: a pixel-aligned rectangle [x0,x1)x[y0,y1) at depth z, with its pipeline state.
struct Rect {
    uint32_t x0, y0, x1, y1;
    float z = 0.5f;
    bool depth = false;                                     // LESS, write on
    enum Stencil { kNone, kMark, kEqual } stencil = kNone;  // REPLACE 1 always / EQUAL 1
    bool discard = false;                                   // checkerboard discard
    VkRect2D scissor = {{0, 0}, {kW, kH}};
};

VkShaderModule module(VkDevice d, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule m = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateShaderModule(d, &ci, nullptr, &m), VK_SUCCESS);
    return m;
}

// A render target (colour, RGBA8 unless asked, + D32_SFLOAT_S8_UINT cleared to depth 1 / stencil 0 unless
// `with_depth` is false) and pipelines for Rects.
class Rig {
  public:
    Rig(Device& dev, VkSampleCountFlagBits samples, VkFormat color = VK_FORMAT_R8G8B8A8_UNORM, bool with_depth = true)
        : dev_(dev), samples_(samples), with_depth_(with_depth) {
        VkDevice d = dev.device();
        color_ = dev.make_image(color, kW, kH, 1, 1, samples, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        views_[0] = view(color_.image, color, VK_IMAGE_ASPECT_COLOR_BIT);
        if (with_depth) {
            depth_ = dev.make_image(VK_FORMAT_D32_SFLOAT_S8_UINT, kW, kH, 1, 1, samples,
                                    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
            views_[1] = view(depth_.image, VK_FORMAT_D32_SFLOAT_S8_UINT,
                             VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT);
        }
        VkAttachmentDescription att[2] = {};
        for (auto& a : att) {
            a.samples = samples;
            a.loadOp = a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            a.storeOp = a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
            a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        }
        att[0].format = color;
        att[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        att[1].format = VK_FORMAT_D32_SFLOAT_S8_UINT;
        att[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        VkAttachmentReference cref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        VkAttachmentReference dref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &cref;
        sub.pDepthStencilAttachment = with_depth ? &dref : nullptr;
        // Render passes follow each other on the same attachments (SpanRenderPasses): order their accesses.
        VkSubpassDependency dep{
            VK_SUBPASS_EXTERNAL,
            0,
            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
            0};
        VkRenderPassCreateInfo rpci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        rpci.attachmentCount = with_depth ? 2 : 1;
        rpci.pAttachments = att;
        rpci.subpassCount = 1;
        rpci.pSubpasses = &sub;
        rpci.dependencyCount = 1;
        rpci.pDependencies = &dep;
        EXPECT_EQ(vkCreateRenderPass(d, &rpci, nullptr, &rp_), VK_SUCCESS);
        VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fci.renderPass = rp_;
        fci.attachmentCount = with_depth ? 2 : 1;
        fci.pAttachments = views_;
        fci.width = kW;
        fci.height = kH;
        fci.layers = 1;
        EXPECT_EQ(vkCreateFramebuffer(d, &fci, nullptr, &fb_), VK_SUCCESS);
        VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        EXPECT_EQ(vkCreatePipelineLayout(d, &plci, nullptr, &layout_), VK_SUCCESS);
        vs_ = module(d, draw_vert, sizeof draw_vert);
        fs_ = module(d, color_frag, sizeof color_frag);
        discard_fs_ = module(d, discard_frag, sizeof discard_frag);
        vbuf_ = dev.make_buffer(sizeof(Vertex) * 6 * kMaxRects, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    }
    ~Rig() {
        VkDevice d = dev_.device();
        for (VkPipeline p : pipes_) vkDestroyPipeline(d, p, nullptr);
        dev_.destroy(vbuf_);
        vkDestroyShaderModule(d, vs_, nullptr);
        vkDestroyShaderModule(d, fs_, nullptr);
        vkDestroyShaderModule(d, discard_fs_, nullptr);
        vkDestroyPipelineLayout(d, layout_, nullptr);
        vkDestroyFramebuffer(d, fb_, nullptr);
        vkDestroyRenderPass(d, rp_, nullptr);
        for (VkImageView v : views_)
            if (v) vkDestroyImageView(d, v, nullptr);
        dev_.destroy(color_);
        if (with_depth_) dev_.destroy(depth_);
    }

    // Prepares the rectangles' vertices and pipelines (before recording).
    void set(const std::vector<Rect>& rects) {
        rects_ = rects;
        auto* v = static_cast<Vertex*>(vbuf_.map);
        for (size_t i = 0; i < rects.size() && i < kMaxRects; ++i) {
            const Rect& r = rects[i];
            const float x0 = -1 + 2.0f * r.x0 / kW, x1 = -1 + 2.0f * r.x1 / kW;
            const float y0 = -1 + 2.0f * r.y0 / kH, y1 = -1 + 2.0f * r.y1 / kH;
            const float c = 0.1f + 0.1f * float(i);
            const float corners[6][2] = {{x0, y0}, {x1, y0}, {x0, y1}, {x1, y0}, {x1, y1}, {x0, y1}};
            for (int k = 0; k < 6; ++k) v[i * 6 + k] = {{corners[k][0], corners[k][1], r.z, 1}, {c, 1 - c, 0.5f, 1}};
            pipes_.push_back(pipeline(r));
        }
    }

    void begin_pass(VkCommandBuffer cb) const {
        VkClearValue clears[2] = {};
        clears[1].depthStencil = {1.0f, 0};
        VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        bi.renderPass = rp_;
        bi.framebuffer = fb_;
        bi.renderArea = {{0, 0}, {kW, kH}};
        bi.clearValueCount = with_depth_ ? 2 : 1;
        bi.pClearValues = clears;
        vkCmdBeginRenderPass(cb, &bi, VK_SUBPASS_CONTENTS_INLINE);
        VkDeviceSize zero = 0;
        vkCmdBindVertexBuffers(cb, 0, 1, &vbuf_.buffer, &zero);
    }
    // Draws rectangle i of the last set(), with the pipeline made for it.
    void draw(VkCommandBuffer cb, size_t i) const {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_[pipes_.size() - rects_.size() + i]);
        vkCmdDraw(cb, 6, 1, uint32_t(6 * i), 0);
    }

  private:
    static constexpr size_t kMaxRects = 16;
    VkImageView view(VkImage img, VkFormat f, VkImageAspectFlags aspect) {
        VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        ci.image = img;
        ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        ci.format = f;
        ci.subresourceRange = {aspect, 0, 1, 0, 1};
        VkImageView v = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImageView(dev_.device(), &ci, nullptr, &v), VK_SUCCESS);
        return v;
    }
    VkPipeline pipeline(const Rect& r) {
        const VkPipelineShaderStageCreateInfo stages[2] = {
            shader_stage(VK_SHADER_STAGE_VERTEX_BIT, vs_),
            shader_stage(VK_SHADER_STAGE_FRAGMENT_BIT, r.discard ? discard_fs_ : fs_)};
        VkVertexInputBindingDescription vb{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
        VkVertexInputAttributeDescription va[2] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                                   {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16}};
        PipelineStates states(kW, kH);
        states.vertex_input.vertexBindingDescriptionCount = 1;
        states.vertex_input.pVertexBindingDescriptions = &vb;
        states.vertex_input.vertexAttributeDescriptionCount = 2;
        states.vertex_input.pVertexAttributeDescriptions = va;
        states.scissor = r.scissor;
        states.multisample.rasterizationSamples = samples_;
        states.depth_stencil_enabled = with_depth_;
        VkPipelineDepthStencilStateCreateInfo& ds = states.depth_stencil;
        ds.depthTestEnable = ds.depthWriteEnable = r.depth;
        ds.depthCompareOp = VK_COMPARE_OP_LESS;
        ds.stencilTestEnable = r.stencil != Rect::kNone;
        const VkStencilOpState mark{
            VK_STENCIL_OP_KEEP, VK_STENCIL_OP_REPLACE, VK_STENCIL_OP_KEEP, VK_COMPARE_OP_ALWAYS, 0xff, 0xff, 1};
        const VkStencilOpState equal{
            VK_STENCIL_OP_KEEP, VK_STENCIL_OP_KEEP, VK_STENCIL_OP_KEEP, VK_COMPARE_OP_EQUAL, 0xff, 0xff, 1};
        ds.front = ds.back = r.stencil == Rect::kMark ? mark : equal;
        VkPipeline p = VK_NULL_HANDLE;
        EXPECT_EQ(states.create(dev_.device(), rp_, layout_, stages, 2, &p), VK_SUCCESS);
        return p;
    }

    Device& dev_;
    VkSampleCountFlagBits samples_;
    bool with_depth_;
    Device::Image color_{}, depth_{};
    VkImageView views_[2] = {};
    VkRenderPass rp_ = VK_NULL_HANDLE;
    VkFramebuffer fb_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkShaderModule vs_ = VK_NULL_HANDLE, fs_ = VK_NULL_HANDLE, discard_fs_ = VK_NULL_HANDLE;
    Device::Buffer vbuf_{};
    std::vector<Rect> rects_;
    std::vector<VkPipeline> pipes_;
};

VkQueryPool make_pool(VkDevice d, VkQueryType type, uint32_t count) {
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryType = type;
    ci.queryCount = count;
    VkQueryPool p = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateQueryPool(d, &ci, nullptr, &p), VK_SUCCESS);
    return p;
}

// Draws `rects` in one render pass, each inside its own occlusion query; returns the 64-bit results (WAIT).
std::vector<uint64_t> count_per_draw(Device& dev, VkSampleCountFlagBits samples, const std::vector<Rect>& rects) {
    Rig rig(dev, samples);
    rig.set(rects);
    const uint32_t n = uint32_t(rects.size());
    VkQueryPool pool = make_pool(dev.device(), VK_QUERY_TYPE_OCCLUSION, n);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, n);
        rig.begin_pass(cb);
        for (uint32_t i = 0; i < n; ++i) {
            vkCmdBeginQuery(cb, pool, i, 0);
            rig.draw(cb, i);
            vkCmdEndQuery(cb, pool, i);
        }
        vkCmdEndRenderPass(cb);
    }),
              VK_SUCCESS);
    std::vector<uint64_t> out(n, ~0ull);
    EXPECT_EQ(vkGetQueryPoolResults(dev.device(), pool, 0, n, n * 8, out.data(), 8,
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              VK_SUCCESS);
    vkDestroyQueryPool(dev.device(), pool, nullptr);
    return out;
}

class Queries : public TwoDriverSuite {
  protected:
};

// The scene of the counting tests and its counts per pixel, by hand.
std::vector<Rect> counting_scene() {
    std::vector<Rect> r;
    r.push_back({0, 0, kW, kH, 0.5f, true});   // full target: W*H
    r.push_back({4, 4, 20, 12, 0.7f, true});   // behind the first: 0
    r.push_back({10, 6, 30, 20, 0.3f, true});  // in front: 20x14
    r.push_back({24, 2, 36, 22, 0.4f, true});  // in front of 0.5, behind 0.3 on [24,30)x[6,20): 12*20 - 6*14
    Rect sc{0, 0, kW, kH, 0.2f, true};
    sc.scissor = {{5, 3}, {7, 9}};  // scissored: 7x9
    r.push_back(sc);
    Rect dis{0, 0, kW, kH, 0.1f, false};
    dis.discard = true;  // checkerboard discard: half of W*H
    r.push_back(dis);
    Rect mark{0, 0, 16, kH, 0.5f, false, Rect::kMark};  // marks the left 16 columns: 16*H
    r.push_back(mark);
    Rect eq{0, 0, kW, kH, 0.5f, false, Rect::kEqual};  // passes where marked: 16*H
    r.push_back(eq);
    return r;
}
const std::vector<uint64_t> kCountingPerPixel = {kW * kH, 0,          20 * 14, 12 * 20 - 6 * 14,
                                                 7 * 9,   kW* kH / 2, 16 * kH, 16 * kH};

// lavapipe's MSAA scissor (lp_setup.c lp_setup_add_scissor_planes, adj = 127 at 4x) lets the left and top
// scissor planes pass the samples of the column left of / the row above the scissor whose offset is more than half
// a pixel: samples 1 and 3 (x 224/256, 160/256) of column x0-1, samples 2 and 3 (y 160/256, 224/256) of row y0-1,
// and sample 3 of the corner pixel (for a primitive covering them whose bounding box crosses both edges, with x0 and
// y0 not on a 64-px tile boundary). Vulkan's scissor test discards every sample of a pixel outside the scissor;
// tilevk deliberately matches lavapipe (icd/README.md named differences), so both drivers count these samples.
uint64_t lavapipe_msaa_scissor_extra(const VkRect2D& sc) {
    return 2 * uint64_t(sc.extent.height) + 2 * uint64_t(sc.extent.width) + 1;
}

TEST_F(Queries, OcclusionCountsEqualLavapipeAndHandCounts) {
    const size_t kScissored = 4;  // the index of the scissored draw in counting_scene()
    for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT}) {
        const std::vector<Rect> scene = counting_scene();
        const std::vector<uint64_t> t = count_per_draw(*tilevk_, samples, scene);
        const std::vector<uint64_t> l = count_per_draw(*lavapipe_, samples, scene);
        ASSERT_EQ(t.size(), kCountingPerPixel.size());
        ASSERT_EQ(l.size(), kCountingPerPixel.size());
        for (size_t i = 0; i < t.size(); ++i) {
            const uint64_t expected = kCountingPerPixel[i] * uint64_t(samples);
            const bool quirk = samples == VK_SAMPLE_COUNT_4_BIT && i == kScissored;
            const uint64_t with_quirk = expected + (quirk ? lavapipe_msaa_scissor_extra(scene[i].scissor) : 0);
            EXPECT_EQ(t[i], with_quirk) << "tilevk, draw " << i << " at " << samples << "x";
            EXPECT_EQ(l[i], with_quirk) << "lavapipe, draw " << i << " at " << samples << "x";
        }
    }
}

// Discard with depth testing: the depth test runs after the shader (late), and the count must come from after it.
// Full target at 0.5; a checkerboard-discarding full target at 0.3 (half passes and writes 0.3); a discarding
// rectangle at 0.4 (its surviving pixels are exactly those at 0.3 already: 0); a plain full target at 0.4 (passes
// on the other half, still at 0.5).
TEST_F(Queries, DiscardWithLateDepthTest) {
    std::vector<Rect> scene;
    scene.push_back({0, 0, kW, kH, 0.5f, true});
    Rect d{0, 0, kW, kH, 0.3f, true};
    d.discard = true;
    scene.push_back(d);
    d = {0, 0, 20, 12, 0.4f, true};
    d.discard = true;
    scene.push_back(d);
    scene.push_back({0, 0, kW, kH, 0.4f, true});
    for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT}) {
        const std::vector<uint64_t> t = count_per_draw(*tilevk_, samples, scene);
        const std::vector<uint64_t> l = count_per_draw(*lavapipe_, samples, scene);
        const uint64_t n = uint64_t(kW) * kH * samples;
        EXPECT_EQ(t, (std::vector<uint64_t>{n, n / 2, 0, n / 2})) << samples << "x";
        EXPECT_EQ(t, l) << samples << "x";
    }
}

// Three queries — 0 counts one 10x7 rectangle (70), 1 is reset and never begun, 2 counts it twice (140) — read back
// with every flag combination; the bytes must be equal on both drivers (written words and untouched ones).
struct FlagRun {
    VkQueryResultFlags flags;
    uint32_t first;  // first query read
    VkResult result;
    std::vector<uint8_t> bytes;
};
std::vector<FlagRun> flag_runs(Device& dev) {
    Rig rig(dev, VK_SAMPLE_COUNT_1_BIT);
    rig.set({{2, 2, 12, 9}});  // 70 samples
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d, VK_QUERY_TYPE_OCCLUSION, 3);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 3);
        rig.begin_pass(cb);
        vkCmdBeginQuery(cb, pool, 0, 0);
        rig.draw(cb, 0);
        vkCmdEndQuery(cb, pool, 0);
        vkCmdBeginQuery(cb, pool, 2, 0);
        rig.draw(cb, 0);
        rig.draw(cb, 0);  // twice: 140
        vkCmdEndQuery(cb, pool, 2);
        vkCmdEndRenderPass(cb);
    }),
              VK_SUCCESS);
    // Query 1 stays reset: unavailable.
    std::vector<FlagRun> runs;
    for (VkQueryResultFlags flags = 0; flags < 16; ++flags) {
        if (flags & VK_QUERY_RESULT_WAIT_BIT) {
            // WAIT on a query that never becomes available is not allowed: wait only on 0 and 2, one at a time.
            for (uint32_t q : {0u, 2u}) {
                FlagRun r{flags, q, VK_SUCCESS, std::vector<uint8_t>(24, 0xAB)};
                r.result = vkGetQueryPoolResults(d, pool, q, 1, r.bytes.size(), r.bytes.data(), 24, flags);
                runs.push_back(r);
            }
            continue;
        }
        // All three, stride 24 (a multiple of 8 for 64-bit results): bytes after each entry stay untouched.
        FlagRun r{flags, 0, VK_SUCCESS, std::vector<uint8_t>(3 * 24, 0xAB)};
        r.result = vkGetQueryPoolResults(d, pool, 0, 3, r.bytes.size(), r.bytes.data(), 24, flags);
        runs.push_back(r);
    }
    vkDestroyQueryPool(d, pool, nullptr);
    return runs;
}

uint64_t word(const std::vector<uint8_t>& b, size_t offset, bool wide) {
    uint64_t v = 0;
    std::memcpy(&v, b.data() + offset, wide ? 8 : 4);
    return v;
}

TEST_F(Queries, GetResultsWithEveryFlagMatchesLavapipe) {
    const std::vector<FlagRun> t = flag_runs(*tilevk_), l = flag_runs(*lavapipe_);
    ASSERT_EQ(t.size(), l.size());
    for (size_t i = 0; i < t.size(); ++i) {
        EXPECT_EQ(t[i].result, l[i].result) << "run " << i;
        EXPECT_EQ(t[i].bytes, l[i].bytes) << "run " << i;
    }
    auto run = [&](VkQueryResultFlags flags, uint32_t first = 0) -> const FlagRun& {
        for (const FlagRun& r : t)
            if (r.flags == flags && r.first == first) return r;
        ADD_FAILURE() << "no run with flags " << flags;
        return t[0];
    };
    const VkQueryResultFlags k64 = VK_QUERY_RESULT_64_BIT, kWait = VK_QUERY_RESULT_WAIT_BIT,
                             kAvail = VK_QUERY_RESULT_WITH_AVAILABILITY_BIT, kPartial = VK_QUERY_RESULT_PARTIAL_BIT;
    // Independent expectations on tilevk's runs. No flags (32-bit): queries 0 and 2 written, 1 (reset) not.
    EXPECT_EQ(run(0).result, VK_NOT_READY);
    EXPECT_EQ(word(run(0).bytes, 0, false), 70u);
    EXPECT_EQ(word(run(0).bytes, 4, false), 0xABABABABu);
    EXPECT_EQ(word(run(0).bytes, 24, false), 0xABABABABu);
    EXPECT_EQ(word(run(0).bytes, 48, false), 140u);
    // 64-bit + availability: value, 1 / untouched value, 0 / value, 1.
    const FlagRun& a = run(k64 | kAvail);
    EXPECT_EQ(a.result, VK_NOT_READY);
    EXPECT_EQ(word(a.bytes, 0, true), 70u);
    EXPECT_EQ(word(a.bytes, 8, true), 1u);
    EXPECT_EQ(word(a.bytes, 24, true), 0xABABABABABABABABull);
    EXPECT_EQ(word(a.bytes, 32, true), 0u);
    EXPECT_EQ(word(a.bytes, 48, true), 140u);
    EXPECT_EQ(word(a.bytes, 56, true), 1u);
    // PARTIAL + availability: the unavailable query's value is written (0) and the call succeeds.
    const FlagRun& p = run(kPartial | kAvail);
    EXPECT_EQ(p.result, VK_SUCCESS);
    EXPECT_EQ(word(p.bytes, 24, false), 0u);
    EXPECT_EQ(word(p.bytes, 28, false), 0u);
    EXPECT_EQ(word(p.bytes, 52, false), 1u);
    // WAIT on available queries: success, value.
    EXPECT_EQ(run(kWait | k64, 2).result, VK_SUCCESS);
    EXPECT_EQ(word(run(kWait | k64, 2).bytes, 0, true), 140u);
}

// vkCmdCopyQueryPoolResults into a buffer at an offset with a stride, for several flag sets; available queries'
// words must match lavapipe's, and hand counts.
std::vector<uint8_t> copy_runs(Device& dev) {
    Rig rig(dev, VK_SAMPLE_COUNT_4_BIT);
    rig.set({{0, 0, kW, kH, 0.5f, true}, {5, 5, 15, 10, 0.25f, true}});
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d, VK_QUERY_TYPE_OCCLUSION, 2);
    Device::Buffer out = dev.make_buffer(512);
    std::memset(out.map, 0xCD, 512);
    const VkQueryResultFlags sets[] = {VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT,
                                       VK_QUERY_RESULT_WAIT_BIT, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT,
                                       VK_QUERY_RESULT_WITH_AVAILABILITY_BIT | VK_QUERY_RESULT_PARTIAL_BIT};
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 2);
        rig.begin_pass(cb);
        for (uint32_t i = 0; i < 2; ++i) {
            vkCmdBeginQuery(cb, pool, i, 0);
            rig.draw(cb, i);
            vkCmdEndQuery(cb, pool, i);
        }
        vkCmdEndRenderPass(cb);
        for (size_t k = 0; k < 4; ++k) {
            // each copy in its own 128-byte slice, 8 bytes in, stride 40
            vkCmdCopyQueryPoolResults(cb, pool, 0, 2, out.buffer, 128 * k + 8, 40, sets[k]);
        }
    }),
              VK_SUCCESS);
    std::vector<uint8_t> bytes(static_cast<uint8_t*>(out.map), static_cast<uint8_t*>(out.map) + 512);
    dev.destroy(out);
    vkDestroyQueryPool(d, pool, nullptr);
    return bytes;
}

TEST_F(Queries, CopyResultsToBufferMatchesLavapipe) {
    const std::vector<uint8_t> t = copy_runs(*tilevk_), l = copy_runs(*lavapipe_);
    EXPECT_EQ(t, l);
    const uint64_t q0 = 4 * kW * kH, q1 = 4 * 10 * 5;
    // 64-bit + availability
    EXPECT_EQ(word(t, 8, true), q0);
    EXPECT_EQ(word(t, 16, true), 1u);
    EXPECT_EQ(word(t, 48, true), q1);
    EXPECT_EQ(word(t, 56, true), 1u);
    EXPECT_EQ(word(t, 0, true), 0xCDCDCDCDCDCDCDCDull);   // before the offset: untouched
    EXPECT_EQ(word(t, 24, true), 0xCDCDCDCDCDCDCDCDull);  // between entries: untouched
    // 32-bit
    EXPECT_EQ(word(t, 128 + 8, false), q0);
    EXPECT_EQ(word(t, 128 + 48, false), q1);
    EXPECT_EQ(word(t, 128 + 12, false), 0xCDCDCDCDu);
    // 64-bit
    EXPECT_EQ(word(t, 256 + 48, true), q1);
    // 32-bit + availability
    EXPECT_EQ(word(t, 384 + 8, false), q0);
    EXPECT_EQ(word(t, 384 + 12, false), 1u);
}

// One query begun before a render pass and ended after another: it counts the draws of both passes. A reset in
// between on another query; a second submission after a reset counts afresh.
uint64_t span_run(Device& dev, uint64_t* second) {
    Rig rig(dev, VK_SAMPLE_COUNT_1_BIT);
    rig.set({{0, 0, 10, 10}, {0, 0, kW, kH}});
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d, VK_QUERY_TYPE_OCCLUSION, 1);
    auto record = [&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 1);
        vkCmdBeginQuery(cb, pool, 0, 0);
        rig.begin_pass(cb);
        rig.draw(cb, 0);
        vkCmdEndRenderPass(cb);
        rig.begin_pass(cb);
        rig.draw(cb, 1);
        rig.draw(cb, 0);
        vkCmdEndRenderPass(cb);
        vkCmdEndQuery(cb, pool, 0);
    };
    EXPECT_EQ(dev.run(record), VK_SUCCESS);
    uint64_t first = 0;
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, 8, &first, 8, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              VK_SUCCESS);
    EXPECT_EQ(dev.run(record), VK_SUCCESS);
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, 8, second, 8, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              VK_SUCCESS);
    vkDestroyQueryPool(d, pool, nullptr);
    return first;
}

TEST_F(Queries, QuerySpansRenderPassesAndResets) {
    uint64_t t2 = 0, l2 = 0;
    const uint64_t t = span_run(*tilevk_, &t2), l = span_run(*lavapipe_, &l2);
    EXPECT_EQ(t, l);
    EXPECT_EQ(t, uint64_t(100 + kW * kH + 100));
    EXPECT_EQ(t2, t);  // reset: the second submission does not add to the first
    EXPECT_EQ(l2, l);
}

// Clears (vkCmdClearAttachments between draws, vkCmdClearColorImage) and transfers inside an active query count
// nothing; the draws around them do.
uint64_t clears_run(Device& dev) {
    Rig rig(dev, VK_SAMPLE_COUNT_4_BIT);
    rig.set({{0, 0, kW, kH, 0.5f, true}, {2, 3, 12, 13, 0.6f, true}});
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d, VK_QUERY_TYPE_OCCLUSION, 1);
    Device::Buffer a = dev.make_buffer(256), b = dev.make_buffer(256);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 1);
        vkCmdBeginQuery(cb, pool, 0, 0);
        rig.begin_pass(cb);
        rig.draw(cb, 0);  // 4*W*H
        VkClearAttachment ca[2] = {{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}},
                                   {VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT, 0, {}}};
        ca[1].clearValue.depthStencil = {1.0f, 0};
        VkClearRect rect{{{0, 0}, {kW, kH}}, 0, 1};
        vkCmdClearAttachments(cb, 2, ca, 1, &rect);
        rig.draw(cb, 1);  // behind nothing after the depth clear: 4*10*10
        vkCmdEndRenderPass(cb);
        VkBufferCopy region{0, 0, 256};
        vkCmdCopyBuffer(cb, a.buffer, b.buffer, 1, &region);
        vkCmdEndQuery(cb, pool, 0);
    }),
              VK_SUCCESS);
    uint64_t n = 0;
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, 8, &n, 8, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              VK_SUCCESS);
    dev.destroy(a);
    dev.destroy(b);
    vkDestroyQueryPool(d, pool, nullptr);
    return n;
}

TEST_F(Queries, ClearsAndTransfersCountNothing) {
    const uint64_t t = clears_run(*tilevk_), l = clears_run(*lavapipe_);
    EXPECT_EQ(t, l);
    EXPECT_EQ(t, uint64_t(4 * (kW * kH + 100)));
}

// lavapipe's linear rasterizer (B8G8R8A8, no depth, rectangle-only bins) never adds to the occlusion counter: with
// the query begun before the render pass (so no query command is binned into the tiles) its count of a rectangle is
// 0. tilevk counts it, as a precise query must (a named difference, icd/README.md "Queries"). Begun inside the pass,
// lavapipe takes the general path and both agree.
uint64_t linear_run(Device& dev, bool begin_inside) {
    Rig rig(dev, VK_SAMPLE_COUNT_1_BIT, VK_FORMAT_B8G8R8A8_UNORM, false);
    rig.set({{8, 4, 32, 20}});  // 24x16
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d, VK_QUERY_TYPE_OCCLUSION, 1);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 1);
        if (!begin_inside) vkCmdBeginQuery(cb, pool, 0, 0);
        rig.begin_pass(cb);
        if (begin_inside) vkCmdBeginQuery(cb, pool, 0, 0);
        rig.draw(cb, 0);
        if (begin_inside) vkCmdEndQuery(cb, pool, 0);
        vkCmdEndRenderPass(cb);
        if (!begin_inside) vkCmdEndQuery(cb, pool, 0);
    }),
              VK_SUCCESS);
    uint64_t n = ~0ull;
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, 8, &n, 8, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              VK_SUCCESS);
    vkDestroyQueryPool(d, pool, nullptr);
    return n;
}

TEST_F(Queries, LavapipeLinearPathCountsNothing) {
    EXPECT_EQ(linear_run(*tilevk_, true), 24u * 16u);
    EXPECT_EQ(linear_run(*lavapipe_, true), 24u * 16u);
    EXPECT_EQ(linear_run(*tilevk_, false), 24u * 16u);
    EXPECT_EQ(linear_run(*lavapipe_, false), 0u);  // lavapipe 22.3.6's linear path
}

TEST_F(Queries, TimestampsAreMonotonicNanoseconds) {
    VkQueueFamilyProperties qf;
    uint32_t nq = 1;
    vkGetPhysicalDeviceQueueFamilyProperties(tilevk_->physical(), &nq, &qf);
    EXPECT_EQ(qf.timestampValidBits, 64u);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &props);
    EXPECT_EQ(props.limits.timestampPeriod, 1.0f);
    Device& dev = *tilevk_;
    Rig rig(dev, VK_SAMPLE_COUNT_4_BIT);
    rig.set({{0, 0, kW, kH}});
    VkQueryPool pool = make_pool(dev.device(), VK_QUERY_TYPE_TIMESTAMP, 3);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 3);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool, 0);
        rig.begin_pass(cb);
        for (int i = 0; i < 50; ++i) rig.draw(cb, 0);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool, 1);  // after the rendering above
        vkCmdEndRenderPass(cb);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool, 2);
    }),
              VK_SUCCESS);
    uint64_t ts[6] = {};
    EXPECT_EQ(vkGetQueryPoolResults(dev.device(), pool, 0, 3, sizeof ts, ts, 16,
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT),
              VK_SUCCESS);
    EXPECT_EQ(ts[1], 1u);
    EXPECT_EQ(ts[3], 1u);
    EXPECT_EQ(ts[5], 1u);
    EXPECT_GT(ts[2], ts[0]);  // 50 full-target 4x draws take more than a nanosecond
    EXPECT_GE(ts[4], ts[2]);
    vkDestroyQueryPool(dev.device(), pool, nullptr);
}

// Storage texel buffers share the storage images' code (shader/ imageBuffer as one row): exactly the formats with
// STORAGE_IMAGE have STORAGE_TEXEL_BUFFER, exactly those with STORAGE_IMAGE_ATOMIC (R32_UINT, R32_SINT, R32_SFLOAT)
// have STORAGE_TEXEL_BUFFER_ATOMIC. (tests/icd/api_breadth_stages_stores_test.cpp ApiStorageTexelBuffers uses them.)
TEST_F(Queries, StorageTexelBufferFormatsAreTheStorageImageFormats) {
    uint32_t storage = 0, atomic = 0;
    for (int f = 1; f <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++f) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), VkFormat(f), &fp);
        const bool image = fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
        const bool image_atomic = fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_ATOMIC_BIT;
        EXPECT_EQ(bool(fp.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT), image) << "format " << f;
        EXPECT_EQ(bool(fp.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_ATOMIC_BIT), image_atomic)
            << "format " << f;
        storage += image;
        atomic += image_atomic;
    }
    // The formats Vulkan requires for STORAGE_IMAGE, the extended ones, and B8G8R8A8_UNORM and A8B8G8R8_*_PACK32
    // (lavapipe's too; cts compute.image.*.bgra8_unorm / abgr8_*).
    EXPECT_EQ(storage, 16u + 23u + 5u);
    EXPECT_EQ(atomic, 3u);  // R32_SFLOAT for VK_EXT_shader_atomic_float, as lavapipe
}

// Invalid on purpose (no validation layer): what tilevk lacks fails clearly and never crashes.
TEST(QueriesInvalid, BufferViewsDispatchSparseStatistics) {
    Harness h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    Device dev(pd);
    ASSERT_TRUE(dev.ok());
    VkDevice d = dev.device();
    // Buffer views: the object exists; an offset past the buffer is refused.
    Device::Buffer buf = dev.make_buffer(256, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    VkBufferViewCreateInfo bvci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    bvci.buffer = buf.buffer;
    bvci.format = VK_FORMAT_R8G8B8A8_UNORM;
    bvci.range = VK_WHOLE_SIZE;
    VkBufferView view = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateBufferView(d, &bvci, nullptr, &view), VK_SUCCESS);
    EXPECT_NE(view, VK_NULL_HANDLE);
    vkDestroyBufferView(d, view, nullptr);
    bvci.offset = 512;  // past the end
    EXPECT_NE(vkCreateBufferView(d, &bvci, nullptr, &view), VK_SUCCESS);
    // Dispatches with no compute pipeline bound (invalid usage) do nothing and the submission still succeeds.
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdDispatch(cb, 4, 4, 1);
        vkCmdDispatchIndirect(cb, buf.buffer, 0);
        vkCmdFillBuffer(cb, buf.buffer, 0, 4, 0x01020304u);
    }),
              VK_SUCCESS);
    EXPECT_EQ(*static_cast<uint32_t*>(buf.map), 0x01020304u);  // commands after them still ran
    dev.destroy(buf);
    // Sparse binding: refused.
    VkQueue queue = VK_NULL_HANDLE;
    vkGetDeviceQueue(d, 0, 0, &queue);
    EXPECT_EQ(vkQueueBindSparse(queue, 0, nullptr, VK_NULL_HANDLE), VK_ERROR_FEATURE_NOT_PRESENT);
    // Pipeline statistics: refused at pool creation, this device was made without pipelineStatisticsQuery
    // (pipeline_statistics_test.cpp tests the pools).
    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
    qci.queryCount = 4;
    VkQueryPool qp = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateQueryPool(d, &qci, nullptr, &qp), VK_ERROR_FEATURE_NOT_PRESENT);
    // Queries out of range and a query never ended: messages, no crash, nothing waits forever.
    VkQueryPool pool = make_pool(d, VK_QUERY_TYPE_OCCLUSION, 2);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 5);
        vkCmdBeginQuery(cb, pool, 7, 0);
        vkCmdBeginQuery(cb, pool, 1, 0);  // never ended
    }),
              VK_SUCCESS);
    uint64_t r[4] = {9, 9, 9, 9};
    EXPECT_EQ(vkGetQueryPoolResults(
                  d, pool, 0, 2, sizeof r, r, 16,
                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT),
              VK_NOT_READY);  // query 0 was only reset: unavailable, never waited for
    EXPECT_EQ(r[1], 0u);
    EXPECT_EQ(r[2], 0u);  // query 1: ended by the driver at the end of the command buffer, 0 samples
    EXPECT_EQ(r[3], 1u);
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 1, 4, sizeof r, r, 16, VK_QUERY_RESULT_64_BIT), VK_SUCCESS);
    vkDestroyQueryPool(d, pool, nullptr);
}

}  // namespace
