#include "device_properties.h"

#include <cstdio>
#include <cstring>

#include "memory_external.h"
#include "physical_device.h"
#include "shader/program.h"

namespace tilevk::icd {
namespace {

// Vulkan 1.1: identity, subgroups, point clipping, multiview, descriptor-set and allocation sizes.
void fill_v11(const PhysicalDevice& pd, VkPhysicalDeviceVulkan11Properties& p) {
    // No external memory sharing exists (no handle types), so the UUIDs only have to be stable and distinct.
    static const uint8_t kDevice[VK_UUID_SIZE] = {'t', 'i', 'l', 'e', 'v', 'k', '-', 'd', 'e', 'v', 0, 0, 0, 0, 0, 1};
    static const uint8_t kDriver[VK_UUID_SIZE] = {'t', 'i', 'l', 'e', 'v', 'k', '-', 'd', 'r', 'v', 0, 0, 0, 0, 0, 1};
    std::memcpy(p.deviceUUID, kDevice, VK_UUID_SIZE);
    std::memcpy(p.driverUUID, kDriver, VK_UUID_SIZE);
    p.deviceLUIDValid = VK_FALSE;  // LUIDs identify Windows adapters
    p.deviceNodeMask = 0;
    // Subgroups of shader/'s kSubgroupSize (8, lavapipe's on AVX2) in compute shaders only: basic, vote and ballot
    // operations (shader/translate_subgroup.cpp), the BASIC-in-compute that Vulkan 1.1 requires; other stages refuse
    // them by name.
    p.subgroupSize = shader::kSubgroupSize;
    p.subgroupSupportedStages = VK_SHADER_STAGE_COMPUTE_BIT;
    p.subgroupSupportedOperations =
        VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
    p.subgroupQuadOperationsInAllStages = VK_FALSE;
    // rast/geometry clips points as draw does (clip_point_keep: dropped by the z planes, x/y by the guard band), which
    // is what lavapipe reports as ALL_CLIP_PLANES.
    p.pointClippingBehavior = VK_POINT_CLIPPING_BEHAVIOR_ALL_CLIP_PLANES;
    // Multiview (execute.cpp: each view of a subpass is its own pass over its layers): lavapipe 22.3's values.
    p.maxMultiviewViewCount = kMaxMultiviewViews;
    p.maxMultiviewInstanceIndex = 0x7fffffff;
    p.protectedNoFault = VK_FALSE;
    // Descriptor sets are plain arrays sized by their layout: 1024 (the Vulkan minimum) is always satisfiable.
    p.maxPerSetDescriptors = 1024;
    p.maxMemoryAllocationSize = pd.memory.memoryHeaps[0].size;  // vkAllocateMemory refuses more than the heap
}

// Vulkan 1.2: driver identity, float controls, descriptor indexing, resolves, timeline semaphores.
void fill_v12(const PhysicalDevice& pd, VkPhysicalDeviceVulkan12Properties& p) {
    const VkPhysicalDeviceLimits& limits = pd.properties.limits;
    // tilevk has no Khronos-registered VkDriverId; 0 (no VkDriverId value) rather than another driver's id.
    p.driverID = VkDriverId(0);
    std::snprintf(p.driverName, sizeof p.driverName, "tilevk");
    std::snprintf(p.driverInfo, sizeof p.driverInfo, "binned Larrabee-style rasterizer, held to lavapipe 22.3.6");
    p.conformanceVersion = {0, 0, 0, 0};  // never run through the Khronos conformance process
    // Shader float controls: no execution mode is offered (shader/ always flushes denormals, rounds to nearest).
    p.denormBehaviorIndependence = VK_SHADER_FLOAT_CONTROLS_INDEPENDENCE_NONE;
    p.roundingModeIndependence = VK_SHADER_FLOAT_CONTROLS_INDEPENDENCE_NONE;
    // Descriptor indexing (update-after-bind, non-uniform indexing) is not implemented, but the spec bounds every
    // pipeline layout by the update-after-bind limits too (VUID-VkPipelineLayoutCreateInfo-descriptorType-03022 and
    // the rest): they are the plain limits (physical_device.cpp make_limits), which any set tilevk creates can hold. No
    // pool holds update-after-bind descriptors (maxUpdateAfterBindDescriptorsInAllPools 0).
    p.maxPerStageDescriptorUpdateAfterBindSamplers = limits.maxPerStageDescriptorSamplers;
    p.maxPerStageDescriptorUpdateAfterBindUniformBuffers = limits.maxPerStageDescriptorUniformBuffers;
    p.maxPerStageDescriptorUpdateAfterBindStorageBuffers = limits.maxPerStageDescriptorStorageBuffers;
    p.maxPerStageDescriptorUpdateAfterBindSampledImages = limits.maxPerStageDescriptorSampledImages;
    p.maxPerStageDescriptorUpdateAfterBindStorageImages = limits.maxPerStageDescriptorStorageImages;
    p.maxPerStageDescriptorUpdateAfterBindInputAttachments = limits.maxPerStageDescriptorInputAttachments;
    p.maxPerStageUpdateAfterBindResources = limits.maxPerStageResources;
    p.maxDescriptorSetUpdateAfterBindSamplers = limits.maxDescriptorSetSamplers;
    p.maxDescriptorSetUpdateAfterBindUniformBuffers = limits.maxDescriptorSetUniformBuffers;
    p.maxDescriptorSetUpdateAfterBindUniformBuffersDynamic = limits.maxDescriptorSetUniformBuffersDynamic;
    p.maxDescriptorSetUpdateAfterBindStorageBuffers = limits.maxDescriptorSetStorageBuffers;
    p.maxDescriptorSetUpdateAfterBindStorageBuffersDynamic = limits.maxDescriptorSetStorageBuffersDynamic;
    p.maxDescriptorSetUpdateAfterBindSampledImages = limits.maxDescriptorSetSampledImages;
    p.maxDescriptorSetUpdateAfterBindStorageImages = limits.maxDescriptorSetStorageImages;
    p.maxDescriptorSetUpdateAfterBindInputAttachments = limits.maxDescriptorSetInputAttachments;
    // Depth/stencil resolves (VK_KHR_depth_stencil_resolve, render_pass.cpp and execute_transfer.cpp): lavapipe's
    // modes; depth and stencil of a combined format resolve with the same mode (both independence flags false).
    p.supportedDepthResolveModes = kDepthResolveModes;
    p.supportedStencilResolveModes = kStencilResolveModes;
    p.independentResolveNone = VK_FALSE;
    p.independentResolve = VK_FALSE;
    // samplerFilterMinmax: the reduction applies to the format's channels before the view's component mapping
    // (shader/texture.cpp), on the single-component formats Vulkan lists (format/support.txt @minmax); lavapipe's.
    p.filterMinmaxSingleComponentFormats = VK_TRUE;
    p.filterMinmaxImageComponentMapping = VK_TRUE;
    // Counters are compared as 64-bit values, never as differences: any distance works (lavapipe: UINT64_MAX).
    p.maxTimelineSemaphoreValueDifference = UINT64_MAX;
    p.framebufferIntegerColorSampleCounts = VK_SAMPLE_COUNT_1_BIT;
}

// Vulkan 1.3: subgroup size control, inline uniform blocks, dot products, texel-buffer alignment, buffer size.
void fill_v13(const PhysicalDevice& pd, VkPhysicalDeviceVulkan13Properties& p) {
    const VkPhysicalDeviceLimits& limits = pd.properties.limits;
    // One subgroup size (VK_EXT_subgroup_size_control: a compute stage may require it, pipeline.cpp
    // check_subgroup_size); subgroups exist in the compute stage only (subgroupSupportedStages).
    p.minSubgroupSize = shader::kSubgroupSize;
    p.maxSubgroupSize = shader::kSubgroupSize;
    p.maxComputeWorkgroupSubgroups = limits.maxComputeWorkGroupInvocations / shader::kSubgroupSize;
    p.requiredSubgroupSizeStages = VK_SHADER_STAGE_COMPUTE_BIT;
    // Inline uniform blocks live in their set's own bytes (descriptor_pool.cpp), so nothing bounds them but memory:
    // lavapipe's limits. The update-after-bind ones bound every pipeline layout whether or not the feature is
    // enabled (as the Vulkan 1.2 ones do), so they equal the others. Integer dot products: none accelerated.
    p.maxInlineUniformBlockSize = 4096;
    p.maxPerStageDescriptorInlineUniformBlocks = 8;
    p.maxPerStageDescriptorUpdateAfterBindInlineUniformBlocks = p.maxPerStageDescriptorInlineUniformBlocks;
    p.maxDescriptorSetInlineUniformBlocks = 8;
    p.maxDescriptorSetUpdateAfterBindInlineUniformBlocks = p.maxDescriptorSetInlineUniformBlocks;
    p.maxInlineUniformTotalSize =
        p.maxInlineUniformBlockSize * p.maxDescriptorSetInlineUniformBlocks * limits.maxBoundDescriptorSets;
    // Texel buffer views read and write from their byte offset whatever its alignment (buffer_view.cpp), so one
    // texel's alignment is enough, as lavapipe reports (ApiSmallExtensions.TexelBufferAlignment*).
    p.storageTexelBufferOffsetAlignmentBytes = limits.minTexelBufferOffsetAlignment;
    p.storageTexelBufferOffsetSingleTexelAlignment = VK_TRUE;
    p.uniformTexelBufferOffsetAlignmentBytes = limits.minTexelBufferOffsetAlignment;
    p.uniformTexelBufferOffsetSingleTexelAlignment = VK_TRUE;
    p.maxBufferSize = pd.memory.memoryHeaps[0].size;  // no buffer larger than the heap can be bound
}

}  // namespace

CoreProperties make_core_properties(const PhysicalDevice& pd) {
    CoreProperties c;
    fill_v11(pd, c.v11);
    fill_v12(pd, c.v12);
    fill_v13(pd, c.v13);
    return c;
}

void write_property_struct(const PhysicalDevice& pd, VkBaseOutStructure* s) {
    const CoreProperties& core = pd.core_properties;
    auto copy_body = [s](const void* from, size_t size) {
        std::memcpy(reinterpret_cast<char*>(s) + sizeof(VkBaseOutStructure),
                    static_cast<const char*>(from) + sizeof(VkBaseOutStructure), size - sizeof(VkBaseOutStructure));
    };
    switch (s->sType) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES:
            copy_body(&core.v11, sizeof core.v11);
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES:
            copy_body(&core.v12, sizeof core.v12);
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES:
            copy_body(&core.v13, sizeof core.v13);
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_ATTRIBUTE_DIVISOR_PROPERTIES_EXT:
            // Any divisor: element_index divides in 32 bits (lavapipe: UINT32_MAX).
            reinterpret_cast<VkPhysicalDeviceVertexAttributeDivisorPropertiesEXT*>(s)->maxVertexAttribDivisor =
                UINT32_MAX;
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTI_DRAW_PROPERTIES_EXT:
            // lavapipe's 2048; the entries are copied into the command buffer's arena, any number would do.
            reinterpret_cast<VkPhysicalDeviceMultiDrawPropertiesEXT*>(s)->maxMultiDrawCount = 2048;
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_PROPERTIES_EXT: {
            // The mode is pipeline state (PipelineState::flatshade_first); no transform feedback to preserve it in.
            auto* pv = reinterpret_cast<VkPhysicalDeviceProvokingVertexPropertiesEXT*>(s);
            pv->provokingVertexModePerPipeline = VK_TRUE;
            pv->transformFeedbackPreservesTriangleFanProvokingVertex = VK_FALSE;
            return;
        }
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_3_PROPERTIES_EXT:
            // vkCmdSetPrimitiveTopology may change the topology class: each draw's topology is applied whole
            // (dynamic_state.cpp), as lavapipe's, which says VK_TRUE.
            reinterpret_cast<VkPhysicalDeviceExtendedDynamicState3PropertiesEXT*>(s)
                ->dynamicPrimitiveTopologyUnrestricted = VK_TRUE;
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_PROPERTIES_EXT:
            // Line ends snapped to 1/256 pixel (rast/geometry subpixel_snap), lavapipe's 8 bits.
            reinterpret_cast<VkPhysicalDeviceLineRasterizationPropertiesEXT*>(s)->lineSubPixelPrecisionBits = 8;
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR:
            // A pushed set is an ordinary set (push_descriptor.cpp); 32 is lavapipe's MAX_PUSH_DESCRIPTORS.
            reinterpret_cast<VkPhysicalDevicePushDescriptorPropertiesKHR*>(s)->maxPushDescriptors = 32;
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CUSTOM_BORDER_COLOR_PROPERTIES_EXT:
            // A custom colour lives in its sampler (shader::SamplerState), so any number would do; lavapipe's 32768.
            reinterpret_cast<VkPhysicalDeviceCustomBorderColorPropertiesEXT*>(s)->maxCustomBorderColorSamplers =
                32 * 1024;
            return;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_PROPERTIES_EXT: {
            // Bounds are checked per 32-bit word against the range as given, never a rounded one (docs/
            // lavapipe-rules.md "Buffer bounds"): lavapipe's 1 for both.
            auto* r = reinterpret_cast<VkPhysicalDeviceRobustness2PropertiesEXT*>(s);
            r->robustStorageBufferAccessSizeAlignment = 1;
            r->robustUniformBufferAccessSizeAlignment = 1;
            return;
        }
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT:
            reinterpret_cast<VkPhysicalDeviceExternalMemoryHostPropertiesEXT*>(s)->minImportedHostPointerAlignment =
                kMinImportedHostPointerAlignment;
            return;
        default:
            read_core_properties(core, s);  // the promoted structs; anything else is left untouched
            return;
    }
}

}  // namespace tilevk::icd
