// Pipeline-statistics queries through the loader with validation on, on tilevk and lavapipe (devices with
// pipelineStatisticsQuery and hostQueryReset enabled): the same command buffers — draws inside a query, a query
// spanning a render pass and a dispatch, dispatches alone — must give the same bytes on both drivers for every
// vkGetQueryPoolResults and vkCmdCopyQueryPoolResults flag combination, and the counts the spec fixes (counted by
// hand here; fragment shader invocations depend on coverage and are compared between the drivers only). lavapipe's
// reset of the clipping-invocation total at a discarding draw is pinned on both drivers, and a pipeline without a
// fragment shader counts as lavapipe's (which runs a dummy one).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "vk_harness.h"
#include "vk_pipeline.h"

namespace {

#include "color_frag.h"
#include "draw_vert.h"
#include "ps_compute_comp.h"

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::PipelineStates;
using tilevk::test::shader_stage;
using tilevk::test::SingleAttachmentPass;

constexpr uint32_t kW = 32, kH = 32, kVertices = 64;
constexpr VkQueryPipelineStatisticFlags kAll = 0x7FF;
// The scene's pool: every counter but FRAGMENT_SHADER_INVOCATIONS, which lavapipe's host reads change at every
// read (FragmentInvocationsHostReadsAsLavapipesDefect).
constexpr VkQueryPipelineStatisticFlags kScene = kAll & ~VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
constexpr uint32_t kValues = 10;  // counters in kScene
constexpr uint64_t kAny = ~0ull;  // an expected count not fixed by hand

VkShaderModule module(VkDevice d, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule m = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateShaderModule(d, &ci, nullptr, &m), VK_SUCCESS);
    return m;
}

std::unique_ptr<Device> make_device(VkPhysicalDevice pd, bool statistics) {
    VkPhysicalDeviceFeatures f{};
    f.pipelineStatisticsQuery = statistics;
    static VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    v12.hostQueryReset = VK_TRUE;
    return std::make_unique<Device>(pd, &f, std::vector<const char*>{}, &v12);
}

// A 32x32 RGBA8 target, a ring of vertices, an index buffer, pipelines per (topology, rasterizer discard) and a
// compute pipeline of 4x2x3 invocations per group.
class Rig {
  public:
    explicit Rig(Device& dev) : dev_(dev) {
        VkDevice d = dev.device();
        color_ = dev.make_image(VK_FORMAT_R8G8B8A8_UNORM, kW, kH, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        VkAttachmentDescription att{};
        att.format = VK_FORMAT_R8G8B8A8_UNORM;
        att.samples = VK_SAMPLE_COUNT_1_BIT;
        att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        const VkSubpassDependency dep{VK_SUBPASS_EXTERNAL,
                                      0,
                                      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                      0};
        target_ = SingleAttachmentPass(d, color_.image, att, VK_IMAGE_ASPECT_COLOR_BIT, kW, kH, {dep});
        VkDescriptorSetLayoutBinding b{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo dslci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        dslci.bindingCount = 1;
        dslci.pBindings = &b;
        EXPECT_EQ(vkCreateDescriptorSetLayout(d, &dslci, nullptr, &dsl_), VK_SUCCESS);
        VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        EXPECT_EQ(vkCreatePipelineLayout(d, &plci, nullptr, &layout_), VK_SUCCESS);
        plci.setLayoutCount = 1;
        plci.pSetLayouts = &dsl_;
        EXPECT_EQ(vkCreatePipelineLayout(d, &plci, nullptr, &compute_layout_), VK_SUCCESS);
        vs_ = module(d, draw_vert, sizeof draw_vert);
        fs_ = module(d, color_frag, sizeof color_frag);
        cs_ = module(d, ps_compute_comp, sizeof ps_compute_comp);
        vbuf_ = dev.make_buffer(32 * kVertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        auto* v = static_cast<float*>(vbuf_.map);
        for (uint32_t i = 0; i < kVertices; ++i) {
            const float a = 6.2831853f * float(i) / kVertices + 0.2f * float(i % 2);
            const float vert[8] = {0.9f * std::cos(a), 0.9f * std::sin(a), 0.5f, 1, 0.5f, 0.25f, 1, 1};
            std::memcpy(v + 8 * i, vert, sizeof vert);
        }
        ibuf_ = dev.make_buffer(4 * 64, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        counter_ = dev.make_buffer(4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        std::memset(counter_.map, 0, 4);
        make_compute();
    }
    ~Rig() {
        VkDevice d = dev_.device();
        for (VkPipeline p : pipes_) vkDestroyPipeline(d, p, nullptr);
        vkDestroyPipeline(d, compute_, nullptr);
        vkDestroyDescriptorPool(d, dpool_, nullptr);
        for (VkShaderModule m : {vs_, fs_, cs_}) vkDestroyShaderModule(d, m, nullptr);
        vkDestroyPipelineLayout(d, layout_, nullptr);
        vkDestroyPipelineLayout(d, compute_layout_, nullptr);
        vkDestroyDescriptorSetLayout(d, dsl_, nullptr);
        target_.destroy(d);
        for (Device::Buffer* b : {&vbuf_, &ibuf_, &counter_}) dev_.destroy(*b);
        dev_.destroy(color_);
    }
    void set_indices(const std::vector<uint32_t>& idx) { std::memcpy(ibuf_.map, idx.data(), 4 * idx.size()); }
    uint32_t invocations_run() const { return *static_cast<const uint32_t*>(counter_.map); }

    // Creates its pipeline now (before recording) and returns it.
    VkPipeline pipeline(VkPrimitiveTopology t, bool discard = false, bool restart = false, bool with_fs = true) {
        const VkPipelineShaderStageCreateInfo st[2] = {shader_stage(VK_SHADER_STAGE_VERTEX_BIT, vs_),
                                                       shader_stage(VK_SHADER_STAGE_FRAGMENT_BIT, fs_)};
        VkVertexInputBindingDescription vb{0, 32, VK_VERTEX_INPUT_RATE_VERTEX};
        VkVertexInputAttributeDescription va[2] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                                   {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16}};
        PipelineStates states(kW, kH);
        states.vertex_input.vertexBindingDescriptionCount = 1;
        states.vertex_input.pVertexBindingDescriptions = &vb;
        states.vertex_input.vertexAttributeDescriptionCount = 2;
        states.vertex_input.pVertexAttributeDescriptions = va;
        states.assembly.topology = t;
        states.assembly.primitiveRestartEnable = restart;
        states.raster.rasterizerDiscardEnable = discard;
        VkPipeline p = VK_NULL_HANDLE;
        EXPECT_EQ(states.create(dev_.device(), target_.pass, layout_, st, with_fs ? 2 : 1, &p), VK_SUCCESS);
        pipes_.push_back(p);
        return p;
    }
    void begin_pass(VkCommandBuffer cb) const {
        VkClearValue clear{};
        VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        bi.renderPass = target_.pass;
        bi.framebuffer = target_.framebuffer;
        bi.renderArea = {{0, 0}, {kW, kH}};
        bi.clearValueCount = 1;
        bi.pClearValues = &clear;
        vkCmdBeginRenderPass(cb, &bi, VK_SUBPASS_CONTENTS_INLINE);
        VkDeviceSize zero = 0;
        vkCmdBindVertexBuffers(cb, 0, 1, &vbuf_.buffer, &zero);
        vkCmdBindIndexBuffer(cb, ibuf_.buffer, 0, VK_INDEX_TYPE_UINT32);
    }
    void dispatch(VkCommandBuffer cb, uint32_t x, uint32_t y, uint32_t z) const {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, compute_);
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, compute_layout_, 0, 1, &set_, 0, nullptr);
        vkCmdDispatch(cb, x, y, z);
    }

  private:
    void make_compute() {
        VkDevice d = dev_.device();
        VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        ci.stage.module = cs_;
        ci.stage.pName = "main";
        ci.layout = compute_layout_;
        EXPECT_EQ(vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &ci, nullptr, &compute_), VK_SUCCESS);
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
        VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpci.maxSets = 1;
        dpci.poolSizeCount = 1;
        dpci.pPoolSizes = &size;
        EXPECT_EQ(vkCreateDescriptorPool(d, &dpci, nullptr, &dpool_), VK_SUCCESS);
        VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        ai.descriptorPool = dpool_;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &dsl_;
        EXPECT_EQ(vkAllocateDescriptorSets(d, &ai, &set_), VK_SUCCESS);
        VkDescriptorBufferInfo bi{counter_.buffer, 0, 4};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set_;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        w.pBufferInfo = &bi;
        vkUpdateDescriptorSets(d, 1, &w, 0, nullptr);
    }

    Device& dev_;
    Device::Image color_{};
    SingleAttachmentPass target_;
    VkDescriptorSetLayout dsl_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE, compute_layout_ = VK_NULL_HANDLE;
    VkShaderModule vs_ = VK_NULL_HANDLE, fs_ = VK_NULL_HANDLE, cs_ = VK_NULL_HANDLE;
    VkPipeline compute_ = VK_NULL_HANDLE;
    VkDescriptorPool dpool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    Device::Buffer vbuf_{}, ibuf_{}, counter_{};
    std::vector<VkPipeline> pipes_;
};

VkQueryPool make_pool(VkDevice d, VkQueryPipelineStatisticFlags stats, uint32_t count) {
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
    ci.pipelineStatistics = stats;
    ci.queryCount = count;
    VkQueryPool p = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateQueryPool(d, &ci, nullptr, &p), VK_SUCCESS);
    return p;
}

class PipelineStatistics : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        harness_ = std::make_unique<Harness>();
        ASSERT_TRUE(harness_->ok());
        VkPhysicalDevice t = harness_->find_device("tilevk"), l = harness_->find_device("llvmpipe");
        ASSERT_NE(t, VK_NULL_HANDLE);
        ASSERT_NE(l, VK_NULL_HANDLE);
        VkPhysicalDeviceFeatures f{};
        vkGetPhysicalDeviceFeatures(t, &f);
        ASSERT_TRUE(f.pipelineStatisticsQuery);
        tilevk_ = make_device(t, true);
        ASSERT_TRUE(tilevk_->ok());
        lavapipe_ = make_device(l, true);
        ASSERT_TRUE(lavapipe_->ok());
    }
    static void TearDownTestSuite() {
        tilevk_.reset();
        lavapipe_.reset();
        harness_.reset();
    }
    void TearDown() override { EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report(); }
    static std::unique_ptr<Harness> harness_;
    static std::unique_ptr<Device> tilevk_, lavapipe_;
};
std::unique_ptr<Harness> PipelineStatistics::harness_;
std::unique_ptr<Device> PipelineStatistics::tilevk_, PipelineStatistics::lavapipe_;

// Everything one device reports for the scene: the results of vkGetQueryPoolResults with every flag combination
// (after the WAIT run), then those of vkCmdCopyQueryPoolResults, then the counts per query (64-bit, WAIT).
struct SceneRun {
    std::vector<uint8_t> host, copied;
    std::vector<uint64_t> counts;  // kValues per query, queries 0..2
    uint32_t invocations_run = 0;
};

constexpr uint32_t kQueries = 4;  // 0: draws in a pass; 1: spans a pass and a dispatch; 2: dispatches; 3: reset only

// Query 0: 2 instances of 2 triangles, an indexed strip with a repeated index (indices 0 1 2 3 1 2 4: 7 vertices,
// 5 triangles, 5 distinct indices). Query 1, begun outside a render pass: a fan of 6 (4 triangles) in a second
// pass, then 4x1x2 groups. Query 2: 3x2x1 groups. Groups are 4x2x3 invocations. (Queries of one type may not
// nest in a command buffer.)
void record_scene(Rig& rig, VkCommandBuffer cb, VkQueryPool pool) {
    vkCmdResetQueryPool(cb, pool, 0, kQueries);
    rig.begin_pass(cb);
    vkCmdBeginQuery(cb, pool, 0, 0);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST));
    vkCmdDraw(cb, 6, 2, 0, 0);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP));
    vkCmdDrawIndexed(cb, 7, 1, 0, 0, 0);
    vkCmdEndQuery(cb, pool, 0);
    vkCmdEndRenderPass(cb);
    vkCmdBeginQuery(cb, pool, 1, 0);
    rig.begin_pass(cb);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN));
    vkCmdDraw(cb, 6, 1, 10, 0);
    vkCmdEndRenderPass(cb);
    rig.dispatch(cb, 4, 1, 2);
    vkCmdEndQuery(cb, pool, 1);
    vkCmdBeginQuery(cb, pool, 2, 0);
    rig.dispatch(cb, 3, 2, 1);
    vkCmdEndQuery(cb, pool, 2);
}

// The offset of the first byte where a and b differ (or of the end of the shorter), for failure messages.
size_t first_difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t i = 0;
    while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
    return i;
}

SceneRun scene_run(Device& dev) {
    Rig rig(dev);
    rig.set_indices({0, 1, 2, 3, 1, 2, 4});
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d, kScene, kQueries);
    vkResetQueryPool(d, pool, 0, kQueries);
    // Every combination of 64-bit, availability and partial (WAIT only where no query is left unavailable).
    const size_t entry = 8 * (kValues + 1);
    Device::Buffer dst = dev.make_buffer(16 * entry * kQueries);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        record_scene(rig, cb, pool);
        vkCmdFillBuffer(cb, dst.buffer, 0, VK_WHOLE_SIZE, 0xA5A5A5A5u);
        VkMemoryBarrier fill{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                             VK_ACCESS_TRANSFER_WRITE_BIT};
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &fill, 0,
                             nullptr, 0, nullptr);
        for (VkQueryResultFlags f = 0; f < 8; ++f) {
            const VkQueryResultFlags flags = (f & 1 ? VK_QUERY_RESULT_64_BIT : 0) |
                                             (f & 2 ? VK_QUERY_RESULT_WITH_AVAILABILITY_BIT : 0) |
                                             (f & 4 ? VK_QUERY_RESULT_PARTIAL_BIT : 0);
            // (Query 3, reset and never begun, is read on the host only: copying it is a validation warning.)
            vkCmdCopyQueryPoolResults(cb, pool, 0, 3, dst.buffer, f * entry * kQueries, entry, flags);
            vkCmdCopyQueryPoolResults(cb, pool, 0, 3, dst.buffer, (8 + f) * entry * kQueries, entry,
                                      flags | VK_QUERY_RESULT_WAIT_BIT);
        }
    }),
              VK_SUCCESS);
    SceneRun r;
    r.copied.assign(static_cast<uint8_t*>(dst.map), static_cast<uint8_t*>(dst.map) + 16 * entry * kQueries);
    r.counts.assign(kValues * 3, ~0ull);
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 3, 8 * r.counts.size(), r.counts.data(), 8 * kValues,
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              VK_SUCCESS);
    for (VkQueryResultFlags f = 0; f < 8; ++f) {
        const VkQueryResultFlags flags = (f & 1 ? VK_QUERY_RESULT_64_BIT : 0) |
                                         (f & 2 ? VK_QUERY_RESULT_WITH_AVAILABILITY_BIT : 0) |
                                         (f & 4 ? VK_QUERY_RESULT_PARTIAL_BIT : 0);
        // With PARTIAL, lavapipe fills only the first 8 bytes of its result for a query never begun since its reset
        // and writes the other counters from uninitialised memory (lvp_query.c): query 3 is read without it only.
        const uint32_t n = (flags & VK_QUERY_RESULT_PARTIAL_BIT) ? 3 : kQueries;
        std::vector<uint8_t> out(entry * n, 0x5A);
        const VkResult res = vkGetQueryPoolResults(d, pool, 0, n, out.size(), out.data(), entry, flags);
        r.host.push_back(uint8_t(res == VK_NOT_READY ? 1 : res == VK_SUCCESS ? 0 : 2));
        r.host.insert(r.host.end(), out.begin(), out.end());
    }
    // A host reset makes them unavailable again.
    vkResetQueryPool(d, pool, 0, kQueries);
    uint64_t after[kValues + 1] = {};
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, sizeof after, after, sizeof after,
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT),
              VK_NOT_READY);
    EXPECT_EQ(after[kValues], 0u);
    r.invocations_run = rig.invocations_run();
    dev.destroy(dst);
    vkDestroyQueryPool(d, pool, nullptr);
    return r;
}

// `counts` equals `expected` where that is not kAny.
void expect_counts(const std::vector<uint64_t>& counts, const std::vector<uint64_t>& expected) {
    ASSERT_EQ(counts.size(), expected.size());
    for (size_t i = 0; i < counts.size(); ++i) {
        if (expected[i] != kAny) {
            EXPECT_EQ(counts[i], expected[i]) << "value " << i;
        }
    }
}

TEST_F(PipelineStatistics, DrawsAndDispatchesMatchLavapipeAndHandCounts) {
    // By hand, in bit order: IA vertices, IA primitives, VS invocations, GS invocations, GS primitives, clipping
    // invocations, clipping primitives (every triangle lies inside the frustum and reaches setup), TCS patches, TES
    // invocations, CS invocations.
    const std::vector<uint64_t> expected = {
        2 * 6 + 7, 2 * 2 + 5, 2 * 6 + 5, 0, 0, 2 * 2 + 5, 2 * 2 + 5, 0, 0, 0,       // query 0
        6,         4,         6,         0, 0, 4,         4,         0, 0, 8 * 24,  // query 1
        0,         0,         0,         0, 0, 0,         0,         0, 0, 6 * 24,  // query 2
    };
    const SceneRun l = scene_run(*lavapipe_);
    EXPECT_EQ(l.counts, expected);
    EXPECT_EQ(l.invocations_run, (8u + 6u) * 24u);  // the shader's own count of its invocations
    const SceneRun t = scene_run(*tilevk_);
    EXPECT_EQ(t.counts, l.counts);
    EXPECT_EQ(t.host, l.host) << "first difference at byte " << first_difference(t.host, l.host);
    EXPECT_EQ(t.copied, l.copied) << "first difference at byte " << first_difference(t.copied, l.copied);
    EXPECT_EQ(t.invocations_run, l.invocations_run);
}

// lavapipe sets its running clipping-invocation total to 0 at a draw whose rasterization is discarded
// (lp_setup_vbuf.c lp_setup_pipeline_statistics): a query spanning such a draw counts only the clipping
// invocations of the draws after it; its other counters count every draw. Both drivers give these numbers.
std::vector<uint64_t> discard_run(Device& dev) {
    Rig rig(dev);
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d,
                                 VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
                                     VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT,
                                 1);
    VkPipeline list = rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST);
    VkPipeline discarding = rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, true);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 1);
        rig.begin_pass(cb);
        vkCmdBeginQuery(cb, pool, 0, 0);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, list);
        vkCmdDraw(cb, 6, 1, 0, 0);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, discarding);
        vkCmdDraw(cb, 9, 1, 0, 0);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, list);
        vkCmdDraw(cb, 3, 1, 0, 0);
        vkCmdEndQuery(cb, pool, 0);
        vkCmdEndRenderPass(cb);
    }),
              VK_SUCCESS);
    std::vector<uint64_t> out(2, ~0ull);
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, 16, out.data(), 16, VK_QUERY_RESULT_64_BIT), VK_SUCCESS);
    vkDestroyQueryPool(d, pool, nullptr);
    return out;
}

TEST_F(PipelineStatistics, DiscardingDrawResetsClippingTotalAsLavapipe) {
    // primitives 2 + 3 + 1; clipping invocations 1 (only the draw after the discarding one).
    const std::vector<uint64_t> expected = {6, 1};
    EXPECT_EQ(discard_run(*lavapipe_), expected);
    EXPECT_EQ(discard_run(*tilevk_), expected);
}

// Three large triangles of the ring (the scene's consecutive vertices make slivers that cover no pixel centre).
const std::vector<uint32_t> kBigTriangles = {0, 21, 42, 5, 26, 47, 10, 31, 52};

// A named difference (icd/README.md "Queries"): llvmpipe_get_query_result, which lavapipe's vkGetQueryPoolResults
// calls once per query and read, sets the query's fragment shader invocations to (itself + the binned count) x 16
// (lp_query.c), so the n-th host read since the query ended reports 16c (16^n - 1) / 15 for c block calls: 16c,
// then 272c, ... vkCmdCopyQueryPoolResults computes 16c each time (llvmpipe_get_query_result_resource). tilevk
// reports 16c at every read. Pinned on both drivers: copies and first host reads equal, second reads 16c and 272c.
std::vector<uint64_t> repeated_reads(Device& dev) {
    Rig rig(dev);
    rig.set_indices(kBigTriangles);
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d, VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT, 1);
    Device::Buffer dst = dev.make_buffer(16);
    VkPipeline list = rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 1);
        rig.begin_pass(cb);
        vkCmdBeginQuery(cb, pool, 0, 0);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, list);
        vkCmdDrawIndexed(cb, 9, 1, 0, 0, 0);
        vkCmdEndQuery(cb, pool, 0);
        vkCmdEndRenderPass(cb);
        vkCmdCopyQueryPoolResults(cb, pool, 0, 1, dst.buffer, 0, 8, VK_QUERY_RESULT_64_BIT);
        vkCmdCopyQueryPoolResults(cb, pool, 0, 1, dst.buffer, 8, 8, VK_QUERY_RESULT_64_BIT);
    }),
              VK_SUCCESS);
    std::vector<uint64_t> out(4, ~0ull);
    std::memcpy(out.data(), dst.map, 16);
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, 8, &out[2], 8, VK_QUERY_RESULT_64_BIT), VK_SUCCESS);
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 1, 8, &out[3], 8, VK_QUERY_RESULT_64_BIT), VK_SUCCESS);
    dev.destroy(dst);
    vkDestroyQueryPool(d, pool, nullptr);
    return out;
}

TEST_F(PipelineStatistics, FragmentInvocationsHostReadsAsLavapipesDefect) {
    const std::vector<uint64_t> l = repeated_reads(*lavapipe_), t = repeated_reads(*tilevk_);
    const uint64_t v = l[0];
    EXPECT_GT(v, 0u);
    EXPECT_EQ(v % 16, 0u);  // 16 per 4x4 block
    EXPECT_EQ(l, (std::vector<uint64_t>{v, v, v, 17 * v}));
    EXPECT_EQ(t, (std::vector<uint64_t>{v, v, v, v}));
}

// A pipeline without a fragment shader (and no depth or stencil test): lavapipe gives it a dummy fragment shader,
// which llvmpipe does not take for a null one (nir_tgsi_scan_shader reports 2 instructions for every NIR shader), so
// the draw is rasterized — its triangles reach setup and its blocks call the fragment function — and the clipping
// invocation total is not reset. Clipping invocations, clipping primitives, fragment shader invocations.
std::vector<uint64_t> no_fs_run(Device& dev) {
    Rig rig(dev);
    rig.set_indices(kBigTriangles);
    VkDevice d = dev.device();
    VkQueryPool pool = make_pool(d,
                                 VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
                                     VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |
                                     VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT,
                                 2);
    VkPipeline list = rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST);
    VkPipeline bare = rig.pipeline(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, false, false, /*with_fs=*/false);
    EXPECT_EQ(dev.run([&](VkCommandBuffer cb) {
        vkCmdResetQueryPool(cb, pool, 0, 2);
        rig.begin_pass(cb);
        vkCmdBeginQuery(cb, pool, 0, 0);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, list);
        vkCmdDrawIndexed(cb, 6, 1, 0, 0, 0);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, bare);
        vkCmdDrawIndexed(cb, 9, 1, 0, 0, 0);
        vkCmdEndQuery(cb, pool, 0);
        vkCmdBeginQuery(cb, pool, 1, 0);
        vkCmdDrawIndexed(cb, 9, 1, 0, 0, 0);
        vkCmdEndQuery(cb, pool, 1);
        vkCmdEndRenderPass(cb);
    }),
              VK_SUCCESS);
    std::vector<uint64_t> out(6, ~0ull);
    EXPECT_EQ(vkGetQueryPoolResults(d, pool, 0, 2, 48, out.data(), 24, VK_QUERY_RESULT_64_BIT), VK_SUCCESS);
    vkDestroyQueryPool(d, pool, nullptr);
    return out;
}

TEST_F(PipelineStatistics, DrawWithoutFragmentShaderCountsAsLavapipe) {
    // (Each query is read once: FragmentInvocationsHostReadsAsLavapipesDefect.)
    const std::vector<uint64_t> l = no_fs_run(*lavapipe_);
    expect_counts(l, {2 + 3, 2 + 3, kAny, 3, 3, kAny});
    EXPECT_GT(l[5], 0u);
    EXPECT_EQ(no_fs_run(*tilevk_), l);
}

// tilevk reports pipelineStatisticsQuery; a pool asking for a counter that is not core Vulkan's (here bit 11) is
// refused with VK_ERROR_FEATURE_NOT_PRESENT, and a device without the feature refuses the pool type, by name.
TEST(PipelineStatisticsReported, FeatureAndRefusalsByName) {
    Harness h(/*validation=*/false);  // the layer would report the invalid requests themselves
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    VkPhysicalDeviceFeatures f{};
    vkGetPhysicalDeviceFeatures(pd, &f);
    EXPECT_TRUE(f.pipelineStatisticsQuery);
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
    ci.queryCount = 2;
    ci.pipelineStatistics = kAll;
    VkQueryPool p = VK_NULL_HANDLE;
    std::unique_ptr<Device> with = make_device(pd, true);
    ASSERT_TRUE(with->ok());
    EXPECT_EQ(vkCreateQueryPool(with->device(), &ci, nullptr, &p), VK_SUCCESS);
    vkDestroyQueryPool(with->device(), p, nullptr);
    p = VK_NULL_HANDLE;
    ci.pipelineStatistics = kAll | (1u << 11);
    testing::internal::CaptureStderr();
    EXPECT_EQ(vkCreateQueryPool(with->device(), &ci, nullptr, &p), VK_ERROR_FEATURE_NOT_PRESENT);
    EXPECT_NE(testing::internal::GetCapturedStderr().find("tilevk does not count"), std::string::npos);
    EXPECT_EQ(p, VkQueryPool(VK_NULL_HANDLE));
    std::unique_ptr<Device> without = make_device(pd, false);
    ASSERT_TRUE(without->ok());
    ci.pipelineStatistics = kAll;
    testing::internal::CaptureStderr();
    EXPECT_EQ(vkCreateQueryPool(without->device(), &ci, nullptr, &p), VK_ERROR_FEATURE_NOT_PRESENT);
    EXPECT_NE(testing::internal::GetCapturedStderr().find("pipelineStatisticsQuery"), std::string::npos);
    EXPECT_EQ(p, VkQueryPool(VK_NULL_HANDLE));
}

}  // namespace
