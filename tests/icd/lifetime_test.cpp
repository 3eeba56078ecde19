// Object lifetimes as the Vulkan spec's "Object Lifetime" section allows them (icd/README.md, "Object lifetimes"):
// objects destroyed while objects made from them live on and are still used. Each case runs on tilevk and lavapipe
// under the validation layer (zero messages: the usage is valid), compares the read-back bytes, and checks a few
// pixels against values computed here. Under ASan (tools/run_sanitizers.sh) a driver that still reads a destroyed
// object fails with a use-after-free.
#include "api_breadth.h"
#include "lt_push_frag.h"
#include "lt_sample_frag.h"

namespace tilevk::test::breadth {
namespace {

using Lifetime = ApiBreadth;

constexpr VkDescriptorType kCombined = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kUniformDynamic = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
constexpr VkShaderStageFlags kFrag = VK_SHADER_STAGE_FRAGMENT_BIT;
constexpr uint32_t kTexSize = 4, kUniformStride = 256;  // 256: every minUniformBufferOffsetAlignment allows it

// The uniform vec4 at index i of the uniform buffer (kUniformStride apart).
std::array<float, 4> uniform_value(uint32_t i) {
    return {0.125f * float(i + 1), 0.75f - 0.125f * float(i), 0.5f, 1.0f};
}

// What the lifetime scenes sample: a 4x4 RGBA8 texture with distinct texels and a uniform buffer of four vec4s.
struct Resources {
    Device::Image tex;
    VkImageView view;
    VkSampler nearest;
    Device::Buffer uniforms;
};
Resources resources(Kit& k) {
    Resources r{};
    r.tex = k.image(VK_FORMAT_R8G8B8A8_UNORM, kTexSize, kTexSize,
                    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    upload_rgba8(k, r.tex.image, kTexSize, kTexSize, 7);
    r.view = k.view(r.tex.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT);
    r.nearest = k.sampler();
    r.uniforms = k.buffer(4 * kUniformStride, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    for (uint32_t i = 0; i < 4; ++i) {
        const std::array<float, 4> u = uniform_value(i);
        std::memcpy(static_cast<uint8_t*>(r.uniforms.map) + i * kUniformStride, u.data(), sizeof u);
    }
    return r;
}

// The texel upload_rgba8(seed 7) wrote at (x, y) of the 4x4 texture.
std::array<uint8_t, 4> texel(uint32_t x, uint32_t y) {
    std::array<uint8_t, 4> t{};
    for (uint32_t c = 0; c < 4; ++c) {
        const size_t i = (size_t(y) * kTexSize + x) * 4 + c;
        t[c] = uint8_t((i * 37 + 7 * 101 + (i >> 5) * 11) & 255);
    }
    return t;
}

// A descriptor pool that can free its sets, destroyed at the end of the scene.
VkDescriptorPool free_pool(Kit& k, uint32_t max_sets = 4) {
    const VkDescriptorPoolSize sizes[] = {
        {kCombined, 4 * max_sets}, {kUniform, 4 * max_sets}, {kUniformDynamic, 4 * max_sets}};
    VkDescriptorPoolCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    ci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    ci.maxSets = max_sets;
    ci.poolSizeCount = uint32_t(std::size(sizes));
    ci.pPoolSizes = sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateDescriptorPool(k.d, &ci, nullptr, &pool), VK_SUCCESS);
    k.undo(VK_OBJECT_TYPE_DESCRIPTOR_POOL, pool, [&k, pool] { vkDestroyDescriptorPool(k.d, pool, nullptr); });
    return pool;
}

VkDescriptorSet allocate(Kit& k, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateDescriptorSets(k.d, &ai, &set), VK_SUCCESS);
    return set;
}

// Binding 0: the texture (with `sampler`; ignored for an immutable-sampler binding), binding 1: uniform vec4 0
// (as a dynamic buffer of one vec4 when `dynamic`).
void write_set(Kit& k, VkDescriptorSet set, const Resources& r, VkSampler sampler, bool dynamic) {
    const VkDescriptorImageInfo ii{sampler, r.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    k.write(set, 0, kCombined, nullptr, &ii);
    const VkDescriptorBufferInfo bi{r.uniforms.buffer, 0, 16};
    k.write(set, 1, dynamic ? kUniformDynamic : kUniform, &bi, nullptr);
}

// The set layout of lt_sample.frag: binding 0 a combined image sampler (immutable when `immutable` is set),
// binding 1 a uniform buffer.
VkDescriptorSetLayout sample_layout(Kit& k, bool dynamic, const VkSampler* immutable = nullptr) {
    VkDescriptorSetLayoutBinding b0{0, kCombined, 1, kFrag, immutable};
    VkDescriptorSetLayoutBinding b1{1, dynamic ? kUniformDynamic : kUniform, 1, kFrag, nullptr};
    return k.set_layout({b0, b1});
}

// One pass over the 32x32 target drawing lt_sample.frag's full-screen triangle with set 0 = `set`.
void draw_sample(VkCommandBuffer c, const Target& t, VkPipeline pipe, VkPipelineLayout layout, VkDescriptorSet set,
                 const std::vector<uint32_t>& dynamic_offsets = {}) {
    begin_pass(c, t.rp, t.fb, t.w, t.h, {clear_color(0, 0, 0, 0)});
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, uint32_t(dynamic_offsets.size()),
                            dynamic_offsets.data());
    vkCmdDraw(c, 3, 1, 0, 0);
    vkCmdEndRenderPass(c);
}

// Independent check of a NEAREST-sampled lt_sample.frag image: ab_fullscreen.vert's uv at pixel x is
// 0.25 + (x + 0.5)/64, so pixel (x, y) shows texel (1 + x/16, 1 + y/16) of the 4x4 texture; every channel is
// texel/2 + uniform/2, stored as UNORM8 (one unit of rounding allowed).
void expect_nearest_sample(const Bytes& img, uint32_t uniform_index) {
    ASSERT_EQ(img.size(), 32u * 32u * 4u);
    const std::array<float, 4> u = uniform_value(uniform_index);
    for (uint32_t y = 0; y < 32; y += 5)
        for (uint32_t x = 0; x < 32; x += 5) {
            const std::array<uint8_t, 4> t = texel(1 + x / 16, 1 + y / 16);
            for (uint32_t c = 0; c < 4; ++c) {
                const float want = (float(t[c]) / 255.0f * 0.5f + u[c] * 0.5f) * 255.0f;
                EXPECT_NEAR(float(px(img, x, y)[c]), want, 1.0f) << "pixel " << x << "," << y << " channel " << c;
            }
        }
}

// A descriptor set layout destroyed while a set allocated with it is still bound and drawn with (Object Lifetime:
// "VkDescriptorSetLayout objects may be accessed by commands that operate on descriptor sets allocated using that
// layout"). The layout goes before the pipeline is even created, after the pipeline layout made from it.
TEST_F(Lifetime, SetLayoutDestroyedWhileItsSetIsDrawnWith) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorSetLayout dsl = sample_layout(k, false);
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        write_set(k, set, r, r.nearest, false);
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, dsl);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, pipe, layout, set); }), VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    expect_nearest_sample(img, 0);
}

// The same with a dynamic uniform buffer: the dynamic offsets are matched to the set's bindings when the set is
// bound, after its layout was destroyed.
TEST_F(Lifetime, SetLayoutDestroyedBeforeItsSetIsBoundWithDynamicOffsets) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorSetLayout dsl = sample_layout(k, true);
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        write_set(k, set, r, r.nearest, true);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, dsl);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, pipe, layout, set, {2 * kUniformStride}); }),
                  VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    expect_nearest_sample(img, 2);
}

// Immutable samplers belong to the layout; its sets keep using them after the layout is destroyed. The immutable
// sampler filters LINEAR, the sampler written into the set (ignored for such a binding) NEAREST: the image must
// differ from the NEAREST one of a second, ordinary set drawn the same way.
TEST_F(Lifetime, ImmutableSamplerOutlivesItsDestroyedLayout) {
    both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkSampler linear = k.sampler(VK_FILTER_LINEAR);
        VkDescriptorSetLayout immutable_dsl = sample_layout(k, false, &linear);
        VkDescriptorSetLayout plain_dsl = sample_layout(k, false);
        VkPipelineLayout immutable_layout = k.pipeline_layout({immutable_dsl});
        VkPipelineLayout plain_layout = k.pipeline_layout({plain_dsl});
        VkDescriptorSet immutable_set = k.descriptor_set(immutable_dsl);
        VkDescriptorSet plain_set = k.descriptor_set(plain_dsl);
        write_set(k, immutable_set, r, r.nearest, false);
        write_set(k, plain_set, r, r.nearest, false);
        VkPipeline immutable_pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, immutable_layout));
        VkPipeline plain_pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, plain_layout));
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, immutable_dsl);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, plain_pipe, plain_layout, plain_set); }),
                  VK_SUCCESS);
        const Bytes nearest = k.read(t.image.image, 32, 32, 4);
        expect_nearest_sample(nearest, 0);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, immutable_pipe, immutable_layout, immutable_set); }),
                  VK_SUCCESS);
        const Bytes filtered = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(filtered, nearest) << "the immutable LINEAR sampler was not used";
        return filtered;
    });
}

// A set whose layout was destroyed is drawn with, then freed, and its pool allocates a set of another layout in its
// place. (Copying descriptors out of such a set is not allowed: the validation layer reports
// VUID-VkCopyDescriptorSet-srcSet-parameter, reading "must not be updated with vkUpdateDescriptorSets" as covering
// copies from it.)
TEST_F(Lifetime, SetOfADestroyedLayoutIsFreedAndItsPoolReused) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorPool pool = free_pool(k, 1);
        VkDescriptorSetLayout gone = sample_layout(k, true);
        VkDescriptorSetLayout kept = sample_layout(k, false);
        VkPipelineLayout gone_layout = k.pipeline_layout({gone});
        VkPipelineLayout kept_layout = k.pipeline_layout({kept});
        VkDescriptorSet set = allocate(k, pool, gone);
        write_set(k, set, r, r.nearest, true);
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, gone);
        VkPipeline gone_pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, gone_layout));
        VkPipeline kept_pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, kept_layout));
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, gone_pipe, gone_layout, set, {kUniformStride}); }),
                  VK_SUCCESS);
        const Bytes first = k.read(t.image.image, 32, 32, 4);
        expect_nearest_sample(first, 1);
        EXPECT_EQ(vkFreeDescriptorSets(k.d, pool, 1, &set), VK_SUCCESS);
        VkDescriptorSet next = allocate(k, pool, kept);
        write_set(k, next, r, r.nearest, false);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, kept_pipe, kept_layout, next); }), VK_SUCCESS);
        return concat({first, k.read(t.image.image, 32, 32, 4)});
    });
    expect_nearest_sample(Bytes(img.begin() + 32 * 32 * 4, img.end()), 0);
}

// A pipeline layout needs nothing of its set layouts after its creation: the set layout it was made from is
// destroyed before the pipeline is created, and the set comes from an identical (compatible) layout.
TEST_F(Lifetime, SetLayoutOfAPipelineLayoutDestroyedBeforePipelineCreation) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorSetLayout first = sample_layout(k, false);
        VkPipelineLayout layout = k.pipeline_layout({first});
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, first);
        VkDescriptorSetLayout twin = sample_layout(k, false);
        VkDescriptorSet set = k.descriptor_set(twin);
        write_set(k, set, r, r.nearest, false);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, pipe, layout, set); }), VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    expect_nearest_sample(img, 0);
}

// Descriptors no shader statically uses need not be valid (descriptor validity is required only where a shader
// statically uses a descriptor, VUID-vkCmdDraw-None-02699): bindings 2 and 3 of the set name an image view, an
// image, a sampler and a buffer that were destroyed before the draw was recorded (no validation message on either
// driver). lavapipe 22.3 crashes on this (it binds every descriptor of the set), so it draws the same scene with
// those objects alive, and tilevk's image must equal that one.
Bytes unused_descriptors_scene(Kit& k, bool destroy_unused) {
    Target t = target(k);
    Resources r = resources(k);
    VkDescriptorSetLayout dsl = k.set_layout({{0, kCombined, 1, kFrag, nullptr},
                                              {1, kUniform, 1, kFrag, nullptr},
                                              {2, kCombined, 1, kFrag, nullptr},
                                              {3, kUniform, 1, kFrag, nullptr}});
    VkPipelineLayout layout = k.pipeline_layout({dsl});
    VkDescriptorSet set = k.descriptor_set(dsl);
    write_set(k, set, r, r.nearest, false);
    Device::Image stale_image =
        k.image(VK_FORMAT_R8G8B8A8_UNORM, 8, 8, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    upload_rgba8(k, stale_image.image, 8, 8, 3);
    VkImageView stale_view = k.view(stale_image.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT);
    VkSampler stale_sampler = k.sampler(VK_FILTER_LINEAR);
    Device::Buffer stale_buffer = k.buffer(64, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    const VkDescriptorImageInfo ii{stale_sampler, stale_view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    k.write(set, 2, kCombined, nullptr, &ii);
    const VkDescriptorBufferInfo bi{stale_buffer.buffer, 0, 16};
    k.write(set, 3, kUniform, &bi, nullptr);
    if (destroy_unused) {
        k.destroy_now(VK_OBJECT_TYPE_IMAGE_VIEW, stale_view);
        k.destroy_now(VK_OBJECT_TYPE_IMAGE, stale_image.image);
        k.destroy_now(VK_OBJECT_TYPE_SAMPLER, stale_sampler);
        k.destroy_now(VK_OBJECT_TYPE_BUFFER, stale_buffer.buffer);
    }
    VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
    EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, pipe, layout, set); }), VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 4);
}

TEST_F(Lifetime, UnusedDescriptorsMayNameDestroyedObjects) {
    Bytes tilevk, lavapipe;
    {
        Kit k(*tilevk_);
        tilevk = unused_descriptors_scene(k, true);
    }
    {
        Kit k(*lavapipe_);
        lavapipe = unused_descriptors_scene(k, false);
    }
    expect_same(tilevk, lavapipe);
    expect_nearest_sample(tilevk, 0);
}

// A pipeline layout may be destroyed once recording has ended (VUID-vkDestroyPipelineLayout-pipelineLayout-02004
// forbids it only while a command buffer that used it is still recording): the command buffer that bound sets and
// pushed constants with it is submitted twice after its destruction.
TEST_F(Lifetime, PipelineLayoutDestroyedAfterRecording) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorSetLayout dsl = k.set_layout({{0, kCombined, 1, kFrag, nullptr}});
        VkPipelineLayout layout = k.pipeline_layout({dsl}, {{kFrag, 0, 16}});
        VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorImageInfo ii{r.nearest, r.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(set, 0, kCombined, nullptr, &ii);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_push_frag), t, layout));
        VkCommandBuffer cb = k.command_buffer();
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        EXPECT_EQ(vkBeginCommandBuffer(cb, &bi), VK_SUCCESS);
        begin_pass(cb, t.rp, t.fb, t.w, t.h, {clear_color(0, 0, 0, 0)});
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
        const std::array<float, 4> u = uniform_value(1);
        vkCmdPushConstants(cb, layout, kFrag, 0, 16, u.data());
        vkCmdDraw(cb, 3, 1, 0, 0);
        vkCmdEndRenderPass(cb);
        EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
        k.destroy_now(VK_OBJECT_TYPE_PIPELINE_LAYOUT, layout);
        EXPECT_EQ(k.submit(cb), VK_SUCCESS);
        EXPECT_EQ(k.submit(cb), VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    expect_nearest_sample(img, 1);
}

// A descriptor update template needs nothing of the set layout it was made from after its creation ("a
// VkDescriptorSetLayout object passed as a parameter to create another object is not further accessed by that
// object"): that layout is destroyed, then the template writes a set of an identical layout, which is drawn with.
// Without the validation layer: Debian's (1.3.239) reads the template's destroyed layout in
// vkUpdateDescriptorSetWithTemplate and crashes.
TEST_F(Lifetime, SetLayoutOfADescriptorUpdateTemplateDestroyedBeforeTheUpdate) {
    Harness plain(false);
    ASSERT_TRUE(plain.ok());
    Device tilevk(plain.find_device("tilevk"), nullptr, {VK_KHR_DESCRIPTOR_UPDATE_TEMPLATE_EXTENSION_NAME});
    Device lavapipe(plain.find_device("llvmpipe"), nullptr, {VK_KHR_DESCRIPTOR_UPDATE_TEMPLATE_EXTENSION_NAME});
    ASSERT_TRUE(tilevk.ok() && lavapipe.ok());
    const Bytes img = both_on(tilevk, lavapipe, [](Kit& k) {
        auto create = reinterpret_cast<PFN_vkCreateDescriptorUpdateTemplateKHR>(
            vkGetDeviceProcAddr(k.d, "vkCreateDescriptorUpdateTemplateKHR"));
        auto update = reinterpret_cast<PFN_vkUpdateDescriptorSetWithTemplateKHR>(
            vkGetDeviceProcAddr(k.d, "vkUpdateDescriptorSetWithTemplateKHR"));
        auto destroy = reinterpret_cast<PFN_vkDestroyDescriptorUpdateTemplateKHR>(
            vkGetDeviceProcAddr(k.d, "vkDestroyDescriptorUpdateTemplateKHR"));
        EXPECT_TRUE(create && update && destroy);
        Target t = target(k);
        Resources r = resources(k);
        struct Data {
            VkDescriptorImageInfo image;
            VkDescriptorBufferInfo buffer;
        } data{{r.nearest, r.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}, {r.uniforms.buffer, 0, 16}};
        const VkDescriptorUpdateTemplateEntry entries[] = {{0, 0, 1, kCombined, offsetof(Data, image), 0},
                                                           {1, 0, 1, kUniform, offsetof(Data, buffer), 0}};
        VkDescriptorSetLayout first = sample_layout(k, false);
        VkDescriptorUpdateTemplateCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_UPDATE_TEMPLATE_CREATE_INFO};
        ci.descriptorUpdateEntryCount = uint32_t(std::size(entries));
        ci.pDescriptorUpdateEntries = entries;
        ci.templateType = VK_DESCRIPTOR_UPDATE_TEMPLATE_TYPE_DESCRIPTOR_SET;
        ci.descriptorSetLayout = first;
        VkDescriptorUpdateTemplate tpl = VK_NULL_HANDLE;
        EXPECT_EQ(create(k.d, &ci, nullptr, &tpl), VK_SUCCESS);
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, first);
        VkDescriptorSetLayout twin = sample_layout(k, false);
        VkPipelineLayout layout = k.pipeline_layout({twin});
        VkDescriptorSet set = k.descriptor_set(twin);
        update(k.d, set, tpl, &data);
        destroy(k.d, tpl, nullptr);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, pipe, layout, set); }), VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    expect_nearest_sample(img, 0);
}

// A render pass passed to vkCreateGraphicsPipelines and vkCreateFramebuffer is not accessed by them afterwards:
// both are used with a compatible render pass after the one they were made with is destroyed.
TEST_F(Lifetime, RenderPassDestroyedAfterPipelineAndFramebufferCreation) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkRenderPass first = k.render_pass(
            {attachment(VK_FORMAT_R8G8B8A8_UNORM, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)},
            {subpass(&kColour0)});
        VkFramebuffer fb =
            k.framebuffer(first, {k.view(t.image.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT)}, 32, 32);
        VkDescriptorSetLayout dsl = sample_layout(k, false);
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        write_set(k, set, r, r.nearest, false);
        Pipe p = fullscreen_pipe(SPV(lt_sample_frag), t, layout);
        p.rp = first;
        VkPipeline pipe = k.pipeline(p);
        k.destroy_now(VK_OBJECT_TYPE_RENDER_PASS, first);
        Target compatible = t;  // t.rp: the same attachment and subpass, so compatible
        compatible.fb = fb;
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, compatible, pipe, layout, set); }), VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    expect_nearest_sample(img, 0);
}

// Shader modules and pipeline caches are consumed by pipeline creation: both are destroyed before the pipeline is
// used, and a second pipeline is then made from the same SPIR-V in new modules.
TEST_F(Lifetime, ShaderModulesAndPipelineCacheDestroyedAfterPipelineCreation) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorSetLayout dsl = sample_layout(k, false);
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        write_set(k, set, r, r.nearest, false);
        VkPipelineCacheCreateInfo cci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
        VkPipelineCache cache = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreatePipelineCache(k.d, &cci, nullptr, &cache), VK_SUCCESS);
        Pipe p = fullscreen_pipe(SPV(lt_sample_frag), t, layout);
        p.cache = cache;
        VkPipeline pipe = k.pipeline(p);
        vkDestroyPipelineCache(k.d, cache, nullptr);
        k.destroy_now<VkShaderModule>(VK_OBJECT_TYPE_SHADER_MODULE, VK_NULL_HANDLE);
        VkPipeline again = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
        k.destroy_now<VkShaderModule>(VK_OBJECT_TYPE_SHADER_MODULE, VK_NULL_HANDLE);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, pipe, layout, set); }), VK_SUCCESS);
        const Bytes first = k.read(t.image.image, 32, 32, 4);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, again, layout, set); }), VK_SUCCESS);
        EXPECT_EQ(k.read(t.image.image, 32, 32, 4), first);
        return first;
    });
    expect_nearest_sample(img, 0);
}

// Objects destroyed in any order, each while another object that used it lives on and is afterwards only destroyed
// or reset (Object Lifetime, "objects can be destroyed or freed in any order"): memory freed before the image and
// buffer bound to it, an image before its view, a view before the framebuffer and set naming it, a render pass and
// a pipeline layout before the pipeline, a buffer before the descriptor set, objects recorded in an executable
// command buffer before it is reset, re-recorded with live objects and submitted.
TEST_F(Lifetime, ObjectsDestroyedInAnyOrder) {
    const Bytes img = both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorSetLayout dsl = sample_layout(k, false);
        VkDescriptorPool pool = free_pool(k);
        // A complete scene of its own, recorded but never submitted, then torn down from the bottom up.
        Target doomed = target(k);
        Resources doomed_r = resources(k);
        VkPipelineLayout doomed_layout = k.pipeline_layout({dsl});
        VkDescriptorSet doomed_set = allocate(k, pool, dsl);
        write_set(k, doomed_set, doomed_r, doomed_r.nearest, false);
        VkPipeline doomed_pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), doomed, doomed_layout));
        VkCommandBuffer cb = k.command_buffer();
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        EXPECT_EQ(vkBeginCommandBuffer(cb, &bi), VK_SUCCESS);
        draw_sample(cb, doomed, doomed_pipe, doomed_layout, doomed_set);
        EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
        vkFreeMemory(k.d, doomed_r.tex.memory, nullptr);
        vkFreeMemory(k.d, doomed_r.uniforms.memory, nullptr);
        vkFreeMemory(k.d, doomed.image.memory, nullptr);
        vkDestroyImage(k.d, doomed_r.tex.image, nullptr);
        vkDestroyImage(k.d, doomed.image.image, nullptr);
        vkDestroyBuffer(k.d, doomed_r.uniforms.buffer, nullptr);
        k.destroy_now(VK_OBJECT_TYPE_RENDER_PASS, doomed.rp);
        k.destroy_now(VK_OBJECT_TYPE_PIPELINE_LAYOUT, doomed_layout);
        k.destroy_now(VK_OBJECT_TYPE_IMAGE_VIEW, doomed_r.view);
        k.destroy_now(VK_OBJECT_TYPE_SAMPLER, doomed_r.nearest);
        k.destroy_now(VK_OBJECT_TYPE_PIPELINE, doomed_pipe);
        EXPECT_EQ(vkFreeDescriptorSets(k.d, pool, 1, &doomed_set), VK_SUCCESS);
        k.destroy_now(VK_OBJECT_TYPE_FRAMEBUFFER, doomed.fb);
        // The memory and handles above are gone; the Kit must not destroy them again.
        k.forget(VK_OBJECT_TYPE_IMAGE, doomed_r.tex.image);
        k.forget(VK_OBJECT_TYPE_IMAGE, doomed.image.image);
        k.forget(VK_OBJECT_TYPE_BUFFER, doomed_r.uniforms.buffer);
        // The command buffer that used all of it is reset by beginning it again, and used for the real scene.
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = allocate(k, pool, dsl);
        write_set(k, set, r, r.nearest, false);
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
        EXPECT_EQ(vkBeginCommandBuffer(cb, &bi), VK_SUCCESS);
        draw_sample(cb, t, pipe, layout, set);
        EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
        EXPECT_EQ(k.submit(cb), VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    expect_nearest_sample(img, 0);
}

// Pools free their children: a command pool destroyed with recorded command buffers, a descriptor pool reset and
// then destroyed with sets whose layout was destroyed first.
TEST_F(Lifetime, PoolsFreeTheirChildren) {
    both([](Kit& k) {
        Target t = target(k);
        Resources r = resources(k);
        VkDescriptorSetLayout dsl = sample_layout(k, false);
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), t, layout));
        VkDescriptorPool pool = free_pool(k);
        VkDescriptorSet sets[3];
        for (VkDescriptorSet& s : sets) {
            s = allocate(k, pool, dsl);
            write_set(k, s, r, r.nearest, false);
        }
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, dsl);
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        VkCommandPool cmd_pool = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateCommandPool(k.d, &pci, nullptr, &cmd_pool), VK_SUCCESS);
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = cmd_pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 2;
        VkCommandBuffer cbs[2];
        EXPECT_EQ(vkAllocateCommandBuffers(k.d, &ai, cbs), VK_SUCCESS);
        for (VkCommandBuffer cb : cbs) {
            VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            EXPECT_EQ(vkBeginCommandBuffer(cb, &bi), VK_SUCCESS);
            draw_sample(cb, t, pipe, layout, sets[0]);
            EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
        }
        EXPECT_EQ(k.submit(cbs[1]), VK_SUCCESS);
        vkDestroyCommandPool(k.d, cmd_pool, nullptr);
        EXPECT_EQ(vkFreeDescriptorSets(k.d, pool, 1, &sets[1]), VK_SUCCESS);
        EXPECT_EQ(vkResetDescriptorPool(k.d, pool, 0), VK_SUCCESS);
        VkDescriptorSetLayout again = sample_layout(k, false);
        VkDescriptorSet fresh = allocate(k, pool, again);
        write_set(k, fresh, r, r.nearest, false);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_sample(c, t, pipe, layout, fresh); }), VK_SUCCESS);
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_POOL, pool);
        const Bytes img = k.read(t.image.image, 32, 32, 4);
        expect_nearest_sample(img, 0);
        return img;
    });
}

}  // namespace
}  // namespace tilevk::test::breadth
