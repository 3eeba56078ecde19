// API breadth: the device extensions tilevk offers (Vulkan 1.1-1.3 functionality for 1.0 applications), each used
// on tilevk and on lavapipe with the extension enabled, the validation layer on (zero messages) and the results
// compared byte for byte; the new commands are also compared with the Vulkan 1.0 commands they extend.
#include "api_breadth.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

class ApiExtensions : public ApiBreadth {
  protected:
    std::unique_ptr<DevicePair> devices(const std::vector<const char*>& extensions, const void* chain = nullptr) {
        return device_pair(extensions, chain);
    }
    template <class F>
    static F instance_proc(const char* name) {
        auto f = reinterpret_cast<F>(vkGetInstanceProcAddr(harness_->instance(), name));
        EXPECT_NE(f, nullptr) << name;
        return f;
    }
};

// The descriptor sets of DescriptorSetsDynamicOffsetsSeparateSamplers (without the dynamic buffer), written either
// with vkUpdateDescriptorSets or through one update template per set whose data is a packed, strided struct.
Bytes descriptor_scene(Kit& k, bool with_template) {
    Target t = target(k);
    const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
    VkDescriptorSetLayout l0 = k.set_layout(
        {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, F}, {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, F}});
    VkDescriptorSetLayout l1 = k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, F},
                                             {1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1, F},
                                             {2, VK_DESCRIPTOR_TYPE_SAMPLER, 1, F}});
    VkPipelineLayout layout = k.pipeline_layout({l0, l1});
    VkDescriptorSet s0 = k.descriptor_set(l0), s1 = k.descriptor_set(l1);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
    const VkDeviceSize align = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
    Device::Buffer ubo = k.buffer(align * 2, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    const float vals[2][4] = {{0.2f, 0.4f, 0.6f, 0.8f}, {1, 0, 0.5f, 1}};
    for (int i = 0; i < 2; ++i) std::memcpy(static_cast<uint8_t*>(ubo.map) + i * align, vals[i], 16);
    Device::Image t1 =
        k.image(VK_FORMAT_R8G8B8A8_UNORM, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    Device::Image t2 =
        k.image(VK_FORMAT_R8G8B8A8_UNORM, 8, 2, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    upload_rgba8(k, t1.image, 4, 4, 1);
    upload_rgba8(k, t2.image, 8, 2, 2);
    VkSampler smp = k.sampler(VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT);
    const VkDescriptorBufferInfo b0{ubo.buffer, 0, 16}, b1{ubo.buffer, align, 16};
    const VkDescriptorImageInfo i1{smp, k.view(t1.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorImageInfo i2{VK_NULL_HANDLE,
                                   k.view(t2.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorImageInfo is{smp, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
    if (!with_template) {
        k.write(s0, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &b0, nullptr);
        k.write(s0, 3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &i1);
        k.write(s1, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &b1, nullptr);
        k.write(s1, 1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, nullptr, &i2);
        k.write(s1, 2, VK_DESCRIPTOR_TYPE_SAMPLER, nullptr, &is);
    } else {
        auto create = device_proc<PFN_vkCreateDescriptorUpdateTemplateKHR>(k, "vkCreateDescriptorUpdateTemplateKHR");
        auto update = device_proc<PFN_vkUpdateDescriptorSetWithTemplateKHR>(k, "vkUpdateDescriptorSetWithTemplateKHR");
        auto destroy = device_proc<PFN_vkDestroyDescriptorUpdateTemplateKHR>(k, "vkDestroyDescriptorUpdateTemplateKHR");
        // Set 0: the image first in memory, the buffer after it (offsets need not follow binding order).
        struct Packed0 {
            VkDescriptorImageInfo image;
            uint32_t pad;  // unaligned neighbours are allowed: offsets are bytes
            VkDescriptorBufferInfo buffer;
        } d0{i1, 0xdeadbeef, b0};
        const VkDescriptorUpdateTemplateEntry e0[] = {
            {3, 0, 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, offsetof(Packed0, image), 0},
            {0, 0, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, offsetof(Packed0, buffer), 0}};
        // Set 1: three entries read from an array of records with a stride.
        struct Record {
            VkDescriptorImageInfo image;
            VkDescriptorBufferInfo buffer;
        } d1[2] = {{i2, b1}, {is, {}}};
        const VkDescriptorUpdateTemplateEntry e1[] = {
            {0, 0, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, offsetof(Record, buffer), sizeof(Record)},
            {1, 0, 1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, offsetof(Record, image), sizeof(Record)},
            {2, 0, 1, VK_DESCRIPTOR_TYPE_SAMPLER, sizeof(Record) + offsetof(Record, image), sizeof(Record)}};
        VkDescriptorUpdateTemplate tpl[2] = {};
        const VkDescriptorUpdateTemplateEntry* entries[2] = {e0, e1};
        const uint32_t counts[2] = {2, 3};
        const VkDescriptorSetLayout layouts[2] = {l0, l1};
        for (int i = 0; i < 2; ++i) {
            VkDescriptorUpdateTemplateCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_UPDATE_TEMPLATE_CREATE_INFO};
            ci.descriptorUpdateEntryCount = counts[i];
            ci.pDescriptorUpdateEntries = entries[i];
            ci.templateType = VK_DESCRIPTOR_UPDATE_TEMPLATE_TYPE_DESCRIPTOR_SET;
            ci.descriptorSetLayout = layouts[i];
            EXPECT_EQ(create(k.d, &ci, nullptr, &tpl[i]), VK_SUCCESS);
        }
        update(k.d, s0, tpl[0], &d0);
        update(k.d, s1, tpl[1], d1);
        for (VkDescriptorUpdateTemplate x : tpl) destroy(k.d, x, nullptr);
    }
    Pipe p;
    p.fs = SPV(ab_descriptors_frag);
    p.rp = t.rp;
    p.layout = layout;
    VkPipeline pipe = k.pipeline(p);
    const std::vector<Vertex> verts = {v(-1, -1, 0, 0, 0, 0), v(1, -1, 0, 1.5f, 0, 0), v(-1, 1, 0, 0, 1.5f, 0)};
    Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        const VkDescriptorSet sets[2] = {s0, s1};
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 2, sets, 0, nullptr);
        vkCmdDraw(c, 3, 1, 0, 0);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 4);
}

TEST_F(ApiExtensions, DescriptorUpdateTemplatesWriteWhatUpdatesWrite) {
    auto dev = devices({VK_KHR_DESCRIPTOR_UPDATE_TEMPLATE_EXTENSION_NAME});
    ASSERT_TRUE(dev->ok());
    const Bytes with_template = both_on(dev->tilevk, dev->lavapipe, [](Kit& k) { return descriptor_scene(k, true); });
    Kit k(dev->tilevk);
    const Bytes with_writes = descriptor_scene(k, false);
    expect_same(with_template, with_writes, "template vs vkUpdateDescriptorSets on tilevk");
    EXPECT_NE(px(with_template, 2, 2)[0], 64);  // drawn
}

// A 16x16 RGBA8 image and two buffers whose memory is found with vkGet*MemoryRequirements2 (dedicated requirements
// chained), allocated dedicated and bound with vkBind*Memory2; an upload, a scaled linear blit, an image copy, a
// read-back and a buffer copy recorded with the copy_commands2 forms (or the 1.0 forms: `v2` false).
Bytes transfer_scene(Kit& k, bool v2) {
    const VkFormat f = VK_FORMAT_R8G8B8A8_UNORM;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = f;
    ici.extent = {16, 16, 1};
    ici.mipLevels = ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.usage = usage;
    VkImage img = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateImage(k.d, &ici, nullptr, &img), VK_SUCCESS);
    auto reqs2 = device_proc<PFN_vkGetImageMemoryRequirements2KHR>(k, "vkGetImageMemoryRequirements2KHR");
    auto bind2 = device_proc<PFN_vkBindImageMemory2KHR>(k, "vkBindImageMemory2KHR");
    VkMemoryDedicatedRequirements dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
    VkMemoryRequirements2 r2{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    r2.pNext = &dedicated;
    VkImageMemoryRequirementsInfo2 info{VK_STRUCTURE_TYPE_IMAGE_MEMORY_REQUIREMENTS_INFO_2};
    info.image = img;
    reqs2(k.d, &info, &r2);
    VkMemoryRequirements r1;
    vkGetImageMemoryRequirements(k.d, img, &r1);
    EXPECT_EQ(r2.memoryRequirements.size, r1.size);
    EXPECT_EQ(r2.memoryRequirements.alignment, r1.alignment);
    EXPECT_EQ(r2.memoryRequirements.memoryTypeBits, r1.memoryTypeBits);
    VkMemoryDedicatedAllocateInfo dai{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
    dai.image = img;
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.pNext = &dai;  // dedicated whether or not the driver asks for it
    ai.allocationSize = r2.memoryRequirements.size;
    ai.memoryTypeIndex = 0;
    while (!(r2.memoryRequirements.memoryTypeBits & (1u << ai.memoryTypeIndex))) ++ai.memoryTypeIndex;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateMemory(k.d, &ai, nullptr, &mem), VK_SUCCESS);
    VkBindImageMemoryInfo bi{VK_STRUCTURE_TYPE_BIND_IMAGE_MEMORY_INFO};
    bi.image = img;
    bi.memory = mem;
    EXPECT_EQ(bind2(k.d, 1, &bi), VK_SUCCESS);
    Device::Image small = k.image(f, 8, 8, usage);

    Device::Buffer src = k.buffer(16 * 16 * 4), dst = k.buffer(16 * 16 * 4 + 8 * 8 * 4), out = k.buffer(dst.size);
    auto* p = static_cast<uint8_t*>(src.map);
    for (size_t i = 0; i < src.size; ++i) p[i] = uint8_t((i * 29 + (i >> 6) * 7) & 255);
    const VkImageSubresourceLayers sub{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    const VkBufferImageCopy up{0, 0, 0, sub, {0, 0, 0}, {16, 16, 1}};
    const VkImageBlit blit{sub, {{1, 2, 0}, {15, 13, 1}}, sub, {{0, 0, 0}, {8, 8, 1}}};
    const VkImageCopy copy{sub, {8, 8, 0}, sub, {0, 0, 0}, {4, 4, 1}};
    const VkBufferImageCopy down_big{0, 0, 0, sub, {0, 0, 0}, {16, 16, 1}};
    const VkBufferImageCopy down_small{16 * 16 * 4, 0, 0, sub, {0, 0, 0}, {8, 8, 1}};
    const VkBufferCopy bcopy{4, 0, dst.size - 4};
    auto cmd_copy_b2i = device_proc<PFN_vkCmdCopyBufferToImage2KHR>(k, "vkCmdCopyBufferToImage2KHR");
    auto cmd_blit = device_proc<PFN_vkCmdBlitImage2KHR>(k, "vkCmdBlitImage2KHR");
    auto cmd_copy_img = device_proc<PFN_vkCmdCopyImage2KHR>(k, "vkCmdCopyImage2KHR");
    auto cmd_copy_i2b = device_proc<PFN_vkCmdCopyImageToBuffer2KHR>(k, "vkCmdCopyImageToBuffer2KHR");
    auto cmd_copy_buf = device_proc<PFN_vkCmdCopyBuffer2KHR>(k, "vkCmdCopyBuffer2KHR");
    const VkImageLayout SRC = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, DST = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    auto barrier = [](VkCommandBuffer c) {
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, nullptr,
                             0, nullptr);
    };
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        transition(c, img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, DST);
        transition(c, small.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, DST);
        if (v2) {
            VkBufferImageCopy2 r{VK_STRUCTURE_TYPE_BUFFER_IMAGE_COPY_2};
            r.imageSubresource = sub;
            r.imageExtent = up.imageExtent;
            VkCopyBufferToImageInfo2 ci{VK_STRUCTURE_TYPE_COPY_BUFFER_TO_IMAGE_INFO_2};
            ci.srcBuffer = src.buffer;
            ci.dstImage = img;
            ci.dstImageLayout = DST;
            ci.regionCount = 1;
            ci.pRegions = &r;
            cmd_copy_b2i(c, &ci);
        } else {
            vkCmdCopyBufferToImage(c, src.buffer, img, DST, 1, &up);
        }
        transition(c, img, VK_IMAGE_ASPECT_COLOR_BIT, DST, SRC);
        if (v2) {
            VkImageBlit2 r{VK_STRUCTURE_TYPE_IMAGE_BLIT_2};
            r.srcSubresource = r.dstSubresource = sub;
            std::memcpy(r.srcOffsets, blit.srcOffsets, sizeof r.srcOffsets);
            std::memcpy(r.dstOffsets, blit.dstOffsets, sizeof r.dstOffsets);
            VkBlitImageInfo2 bi2{VK_STRUCTURE_TYPE_BLIT_IMAGE_INFO_2};
            bi2.srcImage = img;
            bi2.srcImageLayout = SRC;
            bi2.dstImage = small.image;
            bi2.dstImageLayout = DST;
            bi2.regionCount = 1;
            bi2.pRegions = &r;
            bi2.filter = VK_FILTER_LINEAR;
            cmd_blit(c, &bi2);
        } else {
            vkCmdBlitImage(c, img, SRC, small.image, DST, 1, &blit, VK_FILTER_LINEAR);
        }
        barrier(c);
        if (v2) {
            VkImageCopy2 r{VK_STRUCTURE_TYPE_IMAGE_COPY_2};
            r.srcSubresource = r.dstSubresource = sub;
            r.srcOffset = copy.srcOffset;
            r.extent = copy.extent;
            VkCopyImageInfo2 ci{VK_STRUCTURE_TYPE_COPY_IMAGE_INFO_2};
            ci.srcImage = img;
            ci.srcImageLayout = SRC;
            ci.dstImage = small.image;
            ci.dstImageLayout = DST;
            ci.regionCount = 1;
            ci.pRegions = &r;
            cmd_copy_img(c, &ci);
        } else {
            vkCmdCopyImage(c, img, SRC, small.image, DST, 1, &copy);
        }
        transition(c, small.image, VK_IMAGE_ASPECT_COLOR_BIT, DST, SRC);
        if (v2) {
            VkBufferImageCopy2 r[2] = {{VK_STRUCTURE_TYPE_BUFFER_IMAGE_COPY_2},
                                       {VK_STRUCTURE_TYPE_BUFFER_IMAGE_COPY_2}};
            r[0].imageSubresource = r[1].imageSubresource = sub;
            r[0].imageExtent = down_big.imageExtent;
            r[1].bufferOffset = down_small.bufferOffset;
            r[1].imageExtent = down_small.imageExtent;
            VkCopyImageToBufferInfo2 ci{VK_STRUCTURE_TYPE_COPY_IMAGE_TO_BUFFER_INFO_2};
            ci.srcImageLayout = SRC;
            ci.dstBuffer = dst.buffer;
            ci.regionCount = 1;
            ci.srcImage = img;
            ci.pRegions = &r[0];
            cmd_copy_i2b(c, &ci);
            ci.srcImage = small.image;
            ci.pRegions = &r[1];
            cmd_copy_i2b(c, &ci);
        } else {
            vkCmdCopyImageToBuffer(c, img, SRC, dst.buffer, 1, &down_big);
            vkCmdCopyImageToBuffer(c, small.image, SRC, dst.buffer, 1, &down_small);
        }
        barrier(c);
        if (v2) {
            VkBufferCopy2 r{VK_STRUCTURE_TYPE_BUFFER_COPY_2};
            r.srcOffset = bcopy.srcOffset;
            r.size = bcopy.size;
            VkCopyBufferInfo2 ci{VK_STRUCTURE_TYPE_COPY_BUFFER_INFO_2};
            ci.srcBuffer = dst.buffer;
            ci.dstBuffer = out.buffer;
            ci.regionCount = 1;
            ci.pRegions = &r;
            cmd_copy_buf(c, &ci);
        } else {
            vkCmdCopyBuffer(c, dst.buffer, out.buffer, 1, &bcopy);
        }
    }),
              VK_SUCCESS);
    vkDestroyImage(k.d, img, nullptr);
    vkFreeMemory(k.d, mem, nullptr);
    return Kit::bytes(out);
}

TEST_F(ApiExtensions, MemoryRequirements2BindMemory2DedicatedAndCopyCommands2) {
    auto dev = devices({VK_KHR_BIND_MEMORY_2_EXTENSION_NAME, VK_KHR_GET_MEMORY_REQUIREMENTS_2_EXTENSION_NAME,
                        VK_KHR_DEDICATED_ALLOCATION_EXTENSION_NAME, VK_KHR_COPY_COMMANDS_2_EXTENSION_NAME});
    ASSERT_TRUE(dev->ok());
    const Bytes v2 = both_on(dev->tilevk, dev->lavapipe, [](Kit& k) { return transfer_scene(k, true); });
    Kit k(dev->tilevk);
    expect_same(v2, transfer_scene(k, false), "copy_commands2 vs the Vulkan 1.0 commands on tilevk");
    // Buffers: vkGetBufferMemoryRequirements2 agrees with the 1.0 query, and vkBindBufferMemory2 binds.
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = 1000;
    bci.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer buf;
    ASSERT_EQ(vkCreateBuffer(k.d, &bci, nullptr, &buf), VK_SUCCESS);
    VkMemoryRequirements r1;
    vkGetBufferMemoryRequirements(k.d, buf, &r1);
    VkMemoryDedicatedRequirements ded{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
    ded.prefersDedicatedAllocation = ded.requiresDedicatedAllocation = VK_TRUE;
    VkMemoryRequirements2 r2{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2, &ded};
    VkBufferMemoryRequirementsInfo2 info{VK_STRUCTURE_TYPE_BUFFER_MEMORY_REQUIREMENTS_INFO_2, nullptr, buf};
    device_proc<PFN_vkGetBufferMemoryRequirements2KHR>(k, "vkGetBufferMemoryRequirements2KHR")(k.d, &info, &r2);
    EXPECT_EQ(r2.memoryRequirements.size, r1.size);
    EXPECT_EQ(ded.prefersDedicatedAllocation, VK_FALSE);
    EXPECT_EQ(ded.requiresDedicatedAllocation, VK_FALSE);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, r1.size, 0};
    VkDeviceMemory mem;
    ASSERT_EQ(vkAllocateMemory(k.d, &ai, nullptr, &mem), VK_SUCCESS);
    VkBindBufferMemoryInfo bind{VK_STRUCTURE_TYPE_BIND_BUFFER_MEMORY_INFO, nullptr, buf, mem, 0};
    EXPECT_EQ(device_proc<PFN_vkBindBufferMemory2KHR>(k, "vkBindBufferMemory2KHR")(k.d, 1, &bind), VK_SUCCESS);
    vkDestroyBuffer(k.d, buf, nullptr);
    vkFreeMemory(k.d, mem, nullptr);
}

// vkResetQueryPool from the host (hostQueryReset): a reset before use, a draw counted in query 1, results of all
// four with PARTIAL | WITH_AVAILABILITY (only query 1 available), then a host reset of query 1 makes it unavailable
// again (VK_NOT_READY without PARTIAL).
TEST_F(ApiExtensions, HostQueryReset) {
    VkPhysicalDeviceHostQueryResetFeatures reset{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES};
    reset.hostQueryReset = VK_TRUE;
    auto dev = devices({VK_EXT_HOST_QUERY_RESET_EXTENSION_NAME}, &reset);
    ASSERT_TRUE(dev->ok());
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        auto host_reset = device_proc<PFN_vkResetQueryPoolEXT>(k, "vkResetQueryPoolEXT");
        VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qci.queryType = VK_QUERY_TYPE_OCCLUSION;
        qci.queryCount = 4;
        VkQueryPool pool;
        EXPECT_EQ(vkCreateQueryPool(k.d, &qci, nullptr, &pool), VK_SUCCESS);
        host_reset(k.d, pool, 0, 4);
        Target t = target(k);
        Pipe p;
        p.rp = t.rp;
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            vkCmdBeginQuery(c, pool, 1, 0);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndQuery(c, pool, 1);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        uint64_t all[8] = {};
        const VkQueryResultFlags flags =
            VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_PARTIAL_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT;
        // With PARTIAL, unavailable queries do not make the call VK_NOT_READY (both drivers).
        EXPECT_EQ(vkGetQueryPoolResults(k.d, pool, 0, 4, sizeof all, all, 16, flags), VK_SUCCESS);
        EXPECT_EQ(all[1], 0u);  // query 0 was reset and never begun
        EXPECT_EQ(all[3], 1u);  // query 1 available
        EXPECT_GT(all[2], 100u);
        host_reset(k.d, pool, 1, 1);
        uint64_t again[2] = {7, 7};
        EXPECT_EQ(vkGetQueryPoolResults(k.d, pool, 1, 1, sizeof again, again, 16, flags), VK_SUCCESS);
        EXPECT_EQ(again[1], 0u);  // unavailable again
        uint64_t value = 7;
        EXPECT_EQ(vkGetQueryPoolResults(k.d, pool, 1, 1, 8, &value, 8, VK_QUERY_RESULT_64_BIT), VK_NOT_READY);
        vkDestroyQueryPool(k.d, pool, nullptr);
        Bytes b(sizeof all + sizeof again[1]);
        std::memcpy(b.data(), all, sizeof all);
        std::memcpy(b.data() + sizeof all, &again[1], sizeof again[1]);
        return b;
    });
}

// Private data: two slots, values on the device and on objects of three types, read back; a value never set is
// 0; a destroyed object's values are gone (a new object, which may reuse the handle, reads 0).
TEST_F(ApiExtensions, PrivateData) {
    VkPhysicalDevicePrivateDataFeatures pdf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PRIVATE_DATA_FEATURES};
    pdf.privateData = VK_TRUE;
    auto dev = devices({VK_EXT_PRIVATE_DATA_EXTENSION_NAME}, &pdf);
    ASSERT_TRUE(dev->ok());
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        auto create = device_proc<PFN_vkCreatePrivateDataSlotEXT>(k, "vkCreatePrivateDataSlotEXT");
        auto destroy = device_proc<PFN_vkDestroyPrivateDataSlotEXT>(k, "vkDestroyPrivateDataSlotEXT");
        auto set = device_proc<PFN_vkSetPrivateDataEXT>(k, "vkSetPrivateDataEXT");
        auto get = device_proc<PFN_vkGetPrivateDataEXT>(k, "vkGetPrivateDataEXT");
        VkPrivateDataSlotCreateInfo ci{VK_STRUCTURE_TYPE_PRIVATE_DATA_SLOT_CREATE_INFO};
        VkPrivateDataSlot a, b;
        EXPECT_EQ(create(k.d, &ci, nullptr, &a), VK_SUCCESS);
        EXPECT_EQ(create(k.d, &ci, nullptr, &b), VK_SUCCESS);
        Device::Buffer buf = k.buffer(64);
        VkPipelineLayout layout = k.empty_layout();
        VkSampler smp = k.sampler();
        const auto h = [](auto x) { return uint64_t(reinterpret_cast<uintptr_t>(x)); };
        EXPECT_EQ(set(k.d, VK_OBJECT_TYPE_DEVICE, h(k.d), a, 11), VK_SUCCESS);
        EXPECT_EQ(set(k.d, VK_OBJECT_TYPE_BUFFER, h(buf.buffer), a, 22), VK_SUCCESS);
        EXPECT_EQ(set(k.d, VK_OBJECT_TYPE_BUFFER, h(buf.buffer), b, 33), VK_SUCCESS);
        EXPECT_EQ(set(k.d, VK_OBJECT_TYPE_PIPELINE_LAYOUT, h(layout), b, 44), VK_SUCCESS);
        EXPECT_EQ(set(k.d, VK_OBJECT_TYPE_SAMPLER, h(smp), a, ~0ull), VK_SUCCESS);
        EXPECT_EQ(set(k.d, VK_OBJECT_TYPE_BUFFER, h(buf.buffer), a, 55), VK_SUCCESS);  // overwritten
        uint64_t v[7] = {};
        get(k.d, VK_OBJECT_TYPE_DEVICE, h(k.d), a, &v[0]);
        get(k.d, VK_OBJECT_TYPE_BUFFER, h(buf.buffer), a, &v[1]);
        get(k.d, VK_OBJECT_TYPE_BUFFER, h(buf.buffer), b, &v[2]);
        get(k.d, VK_OBJECT_TYPE_PIPELINE_LAYOUT, h(layout), b, &v[3]);
        get(k.d, VK_OBJECT_TYPE_SAMPLER, h(smp), a, &v[4]);
        get(k.d, VK_OBJECT_TYPE_PIPELINE_LAYOUT, h(layout), a, &v[5]);  // never set
        const uint64_t want[6] = {11, 55, 33, 44, ~0ull, 0};
        for (int i = 0; i < 6; ++i) EXPECT_EQ(v[i], want[i]) << i;
        VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bci.size = 64;
        bci.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        VkBuffer tmp, next;
        EXPECT_EQ(vkCreateBuffer(k.d, &bci, nullptr, &tmp), VK_SUCCESS);
        EXPECT_EQ(set(k.d, VK_OBJECT_TYPE_BUFFER, h(tmp), a, 66), VK_SUCCESS);
        vkDestroyBuffer(k.d, tmp, nullptr);
        EXPECT_EQ(vkCreateBuffer(k.d, &bci, nullptr, &next), VK_SUCCESS);
        get(k.d, VK_OBJECT_TYPE_BUFFER, h(next), a, &v[6]);
        EXPECT_EQ(v[6], 0u);
        vkDestroyBuffer(k.d, next, nullptr);
        destroy(k.d, a, nullptr);
        destroy(k.d, b, nullptr);
        return Bytes(reinterpret_cast<uint8_t*>(v), reinterpret_cast<uint8_t*>(v) + sizeof v);
    });
}

// maintenance1: a negative viewport height flips the image (the same pixels as lavapipe's), vkTrimCommandPool;
// maintenance3: vkGetDescriptorSetLayoutSupport.
TEST_F(ApiExtensions, Maintenance1NegativeViewportTrimAndMaintenance3) {
    auto dev = devices({VK_KHR_MAINTENANCE_1_EXTENSION_NAME, VK_KHR_MAINTENANCE_3_EXTENSION_NAME});
    ASSERT_TRUE(dev->ok());
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Target t = target(k);
        Pipe p;
        p.rp = t.rp;
        p.dynamic = {VK_DYNAMIC_STATE_VIEWPORT};
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            const VkViewport flipped{0, 32, 32, -32, 0, 1}, partial{3, 27.5f, 21, -19.25f, 0.25f, 0.75f};
            vkCmdSetViewport(c, 0, 1, &flipped);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdSetViewport(c, 0, 1, &partial);
            vkCmdDraw(c, 3, 1, 3, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        device_proc<PFN_vkTrimCommandPoolKHR>(k, "vkTrimCommandPoolKHR")(k.d, k.pool, 0);
        VkDescriptorSetLayoutBinding b[2] = {
            {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 12, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
            {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}};
        VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        lci.bindingCount = 2;
        lci.pBindings = b;
        VkDescriptorSetLayoutSupport support{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_SUPPORT};
        device_proc<PFN_vkGetDescriptorSetLayoutSupportKHR>(k, "vkGetDescriptorSetLayoutSupportKHR")(k.d, &lci,
                                                                                                     &support);
        EXPECT_EQ(support.supported, VK_TRUE);
        Bytes img = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(px(img, 16, 16)[2], 64);
        return img;
    });
}

// Format properties through VkFormatProperties3: the low 32 bits are the Vulkan 1.0 flags, and sampled depth
// formats take depth comparisons, on both drivers (hand rule); tilevk also reports nothing above bit 31 but that and
// STORAGE_WRITE_WITHOUT_FORMAT exactly on its storage image / storage texel buffer formats
// (shaderStorageImageWriteWithoutFormat).
TEST_F(ApiExtensions, FormatFeatureFlags2) {
    auto props2 = instance_proc<PFN_vkGetPhysicalDeviceFormatProperties2KHR>("vkGetPhysicalDeviceFormatProperties2KHR");
    for (VkPhysicalDevice pd : {tilevk_->physical(), lavapipe_->physical()}) {
        for (int f = 1; f <= int(VK_FORMAT_ASTC_12x12_SRGB_BLOCK); ++f) {
            VkFormatProperties3 p3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
            VkFormatProperties2 p2{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2, &p3};
            props2(pd, VkFormat(f), &p2);
            const VkFormatProperties& p = p2.formatProperties;
            EXPECT_EQ(uint32_t(p3.optimalTilingFeatures), p.optimalTilingFeatures) << f;
            EXPECT_EQ(uint32_t(p3.linearTilingFeatures), p.linearTilingFeatures) << f;
            EXPECT_EQ(uint32_t(p3.bufferFeatures), p.bufferFeatures) << f;
            const bool depth = f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D32_SFLOAT;
            if (depth && (p.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)) {
                EXPECT_TRUE(p3.optimalTilingFeatures & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_DEPTH_COMPARISON_BIT) << f;
            }
            if (pd == tilevk_->physical()) {
                const VkFormatFeatureFlags2 write_nf = VK_FORMAT_FEATURE_2_STORAGE_WRITE_WITHOUT_FORMAT_BIT;
                EXPECT_EQ(p3.optimalTilingFeatures >> 32,
                          ((depth && (p.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)
                                ? VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_DEPTH_COMPARISON_BIT
                                : 0u) |
                           (p.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT ? write_nf : 0u)) >>
                              32)
                    << f;
                EXPECT_EQ(p3.bufferFeatures >> 32,
                          (p.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT ? write_nf : 0u) >> 32)
                    << f;
            }
        }
    }
}

// Pipeline creation cache control: FAIL_ON_PIPELINE_COMPILE_REQUIRED gives VK_PIPELINE_COMPILE_REQUIRED and a null
// handle (as lavapipe, tilevk compiles every pipeline it creates); creation feedback is valid.
TEST_F(ApiExtensions, PipelineCreationCacheControlAndFeedback) {
    VkPhysicalDevicePipelineCreationCacheControlFeatures cc{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_CREATION_CACHE_CONTROL_FEATURES};
    cc.pipelineCreationCacheControl = VK_TRUE;
    auto dev = devices(
        {VK_EXT_PIPELINE_CREATION_CACHE_CONTROL_EXTENSION_NAME, VK_EXT_PIPELINE_CREATION_FEEDBACK_EXTENSION_NAME}, &cc);
    ASSERT_TRUE(dev->ok());
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Target t = target(k);
        Pipe p;
        p.rp = t.rp;
        VkPipelineCreationFeedback whole{}, stages[2] = {};
        VkPipelineCreationFeedbackCreateInfo fb{VK_STRUCTURE_TYPE_PIPELINE_CREATION_FEEDBACK_CREATE_INFO};
        fb.pPipelineCreationFeedback = &whole;
        fb.pipelineStageCreationFeedbackCount = 2;
        fb.pPipelineStageCreationFeedbacks = stages;
        p.pnext = &fb;
        EXPECT_NE(k.pipeline(p), VkPipeline(VK_NULL_HANDLE));
        EXPECT_TRUE(whole.flags & VK_PIPELINE_CREATION_FEEDBACK_VALID_BIT);
        EXPECT_GT(whole.duration, 0u);
        return Bytes{uint8_t(whole.flags & VK_PIPELINE_CREATION_FEEDBACK_VALID_BIT)};
    });
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Target t = target(k);
        Pipe p;
        p.rp = t.rp;
        p.flags =
            VK_PIPELINE_CREATE_FAIL_ON_PIPELINE_COMPILE_REQUIRED_BIT | VK_PIPELINE_CREATE_EARLY_RETURN_ON_FAILURE_BIT;
        VkResult r = VK_SUCCESS;
        EXPECT_EQ(k.pipeline(p, &r), VkPipeline(VK_NULL_HANDLE));
        EXPECT_EQ(r, VK_PIPELINE_COMPILE_REQUIRED);
        return Bytes{uint8_t(r == VK_PIPELINE_COMPILE_REQUIRED)};
    });
}

// Instance-level queries through the KHR aliases: OPAQUE_FD memory is exportable and importable (the handle types:
// api_breadth_external_memory_test.cpp), no fence or semaphore handle type on tilevk; the tools both drivers report
// are the same (the validation layer's own entry). (Device groups: honest_reports_test.cpp, without the layer, whose
// 1.3.239 flags vkEnumeratePhysicalDeviceGroupsKHR as a 1.1 command on a 1.0 instance.)
TEST_F(ApiExtensions, ExternalCapabilitiesAndTools) {
    VkPhysicalDeviceExternalBufferInfo bi{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_BUFFER_INFO};
    bi.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    bi.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkExternalBufferProperties bp{VK_STRUCTURE_TYPE_EXTERNAL_BUFFER_PROPERTIES};
    bp.externalMemoryProperties.externalMemoryFeatures = ~0u;
    instance_proc<PFN_vkGetPhysicalDeviceExternalBufferPropertiesKHR>("vkGetPhysicalDeviceExternalBufferPropertiesKHR")(
        tilevk_->physical(), &bi, &bp);
    EXPECT_EQ(bp.externalMemoryProperties.externalMemoryFeatures,
              VkExternalMemoryFeatureFlags(VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT |
                                           VK_EXTERNAL_MEMORY_FEATURE_IMPORTABLE_BIT));
    VkPhysicalDeviceExternalFenceInfo fi{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_FENCE_INFO};
    fi.handleType = VK_EXTERNAL_FENCE_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkExternalFenceProperties fp{VK_STRUCTURE_TYPE_EXTERNAL_FENCE_PROPERTIES};
    fp.externalFenceFeatures = ~0u;
    instance_proc<PFN_vkGetPhysicalDeviceExternalFencePropertiesKHR>("vkGetPhysicalDeviceExternalFencePropertiesKHR")(
        tilevk_->physical(), &fi, &fp);
    EXPECT_EQ(fp.externalFenceFeatures, 0u);
    VkPhysicalDeviceExternalSemaphoreInfo si{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_SEMAPHORE_INFO};
    si.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkExternalSemaphoreProperties sp{VK_STRUCTURE_TYPE_EXTERNAL_SEMAPHORE_PROPERTIES};
    sp.externalSemaphoreFeatures = ~0u;
    instance_proc<PFN_vkGetPhysicalDeviceExternalSemaphorePropertiesKHR>(
        "vkGetPhysicalDeviceExternalSemaphorePropertiesKHR")(tilevk_->physical(), &si, &sp);
    EXPECT_EQ(sp.externalSemaphoreFeatures, 0u);
    auto tools = instance_proc<PFN_vkGetPhysicalDeviceToolPropertiesEXT>("vkGetPhysicalDeviceToolPropertiesEXT");
    uint32_t nt = 0, nl = 0;
    EXPECT_EQ(tools(tilevk_->physical(), &nt, nullptr), VK_SUCCESS);
    EXPECT_EQ(tools(lavapipe_->physical(), &nl, nullptr), VK_SUCCESS);
    EXPECT_EQ(nt, nl);
}

// Vulkan 1.1's own commands: vkGetDeviceQueue2 gives the queue vkGetDeviceQueue gives (both drivers, validation
// layer on); on tilevk alone (no layer: these are invalid usage for a driver without protected memory or Y'CbCr
// conversion) a protected VkDeviceQueueInfo2 finds no queue, a protected queue is refused at vkCreateDevice and
// vkCreateSamplerYcbcrConversion is refused by name.
TEST_F(ApiExtensions, Vulkan11DeviceQueue2ProtectedQueuesAndYcbcr) {
    for (Device* d : {tilevk_.get(), lavapipe_.get()}) {
        auto get_queue2 =
            reinterpret_cast<PFN_vkGetDeviceQueue2>(vkGetDeviceProcAddr(d->device(), "vkGetDeviceQueue2"));
        ASSERT_NE(get_queue2, nullptr);
        const VkDeviceQueueInfo2 qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_INFO_2, nullptr, 0, 0, 0};
        VkQueue q = VK_NULL_HANDLE;
        get_queue2(d->device(), &qi, &q);
        EXPECT_EQ(q, d->queue());
    }
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    const VkPhysicalDevice pd = plain.find_device("tilevk");
    Device dev(pd, nullptr, {}, nullptr);
    ASSERT_TRUE(dev.ok());
    auto get_queue2 = reinterpret_cast<PFN_vkGetDeviceQueue2>(vkGetDeviceProcAddr(dev.device(), "vkGetDeviceQueue2"));
    const VkDeviceQueueInfo2 protected_qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_INFO_2, nullptr,
                                          VK_DEVICE_QUEUE_CREATE_PROTECTED_BIT, 0, 0};
    VkQueue q = dev.queue();
    get_queue2(dev.device(), &protected_qi, &q);
    EXPECT_EQ(q, VkQueue(VK_NULL_HANDLE));
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.flags = VK_DEVICE_QUEUE_CREATE_PROTECTED_BIT;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    VkDevice refused = VK_NULL_HANDLE;
    std::string err =
        stderr_of([&] { EXPECT_EQ(vkCreateDevice(pd, &dci, nullptr, &refused), VK_ERROR_FEATURE_NOT_PRESENT); });
    EXPECT_NE(err.find("protectedMemory"), std::string::npos) << err;
    EXPECT_EQ(refused, VkDevice(VK_NULL_HANDLE));
    auto create_ycbcr = reinterpret_cast<PFN_vkCreateSamplerYcbcrConversion>(
        vkGetDeviceProcAddr(dev.device(), "vkCreateSamplerYcbcrConversion"));
    ASSERT_NE(create_ycbcr, nullptr);
    VkSamplerYcbcrConversionCreateInfo yci{VK_STRUCTURE_TYPE_SAMPLER_YCBCR_CONVERSION_CREATE_INFO};
    yci.format = VK_FORMAT_G8_B8R8_2PLANE_420_UNORM;
    VkSamplerYcbcrConversion conv = VK_NULL_HANDLE;
    err = stderr_of([&] { EXPECT_EQ(create_ycbcr(dev.device(), &yci, nullptr, &conv), VK_ERROR_FEATURE_NOT_PRESENT); });
    EXPECT_NE(err.find("samplerYcbcrConversion"), std::string::npos) << err;
    EXPECT_EQ(conv, VkSamplerYcbcrConversion(VK_NULL_HANDLE));
}

// maintenance2's structs are accepted where they go: a view whose usage is restricted (VkImageViewUsageCreateInfo)
// sampled in a draw, and a render pass declaring an input attachment's aspect; the draw equals lavapipe's.
TEST_F(ApiExtensions, Maintenance2ViewUsageAndInputAttachmentAspect) {
    auto dev = devices({VK_KHR_MAINTENANCE_2_EXTENSION_NAME});
    ASSERT_TRUE(dev->ok());
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Device::Image tex =
            k.image(VK_FORMAT_R8G8B8A8_UNORM, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        upload_rgba8(k, tex.image, 4, 4, 3);
        VkImageViewUsageCreateInfo usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
        usage.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, &usage};
        vci.image = tex.image;
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = VK_FORMAT_R8G8B8A8_UNORM;
        vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view;
        EXPECT_EQ(vkCreateImageView(k.d, &vci, nullptr, &view), VK_SUCCESS);
        // A render pass whose second subpass reads attachment 0 as an input attachment (colour aspect declared).
        const VkAttachmentDescription att =
            attachment(VK_FORMAT_R8G8B8A8_UNORM, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE);
        const VkAttachmentReference in{0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkSubpassDescription subs[2] = {subpass(&kColour0), {}};
        subs[1].pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subs[1].inputAttachmentCount = 1;
        subs[1].pInputAttachments = &in;
        const VkInputAttachmentAspectReference aspect{1, 0, VK_IMAGE_ASPECT_COLOR_BIT};
        VkRenderPassInputAttachmentAspectCreateInfo ia{
            VK_STRUCTURE_TYPE_RENDER_PASS_INPUT_ATTACHMENT_ASPECT_CREATE_INFO};
        ia.aspectReferenceCount = 1;
        ia.pAspectReferences = &aspect;
        const VkSubpassDependency dep{0,
                                      1,
                                      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                                      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                      VK_ACCESS_INPUT_ATTACHMENT_READ_BIT,
                                      VK_DEPENDENCY_BY_REGION_BIT};
        VkRenderPassCreateInfo rci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO, &ia};
        rci.attachmentCount = 1;
        rci.pAttachments = &att;
        rci.subpassCount = 2;
        rci.pSubpasses = subs;
        rci.dependencyCount = 1;
        rci.pDependencies = &dep;
        VkRenderPass rp;
        EXPECT_EQ(vkCreateRenderPass(k.d, &rci, nullptr, &rp), VK_SUCCESS);
        // Sample the restricted view in a draw.
        Target t = target(k);
        SamplerSet ss = sampler_set(k);
        VkDescriptorImageInfo ii{k.sampler(), view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(ss.set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        Pipe p = fullscreen_pipe(SPV(ab_sample_frag), t, ss.layout);
        VkPipeline pipe = k.pipeline(p);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, t, pipe, ss.layout, ss.set); }), VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        vkDestroyRenderPass(k.d, rp, nullptr);
        vkDestroyImageView(k.d, view, nullptr);
        return b;
    });
}

// Extended dynamic state across binds: values set before a pipeline is bound apply to it; a pipeline without the
// state draws with its own; the dynamic pipeline bound again draws with the values set after it. Cull mode, front
// face, topology (strip vs list), depth test/compare and rasterizer discard, each changed between draws.
TEST_F(ApiExtensions, ExtendedDynamicStateAcrossBinds) {
    VkPhysicalDeviceExtendedDynamicStateFeaturesEXT eds{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_FEATURES_EXT};
    eds.extendedDynamicState = VK_TRUE;
    VkPhysicalDeviceExtendedDynamicState2FeaturesEXT eds2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_2_FEATURES_EXT, &eds};
    eds2.extendedDynamicState2 = eds2.extendedDynamicState2LogicOp = VK_TRUE;
    VkPhysicalDeviceFeatures logic{};
    logic.logicOp = VK_TRUE;
    const std::vector<const char*> exts = {VK_EXT_EXTENDED_DYNAMIC_STATE_EXTENSION_NAME,
                                           VK_EXT_EXTENDED_DYNAMIC_STATE_2_EXTENSION_NAME};
    Device t(tilevk_->physical(), &logic, exts, &eds2), l(lavapipe_->physical(), &logic, exts, &eds2);
    ASSERT_TRUE(t.ok() && l.ok());
    both_on(t, l, [](Kit& k) {
        DepthTarget dt = depth_target(k, VK_FORMAT_D32_SFLOAT);
        auto cull = device_proc<PFN_vkCmdSetCullModeEXT>(k, "vkCmdSetCullModeEXT");
        auto front = device_proc<PFN_vkCmdSetFrontFaceEXT>(k, "vkCmdSetFrontFaceEXT");
        auto topo = device_proc<PFN_vkCmdSetPrimitiveTopologyEXT>(k, "vkCmdSetPrimitiveTopologyEXT");
        auto dtest = device_proc<PFN_vkCmdSetDepthTestEnableEXT>(k, "vkCmdSetDepthTestEnableEXT");
        auto dcmp = device_proc<PFN_vkCmdSetDepthCompareOpEXT>(k, "vkCmdSetDepthCompareOpEXT");
        auto discard = device_proc<PFN_vkCmdSetRasterizerDiscardEnableEXT>(k, "vkCmdSetRasterizerDiscardEnableEXT");
        VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
        Pipe dyn;
        dyn.rp = dt.rp;
        dyn.ds = &ds;
        dyn.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        dyn.dynamic = {VK_DYNAMIC_STATE_CULL_MODE,          VK_DYNAMIC_STATE_FRONT_FACE,
                       VK_DYNAMIC_STATE_PRIMITIVE_TOPOLOGY, VK_DYNAMIC_STATE_DEPTH_TEST_ENABLE,
                       VK_DYNAMIC_STATE_DEPTH_COMPARE_OP,   VK_DYNAMIC_STATE_RASTERIZER_DISCARD_ENABLE};
        VkPipeline pd = k.pipeline(dyn);
        Pipe fixed = dyn;
        fixed.dynamic = {};
        VkPipeline pf = k.pipeline(fixed);
        Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, dt.rp, dt.fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(0.5f)});
            cull(c, VK_CULL_MODE_BACK_BIT);  // before the bind
            front(c, VK_FRONT_FACE_CLOCKWISE);
            topo(c, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP);
            dtest(c, VK_TRUE);
            dcmp(c, VK_COMPARE_OP_GREATER);
            discard(c, VK_FALSE);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pd);
            bind_vertices(c, vb);
            vkCmdDraw(c, 6, 1, 0, 0);  // a strip of four triangles, back faces culled (clockwise front)
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pf);
            vkCmdDraw(c, 3, 1, 3, 0);  // the pipeline's own state: list, no culling, LESS
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pd);
            // The static pipeline made every state undefined again (Vulkan: a bind overwrites non-dynamic state).
            cull(c, VK_CULL_MODE_NONE);
            front(c, VK_FRONT_FACE_COUNTER_CLOCKWISE);
            dcmp(c, VK_COMPARE_OP_ALWAYS);
            dtest(c, VK_TRUE);
            discard(c, VK_FALSE);
            topo(c, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST);
            vkCmdDraw(c, 3, 1, 0, 0);
            discard(c, VK_TRUE);
            vkCmdDraw(c, 6, 1, 0, 0);  // discarded
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = concat({k.read(dt.col.image, 32, 32, 4), k.read(dt.dep.image, 32, 32, 4, VK_IMAGE_ASPECT_DEPTH_BIT)});
        EXPECT_NE(px(b, 16, 16)[2], 64);
        return b;
    });
}

// synchronization2: layout transitions with vkCmdPipelineBarrier2 (including the new ATTACHMENT_OPTIMAL and
// READ_ONLY_OPTIMAL layouts), an event set with vkCmdSetEvent2 and waited with vkCmdWaitEvents2, another reset with
// vkCmdResetEvent2, two vkCmdWriteTimestamp2 around a draw, all submitted with vkQueueSubmit2 (a semaphore signalled
// by the first submission and waited by the second, a fence). The image and event states equal lavapipe's; the
// timestamps are available and ordered.
TEST_F(ApiExtensions, Synchronization2) {
    VkPhysicalDeviceSynchronization2Features sync2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
    sync2.synchronization2 = VK_TRUE;
    auto dev = devices({VK_KHR_SYNCHRONIZATION_2_EXTENSION_NAME}, &sync2);
    ASSERT_TRUE(dev->ok());
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        auto barrier2 = device_proc<PFN_vkCmdPipelineBarrier2KHR>(k, "vkCmdPipelineBarrier2KHR");
        auto set2 = device_proc<PFN_vkCmdSetEvent2KHR>(k, "vkCmdSetEvent2KHR");
        auto reset2 = device_proc<PFN_vkCmdResetEvent2KHR>(k, "vkCmdResetEvent2KHR");
        auto wait2 = device_proc<PFN_vkCmdWaitEvents2KHR>(k, "vkCmdWaitEvents2KHR");
        auto ts2 = device_proc<PFN_vkCmdWriteTimestamp2KHR>(k, "vkCmdWriteTimestamp2KHR");
        auto submit2 = device_proc<PFN_vkQueueSubmit2KHR>(k, "vkQueueSubmit2KHR");
        const VkFormat f = VK_FORMAT_R8G8B8A8_UNORM;
        Device::Image img = k.image(
            f, 32, 32,
            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        VkAttachmentDescription att = attachment(f, VK_ATTACHMENT_LOAD_OP_LOAD, VK_ATTACHMENT_STORE_OP_STORE);
        att.initialLayout = VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL;
        att.finalLayout = VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL;
        const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL};
        VkRenderPass rp = k.render_pass({att}, {subpass(&ref)});
        VkFramebuffer fb = k.framebuffer(rp, {k.view(img.image, f, VK_IMAGE_ASPECT_COLOR_BIT)}, 32, 32);
        Pipe p;
        p.rp = rp;
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer out = k.buffer(32 * 32 * 4);
        VkEventCreateInfo eci{VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
        VkEvent ev[2];
        for (VkEvent& e : ev) EXPECT_EQ(vkCreateEvent(k.d, &eci, nullptr, &e), VK_SUCCESS);
        EXPECT_EQ(vkSetEvent(k.d, ev[1]), VK_SUCCESS);
        VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qci.queryCount = 2;
        VkQueryPool qp;
        EXPECT_EQ(vkCreateQueryPool(k.d, &qci, nullptr, &qp), VK_SUCCESS);
        auto transition2 = [&](VkCommandBuffer c, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 src,
                               VkAccessFlags2 src_access, VkPipelineStageFlags2 dst, VkAccessFlags2 dst_access) {
            VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            b.srcStageMask = src;
            b.srcAccessMask = src_access;
            b.dstStageMask = dst;
            b.dstAccessMask = dst_access;
            b.oldLayout = from;
            b.newLayout = to;
            b.image = img.image;
            b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            di.imageMemoryBarrierCount = 1;
            di.pImageMemoryBarriers = &b;
            barrier2(c, &di);
        };
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = k.pool;
        ai.commandBufferCount = 2;
        VkCommandBuffer cbs[2];
        EXPECT_EQ(vkAllocateCommandBuffers(k.d, &ai, cbs), VK_SUCCESS);
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        // First: clear to blue, set event 0 (its dependency: the clear), move into ATTACHMENT_OPTIMAL.
        vkBeginCommandBuffer(cbs[0], &bi);
        vkCmdResetQueryPool(cbs[0], qp, 0, 2);
        transition2(cbs[0], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                    VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        const VkClearColorValue blue{{0, 0, 1, 1}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cbs[0], img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &blue, 1, &all);
        VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        mb.srcStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT;
        mb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        mb.dstStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        mb.dstAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &mb;
        set2(cbs[0], ev[0], &dep);
        reset2(cbs[0], ev[1], VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
        vkEndCommandBuffer(cbs[0]);
        // Second: wait for event 0, draw between two timestamps, read back through READ_ONLY_OPTIMAL.
        vkBeginCommandBuffer(cbs[1], &bi);
        wait2(cbs[1], 1, &ev[0], &dep);
        transition2(cbs[1], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
        ts2(cbs[1], VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, qp, 0);
        begin_pass(cbs[1], rp, fb, 32, 32, {});
        vkCmdBindPipeline(cbs[1], VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(cbs[1], vb);
        vkCmdDraw(cbs[1], 3, 1, 0, 0);
        vkCmdEndRenderPass(cbs[1]);
        ts2(cbs[1], VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, qp, 1);
        transition2(cbs[1], VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        transition2(cbs[1], VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy r{};
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        r.imageExtent = {32, 32, 1};
        vkCmdCopyImageToBuffer(cbs[1], img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.buffer, 1, &r);
        vkEndCommandBuffer(cbs[1]);
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore sem;
        EXPECT_EQ(vkCreateSemaphore(k.d, &sci, nullptr, &sem), VK_SUCCESS);
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence fence;
        EXPECT_EQ(vkCreateFence(k.d, &fci, nullptr, &fence), VK_SUCCESS);
        VkCommandBufferSubmitInfo cbi[2] = {{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO},
                                            {VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO}};
        cbi[0].commandBuffer = cbs[0];
        cbi[1].commandBuffer = cbs[1];
        VkSemaphoreSubmitInfo ssi{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        ssi.semaphore = sem;
        ssi.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        VkSubmitInfo2 si[2] = {{VK_STRUCTURE_TYPE_SUBMIT_INFO_2}, {VK_STRUCTURE_TYPE_SUBMIT_INFO_2}};
        si[0].commandBufferInfoCount = 1;
        si[0].pCommandBufferInfos = &cbi[0];
        si[0].signalSemaphoreInfoCount = 1;
        si[0].pSignalSemaphoreInfos = &ssi;
        si[1].waitSemaphoreInfoCount = 1;
        si[1].pWaitSemaphoreInfos = &ssi;
        si[1].commandBufferInfoCount = 1;
        si[1].pCommandBufferInfos = &cbi[1];
        EXPECT_EQ(submit2(k.queue, 2, si, fence), VK_SUCCESS);
        EXPECT_EQ(vkWaitForFences(k.d, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
        uint64_t ts[4] = {};
        EXPECT_EQ(vkGetQueryPoolResults(k.d, qp, 0, 2, sizeof ts, ts, 16,
                                        VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT),
                  VK_SUCCESS);
        EXPECT_EQ(ts[1], 1u);
        EXPECT_EQ(ts[3], 1u);
        EXPECT_LE(ts[0], ts[2]);
        Bytes b = Kit::bytes(out);
        b.push_back(uint8_t(vkGetEventStatus(k.d, ev[0])));
        b.push_back(uint8_t(vkGetEventStatus(k.d, ev[1])));
        EXPECT_EQ(vkGetEventStatus(k.d, ev[0]), VK_EVENT_SET);
        EXPECT_EQ(vkGetEventStatus(k.d, ev[1]), VK_EVENT_RESET);
        EXPECT_EQ(px(b, 0, 0)[2], 255);    // the clear
        EXPECT_NE(px(b, 10, 12)[2], 255);  // the draw
        vkDestroyFence(k.d, fence, nullptr);
        vkDestroySemaphore(k.d, sem, nullptr);
        vkDestroyQueryPool(k.d, qp, nullptr);
        for (VkEvent e : ev) vkDestroyEvent(k.d, e, nullptr);
        vkFreeCommandBuffers(k.d, k.pool, 2, cbs);
        return b;
    });
}

// Draw counts from a buffer (VK_KHR_draw_indirect_count): a count below maxDrawCount, one above it (capped), and 0;
// plain and indexed, records 24 bytes apart. Equal to lavapipe and to the same draws made with vkCmdDraw*Indirect.
Bytes indirect_count_scene(Kit& k, bool with_count) {
    Target t = target(k);
    Pipe p;
    p.rp = t.rp;
    p.blend = {alpha_over()};
    VkPipeline pipe = k.pipeline(p);
    std::vector<Vertex> verts = kBothTriangles;
    verts.push_back(v(-1, -1, 0, 1, 1, 1, 0.5f));
    Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    const std::vector<uint16_t> idx = {0, 1, 2, 3, 4, 5, 6, 0, 4};
    Device::Buffer ib = k.buffer_of(idx, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    std::vector<uint32_t> ind(64, 0);
    const uint32_t plain[3][4] = {{3, 1, 0, 0}, {3, 1, 3, 0}, {3, 1, 4, 0}};
    for (int i = 0; i < 3; ++i) std::memcpy(&ind[6 * i], plain[i], 16);
    const uint32_t indexed[3][5] = {{3, 1, 6, 0, 0}, {3, 1, 0, 1, 0}, {3, 1, 3, 0, 0}};
    for (int i = 0; i < 3; ++i) std::memcpy(&ind[24 + 6 * i], indexed[i], 20);
    ind[60] = 2;  // counts
    ind[61] = 7;
    ind[62] = 0;
    Device::Buffer indirect = k.buffer_of(ind, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    auto draw_count = with_count ? device_proc<PFN_vkCmdDrawIndirectCountKHR>(k, "vkCmdDrawIndirectCountKHR") : nullptr;
    auto indexed_count =
        with_count ? device_proc<PFN_vkCmdDrawIndexedIndirectCountKHR>(k, "vkCmdDrawIndexedIndirectCountKHR") : nullptr;
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdBindIndexBuffer(c, ib.buffer, 0, VK_INDEX_TYPE_UINT16);
        if (with_count) {
            draw_count(c, indirect.buffer, 0, indirect.buffer, 240, 5, 24);       // 2 draws
            indexed_count(c, indirect.buffer, 96, indirect.buffer, 244, 1, 24);   // 7, capped at 1
            draw_count(c, indirect.buffer, 48, indirect.buffer, 248, 3, 24);      // 0
            indexed_count(c, indirect.buffer, 120, indirect.buffer, 240, 3, 24);  // 2
        } else {
            vkCmdDrawIndirect(c, indirect.buffer, 0, 2, 24);
            vkCmdDrawIndexedIndirect(c, indirect.buffer, 96, 1, 24);
            vkCmdDrawIndexedIndirect(c, indirect.buffer, 120, 2, 24);
        }
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return k.read(t.image.image, 32, 32, 4);
}

TEST_F(ApiExtensions, DrawIndirectCount) {
    VkPhysicalDeviceFeatures multi{};
    multi.multiDrawIndirect = VK_TRUE;
    const std::vector<const char*> exts = {VK_KHR_DRAW_INDIRECT_COUNT_EXTENSION_NAME};
    Device t(tilevk_->physical(), &multi, exts), l(lavapipe_->physical(), &multi, exts);
    ASSERT_TRUE(t.ok() && l.ok());
    const Bytes counted = both_on(t, l, [](Kit& k) { return indirect_count_scene(k, true); });
    Kit k(t);
    expect_same(counted, indirect_count_scene(k, false), "count buffers vs the same fixed counts on tilevk");
    EXPECT_NE(px(counted, 16, 16)[2], 64);
}

}  // namespace
}  // namespace tilevk::test::breadth
