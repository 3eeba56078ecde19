// Compute through the API (suite ApiCompute): compute pipelines with specialization, push constants and descriptor
// sets at the compute bind point, vkCmdDispatch / vkCmdDispatchIndirect, every compute built-in, transfer and
// graphics work ordered around dispatches by pipeline barriers — on tilevk and lavapipe with the validation layer,
// bytes compared, plus the answers computed here (SAXPY, the built-ins). Then tilevk alone: the same bytes for one
// worker thread and four, and bad input (limits, a missing entry point, what is not implemented yet) refused with a
// message naming it. Shared memory, barriers and atomics: results whose order the shader leaves open are checked
// order-free (sums, minima, sorted counters) and compared byte for byte.
// Then suite ApiDeviceGroup (VK_KHR_device_group): vkCmdDispatchBase, device render areas, peer memory.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>

#include "api_breadth.h"
#include "api_breadth_compute.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

#include "cp_atomic_comp.h"
#include "cp_barrier_comp.h"
#include "cp_binds_comp.h"
#include "cp_broadcast_dynamic_comp.h"
#include "cp_counters_comp.h"
#include "cp_dispatch_base_comp.h"
#include "cp_double_atomic_comp.h"
#include "cp_ids_comp.h"
#include "cp_reduce_comp.h"
#include "cp_saxpy_comp.h"
#include "cp_shared_comp.h"
#include "cp_shared_size_comp.h"
#include "cp_subgroup_comp.h"
#include "cp_vertices_comp.h"

class ApiCompute : public ApiBreadth {};

std::vector<float> random_floats(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(-100.0f, 100.0f);
    std::vector<float> v(n);
    for (float& f : v) f = dist(rng);
    return v;
}

// SAXPY over n elements: y filled by vkCmdFillBuffer's pattern and then updated, the dispatch, its result copied to
// another buffer (transfer -> compute -> transfer). Returns the copy.
Bytes saxpy(Kit& k, uint32_t n, float a) {
    const std::vector<float> x = random_floats(n, 7);
    Device::Buffer xb = k.buffer_of(x, kStorage);
    Device::Buffer yb = k.buffer(VkDeviceSize(n) * 4, kStorage);
    Device::Buffer out = k.buffer(VkDeviceSize(n) * 4);
    StorageSet s = storage_set(k, {&xb, &yb}, 8);
    VkPipeline p = compute_pipeline(k, SPV(cp_saxpy_comp), s.layout);
    struct {
        float a;
        uint32_t n;
    } push{a, n};
    const uint32_t two = 0x40000000u;  // 2.0f
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdFillBuffer(c, yb.buffer, 0, VK_WHOLE_SIZE, two);
        vkCmdUpdateBuffer(c, yb.buffer, 0, 4, &two);
        barrier(c, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdPushConstants(c, s.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        vkCmdDispatch(c, (n + 63) / 64, 1, 1);
        barrier(c, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_READ_BIT);
        const VkBufferCopy r{0, 0, VkDeviceSize(n) * 4};
        vkCmdCopyBuffer(c, yb.buffer, out.buffer, 1, &r);
    }),
              VK_SUCCESS);
    const auto* y = static_cast<const float*>(out.map);
    size_t wrong = 0;
    for (uint32_t i = 0; i < n; ++i) wrong += y[i] != a * x[i] + 2.0f;  // mul, then add (no fused multiply-add)
    EXPECT_EQ(wrong, 0u) << "of " << n;
    return Kit::bytes(out);
}

// cp_ids.comp at workgroup size (sx, sy, 2) (no specialization: (1, 1, 2)) over `groups` workgroups, directly or
// through vkCmdDispatchIndirect (its counts written by vkCmdUpdateBuffer in the same command buffer). Checks every
// record against the built-ins' definitions and returns the buffer.
Bytes ids(Kit& k, const uint32_t groups[3], int sx, int sy, bool indirect) {
    const uint32_t size[3] = {sx > 0 ? uint32_t(sx) : 1, sy > 0 ? uint32_t(sy) : 1, 2};
    const uint32_t total[3] = {groups[0] * size[0], groups[1] * size[1], groups[2] * size[2]};
    const uint32_t n = total[0] * total[1] * total[2];
    Device::Buffer out = k.buffer(VkDeviceSize(n) * 64, kStorage);
    Device::Buffer args = k.buffer(16, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    StorageSet s = storage_set(k, {&out});
    const VkSpecializationMapEntry entries[2] = {{0, 0, 4}, {1, 4, 4}};
    const uint32_t values[2] = {size[0], size[1]};
    VkSpecializationInfo spec{2, entries, sizeof values, values};
    VkPipeline p = compute_pipeline(k, SPV(cp_ids_comp), s.layout, sx > 0 ? &spec : nullptr);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        if (indirect) {
            const uint32_t cmd[4] = {groups[0], groups[1], groups[2], 0};
            vkCmdUpdateBuffer(c, args.buffer, 0, sizeof cmd, cmd);
            barrier(c, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
            vkCmdDispatchIndirect(c, args.buffer, 0);
        } else {
            vkCmdDispatch(c, groups[0], groups[1], groups[2]);
        }
    }),
              VK_SUCCESS);
    const auto* rec = static_cast<const uint32_t*>(out.map);
    size_t wrong = 0;
    for (uint32_t z = 0; z < total[2]; ++z)
        for (uint32_t y = 0; y < total[1]; ++y)
            for (uint32_t x = 0; x < total[0]; ++x) {
                const uint32_t* r = rec + 16 * (x + total[0] * (y + total[1] * z));
                const uint32_t g[3] = {x, y, z};
                const uint32_t l[3] = {x % size[0], y % size[1], z % size[2]};
                // clang-format off: one record per line
                const uint32_t want[16] = {l[0],
                                           l[1],
                                           l[2],
                                           l[0] + size[0] * (l[1] + size[1] * l[2]),
                                           x,
                                           y,
                                           z,
                                           0xC0FFEEu,
                                           g[0] / size[0],
                                           g[1] / size[1],
                                           g[2] / size[2],
                                           7u,
                                           groups[0],
                                           groups[1],
                                           groups[2],
                                           size[0] * 10000 + size[1] * 100 + size[2]};
                // clang-format on
                wrong += std::memcmp(r, want, sizeof want) != 0;
            }
    EXPECT_EQ(wrong, 0u) << "invocations of " << n;
    return Kit::bytes(out);
}

TEST_F(ApiCompute, SaxpyBetweenTransfers) {
    both([](Kit& k) { return saxpy(k, 100003, 1.7f); });
}

TEST_F(ApiCompute, BuiltInsWithSpecializedLocalSize) {
    const uint32_t groups[3] = {3, 2, 2};
    both([&](Kit& k) { return ids(k, groups, 5, 3, false); });  // 30 invocations: two batches, one of 14
}

TEST_F(ApiCompute, BuiltInsWithTheDefaultLocalSize) {
    const uint32_t groups[3] = {7, 3, 2};
    both([&](Kit& k) { return ids(k, groups, 0, 0, false); });  // (1, 1, 2): the shader's defaults
}

TEST_F(ApiCompute, DispatchIndirectReadsCountsWrittenEarlierInTheSubmission) {
    const uint32_t groups[3] = {4, 3, 1};
    both([&](Kit& k) { return ids(k, groups, 16, 2, true); });
}

// Uniform buffer, dynamic storage buffer and push constants at the compute bind point, while other sets and a
// graphics pipeline are bound at the graphics bind point (which a dispatch must not use).
TEST_F(ApiCompute, DescriptorSetsAndPushConstantsOfTheComputeBindPoint) {
    both([](Kit& k) {
        struct {
            float scale[4];
            uint32_t rounds, pad[3];
        } u{{0.5f, -1.25f, 3.0f, 0.125f}, 5, {}};
        Device::Buffer ub = k.buffer(sizeof u, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        std::memcpy(ub.map, &u, sizeof u);
        Device::Buffer ob = k.buffer(8192, kStorage);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT},
                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 1, VK_SHADER_STAGE_COMPUTE_BIT}});
        VkPipelineLayout layout = k.pipeline_layout({dsl}, {{VK_SHADER_STAGE_COMPUTE_BIT, 0, 16}});
        VkDescriptorSet set = k.descriptor_set(dsl), other = k.descriptor_set(dsl);
        const VkDescriptorBufferInfo ui = whole(ub), oi{ob.buffer, 0, 256 * 16};
        for (VkDescriptorSet s : {set, other}) {
            k.write(s, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &ui, nullptr);
            k.write(s, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, &oi, nullptr);
        }
        VkPipeline p = compute_pipeline(k, SPV(cp_binds_comp), layout);
        Target t = target(k);
        Pipe gp;
        gp.rp = t.rp;
        VkPipeline graphics = k.pipeline(gp);
        const float bias[4] = {10.0f, -20.0f, 0.5f, 1e-3f};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            const uint32_t offset = 4096;
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 1, &offset);
            const uint32_t wrong_offset = 0;  // the graphics bind point's set: must not be used
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &other, 1, &wrong_offset);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, graphics);
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof bias, bias);
            vkCmdDispatch(c, 8, 1, 1);
        }),
                  VK_SUCCESS);
        const Bytes b = Kit::bytes(ob);
        const auto* f = reinterpret_cast<const float*>(b.data());
        EXPECT_EQ(f[0], 0.0f);      // the graphics set's offset: untouched
        EXPECT_EQ(f[1024], 10.0f);  // invocation 0 at the compute set's offset: scale * 0 + bias (no rounds, even)
        return b;
    });
}

// A dispatch writes the vertices a draw pulls from a storage buffer (compute -> vertex shader), and the draw's
// image is copied after it.
TEST_F(ApiCompute, DispatchWritesWhatADrawReads) {
    both([](Kit& k) {
        Device::Buffer verts = k.buffer(8 * 32, kStorage);
        VkDescriptorSetLayout dsl = k.set_layout(
            {{1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorBufferInfo vi = whole(verts);
        k.write(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &vi, nullptr);
        VkPipeline cp = compute_pipeline(k, SPV(cp_vertices_comp), layout);
        Target t = target(k);
        Pipe gp;
        gp.vs = SPV(ab_pull_vert);
        gp.bindings = {};
        gp.attrs = {};
        gp.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
        gp.rp = t.rp;
        gp.layout = layout;
        VkPipeline draw = k.pipeline(gp);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, cp);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
            vkCmdDispatch(c, 2, 1, 1);
            barrier(c, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_PIPELINE_STAGE_VERTEX_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, draw);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
            vkCmdDraw(c, 8, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        const Bytes image = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(px(image, 16, 16)[0] + px(image, 16, 16)[1], 0);  // the strip covers the centre
        return concat({image, Kit::bytes(verts)});
    });
}

// ---- tilevk alone ---------------------------------------------------------------------------------------------

// cp_reduce.comp at workgroup size n over `groups` (<= 64) workgroups: the sums checked against the input here.
Bytes reduce(Kit& k, uint32_t n, uint32_t groups) {
    std::mt19937 rng(n);
    std::vector<uint32_t> x(size_t(n) * groups);
    for (uint32_t& w : x) w = rng() % 100000;
    Device::Buffer xb = k.buffer_of(x, kStorage);
    Device::Buffer yb = k.buffer(VkDeviceSize(64 + x.size()) * 4, kStorage);
    StorageSet s = storage_set(k, {&xb, &yb});
    const VkSpecializationMapEntry entry{0, 0, 4};
    VkSpecializationInfo spec{1, &entry, 4, &n};
    VkPipeline p = compute_pipeline(k, SPV(cp_reduce_comp), s.layout, &spec);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdDispatch(c, groups, 1, 1);
    }),
              VK_SUCCESS);
    const auto* y = static_cast<const uint32_t*>(yb.map);
    size_t wrong = 0;
    for (uint32_t g = 0; g < groups; ++g)
        wrong += y[g] != std::accumulate(x.begin() + g * n, x.begin() + (g + 1) * n, 0u);
    EXPECT_EQ(wrong, 0u) << "workgroups of " << groups << " at size " << n;
    return Kit::bytes(yb);
}

// cp_counters.comp over `groups` workgroups of 48: every counter checked against the input here.
Bytes counters(Kit& k, uint32_t groups) {
    const uint32_t n = groups * 48;
    std::mt19937 rng(groups);
    std::vector<uint32_t> x(n);
    for (uint32_t& w : x) w = rng() % 100000;
    Device::Buffer xb = k.buffer_of(x, kStorage);
    std::vector<uint32_t> init(16 + 4 * size_t(groups), 0);
    init[1] = 0x7FFFFFFF, init[2] = 0x80000000u, init[3] = ~0u, init[5] = ~0u;
    Device::Buffer cb = k.buffer_of(init, kStorage);
    StorageSet s = storage_set(k, {&xb, &cb});
    VkPipeline p = compute_pipeline(k, SPV(cp_counters_comp), s.layout);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdDispatch(c, groups, 1, 1);
    }),
              VK_SUCCESS);
    uint32_t sum = 0, andv = ~0u, orv = 0, xorv = 0;
    for (uint32_t v : x) sum += v, andv &= ~(1u << (v % 32)), orv |= 1u << (v % 31), xorv ^= v;
    const uint32_t lo = *std::min_element(x.begin(), x.end()), hi = *std::max_element(x.begin(), x.end());
    const uint32_t want[13] = {sum, lo - 50000, hi - 50000, lo, hi, andv, orv, xorv, n, 7, 1, 1, hi};
    const auto* c = static_cast<const uint32_t*>(cb.map);
    for (int i = 0; i < 13; ++i) EXPECT_EQ(c[i], want[i]) << "counter " << i;
    size_t wrong = 0;
    for (uint32_t g = 0; g < groups; ++g) {
        const auto first = x.begin() + g * 48, last = first + 48;
        uint32_t cas = 0;
        for (auto it = first; it != last; ++it) cas = std::max(cas, *it ^ 0x5555u);
        const uint32_t* r = c + 16 + 4 * g;
        wrong += r[0] != std::accumulate(first, last, 0u) || r[1] != *std::max_element(first, last) || r[2] != cas ||
                 r[3] != *std::min_element(first, last);
    }
    EXPECT_EQ(wrong, 0u) << "workgroups of " << groups;
    return Kit::bytes(cb);
}

// Shared-memory reductions between barriers at workgroup sizes 64, 256 and 24 (two batches, the second of 8
// invocations), 37 workgroups each: the sums, and the partial sums left in shared memory, byte for byte.
TEST_F(ApiCompute, SharedMemoryReductionWithBarriers) {
    for (uint32_t n : {64u, 256u, 24u}) {
        SCOPED_TRACE(n);
        both([&](Kit& k) { return reduce(k, n, 37); });
    }
}

// Storage-buffer atomics of every kind from 300 workgroups (spread over the worker threads), compare-exchange
// loops on a buffer and on shared memory, shared-memory atomics between barriers: results the order of the
// invocations does not change, byte for byte.
TEST_F(ApiCompute, AtomicCountersAndCompareExchange) {
    both([](Kit& k) { return counters(k, 300); });
}

// The shaders that were refused before compute step 2 (cp_shared.comp: a reversal through shared memory;
// cp_barrier.comp: a neighbour's storage-buffer write read after a barrier), and cp_atomic.comp's counter, whose
// returned values are a permutation of 0..n-1 in an order lavapipe and tilevk need not share: compared sorted.
TEST_F(ApiCompute, SharedMemoryBarriersAndAtomicCounter) {
    both([](Kit& k) {
        std::vector<uint32_t> x(128);
        for (uint32_t i = 0; i < 128; ++i) x[i] = i * 2654435761u;
        Device::Buffer sb = k.buffer_of(x, kStorage), bb = k.buffer(128 * 4, kStorage);
        Device::Buffer ab = k.buffer(4 + 96 * 4, kStorage);
        StorageSet ss = storage_set(k, {&sb}), sbar = storage_set(k, {&bb}), sat = storage_set(k, {&ab});
        VkPipeline shared = compute_pipeline(k, SPV(cp_shared_comp), ss.layout);
        VkPipeline bar = compute_pipeline(k, SPV(cp_barrier_comp), sbar.layout);
        VkPipeline atomic = compute_pipeline(k, SPV(cp_atomic_comp), sat.layout);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            const std::pair<VkPipeline, const StorageSet*> runs[3] = {{shared, &ss}, {bar, &sbar}, {atomic, &sat}};
            const uint32_t groups[3] = {4, 2, 6};
            for (int i = 0; i < 3; ++i) {
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, runs[i].first);
                vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, runs[i].second->layout, 0, 1,
                                        &runs[i].second->set, 0, nullptr);
                vkCmdDispatch(c, groups[i], 1, 1);
            }
        }),
                  VK_SUCCESS);
        const auto* r = static_cast<const uint32_t*>(sb.map);
        for (uint32_t i = 0; i < 128; ++i) EXPECT_EQ(r[i], x[(i & ~31u) + 31 - i % 32]) << i;
        const auto* b = static_cast<const uint32_t*>(bb.map);
        for (uint32_t i = 0; i < 64; ++i) EXPECT_EQ(b[64 + i], (i ^ 17u) * 3 + 1) << i;
        Bytes counter = Kit::bytes(ab);
        auto* words = reinterpret_cast<uint32_t*>(counter.data());
        EXPECT_EQ(words[0], 96u);
        std::sort(words + 1, words + 97);
        for (uint32_t i = 0; i < 96; ++i) EXPECT_EQ(words[1 + i], i);
        return concat({Kit::bytes(sb), Kit::bytes(bb), counter});
    });
}

// The same bytes for one worker thread and four (TILEVK_THREADS is read at a queue's first submission).
TEST_F(ApiCompute, SameBytesForEveryThreadCount) {
    std::vector<Bytes> results;
    for (const char* threads : {"1", "4"}) {
        setenv("TILEVK_THREADS", threads, 1);
        Device dev(harness_->find_device("tilevk"));
        ASSERT_TRUE(dev.ok());
        Kit k(dev);
        const uint32_t groups[3] = {9, 5, 3};
        results.push_back(concat({saxpy(k, 250000, -0.3f), ids(k, groups, 7, 5, false), reduce(k, 24, 64),
                                  reduce(k, 256, 40), counters(k, 500)}));
    }
    unsetenv("TILEVK_THREADS");
    expect_same(results[0], results[1], "TILEVK_THREADS=1 vs 4");
}

// Invalid or unsupported compute input on tilevk without the validation layer: pipelines are refused with an
// error, a null handle and a message naming the limit or the SPIR-V it lacks; dispatches past the limits do
// nothing; the device keeps dispatching.
TEST_F(ApiCompute, BadInputIsRefusedByName) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    Device dev(plain.find_device("tilevk"));
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    Device::Buffer buf = k.buffer(4096, kStorage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    StorageSet s = storage_set(k, {&buf});
    const auto refused = [&](Spv code, const VkSpecializationInfo* spec, const char* entry, const char* named) {
        VkResult r = VK_SUCCESS;
        VkPipeline p = VK_NULL_HANDLE;
        const std::string err = stderr_of([&] { p = compute_pipeline(k, code, s.layout, spec, &r, entry); });
        EXPECT_EQ(r, VK_ERROR_INITIALIZATION_FAILED) << named;
        EXPECT_EQ(p, VK_NULL_HANDLE) << named;
        EXPECT_NE(err.find(named), std::string::npos) << "message: " << err;
    };
    const VkSpecializationMapEntry entries[2] = {{0, 0, 4}, {1, 4, 4}};
    const uint32_t too_wide[2] = {2000, 1}, too_many[2] = {512, 2};
    VkSpecializationInfo wide{2, entries, 8, too_wide}, many{2, entries, 8, too_many};
    refused(SPV(cp_ids_comp), &wide, "main", "maxComputeWorkGroupSize[0] = 1024");
    refused(SPV(cp_ids_comp), &many, "main", "maxComputeWorkGroupInvocations = 1024");
    refused(SPV(cp_ids_comp), nullptr, "nope", "no compute entry point named 'nope'");
    const uint32_t shared_words = 8193;  // 32772 bytes of Workgroup memory
    VkSpecializationInfo big{1, entries, 4, &shared_words};
    refused(
        SPV(cp_shared_size_comp), &big, "main",
        "Workgroup variables need 32772 bytes, more than VkPhysicalDeviceLimits::maxComputeSharedMemorySize = 32768");
    refused(SPV(cp_double_atomic_comp), nullptr, "main", "OpAtomicExchange on a 64-bit float");
    compute_pipeline(k, SPV(cp_shared_size_comp), s.layout);  // 8192 words: exactly the limit

    VkPipeline p = compute_pipeline(k, SPV(cp_ids_comp), s.layout);  // (1, 1, 2)
    const std::string err = stderr_of([&] {
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdDispatch(c, 1, 1, 1);  // nothing bound
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
            vkCmdDispatch(c, 70000, 1, 1);
            vkCmdDispatchIndirect(c, buf.buffer, 4090);  // past the end
            const uint32_t huge[3] = {1, 1, 65536};
            vkCmdUpdateBuffer(c, buf.buffer, 0, sizeof huge, huge);
            vkCmdDispatchIndirect(c, buf.buffer, 0);
        }),
                  VK_SUCCESS);
    });
    EXPECT_NE(err.find("no compute pipeline is bound"), std::string::npos) << err;
    EXPECT_NE(err.find("groupCountX = 70000"), std::string::npos) << err;
    EXPECT_NE(err.find("groupCountZ = 65536"), std::string::npos) << err;
    EXPECT_NE(err.find("outside the buffer"), std::string::npos) << err;
    const auto* words = static_cast<const uint32_t*>(buf.map);
    EXPECT_EQ(words[7], 0u);  // no dispatch wrote the first record's marker
    // The device still dispatches: one workgroup of (1, 1, 2) writes two records.
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdDispatch(c, 1, 1, 1);
    }),
              VK_SUCCESS);
    EXPECT_EQ(words[16 + 2], 1u);  // the second invocation's LocalInvocationId.z
    EXPECT_EQ(words[16 + 3], 1u);  // and LocalInvocationIndex
    EXPECT_EQ(words[7], 0xC0FFEEu);
}

// VK_KHR_device_group on both drivers' one-device groups: vkCmdDispatchBase (workgroup IDs from the base, checked
// against their definitions here), a render area given per device by VkDeviceGroupRenderPassBeginInfo (it
// overrides renderArea; lavapipe 22.3 ignores it, a named difference) and vkCmdSetDeviceMask(1).
class ApiDeviceGroup : public ApiCompute {
  protected:
    void SetUp() override {
        const std::vector<const char*> ext = {VK_KHR_DEVICE_GROUP_EXTENSION_NAME};
        tilevk_group_ = std::make_unique<Device>(tilevk_->physical(), nullptr, ext);
        lavapipe_group_ = std::make_unique<Device>(lavapipe_->physical(), nullptr, ext);
        ASSERT_TRUE(tilevk_group_->ok() && lavapipe_group_->ok());
    }
    Bytes both(const std::function<Bytes(Kit&)>& scene) { return both_on(*tilevk_group_, *lavapipe_group_, scene); }
    std::unique_ptr<Device> tilevk_group_, lavapipe_group_;
};

// cp_dispatch_base.comp (workgroups of 4x2x1) from workgroup `base`, `groups` of them, in a pipeline made with
// VK_PIPELINE_CREATE_DISPATCH_BASE_BIT. Every invocation of the grid up to base + groups is checked: those of the
// dispatch against the built-ins' definitions, the others untouched.
Bytes dispatch_base(Kit& k, const uint32_t base[3], const uint32_t groups[3]) {
    const uint32_t size[3] = {4, 2, 1};
    uint32_t extent[3];
    for (int i = 0; i < 3; ++i) extent[i] = (base[i] + groups[i]) * size[i];
    const uint32_t n = extent[0] * extent[1] * extent[2];
    Device::Buffer out = k.buffer(VkDeviceSize(n) * 64, kStorage);
    StorageSet s = storage_set(k, {&out}, 8);
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.flags = VK_PIPELINE_CREATE_DISPATCH_BASE_BIT;
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = k.shader(SPV(cp_dispatch_base_comp));
    ci.stage.pName = "main";
    ci.layout = s.layout;
    VkPipeline p = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateComputePipelines(k.d, VK_NULL_HANDLE, 1, &ci, nullptr, &p), VK_SUCCESS);
    k.undo(VK_OBJECT_TYPE_PIPELINE, p, [&k, p] { vkDestroyPipeline(k.d, p, nullptr); });
    auto dispatch_base_fn =
        reinterpret_cast<PFN_vkCmdDispatchBaseKHR>(vkGetDeviceProcAddr(k.d, "vkCmdDispatchBaseKHR"));
    auto set_mask = reinterpret_cast<PFN_vkCmdSetDeviceMaskKHR>(vkGetDeviceProcAddr(k.d, "vkCmdSetDeviceMaskKHR"));
    EXPECT_NE(dispatch_base_fn, nullptr);
    EXPECT_NE(set_mask, nullptr);
    if (dispatch_base_fn == nullptr || set_mask == nullptr) return {};
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdFillBuffer(c, out.buffer, 0, VK_WHOLE_SIZE, 0xDEADBEEFu);
        barrier(c, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_WRITE_BIT);
        set_mask(c, 1);
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdPushConstants(c, s.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 8, extent);
        dispatch_base_fn(c, base[0], base[1], base[2], groups[0], groups[1], groups[2]);
    }),
              VK_SUCCESS);
    const auto* rec = static_cast<const uint32_t*>(out.map);
    size_t wrong = 0, dispatched = 0;
    for (uint32_t z = 0; z < extent[2]; ++z)
        for (uint32_t y = 0; y < extent[1]; ++y)
            for (uint32_t x = 0; x < extent[0]; ++x) {
                const uint32_t* r = rec + 16 * (x + extent[0] * (y + extent[1] * z));
                const uint32_t g[3] = {x, y, z}, wg[3] = {x / size[0], y / size[1], z / size[2]};
                const bool inside = wg[0] >= base[0] && wg[1] >= base[1] && wg[2] >= base[2];
                dispatched += inside;
                uint32_t want[16];
                if (inside) {
                    const uint32_t l[3] = {x % size[0], y % size[1], z % size[2]};
                    const uint32_t record[16] = {l[0],      l[1],      l[2],      l[0] + size[0] * l[1],
                                                 g[0],      g[1],      g[2],      0xC0FFEEu,
                                                 wg[0],     wg[1],     wg[2],     7u,
                                                 groups[0], groups[1], groups[2], 0xBA5Eu};
                    std::memcpy(want, record, sizeof want);
                } else {
                    std::fill(std::begin(want), std::end(want), 0xDEADBEEFu);
                }
                wrong += std::memcmp(r, want, sizeof want) != 0;
            }
    EXPECT_EQ(wrong, 0u) << "records of " << n;
    EXPECT_EQ(dispatched, size_t(groups[0] * groups[1] * groups[2]) * 8);
    return Kit::bytes(out);
}

TEST_F(ApiDeviceGroup, DispatchBaseOffsetsTheWorkgroupIds) {
    const uint32_t base[3] = {3, 1, 2}, groups[3] = {5, 3, 2};
    both([&](Kit& k) { return dispatch_base(k, base, groups); });
    const uint32_t zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
    both([&](Kit& k) { return dispatch_base(k, zero, one); });
}

// An image filled with one colour, then a render pass that clears it to another inside the device render area
// (VkDeviceGroupRenderPassBeginInfo; renderArea says the whole image and must be overridden, as the spec says).
// Named difference: lavapipe 22.3 ignores the device render area and clears all of renderArea; both are pinned.
Bytes clear_in_device_render_area(Kit& k, const VkRect2D& area) {
    const VkFormat f = VK_FORMAT_R8G8B8A8_UNORM;
    Device::Image img = k.image(
        f, 32, 32,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    VkAttachmentDescription a = attachment(f, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE);
    a.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;  // what lies outside the area is kept
    VkRenderPass rp = k.render_pass({a}, {subpass(&kColour0)});
    VkFramebuffer fb = k.framebuffer(rp, {k.view(img.image, f, VK_IMAGE_ASPECT_COLOR_BIT)}, 32, 32);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        transition(c, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkClearColorValue before = {{0.0f, 0.0f, 1.0f, 1.0f}};
        const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(c, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &before, 1, &all);
        barrier(c, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
        VkDeviceGroupRenderPassBeginInfo group{VK_STRUCTURE_TYPE_DEVICE_GROUP_RENDER_PASS_BEGIN_INFO};
        group.deviceMask = 1;
        group.deviceRenderAreaCount = 1;
        group.pDeviceRenderAreas = &area;
        const VkClearValue inside = clear_color(1.0f, 0.0f, 0.0f, 1.0f);
        VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        bi.pNext = &group;
        bi.renderPass = rp;
        bi.framebuffer = fb;
        bi.renderArea = {{0, 0}, {32, 32}};
        bi.clearValueCount = 1;
        bi.pClearValues = &inside;
        vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(img.image, 32, 32, 4);
}

// How many texels of a 32x32 RGBA8 image are not red inside `area` and blue outside it.
size_t wrong_texels(const Bytes& got, const VkRect2D& area) {
    if (got.size() != 32 * 32 * 4) return 32 * 32;
    size_t wrong = 0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const bool in = x >= uint32_t(area.offset.x) && x < area.offset.x + area.extent.width &&
                            y >= uint32_t(area.offset.y) && y < area.offset.y + area.extent.height;
            const uint8_t want[4] = {uint8_t(in ? 255 : 0), 0, uint8_t(in ? 0 : 255), 255};
            wrong += std::memcmp(&got[(y * 32 + x) * 4], want, 4) != 0;
        }
    return wrong;
}

TEST_F(ApiDeviceGroup, DeviceRenderAreaOverridesTheRenderArea) {
    const VkRect2D area = {{8, 4}, {17, 13}}, whole = {{0, 0}, {32, 32}};
    Bytes tilevk, lavapipe;
    {
        Kit k(*tilevk_group_);
        tilevk = clear_in_device_render_area(k, area);
    }
    {
        Kit k(*lavapipe_group_);
        lavapipe = clear_in_device_render_area(k, area);
    }
    EXPECT_EQ(wrong_texels(tilevk, area), 0u) << "tilevk";
    EXPECT_EQ(wrong_texels(lavapipe, whole), 0u) << "lavapipe (known to clear all of renderArea)";
}

// Subgroups of 8 (lavapipe's size): workgroup sizes that are multiples of 8 give lavapipe's records byte for byte.
// Named difference at other sizes: lavapipe 22.3 reports gl_NumSubgroups = floor(size / 8) (1 for 13 invocations,
// though it numbers the second subgroup 1); tilevk the spec's ceil(size / 8). Every other word is equal.
TEST_F(ApiCompute, Subgroups) {
    for (uint32_t n : {64u, 24u, 16u, 8u}) {
        SCOPED_TRACE(n);
        both([n](Kit& k) { return subgroup_records(k, SPV(cp_subgroup_comp), n); });
    }
    Bytes t, l;
    {
        Kit k(*tilevk_);
        t = subgroup_records(k, SPV(cp_subgroup_comp), 13);
    }
    {
        Kit k(*lavapipe_);
        l = subgroup_records(k, SPV(cp_subgroup_comp), 13);
    }
    ASSERT_EQ(t.size(), l.size());
    for (size_t w = 0; w < t.size() / 4; ++w) {
        uint32_t tw, lw;
        std::memcpy(&tw, &t[w * 4], 4);
        std::memcpy(&lw, &l[w * 4], 4);
        if (w % 16 == 7 && w / 16 % 13 >= 8) continue;  // subgroupBroadcast(v, 5): no lane 5 in the last subgroup
        if (w % 16 == 3) {                              // gl_NumSubgroups
            EXPECT_EQ(tw, 2u) << "word " << w;
            EXPECT_EQ(lw, 1u) << "word " << w;
        } else {
            EXPECT_EQ(tw, lw) << "word " << w;
        }
    }
}

// Vulkan 1.2 subgroupBroadcastDynamicId: a SPIR-V 1.5 module broadcasts from a lane chosen at run time (the same
// within a subgroup, different between subgroups and workgroups); every word equals lavapipe's, and the test's own
// model (the value of the subgroup's lane `id`) holds on tilevk.
TEST_F(ApiCompute, SubgroupBroadcastDynamicId) {
    const Bytes out = both([](Kit& k) {
        std::vector<uint32_t> x(256);
        for (size_t i = 0; i < x.size(); ++i) x[i] = uint32_t(i * 2654435761u >> 7);
        return dispatch_two_words_per_input(k, x, SPV(cp_broadcast_dynamic_comp), 4);
    });
    ASSERT_EQ(out.size(), 256u * 8);
    std::vector<uint32_t> x(256), y(512);
    for (size_t i = 0; i < x.size(); ++i) x[i] = uint32_t(i * 2654435761u >> 7);
    std::memcpy(y.data(), out.data(), out.size());
    for (uint32_t g = 0; g < 256; ++g) {
        const uint32_t id = (x[g / 64] + (g % 64) / 8 * 3) % 8;
        ASSERT_EQ(y[2 * g + 1], id) << g;
        EXPECT_EQ(y[2 * g], x[g / 8 * 8 + id]) << g;
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
