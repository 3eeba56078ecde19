// Vulkan 1.2 as a whole (suite ApiVulkan12): the version reported, the features Vulkan 1.2 requires (the spec's
// "Feature Requirements"), every 1.2 command reachable, and the allocations of buffer device addresses (capture and
// replay refused by name; the shaders that use addresses: api_breadth_bda_test.cpp). The 1.2 pieces themselves are
// tested where they are: timeline semaphores (api_breadth_timeline_test.cpp), imageless framebuffers, render pass 2,
// depth/stencil resolves and separate depth/stencil layouts (api_breadth_ds_resolve_test.cpp), a dynamic broadcast id
// (ApiCompute), SPIR-V 1.5 modules (the conformance subset with --spirv 1.5).
#include "api_breadth.h"
#include "stderr_capture.h"

#include "ab_copy_logical_frag.h"
#include "ab_sample_sint_frag_spv15.h"
#include "ab_sample_uint_frag_spv15.h"

namespace tilevk::test::breadth {
namespace {

using tilevk::test::stderr_of;

class ApiVulkan12 : public ApiBreadth {};

// What VkPhysicalDeviceVulkan12Features says on `pd`, with the promoted structs that carry the same members read in
// the same call (they must agree with it).
struct Features12 {
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceSeparateDepthStencilLayoutsFeatures layouts{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SEPARATE_DEPTH_STENCIL_LAYOUTS_FEATURES};
    VkPhysicalDeviceShaderSubgroupExtendedTypesFeatures extended{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_SUBGROUP_EXTENDED_TYPES_FEATURES};
    VkPhysicalDeviceBufferDeviceAddressFeatures address{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
    explicit Features12(VkPhysicalDevice pd) {
        v12.pNext = &layouts;
        layouts.pNext = &extended;
        extended.pNext = &address;
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &v12};
        vkGetPhysicalDeviceFeatures2(pd, &f2);
    }
};

// The Vulkan 1.2 members every 1.2 device must support (Vulkan spec, "Feature Requirements"; descriptor indexing only
// with its extension, which tilevk does not offer), plus the three a 1.3 device must (vulkanMemoryModel,
// vulkanMemoryModelDeviceScope, bufferDeviceAddress).
void expect_required_12(const VkPhysicalDeviceVulkan12Features& f, const char* who) {
    EXPECT_TRUE(f.uniformBufferStandardLayout) << who;
    EXPECT_TRUE(f.subgroupBroadcastDynamicId) << who;
    EXPECT_TRUE(f.imagelessFramebuffer) << who;
    EXPECT_TRUE(f.separateDepthStencilLayouts) << who;
    EXPECT_TRUE(f.hostQueryReset) << who;
    EXPECT_TRUE(f.timelineSemaphore) << who;
    EXPECT_TRUE(f.shaderSubgroupExtendedTypes) << who;
    EXPECT_TRUE(f.vulkanMemoryModel) << who;
    EXPECT_TRUE(f.vulkanMemoryModelDeviceScope) << who;
    EXPECT_TRUE(f.bufferDeviceAddress) << who;
}

TEST_F(ApiVulkan12, ReportsVulkan12AndTheFeaturesItRequires) {
    VkPhysicalDeviceProperties p{};
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &p);
    EXPECT_EQ(VK_API_VERSION_MAJOR(p.apiVersion), 1u);
    EXPECT_GE(VK_API_VERSION_MINOR(p.apiVersion), 2u);  // icd/meson.build icd_api_minor (ApiVulkan13: 3)
    const Features12 t(tilevk_->physical()), l(lavapipe_->physical());
    expect_required_12(t.v12, "tilevk");
    expect_required_12(l.v12, "lavapipe (proves the list holds for a 1.3 driver)");
    EXPECT_EQ(t.layouts.separateDepthStencilLayouts, t.v12.separateDepthStencilLayouts);
    EXPECT_EQ(t.extended.shaderSubgroupExtendedTypes, t.v12.shaderSubgroupExtendedTypes);
    // The promoted struct answers as the Vulkan12 one; no capture/replay, no multi-device addresses.
    EXPECT_TRUE(t.address.bufferDeviceAddress);
    EXPECT_FALSE(t.v12.bufferDeviceAddressCaptureReplay || t.v12.bufferDeviceAddressMultiDevice);
    EXPECT_EQ(t.v12.descriptorIndexing, VK_FALSE);
    // 8- and 16-bit integers and the 8-bit storage features as lavapipe reports them, not half arithmetic
    // (shader/README.md "8- and 16-bit types"); 64-bit integers and doubles are reported ("64-bit types").
    VkPhysicalDeviceFeatures core{};
    vkGetPhysicalDeviceFeatures(tilevk_->physical(), &core);
    EXPECT_TRUE(core.shaderInt16 && t.v12.shaderInt8);
    EXPECT_TRUE(t.v12.storageBuffer8BitAccess && t.v12.uniformAndStorageBuffer8BitAccess && t.v12.storagePushConstant8);
    EXPECT_FALSE(t.v12.shaderFloat16);
    EXPECT_EQ(t.v12.storageBuffer8BitAccess, l.v12.storageBuffer8BitAccess);
    EXPECT_EQ(t.v12.shaderInt8, l.v12.shaderInt8);
    EXPECT_TRUE(core.shaderInt64 && core.shaderFloat64);
}

// The update-after-bind limits bound every pipeline layout (VUID-VkPipelineLayoutCreateInfo-descriptorType-03022 and
// the rest), with or without descriptor indexing: they must hold what the 1.0 limits allow (0 made the validation
// layer reject every layout with a descriptor).
TEST_F(ApiVulkan12, UpdateAfterBindLimitsHoldTheVulkan10Limits) {
    VkPhysicalDeviceVulkan12Properties p12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p12};
    vkGetPhysicalDeviceProperties2(tilevk_->physical(), &p2);
    const VkPhysicalDeviceLimits& l = p2.properties.limits;
    EXPECT_GE(p12.maxPerStageDescriptorUpdateAfterBindSamplers, l.maxPerStageDescriptorSamplers);
    EXPECT_GE(p12.maxPerStageDescriptorUpdateAfterBindUniformBuffers, l.maxPerStageDescriptorUniformBuffers);
    EXPECT_GE(p12.maxPerStageDescriptorUpdateAfterBindStorageBuffers, l.maxPerStageDescriptorStorageBuffers);
    EXPECT_GE(p12.maxPerStageDescriptorUpdateAfterBindSampledImages, l.maxPerStageDescriptorSampledImages);
    EXPECT_GE(p12.maxPerStageDescriptorUpdateAfterBindStorageImages, l.maxPerStageDescriptorStorageImages);
    EXPECT_GE(p12.maxPerStageDescriptorUpdateAfterBindInputAttachments, l.maxPerStageDescriptorInputAttachments);
    EXPECT_GE(p12.maxPerStageUpdateAfterBindResources, l.maxPerStageResources);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindSamplers, l.maxDescriptorSetSamplers);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindUniformBuffers, l.maxDescriptorSetUniformBuffers);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindUniformBuffersDynamic, l.maxDescriptorSetUniformBuffersDynamic);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindStorageBuffers, l.maxDescriptorSetStorageBuffers);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindStorageBuffersDynamic, l.maxDescriptorSetStorageBuffersDynamic);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindSampledImages, l.maxDescriptorSetSampledImages);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindStorageImages, l.maxDescriptorSetStorageImages);
    EXPECT_GE(p12.maxDescriptorSetUpdateAfterBindInputAttachments, l.maxDescriptorSetInputAttachments);
}

// Every command of Vulkan 1.2 core, through vkGetDeviceProcAddr on both drivers (icd/gen/gen_entrypoints.py fails
// the build when one is not written; this checks the loader hands them out).
TEST_F(ApiVulkan12, EveryVulkan12CommandIsReachable) {
    const char* commands[] = {"vkCmdDrawIndirectCount",
                              "vkCmdDrawIndexedIndirectCount",
                              "vkCreateRenderPass2",
                              "vkCmdBeginRenderPass2",
                              "vkCmdNextSubpass2",
                              "vkCmdEndRenderPass2",
                              "vkResetQueryPool",
                              "vkGetSemaphoreCounterValue",
                              "vkWaitSemaphores",
                              "vkSignalSemaphore",
                              "vkGetBufferDeviceAddress",
                              "vkGetBufferOpaqueCaptureAddress",
                              "vkGetDeviceMemoryOpaqueCaptureAddress"};
    for (Device* d : {tilevk_.get(), lavapipe_.get()})
        for (const char* name : commands) EXPECT_NE(vkGetDeviceProcAddr(d->device(), name), nullptr) << name;
}

// SPIR-V 1.4+ forms glslang emits that SPIR-V 1.0 has not: a block's struct copied into a local one (OpCopyLogical)
// and integer texture reads marked ZeroExtend / SignExtend. Each draw equals lavapipe's, and the integer reads equal
// the SPIR-V 1.0 module's on tilevk.
TEST_F(ApiVulkan12, Spirv15CopyLogicalAndIntegerTextures) {
    both([](Kit& k) {
        Target t = target(k);
        VkPipelineLayout layout =
            k.pipeline_layout({}, {{VK_SHADER_STAGE_VERTEX_BIT, 0, 16}, {VK_SHADER_STAGE_FRAGMENT_BIT, 16, 32}});
        Pipe p;
        p.vs = SPV(ab_push_vert);
        p.fs = SPV(ab_copy_logical_frag);
        p.rp = t.rp;
        p.layout = layout;
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            const float off[4] = {0.1f, -0.05f, 0, 0}, tint[8] = {1, 0.5f, 0.25f, 1, 0, 0.1f, 0.2f, 0};
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, 16, off);
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_FRAGMENT_BIT, 16, 32, tint);
            draw_vertices(c, t, pipe, vb, 3, clear_color(0, 0, 0.25f, 1));
        }),
                  VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    for (const VkFormat f : {VK_FORMAT_R8G8B8A8_UINT, VK_FORMAT_R8G8B8A8_SINT, VK_FORMAT_R16G16B16A16_SINT}) {
        SCOPED_TRACE(int(f));
        const bool sint = is_sint_format(f);
        const Bytes v15 = both([&](Kit& k) {
            return sample_4x4(k, f, sint ? SPV(ab_sample_sint_frag_spv15) : SPV(ab_sample_uint_frag_spv15));
        });
        Kit k(*tilevk_);
        EXPECT_EQ(v15, sample_4x4(k, f, sint ? SPV(ab_sample_sint_frag) : SPV(ab_sample_uint_frag)));
    }
}

// Without bufferDeviceAddressCaptureReplay the capture-replay allocation flag is invalid usage
// (VUID-VkMemoryAllocateInfo-flags-03330): tilevk (alone, no layer) refuses it by name.
// VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT and the buffer usage bit are accepted. vkGetBufferDeviceAddress answers where
// the bytes are (two buffers bound 256 bytes apart in one allocation are 256 apart), and nothing has a capture address.
TEST_F(ApiVulkan12, BufferDeviceAddressAllocations) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    Device dev(plain.find_device("tilevk"), nullptr, {}, nullptr);
    ASSERT_TRUE(dev.ok());
    const VkDevice d = dev.device();
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = 256;
    bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    VkBuffer with_usage = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateBuffer(d, &bci, nullptr, &with_usage), VK_SUCCESS);
    vkDestroyBuffer(d, with_usage, nullptr);

    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT | VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_CAPTURE_REPLAY_BIT;
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flags};
    mai.allocationSize = 512;
    VkDeviceMemory none = VK_NULL_HANDLE;
    const std::string err =
        stderr_of([&] { EXPECT_EQ(vkAllocateMemory(d, &mai, nullptr, &none), VK_ERROR_FEATURE_NOT_PRESENT); });
    EXPECT_NE(err.find("VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_CAPTURE_REPLAY_BIT"), std::string::npos) << err;
    EXPECT_NE(err.find("bufferDeviceAddressCaptureReplay"), std::string::npos) << err;
    EXPECT_EQ(none, VkDeviceMemory(VK_NULL_HANDLE));

    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateMemory(d, &mai, nullptr, &mem), VK_SUCCESS);
    VkBuffer b[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    VkDeviceAddress at[2] = {0, 0};
    auto address = reinterpret_cast<PFN_vkGetBufferDeviceAddress>(vkGetDeviceProcAddr(d, "vkGetBufferDeviceAddress"));
    auto capture = reinterpret_cast<PFN_vkGetBufferOpaqueCaptureAddress>(
        vkGetDeviceProcAddr(d, "vkGetBufferOpaqueCaptureAddress"));
    auto memory_capture = reinterpret_cast<PFN_vkGetDeviceMemoryOpaqueCaptureAddress>(
        vkGetDeviceProcAddr(d, "vkGetDeviceMemoryOpaqueCaptureAddress"));
    ASSERT_TRUE(address && capture && memory_capture);
    for (int i = 0; i < 2; ++i) {
        ASSERT_EQ(vkCreateBuffer(d, &bci, nullptr, &b[i]), VK_SUCCESS);
        ASSERT_EQ(vkBindBufferMemory(d, b[i], mem, VkDeviceSize(i) * 256), VK_SUCCESS);
        const VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, nullptr, b[i]};
        at[i] = address(d, &info);
        EXPECT_EQ(capture(d, &info), 0u);
    }
    EXPECT_NE(at[0], 0u);
    EXPECT_EQ(at[1] - at[0], 256u);
    const VkDeviceMemoryOpaqueCaptureAddressInfo mem_info{VK_STRUCTURE_TYPE_DEVICE_MEMORY_OPAQUE_CAPTURE_ADDRESS_INFO,
                                                          nullptr, mem};
    EXPECT_EQ(memory_capture(d, &mem_info), 0u);
    for (VkBuffer x : b) vkDestroyBuffer(d, x, nullptr);
    vkFreeMemory(d, mem, nullptr);
}

}  // namespace
}  // namespace tilevk::test::breadth
