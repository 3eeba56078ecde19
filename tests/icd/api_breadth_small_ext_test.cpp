// Small device extensions of Vulkan 1.2 (suites ApiSmallExtensions, ScalarBlockLayout), each on tilevk and lavapipe
// with the extension (and its feature) enabled and the validation layer on; results compared byte for byte and checked
// against values computed here.
#include <spirv-tools/libspirv.hpp>

#include "api_breadth.h"
// after api_breadth.h, which includes <cstdint> for the generated array
#include "ab_demote_frag.h"
#include "ab_draw_params_vert.h"
#include "ab_terminate_frag.h"
#include "ab_ubo_scalar_frag.h"
#include "ab_ubo_std430_frag.h"
#include "cp_scalar_comp.h"

namespace tilevk::test::breadth {
namespace {

class ApiSmallExtensions : public ApiBreadth {
  protected:
    std::unique_ptr<DevicePair> devices(const std::vector<const char*>& extensions, const void* chain = nullptr) {
        return device_pair(extensions, chain);
    }
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

void append_u32(Bytes& out, uint32_t v) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    out.insert(out.end(), p, p + 4);
}

// VK_EXT_separate_stencil_usage, format queries: with VkImageStencilUsageCreateInfo the stencil aspect's usage is
// checked too, so the answer equals the one for the union of both usages — which both drivers give alike without
// the struct. Named difference: lavapipe 22.3 ignores the struct (it answers for the depth usage alone, so STORAGE
// or COLOR_ATTACHMENT stencil usages pass there); pinned here on both drivers.
TEST_F(ApiSmallExtensions, SeparateStencilUsageFormatQueries) {
    ASSERT_TRUE(advertised(tilevk_->physical(), VK_EXT_SEPARATE_STENCIL_USAGE_EXTENSION_NAME));
    auto props2 = reinterpret_cast<PFN_vkGetPhysicalDeviceImageFormatProperties2KHR>(
        vkGetInstanceProcAddr(harness_->instance(), "vkGetPhysicalDeviceImageFormatProperties2KHR"));
    ASSERT_NE(props2, nullptr);
    const VkImageUsageFlags depth_usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const VkImageUsageFlags stencil_usages[] = {
        VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        VK_IMAGE_USAGE_STORAGE_BIT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT};
    const VkResult expected[] = {VK_SUCCESS, VK_SUCCESS, VK_ERROR_FORMAT_NOT_SUPPORTED, VK_ERROR_FORMAT_NOT_SUPPORTED};
    Bytes t, l;
    for (VkFormat f : {VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT_S8_UINT}) {
        for (size_t i = 0; i < std::size(stencil_usages); ++i) {
            VkImageStencilUsageCreateInfo su{VK_STRUCTURE_TYPE_IMAGE_STENCIL_USAGE_CREATE_INFO};
            su.stencilUsage = stencil_usages[i];
            VkPhysicalDeviceImageFormatInfo2 info{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGE_FORMAT_INFO_2};
            info.pNext = &su;
            info.format = f;
            info.type = VK_IMAGE_TYPE_2D;
            info.tiling = VK_IMAGE_TILING_OPTIMAL;
            info.usage = depth_usage;
            VkPhysicalDeviceImageFormatInfo2 both_usages = info;  // the union as the image's own usage
            both_usages.pNext = nullptr;
            both_usages.usage = depth_usage | stencil_usages[i];
            VkImageFormatProperties2 p{VK_STRUCTURE_TYPE_IMAGE_FORMAT_PROPERTIES_2};
            const VkResult tv_struct = props2(tilevk_->physical(), &info, &p);
            const VkResult tv_union = props2(tilevk_->physical(), &both_usages, &p);
            const VkResult lvp_struct = props2(lavapipe_->physical(), &info, &p);
            const VkResult lvp_union = props2(lavapipe_->physical(), &both_usages, &p);
            EXPECT_EQ(tv_struct, expected[i]) << f << " stencil usage " << i;
            EXPECT_EQ(tv_struct, tv_union) << f << " stencil usage " << i;
            EXPECT_EQ(lvp_struct, VK_SUCCESS) << f << " stencil usage " << i << ": lavapipe checks the struct now";
            append_u32(t, uint32_t(tv_union));
            append_u32(l, uint32_t(lvp_union));
        }
    }
    expect_same(t, l, "format query results for the union of the usages");
}

// VK_EXT_separate_stencil_usage, images: a D24S8/D32S8 image whose depth aspect is an attachment and transfer
// source and whose stencil aspect is an attachment only is created, drawn into (the clears of a render pass) and
// its depth read back.
TEST_F(ApiSmallExtensions, SeparateStencilUsageImages) {
    auto dev = devices({VK_EXT_SEPARATE_STENCIL_USAGE_EXTENSION_NAME});
    ASSERT_TRUE(dev->ok());
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Bytes out;
        for (VkFormat f : {VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT_S8_UINT}) {
            VkImageStencilUsageCreateInfo su{VK_STRUCTURE_TYPE_IMAGE_STENCIL_USAGE_CREATE_INFO};
            su.stencilUsage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
            VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
            ci.pNext = &su;
            ci.imageType = VK_IMAGE_TYPE_2D;
            ci.format = f;
            ci.extent = {16, 16, 1};
            ci.mipLevels = ci.arrayLayers = 1;
            ci.samples = VK_SAMPLE_COUNT_1_BIT;
            ci.tiling = VK_IMAGE_TILING_OPTIMAL;
            ci.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
            VkImage img = VK_NULL_HANDLE;
            EXPECT_EQ(vkCreateImage(k.d, &ci, nullptr, &img), VK_SUCCESS);
            VkMemoryRequirements req;
            vkGetImageMemoryRequirements(k.d, img, &req);
            VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
            ai.allocationSize = req.size;
            ai.memoryTypeIndex = uint32_t(__builtin_ctz(req.memoryTypeBits));
            VkDeviceMemory mem = VK_NULL_HANDLE;
            EXPECT_EQ(vkAllocateMemory(k.d, &ai, nullptr, &mem), VK_SUCCESS);
            EXPECT_EQ(vkBindImageMemory(k.d, img, mem, 0), VK_SUCCESS);
            VkDevice d = k.d;
            k.undo(VK_OBJECT_TYPE_IMAGE, img, [d, img, mem] {
                vkDestroyImage(d, img, nullptr);
                vkFreeMemory(d, mem, nullptr);
            });
            const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
            Device::Image col =
                k.image(C, 16, 16, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
            VkRenderPass rp = colour_depth_pass(k, C, f);
            VkFramebuffer fb = k.framebuffer(rp,
                                             {k.view(col.image, C, VK_IMAGE_ASPECT_COLOR_BIT),
                                              k.view(img, f, VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT)},
                                             16, 16);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                begin_pass(c, rp, fb, 16, 16, {clear_color(0.25f, 0.5f, 0.75f, 1), clear_depth(0.375f, 9)});
                vkCmdEndRenderPass(c);
            }),
                      VK_SUCCESS);
            const Bytes depth = k.read(img, 16, 16, 4, VK_IMAGE_ASPECT_DEPTH_BIT);
            out.insert(out.end(), depth.begin(), depth.end());
        }
        return out;
    });
}

// VK_KHR_uniform_buffer_standard_layout: ab_ubo_std430.frag reads a std430 uniform block (array stride 4, the vec3
// at 32, the float packed after it at 44, the vec2 at 48) into an RGBA32F target: pixel x shows a[x & 7], b.y, c,
// d.y, which are word (x & 7), 9, 11 and 13 of the buffer (word k holds k + 1).
TEST_F(ApiSmallExtensions, UniformBufferStandardLayout) {
    VkPhysicalDeviceUniformBufferStandardLayoutFeatures ubsl{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_UNIFORM_BUFFER_STANDARD_LAYOUT_FEATURES};
    ubsl.uniformBufferStandardLayout = VK_TRUE;
    auto dev = devices({VK_KHR_UNIFORM_BUFFER_STANDARD_LAYOUT_EXTENSION_NAME}, &ubsl);
    ASSERT_TRUE(dev->ok());
    const Bytes b = both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        const VkFormat F = VK_FORMAT_R32G32B32A32_SFLOAT;
        Target t = target(k, F, 16, 4);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        Device::Buffer ubo = k.buffer(256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        auto* w = static_cast<float*>(ubo.map);
        for (int i = 0; i < 64; ++i) w[i] = float(i + 1);
        VkDescriptorBufferInfo bi{ubo.buffer, 0, 256};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &bi, nullptr);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(ab_ubo_std430_frag), t, layout));
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, t, pipe, layout, set); }), VK_SUCCESS);
        return k.read(t.image.image, 16, 4, 16);
    });
    ASSERT_EQ(b.size(), 16u * 4 * 16);
    for (uint32_t x = 0; x < 16; ++x) {
        float px[4];
        std::memcpy(px, &b[x * 16], sizeof px);
        EXPECT_EQ(px[0], float((x & 7) + 1)) << x;
        EXPECT_EQ(px[1], 10.0f) << x;
        EXPECT_EQ(px[2], 12.0f) << x;
        EXPECT_EQ(px[3], 14.0f) << x;
    }
}

// VK_EXT_scalar_block_layout, devices with the extension and scalarBlockLayout enabled.
class ScalarBlockLayout : public ApiSmallExtensions {
  protected:
    void SetUp() override {
        features_.scalarBlockLayout = VK_TRUE;
        dev_ = devices({VK_EXT_SCALAR_BLOCK_LAYOUT_EXTENSION_NAME}, &features_);
        ASSERT_TRUE(dev_->ok());
    }
    Bytes both(const std::function<Bytes(Kit&)>& scene) { return both_on(dev_->tilevk, dev_->lavapipe, scene); }
    VkPhysicalDeviceScalarBlockLayoutFeatures features_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SCALAR_BLOCK_LAYOUT_FEATURES};
    std::unique_ptr<DevicePair> dev_;
};

// ab_ubo_scalar.frag reads a scalar uniform block into an RGBA32F target: pixel x shows a + b.y, c[x % 3].z,
// m[x % 3].y and d.y, which are words 0 + 2, 6 + 3i, 14 + 3i and 23 of the buffer (word k holds k + 1).
TEST_F(ScalarBlockLayout, UniformBlock) {
    const Bytes b = both([](Kit& k) {
        const VkFormat F = VK_FORMAT_R32G32B32A32_SFLOAT;
        Target t = target(k, F, 12, 2);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        Device::Buffer ubo = k.buffer(256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        auto* w = static_cast<float*>(ubo.map);
        for (int i = 0; i < 64; ++i) w[i] = float(i + 1);
        VkDescriptorBufferInfo bi{ubo.buffer, 0, 256};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &bi, nullptr);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(ab_ubo_scalar_frag), t, layout));
        if (pipe == VK_NULL_HANDLE) return Bytes{};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, t, pipe, layout, set); }), VK_SUCCESS);
        return k.read(t.image.image, 12, 2, 16);
    });
    ASSERT_EQ(b.size(), 12u * 2 * 16);
    for (uint32_t x = 0; x < 12; ++x) {
        float px[4];
        std::memcpy(px, &b[x * 16], sizeof px);
        const float i = float(x % 3);
        EXPECT_EQ(px[0], 4.0f) << x;
        EXPECT_EQ(px[1], 7.0f + 3.0f * i) << x;
        EXPECT_EQ(px[2], 15.0f + 3.0f * i) << x;
        EXPECT_EQ(px[3], 24.0f) << x;
    }
}

// cp_scalar.comp reads scalar-aligned vec3s and a mat2x3 from one storage buffer (word k holds k + 1) and writes
// vec3 and float arrays at scalar offsets into another, first filled with a marker (its last word stays so).
TEST_F(ScalarBlockLayout, StorageBlocks) {
    const Bytes b = both([](Kit& k) {
        const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        std::vector<float> in(32);
        for (size_t i = 0; i < in.size(); ++i) in[i] = float(i + 1);
        Device::Buffer src = k.buffer_of(in, storage);
        Device::Buffer dst = k.buffer(80, storage);
        std::memset(dst.map, 0xAB, 80);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT},
                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorBufferInfo bs{src.buffer, 0, VK_WHOLE_SIZE}, bd{dst.buffer, 0, VK_WHOLE_SIZE};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bs, nullptr);
        k.write(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bd, nullptr);
        VkPipeline p = compute_pipeline(k, SPV(cp_scalar_comp), layout);
        if (p == VK_NULL_HANDLE) return Bytes{};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
            vkCmdDispatch(c, 1, 1, 1);
        }),
                  VK_SUCCESS);
        return Kit::bytes(dst);
    });
    ASSERT_EQ(b.size(), 80u);
    float got[20];
    std::memcpy(got, b.data(), sizeof got);
    // v[i] = (2 + 3i, 3 + 3i, 4 + 3i), m[0] = (14, 15, 16), m[1] = (17, 18, 19), a = 1.
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(got[3 * i + c], float(2 + 3 * i + c) + float(14 + 3 * (i & 1) + c));
    for (int i = 0; i < 4; ++i) EXPECT_EQ(got[12 + i], float(3 + 3 * i) + 19.0f);
    EXPECT_EQ(got[16], 1.0f);
    EXPECT_EQ(got[17], 14.0f);
    EXPECT_EQ(got[18], 13.0f);
    uint32_t last;
    std::memcpy(&last, &got[19], 4);
    EXPECT_EQ(last, 0xABABABABu);
}

// A fullscreen draw of fragment shader `fs` into a 32x32 RGBA32F target cleared to -1 (so unwritten texels show).
Bytes fullscreen_rgba32f(Kit& k, Spv fs) {
    const VkFormat F = VK_FORMAT_R32G32B32A32_SFLOAT;
    Target t = target(k, F, 32, 32);
    VkPipelineLayout layout = k.pipeline_layout({});
    VkPipeline pipe = k.pipeline(fullscreen_pipe(fs, t, layout));
    if (pipe == VK_NULL_HANDLE) return Bytes{};
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(-1, -1, -1, -1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        vkCmdDraw(c, 3, 1, 0, 0);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 16);
}

float texel(const Bytes& b, uint32_t x, uint32_t y, uint32_t c) {
    float v;
    std::memcpy(&v, &b[((y * 32 + x) * 4 + c) * 4], 4);
    return v;
}

// VK_KHR_shader_terminate_invocation: ab_terminate.frag ends the invocations of odd x ^ y; the others write their
// pixel centre.
TEST_F(ApiSmallExtensions, ShaderTerminateInvocation) {
    VkPhysicalDeviceShaderTerminateInvocationFeatures ti{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_TERMINATE_INVOCATION_FEATURES};
    ti.shaderTerminateInvocation = VK_TRUE;
    auto dev = devices({VK_KHR_SHADER_TERMINATE_INVOCATION_EXTENSION_NAME}, &ti);
    ASSERT_TRUE(dev->ok());
    const Bytes b =
        both_on(dev->tilevk, dev->lavapipe, [](Kit& k) { return fullscreen_rgba32f(k, SPV(ab_terminate_frag)); });
    ASSERT_EQ(b.size(), 32u * 32 * 16);
    size_t wrong = 0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const bool ended = ((x ^ y) & 1) != 0;
            wrong += texel(b, x, y, 0) != (ended ? -1.0f : float(x) + 0.5f);
            wrong += texel(b, x, y, 2) != (ended ? -1.0f : 0.25f);
        }
    EXPECT_EQ(wrong, 0u);
}

// VK_EXT_shader_demote_to_helper_invocation: ab_demote.frag demotes the pixels with (x + y) % 3 == 0; they are not
// written, and the others' derivatives of q = x²/4 + y²/8 + xy still come from their quads (fine derivatives of the
// 2x2 quad: dFdx(q) at the quad's column pair = (2x0 + 1)/4 + y, where x0 is the left column's centre; both drivers
// alike, checked here for the x derivative of the quad's top row), and helperInvocationEXT() is false for them.
TEST_F(ApiSmallExtensions, ShaderDemoteToHelperInvocation) {
    VkPhysicalDeviceShaderDemoteToHelperInvocationFeatures di{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_DEMOTE_TO_HELPER_INVOCATION_FEATURES};
    di.shaderDemoteToHelperInvocation = VK_TRUE;
    auto dev = devices({VK_EXT_SHADER_DEMOTE_TO_HELPER_INVOCATION_EXTENSION_NAME}, &di);
    ASSERT_TRUE(dev->ok());
    const Bytes b =
        both_on(dev->tilevk, dev->lavapipe, [](Kit& k) { return fullscreen_rgba32f(k, SPV(ab_demote_frag)); });
    ASSERT_EQ(b.size(), 32u * 32 * 16);
    size_t wrong = 0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const bool demoted = (x + y) % 3 == 0;
            wrong += texel(b, x, y, 2) != (demoted ? -1.0f : 0.5f);
            if (demoted || (y & 1) != 0) continue;
            // q(x + 1) - q(x) on the quad's top row at centres cx = (x & ~1) + 0.5 and cx + 1, cy = y + 0.5.
            const float cx = float(x & ~1u) + 0.5f, cy = float(y) + 0.5f;
            const auto q = [](float px, float py) { return px * px * 0.25f + py * py * 0.125f + px * py; };
            wrong += texel(b, x, y, 0) != q(cx + 1.0f, cy) - q(cx, cy);
        }
    EXPECT_EQ(wrong, 0u);
}

// VK_KHR_shader_draw_parameters: ab_draw_params.vert places each draw's instances in cells chosen by DrawIndex and
// colours them by DrawIndex, BaseVertex and BaseInstance; a direct draw (DrawIndex 0), three records of
// vkCmdDrawIndirect (DrawIndex 0, 1, 2, with their own firstVertex and firstInstance) and two of
// vkCmdDrawIndexedIndirect (vertexOffset as BaseVertex), each into its own target.
TEST_F(ApiSmallExtensions, ShaderDrawParameters) {
    // The extension alone enables the built-ins for a Vulkan 1.0 device (its feature struct is Vulkan 1.1's).
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.features.multiDrawIndirect = VK_TRUE;
    f2.features.drawIndirectFirstInstance = VK_TRUE;
    auto dev = devices({VK_KHR_SHADER_DRAW_PARAMETERS_EXTENSION_NAME}, &f2);
    ASSERT_TRUE(dev->ok());
    const Bytes b = both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Bytes out;
        for (int kind = 0; kind < 3; ++kind) {
            Target t = target(k);
            Pipe p = fullscreen_pipe(SPV(color_frag), t, VK_NULL_HANDLE);
            p.vs = SPV(ab_draw_params_vert);
            p.layout = k.pipeline_layout({});
            VkPipeline pipe = k.pipeline(p);
            const VkDrawIndirectCommand draws[3] = {{3, 2, 0, 0}, {3, 3, 5, 7}, {3, 1, 12, 20}};
            const VkDrawIndexedIndirectCommand indexed[2] = {{3, 2, 0, 4, 1}, {3, 4, 0, 30, 11}};
            Device::Buffer ind = k.buffer(sizeof draws + sizeof indexed, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
            std::memcpy(ind.map, draws, sizeof draws);
            std::memcpy(static_cast<uint8_t*>(ind.map) + sizeof draws, indexed, sizeof indexed);
            Device::Buffer ib = k.buffer_of(std::vector<uint32_t>{0, 1, 2}, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 0)});
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                if (kind == 0) vkCmdDraw(c, 3, 2, 9, 6);
                if (kind == 1) vkCmdDrawIndirect(c, ind.buffer, 0, 3, sizeof(VkDrawIndirectCommand));
                if (kind == 2) {
                    vkCmdBindIndexBuffer(c, ib.buffer, 0, VK_INDEX_TYPE_UINT32);
                    vkCmdDrawIndexedIndirect(c, ind.buffer, sizeof draws, 2, sizeof(VkDrawIndexedIndirectCommand));
                }
                vkCmdEndRenderPass(c);
            }),
                      VK_SUCCESS);
            const Bytes img = k.read(t.image.image, 32, 32, 4);
            out.insert(out.end(), img.begin(), img.end());
        }
        return out;
    });
    ASSERT_EQ(b.size(), 3u * 32 * 32 * 4);
    // Cell (column c, row r) is 8x8 pixels; a pixel inside the triangle of cell (1, 1) of the indirect target is
    // draw 1's second instance: DrawIndex 1 (red 32), BaseVertex 5 (green 20), BaseInstance 7 (blue 28).
    const uint8_t* p = px(b, 1 * 8 + 1, 1 * 8 + 1) + 32 * 32 * 4;
    EXPECT_EQ(p[0], 32);
    EXPECT_EQ(p[1], 20);
    EXPECT_EQ(p[2], 28);
}

}  // namespace
}  // namespace tilevk::test::breadth

namespace tilevk::test::breadth {
namespace {

// A SPIR-V 1.0 compute module that needs both extensions: its blocks are in the StorageBuffer storage class
// (SPV_KHR_storage_buffer_storage_class; glslang only emits that class for SPIR-V 1.3) and the input block has a vec3
// at offset 4, which only VK_KHR_relaxed_block_layout allows (std430 aligns a vec3 to 16). out.r = (b * a, a).
constexpr const char* kRelaxedStorageBufferComp = R"(
OpCapability Shader
OpExtension "SPV_KHR_storage_buffer_storage_class"
OpMemoryModel Logical GLSL450
OpEntryPoint GLCompute %main "main"
OpExecutionMode %main LocalSize 1 1 1
OpDecorate %In Block
OpMemberDecorate %In 0 Offset 0
OpMemberDecorate %In 1 Offset 4
OpDecorate %Out Block
OpMemberDecorate %Out 0 Offset 0
OpDecorate %in DescriptorSet 0
OpDecorate %in Binding 0
OpDecorate %out DescriptorSet 0
OpDecorate %out Binding 1
%void = OpTypeVoid
%fn = OpTypeFunction %void
%float = OpTypeFloat 32
%v3 = OpTypeVector %float 3
%v4 = OpTypeVector %float 4
%In = OpTypeStruct %float %v3
%Out = OpTypeStruct %v4
%p_in = OpTypePointer StorageBuffer %In
%p_out = OpTypePointer StorageBuffer %Out
%p_float = OpTypePointer StorageBuffer %float
%p_v3 = OpTypePointer StorageBuffer %v3
%p_v4 = OpTypePointer StorageBuffer %v4
%int = OpTypeInt 32 1
%c0 = OpConstant %int 0
%c1 = OpConstant %int 1
%in = OpVariable %p_in StorageBuffer
%out = OpVariable %p_out StorageBuffer
%main = OpFunction %void None %fn
%entry = OpLabel
%pa = OpAccessChain %p_float %in %c0
%a = OpLoad %float %pa
%pb = OpAccessChain %p_v3 %in %c1
%b = OpLoad %v3 %pb
%scaled = OpVectorTimesScalar %v3 %b %a
%r = OpCompositeConstruct %v4 %scaled %a
%pr = OpAccessChain %p_v4 %out %c0
OpStore %pr %r
OpReturn
OpFunctionEnd
)";

std::vector<uint32_t> assemble(const char* text) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::vector<uint32_t> words;
    EXPECT_TRUE(tools.Assemble(text, &words));
    return words;
}

// VK_KHR_storage_buffer_storage_class and VK_KHR_relaxed_block_layout (Vulkan 1.1 core): the module above on both
// drivers with both extensions enabled; the output equals lavapipe's and (6, 8, 10, 2) for a = 2, b = (3, 4, 5).
// (The validation layer does not check the block layout against the enabled extensions; spirv-val does, and
// tilevk's shader/ validates with rules that accept relaxed and scalar layouts.)
TEST_F(ApiSmallExtensions, StorageBufferClassWithRelaxedBlockLayout) {
    auto dev =
        devices({VK_KHR_STORAGE_BUFFER_STORAGE_CLASS_EXTENSION_NAME, VK_KHR_RELAXED_BLOCK_LAYOUT_EXTENSION_NAME});
    ASSERT_TRUE(dev->ok());
    const std::vector<uint32_t> code = assemble(kRelaxedStorageBufferComp);
    ASSERT_FALSE(code.empty());
    const Bytes b = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
        const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        const std::vector<float> in = {2, 3, 4, 5};
        Device::Buffer src = k.buffer_of(in, storage);
        Device::Buffer dst = k.buffer(16, storage);
        std::memset(dst.map, 0xAB, 16);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT},
                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorBufferInfo bs{src.buffer, 0, VK_WHOLE_SIZE}, bd{dst.buffer, 0, VK_WHOLE_SIZE};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bs, nullptr);
        k.write(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bd, nullptr);
        VkPipeline p = compute_pipeline(k, Spv{code.data(), code.size() * 4}, layout);
        if (p == VK_NULL_HANDLE) return Bytes{};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
            vkCmdDispatch(c, 1, 1, 1);
        }),
                  VK_SUCCESS);
        return Kit::bytes(dst);
    });
    ASSERT_EQ(b.size(), 16u);
    float got[4];
    std::memcpy(got, b.data(), sizeof got);
    EXPECT_EQ(got[0], 6.0f);
    EXPECT_EQ(got[1], 8.0f);
    EXPECT_EQ(got[2], 10.0f);
    EXPECT_EQ(got[3], 2.0f);
}

// VK_EXT_texel_buffer_alignment: both drivers report the feature and the same Vulkan 1.3 alignment properties
// (16 bytes, or one texel); uniform texel buffer views at offsets aligned to one texel only (one component for
// R32G32B32_SFLOAT) read the same texels on both, and the first texel read is the one at the view's offset.
TEST_F(ApiSmallExtensions, TexelBufferAlignmentSingleTexelOffsets) {
    for (Device* dev : {tilevk_.get(), lavapipe_.get()}) {
        ASSERT_TRUE(advertised(dev->physical(), VK_EXT_TEXEL_BUFFER_ALIGNMENT_EXTENSION_NAME));
        VkPhysicalDeviceTexelBufferAlignmentFeaturesEXT f{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TEXEL_BUFFER_ALIGNMENT_FEATURES_EXT};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f};
        vkGetPhysicalDeviceFeatures2(dev->physical(), &f2);
        EXPECT_EQ(f.texelBufferAlignment, VK_TRUE);
        VkPhysicalDeviceTexelBufferAlignmentProperties a{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TEXEL_BUFFER_ALIGNMENT_PROPERTIES};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &a};
        vkGetPhysicalDeviceProperties2(dev->physical(), &p2);
        EXPECT_EQ(a.storageTexelBufferOffsetAlignmentBytes, 16u);
        EXPECT_EQ(a.uniformTexelBufferOffsetAlignmentBytes, 16u);
        EXPECT_EQ(a.storageTexelBufferOffsetSingleTexelAlignment, VK_TRUE);
        EXPECT_EQ(a.uniformTexelBufferOffsetSingleTexelAlignment, VK_TRUE);
    }
    VkPhysicalDeviceTexelBufferAlignmentFeaturesEXT want{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TEXEL_BUFFER_ALIGNMENT_FEATURES_EXT};
    want.texelBufferAlignment = VK_TRUE;
    auto d = devices({VK_EXT_TEXEL_BUFFER_ALIGNMENT_EXTENSION_NAME}, &want);
    ASSERT_TRUE(d->ok());
    struct Case {
        VkFormat format;
        VkDeviceSize offset;
    };
    for (const Case c :
         {Case{VK_FORMAT_R8_UNORM, 3}, Case{VK_FORMAT_R8G8B8A8_UNORM, 4}, Case{VK_FORMAT_R16G16_SFLOAT, 8},
          Case{VK_FORMAT_R32_SFLOAT, 20}, Case{VK_FORMAT_R32G32B32_SFLOAT, 4}}) {
        SCOPED_TRACE("format " + std::to_string(int(c.format)) + " offset " + std::to_string(c.offset));
        const uint32_t n = texel_bytes(c.format, VK_IMAGE_ASPECT_COLOR_BIT);
        std::vector<uint8_t> data(c.offset, 0xEE);
        const std::vector<uint8_t> texels = texel_data(c.format, 20, 700 + uint32_t(c.format));
        data.insert(data.end(), texels.begin(), texels.end());
        const Bytes out = both_on(d->tilevk, d->lavapipe, [&](Kit& k) {
            Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
            Device::Buffer buf = k.buffer_of(data, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
            const TexelBufferSet tb = uniform_texel_buffer_set(k, buf, c.format, c.offset, VkDeviceSize(18) * n);
            const VkBufferView view = tb.view;
            const VkPipelineLayout layout = tb.layout;
            const VkDescriptorSet set = tb.set;
            VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(ab_texel_buffer_frag), tg, layout));
            EXPECT_EQ(k.run([&](VkCommandBuffer cb) { draw_fullscreen(cb, tg, pipe, layout, set); }), VK_SUCCESS);
            Bytes o = k.read(tg.image.image, 4, 4, 16);
            vkDestroyBufferView(k.d, view, nullptr);
            return o;
        });
        ASSERT_EQ(out.size(), 256u);
        float red;  // texel 0's first channel, computed here from the bytes at the offset
        std::memcpy(&red, out.data(), 4);
        if (c.format == VK_FORMAT_R8_UNORM || c.format == VK_FORMAT_R8G8B8A8_UNORM) {
            EXPECT_EQ(red, float(texels[0]) * float(1.0 / 255.0));
        }
        if (c.format == VK_FORMAT_R32_SFLOAT || c.format == VK_FORMAT_R32G32B32_SFLOAT) {
            float want_red;
            std::memcpy(&want_red, texels.data(), 4);
            EXPECT_EQ(red, want_red);
        }
    }
}

// VK_EXT_depth_range_unrestricted: with the extension enabled, a viewport depth range of [-0.5, 3] and a depth clear
// of 2.5 reach D32F depth buffers unclamped (lavapipe's unclamped_fragment_depth_values), while D16 stays clamped to
// [0, 1]; with depthClamp on too, z is clamped to the viewport's range only. Bytes equal lavapipe's; the stored
// values are checked against the ranges here.
TEST_F(ApiSmallExtensions, DepthRangeUnrestrictedKeepsFloatDepth) {
    for (Device* dev : {tilevk_.get(), lavapipe_.get()})
        ASSERT_TRUE(advertised(dev->physical(), VK_EXT_DEPTH_RANGE_UNRESTRICTED_EXTENSION_NAME));
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.features.depthClamp = VK_TRUE;
    auto d = devices({VK_EXT_DEPTH_RANGE_UNRESTRICTED_EXTENSION_NAME}, &f2);
    ASSERT_TRUE(d->ok());
    for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D16_UNORM}) {
        for (bool clamp : {false, true}) {
            SCOPED_TRACE("format " + std::to_string(int(f)) + (clamp ? " depthClamp" : ""));
            const Bytes out = both_on(d->tilevk, d->lavapipe, [&](Kit& k) {
                const auto [col, dep, rp, fb] = depth_target(k, f);
                VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
                Pipe p;
                p.rp = rp;
                p.ds = &ds;
                p.depth_clamp = clamp;
                p.dynamic = {VK_DYNAMIC_STATE_VIEWPORT};
                VkPipeline pipe = k.pipeline(p);
                Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
                EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                    begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(2.5f)});
                    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                    // z' = -0.5 + 3.5 z: the triangles' z in [0.1, 0.9] lands in about [-0.15, 2.65]
                    const VkViewport vp{0, 0, 32, 32, -0.5f, 3.0f};
                    vkCmdSetViewport(c, 0, 1, &vp);
                    bind_vertices(c, vb);
                    vkCmdDraw(c, 6, 1, 0, 0);
                    vkCmdEndRenderPass(c);
                }),
                          VK_SUCCESS);
                return k.read(dep.image, 32, 32, f == VK_FORMAT_D16_UNORM ? 2 : 4, VK_IMAGE_ASPECT_DEPTH_BIT);
            });
            if (f == VK_FORMAT_D16_UNORM) {
                ASSERT_EQ(out.size(), 32u * 32u * 2u);
                int at_one = 0;  // the clear value 2.5 and fragments past 1, clamped to 1
                for (size_t i = 0; i < out.size(); i += 2) at_one += (out[i] | (out[i + 1] << 8)) == 0xffff;
                EXPECT_GT(at_one, 0);
                continue;
            }
            ASSERT_EQ(out.size(), 32u * 32u * 4u);
            int above_one = 0, below_zero = 0, cleared = 0;
            for (size_t i = 0; i < out.size(); i += 4) {
                float z;
                std::memcpy(&z, &out[i], 4);
                cleared += z == 2.5f;
                above_one += z > 1.0f && z < 2.5f;
                below_zero += z < 0.0f;
                EXPECT_GE(z, -0.5f);
                EXPECT_LE(z, 2.5f);
            }
            EXPECT_GT(cleared, 0);    // the clear value, unclamped
            EXPECT_GT(above_one, 0);  // fragments past 1 stored as they are
            if (!clamp) {
                EXPECT_GT(below_zero, 0);
            }
        }
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
