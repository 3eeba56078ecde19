// Descriptor arrays indexed by dynamically uniform values, as far as lavapipe 22.3.6 reports them
// (shaderUniformBufferArrayDynamicIndexing, shaderStorageBufferArrayDynamicIndexing; its sampled and storage image
// forms are VK_FALSE): a fragment shader reading uniform-buffer and storage-buffer arrays at push-constant indices,
// and a compute shader reading and writing storage buffer arrays at push-constant indices. Both drivers, byte for
// byte, plus checks that depend on neither driver: the dynamic indices give the image the constant indices give, and
// the compute results are computed here.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "ab_dyn_index_frag.h"
#include "ab_pull_vert.h"
#include "ab_tex_array_frag.h"
#include "api_breadth.h"
#include "cp_dyn_index_comp.h"

namespace tilevk::test::breadth {
namespace {

class ApiDynamicIndexing : public ApiBreadth {
  protected:
    static VkPhysicalDeviceFeatures features() {
        VkPhysicalDeviceFeatures f{};
        f.shaderUniformBufferArrayDynamicIndexing = VK_TRUE;
        f.shaderStorageBufferArrayDynamicIndexing = VK_TRUE;
        return f;
    }
    // Both drivers with the two features enabled; runs `scene` on each, expects the same bytes, returns tilevk's.
    Bytes both_indexing(const std::function<Bytes(Kit&)>& scene) {
        const VkPhysicalDeviceFeatures f = features();
        Device t(tilevk_->physical(), &f), l(lavapipe_->physical(), &f);
        EXPECT_TRUE(t.ok() && l.ok());
        if (!t.ok() || !l.ok()) return {};
        return both_on(t, l, scene);
    }
};

// The push constants of ab_dyn_index.frag: texs[0] * u[u0].scale + texs[2] * u[u1].scale + texs[1] / 8 + b[b0].
struct Indices {
    int32_t u0, u1, b0;
};

// Six pulled vertices (two triangles) drawn with `fs` once per entry of `draws` (push constants pushed before each
// draw when `fs` has them). The descriptor arrays: three textures, two uniform blocks, two storage buffers (b[0] is
// zero, b[1] a colour).
Bytes draw_arrays(Kit& k, Spv fs, const std::vector<Indices>& draws) {
    Target t = target(k);
    const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
    VkDescriptorSetLayout dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3, F},
                                              {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT},
                                              {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2, F},
                                              {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2, F}});
    VkPipelineLayout layout = k.pipeline_layout({dsl}, {{F, 0, sizeof(Indices)}});
    VkDescriptorSet set = k.descriptor_set(dsl);
    VkSampler smp = k.sampler(VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT);
    VkDescriptorImageInfo ii[3];
    for (uint32_t i = 0; i < 3; ++i) {
        Device::Image tex =
            k.image(VK_FORMAT_R8G8B8A8_UNORM, 4 + i, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        upload_rgba8(k, tex.image, 4 + i, 4, 20 + i);
        ii[i] = {smp, k.view(tex.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
    const VkDeviceSize ualign = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
    const VkDeviceSize salign = std::max<VkDeviceSize>(props.limits.minStorageBufferOffsetAlignment, 16);
    Device::Buffer ubo = k.buffer(2 * ualign, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    const float scales[2][4] = {{0.5f, 0.25f, 1.0f, 1.0f}, {0.25f, 0.5f, 0.0f, 0.0f}};
    for (int i = 0; i < 2; ++i) std::memcpy(static_cast<uint8_t*>(ubo.map) + i * ualign, scales[i], 16);
    Device::Buffer adds = k.buffer(2 * salign, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const float add[2][4] = {{0, 0, 0, 0}, {0.125f, 0.0f, 0.375f, 0.0f}};
    for (int i = 0; i < 2; ++i) std::memcpy(static_cast<uint8_t*>(adds.map) + i * salign, add[i], 16);
    std::vector<Vertex> verts = {
        v(-1, -1, 0, 0, 0, 0),     v(1, -1, 0, 1.5f, 0, 0),          v(-1, 1, 0, 0, 1.5f, 0),
        v(0.9f, 0.8f, 0, 1, 1, 0), v(0.2f, -0.9f, 0, 0.3f, 0.7f, 0), v(-0.7f, 0.6f, 0, 0.9f, 0.2f, 0)};
    Device::Buffer pulled = k.buffer_of(verts, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const VkDescriptorBufferInfo sb{pulled.buffer, 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo ub[2] = {{ubo.buffer, 0, 16}, {ubo.buffer, ualign, 16}};
    const VkDescriptorBufferInfo ab[2] = {{adds.buffer, 0, 16}, {adds.buffer, salign, 16}};
    VkWriteDescriptorSet w[4] = {};
    for (auto& x : w) x = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set};
    w[0].dstBinding = 0, w[0].descriptorCount = 3, w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w[0].pImageInfo = ii;
    w[1].dstBinding = 1, w[1].descriptorCount = 1, w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[1].pBufferInfo = &sb;
    w[2].dstBinding = 2, w[2].descriptorCount = 2, w[2].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    w[2].pBufferInfo = ub;
    w[3].dstBinding = 3, w[3].descriptorCount = 2, w[3].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[3].pBufferInfo = ab;
    vkUpdateDescriptorSets(k.d, 4, w, 0, nullptr);
    Pipe p;
    p.vs = SPV(ab_pull_vert);
    p.fs = fs;
    p.bindings = {};
    p.attrs = {};
    p.rp = t.rp;
    p.layout = layout;
    p.blend = {alpha_over()};
    VkPipeline pipe = k.pipeline(p);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
        begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        for (const Indices& d : draws) {
            vkCmdPushConstants(c, layout, F, 0, sizeof d, &d);
            vkCmdDraw(c, 6, 1, 0, 0);
        }
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 4);
}

// ab_tex_array.frag's constant indices (u[0] and u[1]) given as push constants, with the zero storage buffer b[0]:
// the same image as the constant indices, on each driver.
TEST_F(ApiDynamicIndexing, PushConstantIndicesGiveTheConstantIndicesImage) {
    const Indices same{0, 1, 0};
    const Bytes dynamic = both_indexing([&](Kit& k) { return draw_arrays(k, SPV(ab_dyn_index_frag), {same}); });
    const Bytes constant = both_indexing([&](Kit& k) { return draw_arrays(k, SPV(ab_tex_array_frag), {same}); });
    ASSERT_EQ(dynamic.size(), size_t(32) * 32 * 4);
    EXPECT_EQ(dynamic, constant);
    EXPECT_NE(px(dynamic, 2, 2)[2], 64);  // the triangles were drawn
}

// Other indices in each of three blended draws: every array element is read by some draw.
TEST_F(ApiDynamicIndexing, IndicesChangeBetweenDraws) {
    const std::vector<Indices> draws = {{1, 0, 1}, {0, 0, 0}, {1, 1, 1}};
    const Bytes b = both_indexing([&](Kit& k) { return draw_arrays(k, SPV(ab_dyn_index_frag), draws); });
    const Bytes first = both_indexing([&](Kit& k) { return draw_arrays(k, SPV(ab_dyn_index_frag), {draws[0]}); });
    ASSERT_EQ(b.size(), size_t(32) * 32 * 4);
    EXPECT_NE(b, first);  // the later draws' indices took effect
}

// cp_dyn_index.comp: outs[dst].v[i] = ins[src].v[i] * 3 + src * 1000 + dst, dispatched with (src, dst) = (1, 0) and
// then (0, 1); the expected words are computed here.
TEST_F(ApiDynamicIndexing, StorageBufferArraysInCompute) {
    constexpr uint32_t kN = 16 * 8;
    std::vector<uint32_t> input[2];
    std::mt19937 rng(5);
    for (auto& in : input) {
        in.resize(kN);
        for (uint32_t& x : in) x = rng() % 100000;
    }
    const Bytes got = both_indexing([&](Kit& k) {
        const VkShaderStageFlags C = VK_SHADER_STAGE_COMPUTE_BIT;
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2, C}, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2, C}});
        VkPipelineLayout layout = k.pipeline_layout({dsl}, {{C, 0, 8}});
        VkDescriptorSet set = k.descriptor_set(dsl);
        Device::Buffer ins[2] = {k.buffer_of(input[0], VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
                                 k.buffer_of(input[1], VK_BUFFER_USAGE_STORAGE_BUFFER_BIT)};
        Device::Buffer outs[2] = {k.buffer(kN * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
                                  k.buffer(kN * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT)};
        for (auto& o : outs) std::memset(o.map, 0xAB, kN * 4);
        const VkDescriptorBufferInfo in_info[2] = {{ins[0].buffer, 0, VK_WHOLE_SIZE},
                                                   {ins[1].buffer, 0, VK_WHOLE_SIZE}};
        const VkDescriptorBufferInfo out_info[2] = {{outs[0].buffer, 0, VK_WHOLE_SIZE},
                                                    {outs[1].buffer, 0, VK_WHOLE_SIZE}};
        VkWriteDescriptorSet w[2] = {};
        for (uint32_t b = 0; b < 2; ++b) {
            w[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, b, 0, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
            w[b].pBufferInfo = b == 0 ? in_info : out_info;
        }
        vkUpdateDescriptorSets(k.d, 2, w, 0, nullptr);
        const VkPipeline p = compute_pipeline(k, SPV(cp_dyn_index_comp), layout);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
            const uint32_t first[2] = {1, 0}, second[2] = {0, 1};
            vkCmdPushConstants(c, layout, C, 0, 8, first);
            vkCmdDispatch(c, 2, 2, 1);
            vkCmdPushConstants(c, layout, C, 0, 8, second);
            vkCmdDispatch(c, 2, 2, 1);
        }),
                  VK_SUCCESS);
        return concat({Kit::bytes(outs[0]), Kit::bytes(outs[1])});
    });
    ASSERT_EQ(got.size(), size_t(kN) * 8);
    size_t wrong = 0;
    for (uint32_t dst = 0; dst < 2; ++dst)
        for (uint32_t i = 0; i < kN; ++i) {
            const uint32_t src = 1 - dst;
            const uint32_t want = input[src][i] * 3 + src * 1000 + dst;
            uint32_t word;
            std::memcpy(&word, got.data() + (size_t(dst) * kN + i) * 4, 4);
            if (word != want && wrong++ < 5)
                ADD_FAILURE() << "outs[" << dst << "][" << i << "] " << word << " != " << want;
        }
    EXPECT_EQ(wrong, 0u);
}

}  // namespace
}  // namespace tilevk::test::breadth
