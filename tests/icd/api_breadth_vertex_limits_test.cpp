// maxVertexInputAttributes and maxVertexInputBindings at lavapipe's 32 (suite ApiBreadth): 32 attributes from 32
// bindings of mixed formats and input rates, drawn on tilevk and lavapipe and equal byte for byte.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "ab_inputs32_frag.h"
#include "ab_inputs32_vert.h"
#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

constexpr uint32_t kInputs = 32, kSize = 16;

// Binding i holds attribute i (location i); formats cycle float / UNORM8 / half / SNORM8 after the position at 0,
// every fourth binding per instance. A binding left out (or read as zeros) moves the colour of every pixel.
TEST_F(ApiBreadth, VertexInputs32BindingsAtTheLimit) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &props);
    ASSERT_GE(props.limits.maxVertexInputAttributes, kInputs);
    ASSERT_GE(props.limits.maxVertexInputBindings, kInputs);
    both([](Kit& k) {
        const VkFormat afmt[4] = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM,
                                  VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_SNORM};
        const uint32_t asize[4] = {16, 4, 8, 4};
        Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, kSize, kSize);
        Pipe p;
        p.vs = SPV(ab_inputs32_vert);
        p.fs = SPV(ab_inputs32_frag);
        p.rp = tg.rp;
        p.width = p.height = kSize;
        p.bindings.clear();
        p.attrs.clear();
        std::vector<Device::Buffer> vbs;
        for (uint32_t i = 0; i < kInputs; ++i) {
            const uint32_t f = i == 0 ? 0 : i % 4;
            const bool inst = i % 4 == 3;
            p.bindings.push_back({i, asize[f], inst ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
            p.attrs.push_back({i, i, afmt[f], 0});
            std::vector<uint8_t> data = texel_data(afmt[f], 3, 70 + i);
            if (i == 0) {  // positions: a triangle covering most of the target
                const float pos[12] = {-0.9f, -0.9f, 0, 1, 0.95f, -0.6f, 0, 1, -0.5f, 0.9f, 0, 1};
                std::memcpy(data.data(), pos, sizeof pos);
            }
            vbs.push_back(k.buffer_of(data, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
        }
        VkPipeline pipe = k.pipeline(p);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, tg.rp, tg.fb, kSize, kSize, {clear_color(-1, -1, -1, -1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            std::vector<VkBuffer> bufs;
            const std::vector<VkDeviceSize> offs(kInputs, 0);
            for (auto& b : vbs) bufs.push_back(b.buffer);
            vkCmdBindVertexBuffers(c, 0, kInputs, bufs.data(), offs.data());
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes out = k.read(tg.image.image, kSize, kSize, 16);
        float mid[4];
        std::memcpy(mid, px(out, kSize / 2, kSize / 2, 16), sizeof mid);
        EXPECT_NE(mid[0], -1.0f);  // drawn in the middle
        return out;
    });
}

}  // namespace
}  // namespace tilevk::test::breadth
