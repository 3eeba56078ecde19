// API breadth: VK_KHR_push_descriptor. Set 1 of ab_descriptors.frag (a uniform buffer, a sampled image, a sampler)
// is pushed instead of allocated — with vkCmdPushDescriptorSetKHR, with a push-descriptor update template, and
// incrementally (a second push rewrites one binding only; the spec keeps the others) — on tilevk and lavapipe with
// the validation layer on, compared byte for byte; the writes' result also equals the same scene drawn with an
// allocated set on tilevk.
#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

enum class Set1 { kAllocated, kPushed, kPushedWithTemplate };

template <class F>
F device_proc(Kit& k, const char* name) {
    auto f = reinterpret_cast<F>(vkGetDeviceProcAddr(k.d, name));
    EXPECT_NE(f, nullptr) << name;
    return f;
}

VkDescriptorSetLayout push_layout(Kit& k, const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
    VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    ci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    ci.bindingCount = uint32_t(bindings.size());
    ci.pBindings = bindings.data();
    VkDescriptorSetLayout l = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateDescriptorSetLayout(k.d, &ci, nullptr, &l), VK_SUCCESS);
    k.undo(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, l, [&k, l] { vkDestroyDescriptorSetLayout(k.d, l, nullptr); });
    return l;
}

// Two draws (left and right halves): set 1's uniform buffer changes between them (the second push writes binding 0
// only), its images stay.
Bytes push_scene(Kit& k, Set1 how) {
    Target t = target(k);
    const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
    VkDescriptorSetLayout l0 = k.set_layout(
        {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, F}, {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, F}});
    const std::vector<VkDescriptorSetLayoutBinding> b1 = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, F},
                                                          {1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1, F},
                                                          {2, VK_DESCRIPTOR_TYPE_SAMPLER, 1, F}};
    VkDescriptorSetLayout l1 = how == Set1::kAllocated ? k.set_layout(b1) : push_layout(k, b1);
    VkPipelineLayout layout = k.pipeline_layout({l0, l1});
    VkDescriptorSet s0 = k.descriptor_set(l0);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
    const VkDeviceSize align = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
    Device::Buffer ubo = k.buffer(align * 3, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    const float vals[3][4] = {{0.2f, 0.4f, 0.6f, 0.8f}, {1, 0, 0.5f, 1}, {0, 1, 0.25f, 0.5f}};
    for (int i = 0; i < 3; ++i) std::memcpy(static_cast<uint8_t*>(ubo.map) + i * align, vals[i], 16);
    Device::Image t1 =
        k.image(VK_FORMAT_R8G8B8A8_UNORM, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    Device::Image t2 =
        k.image(VK_FORMAT_R8G8B8A8_UNORM, 8, 2, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    upload_rgba8(k, t1.image, 4, 4, 1);
    upload_rgba8(k, t2.image, 8, 2, 2);
    VkSampler smp = k.sampler(VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT);
    const VkDescriptorBufferInfo b0{ubo.buffer, 0, 16}, first{ubo.buffer, align, 16}, second{ubo.buffer, 2 * align, 16};
    const VkDescriptorImageInfo i1{smp, k.view(t1.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorImageInfo i2{VK_NULL_HANDLE,
                                   k.view(t2.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorImageInfo is{smp, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
    k.write(s0, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &b0, nullptr);
    k.write(s0, 3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &i1);
    // Set 1's three descriptors, and binding 0 alone with the second buffer.
    auto write = [](uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* b,
                    const VkDescriptorImageInfo* i) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = binding;
        w.descriptorCount = 1;
        w.descriptorType = type;
        w.pBufferInfo = b;
        w.pImageInfo = i;
        return w;
    };
    VkWriteDescriptorSet all[3] = {write(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &first, nullptr),
                                   write(1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, nullptr, &i2),
                                   write(2, VK_DESCRIPTOR_TYPE_SAMPLER, nullptr, &is)};
    const VkWriteDescriptorSet again = write(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &second, nullptr);
    VkDescriptorSet s1a = VK_NULL_HANDLE, s1b = VK_NULL_HANDLE;
    if (how == Set1::kAllocated) {
        s1a = k.descriptor_set(l1);
        s1b = k.descriptor_set(l1);
        for (VkWriteDescriptorSet& w : all) w.dstSet = s1a;
        vkUpdateDescriptorSets(k.d, 3, all, 0, nullptr);
        for (VkWriteDescriptorSet& w : all) w.dstSet = s1b;
        all[0].pBufferInfo = &second;
        vkUpdateDescriptorSets(k.d, 3, all, 0, nullptr);
        all[0].pBufferInfo = &first;
    }
    // The push template reads the three descriptors from one record.
    struct Record {
        VkDescriptorBufferInfo buffer;
        VkDescriptorImageInfo image, sampler;
    } record{first, i2, is};
    VkDescriptorUpdateTemplate tpl = VK_NULL_HANDLE;
    if (how == Set1::kPushedWithTemplate) {
        const VkDescriptorUpdateTemplateEntry entries[] = {
            {0, 0, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, offsetof(Record, buffer), 0},
            {1, 0, 1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, offsetof(Record, image), 0},
            {2, 0, 1, VK_DESCRIPTOR_TYPE_SAMPLER, offsetof(Record, sampler), 0}};
        VkDescriptorUpdateTemplateCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_UPDATE_TEMPLATE_CREATE_INFO};
        ci.descriptorUpdateEntryCount = 3;
        ci.pDescriptorUpdateEntries = entries;
        ci.templateType = VK_DESCRIPTOR_UPDATE_TEMPLATE_TYPE_PUSH_DESCRIPTORS_KHR;
        ci.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        ci.pipelineLayout = layout;
        ci.set = 1;
        EXPECT_EQ(vkCreateDescriptorUpdateTemplate(k.d, &ci, nullptr, &tpl), VK_SUCCESS);
        k.undo(VK_OBJECT_TYPE_DESCRIPTOR_UPDATE_TEMPLATE, tpl,
               [&k, tpl] { vkDestroyDescriptorUpdateTemplate(k.d, tpl, nullptr); });
    }
    auto push = device_proc<PFN_vkCmdPushDescriptorSetKHR>(k, "vkCmdPushDescriptorSetKHR");
    auto push_template =
        device_proc<PFN_vkCmdPushDescriptorSetWithTemplateKHR>(k, "vkCmdPushDescriptorSetWithTemplateKHR");
    Pipe p;
    p.fs = SPV(ab_descriptors_frag);
    p.rp = t.rp;
    p.layout = layout;
    VkPipeline pipe = k.pipeline(p);
    // Left half, then right half (uv from the colour: 0..1.5 across the target).
    const std::vector<Vertex> verts = {v(-1, -1, 0, 0, 0, 0),    v(0, -1, 0, 0.75f, 0, 0), v(-1, 1, 0, 0, 1.5f, 0),
                                       v(0, -1, 0, 0.75f, 0, 0), v(1, -1, 0, 1.5f, 0, 0),  v(1, 1, 0, 1.5f, 1.5f, 0)};
    Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &s0, 0, nullptr);
        if (how == Set1::kAllocated)
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &s1a, 0, nullptr);
        else if (how == Set1::kPushed)
            push(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 3, all);
        else
            push_template(c, tpl, layout, 1, &record);
        vkCmdDraw(c, 3, 1, 0, 0);
        if (how == Set1::kAllocated)
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &s1b, 0, nullptr);
        else
            push(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &again);
        vkCmdDraw(c, 3, 1, 3, 0);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 4);
}

class ApiPushDescriptor : public ApiBreadth {};

TEST_F(ApiPushDescriptor, PushedSetsDrawAsAllocatedSets) {
    auto dev = device_pair({VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME});
    ASSERT_TRUE(dev->ok());
    Bytes allocated;
    {
        Kit k(dev->tilevk);
        allocated = push_scene(k, Set1::kAllocated);
    }
    EXPECT_NE(px(allocated, 4, 16)[0], px(allocated, 28, 16)[0]);  // the two buffers differ
    for (Set1 how : {Set1::kPushed, Set1::kPushedWithTemplate}) {
        SCOPED_TRACE(how == Set1::kPushed ? "vkCmdPushDescriptorSetKHR" : "vkCmdPushDescriptorSetWithTemplateKHR");
        const Bytes pushed = both_on(dev->tilevk, dev->lavapipe, [how](Kit& k) { return push_scene(k, how); });
        expect_same(pushed, allocated, "pushed vs allocated set on tilevk");
    }
}

TEST_F(ApiPushDescriptor, ReportsMaxPushDescriptors) {
    VkPhysicalDevicePushDescriptorPropertiesKHR push{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &push;
    vkGetPhysicalDeviceProperties2(tilevk_->physical(), &p2);
    EXPECT_EQ(push.maxPushDescriptors, 32u);  // the spec's minimum, and lavapipe's value
}

}  // namespace
}  // namespace tilevk::test::breadth
