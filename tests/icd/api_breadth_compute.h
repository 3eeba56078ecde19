// Compute helpers of the api_breadth suites (ApiCompute, ApiVulkan13): storage buffers in one set at the compute
// stage, and the memory barrier between stages.
#pragma once

#include <cstring>
#include <random>
#include <vector>

#include "api_breadth.h"

namespace tilevk::test::breadth {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

inline VkDescriptorBufferInfo whole(const Device::Buffer& b) {
    return {b.buffer, 0, VK_WHOLE_SIZE};
}

// Storage buffers at bindings 0.. of one set (compute stage), its layout and a pipeline layout with `push` bytes of
// compute push constants.
struct StorageSet {
    VkDescriptorSetLayout dsl;
    VkPipelineLayout layout;
    VkDescriptorSet set;
};
inline StorageSet storage_set(Kit& k, const std::vector<const Device::Buffer*>& buffers, uint32_t push = 0) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (uint32_t i = 0; i < buffers.size(); ++i)
        bindings.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT});
    StorageSet s{};
    s.dsl = k.set_layout(bindings);
    std::vector<VkPushConstantRange> ranges;
    if (push != 0) ranges.push_back({VK_SHADER_STAGE_COMPUTE_BIT, 0, push});
    s.layout = k.pipeline_layout({s.dsl}, ranges);
    s.set = k.descriptor_set(s.dsl);
    for (uint32_t i = 0; i < buffers.size(); ++i) {
        const VkDescriptorBufferInfo bi = whole(*buffers[i]);
        k.write(s.set, i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bi, nullptr);
    }
    return s;
}

// Makes the writes of `src` stages visible to `dst` stages (the buffer barriers Vulkan asks for; tilevk runs
// commands in order, lavapipe needs them).
inline void barrier(VkCommandBuffer c, VkPipelineStageFlags src, VkAccessFlags src_access, VkPipelineStageFlags dst,
                    VkAccessFlags dst_access) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = src_access;
    mb.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(c, src, dst, 0, 1, &mb, 0, nullptr, 0, nullptr);
}

// `code` over `groups` workgroups with the words `x` in storage buffer 0 and two words per input in buffer 1, filled
// with 0xAD first so that unwritten words show; returns buffer 1.
inline Bytes dispatch_two_words_per_input(Kit& k, const std::vector<uint32_t>& x, Spv code, uint32_t groups) {
    Device::Buffer in = k.buffer_of(x, kStorage);
    Device::Buffer res = k.buffer(VkDeviceSize(x.size()) * 8, kStorage);
    std::memset(res.map, 0xAD, x.size() * 8);
    StorageSet s = storage_set(k, {&in, &res});
    VkPipeline p = compute_pipeline(k, code, s.layout);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdDispatch(c, groups, 1, 1);
    }),
              VK_SUCCESS);
    return Kit::bytes(res);
}

// cp_subgroup.comp (`code`: subgroup basic, vote and ballot operations; 16 words per invocation, every one modelled
// in tests/shader/subgroup_test.cpp) at workgroup size n over three workgroups; inputs 0..199 with lane 5 of every
// subgroup taking part in the divergent branch. The stage has `flags` and, when `required_size` is not 0, a
// VkPipelineShaderStageRequiredSubgroupSizeCreateInfo (VK_EXT_subgroup_size_control). Returns the records, untouched
// words (0xAD) included.
inline Bytes subgroup_records(Kit& k, Spv code, uint32_t n, VkPipelineShaderStageCreateFlags flags = 0,
                              uint32_t required_size = 0) {
    std::mt19937 rng(n);
    std::vector<uint32_t> x(size_t(n) * 3);
    for (size_t i = 0; i < x.size(); ++i) {
        x[i] = rng() % 200;
        if (i % 8 == 5 && x[i] % 3 == 0) ++x[i];
    }
    Device::Buffer in = k.buffer_of(x, kStorage);
    Device::Buffer out = k.buffer(VkDeviceSize(x.size()) * 64, kStorage);
    std::memset(out.map, 0xAD, x.size() * 64);
    StorageSet s = storage_set(k, {&in, &out});
    const VkSpecializationMapEntry entry{0, 0, 4};
    const VkSpecializationInfo spec{1, &entry, 4, &n};
    VkPipelineShaderStageRequiredSubgroupSizeCreateInfo required{
        VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_REQUIRED_SUBGROUP_SIZE_CREATE_INFO};
    required.requiredSubgroupSize = required_size;
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.pNext = required_size != 0 ? &required : nullptr;
    ci.stage.flags = flags;
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = k.shader(code);
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = &spec;
    ci.layout = s.layout;
    VkPipeline p = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateComputePipelines(k.d, VK_NULL_HANDLE, 1, &ci, nullptr, &p), VK_SUCCESS);
    if (p == VK_NULL_HANDLE) return {};
    k.undo(VK_OBJECT_TYPE_PIPELINE, p, [&k, p] { vkDestroyPipeline(k.d, p, nullptr); });
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
        vkCmdDispatch(c, 3, 1, 1);
    }),
              VK_SUCCESS);
    return Kit::bytes(out);
}

}  // namespace tilevk::test::breadth
