// The samplers' per-coordinate compute readback, shared by api_breadth_sampler_test.cpp and
// api_breadth_gather_test.cpp (a Kit helper kept out of api_breadth.h, which every api_breadth test includes).
#pragma once

#include <cstring>
#include <vector>

#include "api_breadth.h"

namespace tilevk::test::breadth {

// A compute shader that reads one element of `coords` per invocation (16 invocations a workgroup) from the storage
// buffer at binding `in_binding` of `set` and writes `out_bytes_each` bytes per element to binding in_binding + 1:
// the bytes it wrote (0xAB where it wrote nothing). The samplers' per-coordinate readback.
template <class T>
Bytes dispatch_per_coordinate(Kit& k, Spv code, VkPipelineLayout layout, VkDescriptorSet set, uint32_t in_binding,
                              const std::vector<T>& coords, size_t out_bytes_each) {
    Device::Buffer in = k.buffer_of(coords, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Device::Buffer out = k.buffer(coords.size() * out_bytes_each, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::memset(out.map, 0xAB, out.size);
    const VkDescriptorBufferInfo bi[2] = {{in.buffer, 0, VK_WHOLE_SIZE}, {out.buffer, 0, VK_WHOLE_SIZE}};
    k.write(set, in_binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bi[0], nullptr);
    k.write(set, in_binding + 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bi[1], nullptr);
    const VkPipeline p = compute_pipeline(k, code, layout);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdDispatch(c, uint32_t(coords.size()) / 16, 1, 1);
    }),
              VK_SUCCESS);
    return Kit::bytes(out);
}

}  // namespace tilevk::test::breadth
