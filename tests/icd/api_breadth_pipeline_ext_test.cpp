// Pipeline extensions lavapipe offers (suite ApiPipelineExtensions): VK_EXT_color_write_enable, VK_EXT_multi_draw,
// VK_KHR_shader_non_semantic_info (core in Vulkan 1.3, which lavapipe 22.3 is), VK_GOOGLE_decorate_string and
// VK_GOOGLE_hlsl_functionality1. Each runs on
// tilevk and lavapipe with the extension and its feature enabled and the validation layer on; the images are
// compared byte for byte and checked against what the extension says must be written.
#include <cstring>

#include "api_breadth.h"
// after api_breadth.h, which includes <cstdint> for the generated array
#include "ab_draw_params_vert.h"
#include "ab_hlsl_semantics_frag.h"
#include "ab_non_semantic_debug_frag.h"
#include "ab_non_semantic_frag.h"

namespace tilevk::test::breadth {
namespace {

class ApiPipelineExtensions : public ApiBreadth {
  protected:
    static bool advertised(VkPhysicalDevice pd, const char* name) {
        uint32_t n = 0;
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
        std::vector<VkExtensionProperties> all(n);
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, all.data());
        for (const VkExtensionProperties& e : all)
            if (std::strcmp(e.extensionName, name) == 0) return true;
        return false;
    }
};

// `fs` (no descriptors) on a full-screen triangle over a 32x32 RGBA8 target cleared to 0: the target's bytes.
Bytes fullscreen_bytes(Kit& k, Spv fs) {
    Target t = target(k);
    VkPipeline pipe = k.pipeline(fullscreen_pipe(fs, t, VK_NULL_HANDLE));
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 0)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        vkCmdDraw(c, 3, 1, 0, 0);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 4);
}

// Two RGBA8 attachments (cleared to 0) written by ab_mrt.frag's full-screen triangle; `enables` picks which.
struct TwoTargets {
    Device::Image img[2];
    VkRenderPass rp;
    VkFramebuffer fb;
};
TwoTargets two_targets(Kit& k) {
    const VkFormat f = VK_FORMAT_R8G8B8A8_UNORM;
    TwoTargets t{};
    for (auto& i : t.img) i = k.image(f, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    static const VkAttachmentReference refs[2] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                                  {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
    VkSubpassDescription sub = subpass(&refs[0]);
    sub.colorAttachmentCount = 2;
    const auto att = attachment(f, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE);
    t.rp = k.render_pass({att, att}, {sub});
    t.fb = k.framebuffer(
        t.rp,
        {k.view(t.img[0].image, f, VK_IMAGE_ASPECT_COLOR_BIT), k.view(t.img[1].image, f, VK_IMAGE_ASPECT_COLOR_BIT)},
        32, 32);
    return t;
}

// VK_EXT_color_write_enable: per attachment, statically (VkPipelineColorWriteCreateInfoEXT) and per draw
// (vkCmdSetColorWriteEnableEXT over a pipeline whose struct says the opposite). Four frames: static {1, 0},
// static {0, 1}, dynamic {0, 1}, dynamic {1, 0} then {0, 0} on the same pipeline (the last set wins). A disabled
// attachment keeps its clear (all zero), an enabled one is drawn everywhere (alpha 255 on attachment 0).
TEST_F(ApiPipelineExtensions, ColorWriteEnablePerAttachment) {
    VkPhysicalDeviceColorWriteEnableFeaturesEXT cw{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COLOR_WRITE_ENABLE_FEATURES_EXT};
    cw.colorWriteEnable = VK_TRUE;
    auto dev = device_pair({VK_EXT_COLOR_WRITE_ENABLE_EXTENSION_NAME}, &cw);
    ASSERT_TRUE(dev->ok());
    ASSERT_TRUE(advertised(tilevk_->physical(), VK_EXT_COLOR_WRITE_ENABLE_EXTENSION_NAME));
    struct Frame {
        VkBool32 pipeline[2];
        bool dynamic;
        VkBool32 set[2];
    };
    const Frame frames[] = {{{1, 0}, false, {}}, {{0, 1}, false, {}}, {{1, 0}, true, {0, 1}}, {{0, 1}, true, {0, 0}}};
    const Bytes b = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
        auto set_enables =
            reinterpret_cast<PFN_vkCmdSetColorWriteEnableEXT>(vkGetDeviceProcAddr(k.d, "vkCmdSetColorWriteEnableEXT"));
        EXPECT_NE(set_enables, nullptr);
        Bytes out;
        for (const Frame& f : frames) {
            TwoTargets t = two_targets(k);
            VkPipelineColorWriteCreateInfoEXT ci{VK_STRUCTURE_TYPE_PIPELINE_COLOR_WRITE_CREATE_INFO_EXT};
            ci.attachmentCount = 2;
            ci.pColorWriteEnables = f.pipeline;
            Pipe p;
            p.vs = SPV(ab_fullscreen_vert);
            p.fs = SPV(ab_mrt_frag);
            p.bindings = {};
            p.attrs = {};
            p.rp = t.rp;
            p.color_count = 2;
            p.color_blend_pnext = &ci;
            if (f.dynamic) p.dynamic = {VK_DYNAMIC_STATE_COLOR_WRITE_ENABLE_EXT};
            VkPipeline pipe = k.pipeline(p);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 0), clear_color(0, 0, 0, 0)});
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                if (f.dynamic) {
                    const VkBool32 first[2] = {1, 0};
                    set_enables(c, 2, &first[0]);  // replaced by the next set before the draw
                    set_enables(c, 2, f.set);
                }
                vkCmdDraw(c, 3, 1, 0, 0);
                vkCmdEndRenderPass(c);
            }),
                      VK_SUCCESS);
            for (const auto& img : t.img) {
                const Bytes i = k.read(img.image, 32, 32, 4);
                out.insert(out.end(), i.begin(), i.end());
            }
        }
        return out;
    });
    ASSERT_EQ(b.size(), std::size(frames) * 2 * 32 * 32 * 4);
    for (size_t f = 0; f < std::size(frames); ++f) {
        for (int a = 0; a < 2; ++a) {
            const bool enabled = (frames[f].dynamic ? frames[f].set[a] : frames[f].pipeline[a]) == VK_TRUE;
            const uint8_t* img = b.data() + (f * 2 + a) * 32 * 32 * 4;
            size_t wrong = 0;
            for (size_t i = 0; i < 32 * 32; ++i) {
                const uint32_t word = uint32_t(img[i * 4]) | uint32_t(img[i * 4 + 1]) << 8 |
                                      uint32_t(img[i * 4 + 2]) << 16 | uint32_t(img[i * 4 + 3]) << 24;
                if (!enabled) wrong += word != 0;
                if (enabled && a == 0) wrong += img[i * 4 + 3] != 255;  // ab_mrt.frag: o0 = v_color, alpha 1
                if (enabled && a == 1) wrong += word == 0;
            }
            EXPECT_EQ(wrong, 0u) << "frame " << f << " attachment " << a << (enabled ? " enabled" : " disabled");
        }
    }
}

// The feature is reported as lavapipe reports it (VkPhysicalDeviceColorWriteEnableFeaturesEXT), and a device is
// made with it.
TEST_F(ApiPipelineExtensions, ColorWriteEnableFeatureReported) {
    VkPhysicalDeviceColorWriteEnableFeaturesEXT t{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COLOR_WRITE_ENABLE_FEATURES_EXT};
    VkPhysicalDeviceColorWriteEnableFeaturesEXT l = t;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &t;
    vkGetPhysicalDeviceFeatures2(tilevk_->physical(), &f2);
    f2.pNext = &l;
    vkGetPhysicalDeviceFeatures2(lavapipe_->physical(), &f2);
    EXPECT_EQ(t.colorWriteEnable, VK_TRUE);
    EXPECT_EQ(t.colorWriteEnable, l.colorWriteEnable);
}

// VK_EXT_multi_draw: ab_draw_params.vert places each entry's instances in cells chosen by DrawIndex and colours
// them by DrawIndex, BaseVertex and BaseInstance. vkCmdDrawMultiEXT (three entries 20 bytes apart, two instances
// from 7), vkCmdDrawMultiIndexedEXT with each entry's vertexOffset, and the same with pVertexOffset 40, each into its
// own target; the colours are checked against the entries.
TEST_F(ApiPipelineExtensions, MultiDrawDrawIndexStrideAndVertexOffset) {
    VkPhysicalDeviceMultiDrawFeaturesEXT md{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTI_DRAW_FEATURES_EXT};
    md.multiDraw = VK_TRUE;
    VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    v11.shaderDrawParameters = VK_TRUE;
    v11.pNext = &md;
    auto dev = device_pair({VK_EXT_MULTI_DRAW_EXTENSION_NAME}, &v11);
    ASSERT_TRUE(dev->ok());
    ASSERT_TRUE(advertised(tilevk_->physical(), VK_EXT_MULTI_DRAW_EXTENSION_NAME));
    const Bytes b = both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        auto multi = reinterpret_cast<PFN_vkCmdDrawMultiEXT>(vkGetDeviceProcAddr(k.d, "vkCmdDrawMultiEXT"));
        auto multi_indexed =
            reinterpret_cast<PFN_vkCmdDrawMultiIndexedEXT>(vkGetDeviceProcAddr(k.d, "vkCmdDrawMultiIndexedEXT"));
        EXPECT_NE(multi, nullptr);
        EXPECT_NE(multi_indexed, nullptr);
        Bytes out;
        for (int kind = 0; kind < 3; ++kind) {
            Target t = target(k);
            Pipe p = fullscreen_pipe(SPV(color_frag), t, VK_NULL_HANDLE);
            p.vs = SPV(ab_draw_params_vert);
            p.layout = k.pipeline_layout({});
            VkPipeline pipe = k.pipeline(p);
            // 20-byte entries: {firstVertex, vertexCount} or {firstIndex, indexCount, vertexOffset}, then padding.
            const uint32_t plain[3][5] = {{0, 3, 99, 99, 99}, {5, 3, 99, 99, 99}, {12, 3, 99, 99, 99}};
            const int32_t indexed[3][5] = {{0, 3, 8, 99, 99}, {3, 3, 24, 99, 99}, {0, 3, 16, 99, 99}};
            Device::Buffer ib = k.buffer_of(std::vector<uint32_t>{0, 1, 2, 0, 1, 2}, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
            const int32_t offset = 40;
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 0)});
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                vkCmdBindIndexBuffer(c, ib.buffer, 0, VK_INDEX_TYPE_UINT32);
                const auto* pi = reinterpret_cast<const VkMultiDrawIndexedInfoEXT*>(indexed);
                if (kind == 0) multi(c, 3, reinterpret_cast<const VkMultiDrawInfoEXT*>(plain), 2, 7, 20);
                if (kind == 1) multi_indexed(c, 3, pi, 2, 7, 20, nullptr);
                if (kind == 2) multi_indexed(c, 3, pi, 2, 7, 20, &offset);
                vkCmdEndRenderPass(c);
            }),
                      VK_SUCCESS);
            const Bytes img = k.read(t.image.image, 32, 32, 4);
            out.insert(out.end(), img.begin(), img.end());
        }
        return out;
    });
    ASSERT_EQ(b.size(), 3u * 32 * 32 * 4);
    // Cell (column c, row r) is 8x8 pixels, cell = DrawIndex * 4 + instance; red DrawIndex / 8, green BaseVertex
    // / 64, blue BaseInstance / 64 (as unorm8: 32 per DrawIndex, BaseVertex * 255 / 64 rounded).
    const auto unorm = [](float v) { return int(v * 255.0f + 0.5f); };
    const int base_vertex[3][3] = {{0, 5, 12}, {8, 24, 16}, {40, 40, 40}};
    for (int kind = 0; kind < 3; ++kind) {
        for (int draw = 0; draw < 3; ++draw) {
            for (int inst = 0; inst < 2; ++inst) {
                const uint8_t* p = px(b, inst * 8 + 1, draw * 8 + 1) + kind * 32 * 32 * 4;
                EXPECT_EQ(p[0], unorm(float(draw) / 8.0f)) << kind << " " << draw << " " << inst;
                EXPECT_EQ(p[1], unorm(float(base_vertex[kind][draw]) / 64.0f)) << kind << " " << draw << " " << inst;
                EXPECT_EQ(p[2], unorm(7.0f / 64.0f)) << kind << " " << draw << " " << inst;
            }
        }
    }
}

// VK_KHR_shader_non_semantic_info: ab_non_semantic.frag's NonSemantic.DebugPrintf calls, and the same shader with
// NonSemantic.Shader.DebugInfo.100 (module-level and in-function debug instructions), run as if they were absent:
// every pixel (0.2, 0.4, 0.8, 1) = (51, 102, 204, 255). lavapipe 22.3 does not list the extension (it is core in
// its Vulkan 1.3; spirv_to_nir ignores NonSemantic.* sets), so its device is made without it.
TEST_F(ApiPipelineExtensions, ShaderNonSemanticInfo) {
    ASSERT_TRUE(advertised(tilevk_->physical(), VK_KHR_SHADER_NON_SEMANTIC_INFO_EXTENSION_NAME));
    // a Vulkan 1.3 instance, where lavapipe may take the module without the extension (the suite's asks for 1.2)
    Harness h13(true, {}, VK_API_VERSION_1_3);
    ASSERT_TRUE(h13.ok());
    Device tv(h13.find_device("tilevk"), nullptr, {VK_KHR_SHADER_NON_SEMANTIC_INFO_EXTENSION_NAME});
    Device lvp(h13.find_device("llvmpipe"), nullptr, {});
    ASSERT_TRUE(tv.ok() && lvp.ok());
    for (const Spv fs : {SPV(ab_non_semantic_frag), SPV(ab_non_semantic_debug_frag)}) {
        const Bytes b = both_on(tv, lvp, [&](Kit& k) { return fullscreen_bytes(k, fs); });
        ASSERT_EQ(b.size(), 32u * 32 * 4);
        size_t wrong = 0;
        for (size_t i = 0; i < 32 * 32; ++i)
            wrong += b[i * 4] != 51 || b[i * 4 + 1] != 102 || b[i * 4 + 2] != 204 || b[i * 4 + 3] != 255;
        EXPECT_EQ(wrong, 0u);
    }
    EXPECT_EQ(h13.message_count(), 0) << h13.message_report();
}

// VK_GOOGLE_hlsl_functionality1 and VK_GOOGLE_decorate_string: ab_hlsl_semantics.hlsl, compiled by glslang with
// -fhlsl_functionality1, carries its semantics as OpDecorateString UserSemantic, which change nothing: pixel (x, y)
// is (frac((x + 0.5) / 8), frac((y + 0.5) / 8), 0.75, 1), on both drivers alike.
TEST_F(ApiPipelineExtensions, HlslSemanticDecorations) {
    constexpr uint32_t kOpDecorateString = 5632;
    size_t decorate_strings = 0;
    for (size_t i = 5; i < sizeof ab_hlsl_semantics_frag / 4;) {
        const uint32_t words = ab_hlsl_semantics_frag[i] >> 16;
        decorate_strings += (ab_hlsl_semantics_frag[i] & 0xFFFF) == kOpDecorateString;
        i += words == 0 ? 1 : words;
    }
    ASSERT_GT(decorate_strings, 0u) << "glslang no longer emits OpDecorateString: the test tests nothing";
    auto d = device_pair({VK_GOOGLE_DECORATE_STRING_EXTENSION_NAME, VK_GOOGLE_HLSL_FUNCTIONALITY_1_EXTENSION_NAME});
    ASSERT_TRUE(d->ok());
    const Bytes b =
        both_on(d->tilevk, d->lavapipe, [&](Kit& k) { return fullscreen_bytes(k, SPV(ab_hlsl_semantics_frag)); });
    ASSERT_EQ(b.size(), 32u * 32 * 4);
    const auto unorm = [](float v) { return int(v * 255.0f + 0.5f); };
    size_t wrong = 0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const uint8_t* p = &b[(y * 32 + x) * 4];
            wrong += p[0] != unorm(float(x % 8) / 8.0f + 0.0625f) || p[1] != unorm(float(y % 8) / 8.0f + 0.0625f) ||
                     p[2] != unorm(0.75f) || p[3] != 255;
        }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
}

// The feature and maxMultiDrawCount are lavapipe's.
TEST_F(ApiPipelineExtensions, MultiDrawReported) {
    VkPhysicalDeviceMultiDrawFeaturesEXT f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTI_DRAW_FEATURES_EXT};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f;
    vkGetPhysicalDeviceFeatures2(tilevk_->physical(), &f2);
    EXPECT_EQ(f.multiDraw, VK_TRUE);
    VkPhysicalDeviceMultiDrawPropertiesEXT t{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTI_DRAW_PROPERTIES_EXT};
    VkPhysicalDeviceMultiDrawPropertiesEXT l = t;
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &t;
    vkGetPhysicalDeviceProperties2(tilevk_->physical(), &p2);
    p2.pNext = &l;
    vkGetPhysicalDeviceProperties2(lavapipe_->physical(), &p2);
    EXPECT_EQ(t.maxMultiDrawCount, 2048u);
    EXPECT_EQ(t.maxMultiDrawCount, l.maxMultiDrawCount);
}

}  // namespace
}  // namespace tilevk::test::breadth
