#include "physical_device.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "device_features.h"
#include "device_properties.h"
#include "dynamic_state.h"
#include "entrypoints.h"
#include "extensions.h"
#include "formats.h"
#include "instance.h"
#include "shader/program.h"

namespace tilevk::icd {
namespace {

// Limits: the Vulkan 1.0 required minimums for everything the render path has yet to prove, and tilevk's own
// values where they come from its design (16384 = the 15.8 fixed-point range, 8 sub-pixel bits, 1x/4x MSAA).
// A deliberate twin in shape of device_features.cpp make_supported (a member a line, each with its reason).
VkPhysicalDeviceLimits make_limits() {
    VkPhysicalDeviceLimits l{};
    l.maxImageDimension1D = kMaxImageDimension;
    l.maxImageDimension2D = kMaxImageDimension;
    l.maxImageDimension3D = kMaxImageDimension3D;
    // A cube face is a 2D layer: the 2D limit. lavapipe reports 1 << PIPE_CAP_MAX_TEXTURE_CUBE_LEVELS = 32768,
    // past its own 2D maxExtent of 16384 (lvp_device.c), which no image can reach (icd/README.md, "Limits").
    l.maxImageDimensionCube = kMaxImageDimension;
    l.maxImageArrayLayers = kMaxArrayLayers;
    l.maxTexelBufferElements = kMaxTexelBufferElements;
    // lavapipe's 64 KiB (PIPE_SHADER_CAP_MAX_CONST_BUFFER0_SIZE): a uniform buffer is read in place with its range
    // as the bound (cts compute.limits.uniform_buffers_15_of_64k reads the last vec4 of 15 such buffers).
    l.maxUniformBufferRange = 65536;
    l.maxStorageBufferRange = 1u << 27;
    l.maxPushConstantsSize = 128;
    l.maxMemoryAllocationCount = 4096;
    l.maxSamplerAllocationCount = 4000;
    l.bufferImageGranularity = 1;  // linear and optimal resources share one plain layout: no aliasing hazard
    l.sparseAddressSpaceSize = 0;
    l.maxBoundDescriptorSets = kMaxBoundDescriptorSets;  // lavapipe's 8
    l.maxPerStageDescriptorSamplers = 16;
    // Buffer and storage-image descriptors: lavapipe's counts. A set's descriptors and a draw's bindings are sized
    // by the layout (no fixed table); cts compute.limits.* runs one stage with 32 storage buffers, 15 uniform
    // buffers and 64 storage images in one set.
    l.maxPerStageDescriptorUniformBuffers = 15;
    l.maxPerStageDescriptorStorageBuffers = 32;
    l.maxPerStageDescriptorSampledImages = 16;
    l.maxPerStageDescriptorStorageImages = 64;
    l.maxPerStageDescriptorInputAttachments = 4;
    l.maxPerStageResources = 128;
    l.maxDescriptorSetSamplers = 96;
    l.maxDescriptorSetUniformBuffers = 256;
    l.maxDescriptorSetUniformBuffersDynamic = 8;
    l.maxDescriptorSetStorageBuffers = 256;
    l.maxDescriptorSetStorageBuffersDynamic = 4;
    l.maxDescriptorSetSampledImages = 96;
    l.maxDescriptorSetStorageImages = 256;
    l.maxDescriptorSetInputAttachments = 4;
    // lavapipe's 32 (dynamic_state.h kMaxVertexInputs); api_breadth VertexInputs32BindingsAtTheLimit.
    l.maxVertexInputAttributes = kMaxVertexInputs;
    l.maxVertexInputBindings = kMaxVertexInputs;
    l.maxVertexInputAttributeOffset = 2047;
    l.maxVertexInputBindingStride = 2048;
    // 32 vec4 locations between the stages (shader/program.h kMaxLocations), lavapipe's 128 components; cts
    // rasterization.limits.varyings_128.
    l.maxVertexOutputComponents = 4 * shader::kMaxLocations;
    l.maxFragmentInputComponents = 4 * shader::kMaxLocations;
    l.maxFragmentOutputAttachments = kMaxColorAttachments;
    l.maxFragmentDualSrcAttachments = 1;  // dualSrcBlend: Location 0, Index 1 (lavapipe's 1)
    l.maxFragmentCombinedOutputResources = kMaxColorAttachments;
    l.maxComputeSharedMemorySize = kMaxComputeSharedMemorySize;  // checked at vkCreateComputePipelines
    for (int i = 0; i < 3; ++i) {
        l.maxComputeWorkGroupCount[i] = kMaxComputeWorkGroupCount;
        l.maxComputeWorkGroupSize[i] = kMaxComputeWorkGroupSize;
    }
    l.maxComputeWorkGroupInvocations = kMaxComputeWorkGroupInvocations;
    l.subPixelPrecisionBits = 8;  // 15.8 fixed point, as lavapipe
    l.subTexelPrecisionBits = 4;
    l.mipmapPrecisionBits = 4;
    l.maxDrawIndexedIndexValue = UINT32_MAX;  // fullDrawIndexUint32: indices are 32-bit all the way
    l.maxDrawIndirectCount = UINT32_MAX;      // multiDrawIndirect: execute_draw.cpp loops over the records
    // lavapipe's 16 (PIPE_CAPF_MAX_TEXTURE_LOD_BIAS). The bias is added unclamped after the shader's, as lavapipe does
    // (shader/texture.cpp final_lambda, shader/jit/sample_rgba8.cpp select_levels); cts texture.lod_bias.*.
    l.maxSamplerLodBias = 16.0f;
    l.maxSamplerAnisotropy = 16.0f;  // lavapipe's (lvp_device.c)
    l.maxViewports = kMaxViewports;
    l.maxViewportDimensions[0] = l.maxViewportDimensions[1] = kMaxImageDimension;
    // viewportBoundsRange must hold [-2*maxViewportDimension, 2*maxViewportDimension - 1].
    l.viewportBoundsRange[0] = -2.0f * kMaxImageDimension;
    l.viewportBoundsRange[1] = 2.0f * kMaxImageDimension - 1.0f;
    l.viewportSubPixelBits = 0;
    l.minMemoryMapAlignment = 64;
    l.minTexelBufferOffsetAlignment = 16;
    l.minUniformBufferOffsetAlignment = 16;
    l.minStorageBufferOffsetAlignment = 16;
    l.minTexelOffset = -8;
    l.maxTexelOffset = 7;
    // OpImageGather's constant offsets (shader/texture.cpp gather_texels), lavapipe's range.
    l.minTexelGatherOffset = -32;
    l.maxTexelGatherOffset = 31;
    // InterpolateAtOffset (shader/interpolate.cpp): lavapipe's values (lvp_device.c); the offset is used unclamped.
    l.minInterpolationOffset = -2.0f;
    l.maxInterpolationOffset = 2.0f;
    l.subPixelInterpolationOffsetBits = 8;
    l.maxFramebufferWidth = kMaxImageDimension;
    l.maxFramebufferHeight = kMaxImageDimension;
    l.maxFramebufferLayers = 256;
    l.framebufferColorSampleCounts = kSampleCounts;
    l.framebufferDepthSampleCounts = kSampleCounts;
    l.framebufferStencilSampleCounts = kSampleCounts;
    l.framebufferNoAttachmentsSampleCounts = kSampleCounts;
    l.maxColorAttachments = kMaxColorAttachments;
    // 4x images are read by texelFetch with a sample index (shader/texture.cpp), every sampled format alike.
    l.sampledImageColorSampleCounts = kSampleCounts;
    l.sampledImageIntegerSampleCounts = kSampleCounts;
    l.sampledImageDepthSampleCounts = kSampleCounts;
    l.sampledImageStencilSampleCounts = kSampleCounts;
    l.storageImageSampleCounts = VK_SAMPLE_COUNT_1_BIT;
    l.maxSampleMaskWords = 1;
    // vkCmdWriteTimestamp reads the host's monotonic clock in nanoseconds (query_pool.cpp), on the one graphics queue.
    l.timestampComputeAndGraphics = VK_TRUE;
    l.timestampPeriod = 1.0f;
    // ClipDistance / CullDistance: lavapipe's 8, 8 and 8 combined (draw's two ccdistance vec4s); icd/pipeline.cpp
    // refuses a vertex shader with more than 8 together.
    l.maxClipDistances = shader::kMaxClipDistances;
    l.maxCullDistances = shader::kMaxClipDistances;
    l.maxCombinedClipAndCullDistances = shader::kMaxClipDistances;
    l.discreteQueuePriorities = 2;
    // lavapipe's ranges (lavapipe-rules §6): point sizes clamp at 255, line widths in [1, 255].
    l.pointSizeRange[0] = 0.0f;
    l.pointSizeRange[1] = 255.0f;
    l.lineWidthRange[0] = 1.0f;
    l.lineWidthRange[1] = 255.0f;
    l.pointSizeGranularity = 0.125f;
    l.lineWidthGranularity = 0.0078125f;
    l.strictLines = VK_TRUE;  // lines are rectangles, drawn exactly as lavapipe's (which reports strictLines)
    l.standardSampleLocations = VK_TRUE;  // lavapipe's 4x positions are the standard ones
    l.optimalBufferCopyOffsetAlignment = 1;
    l.optimalBufferCopyRowPitchAlignment = 1;
    l.nonCoherentAtomSize = 1;
    return l;
}

VkDeviceSize heap_size() {
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    VkDeviceSize total = pages > 0 && page > 0 ? VkDeviceSize(pages) * VkDeviceSize(page) : (1ull << 32);
    return total / 2;  // leave the other half to the application and the system
}

}  // namespace

PhysicalDevice::PhysicalDevice() : DispatchableObject(kType) {
    properties.apiVersion = kApiVersion;
    properties.driverVersion = VK_MAKE_VERSION(0, 1, 0);
    properties.vendorID = 0;  // a CPU driver has no PCI vendor and tilevk has no Khronos vendor id
    properties.deviceID = 1;
    properties.deviceType = VK_PHYSICAL_DEVICE_TYPE_CPU;
    snprintf(properties.deviceName, sizeof properties.deviceName, "tilevk (binned Larrabee-style rasterizer)");
    static const uint8_t kUuid[VK_UUID_SIZE] = {'t', 'i', 'l', 'e', 'v', 'k', 0, 1, 0, 0, 0, 0, 0, 0, 0, 1};
    std::memcpy(properties.pipelineCacheUUID, kUuid, VK_UUID_SIZE);
    properties.limits = make_limits();
    properties.sparseProperties = {};

    memory.memoryTypeCount = 1;
    memory.memoryTypes[0].propertyFlags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                          VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    memory.memoryTypes[0].heapIndex = 0;
    memory.memoryHeapCount = 1;
    memory.memoryHeaps[0].size = heap_size();
    memory.memoryHeaps[0].flags = VK_MEMORY_HEAP_DEVICE_LOCAL_BIT;
    core_properties = make_core_properties(*this);
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceProperties(VkPhysicalDevice physicalDevice,
                                                           VkPhysicalDeviceProperties* pProperties) {
    *pProperties = from_handle<PhysicalDevice>(physicalDevice)->properties;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceFeatures(VkPhysicalDevice, VkPhysicalDeviceFeatures* pFeatures) {
    *pFeatures = supported_features().core10;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceMemoryProperties(VkPhysicalDevice physicalDevice,
                                                                 VkPhysicalDeviceMemoryProperties* pMemoryProperties) {
    *pMemoryProperties = from_handle<PhysicalDevice>(physicalDevice)->memory;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceQueueFamilyProperties(VkPhysicalDevice, uint32_t* pCount,
                                                                      VkQueueFamilyProperties* pProps) {
    if (pProps == nullptr) {
        *pCount = 1;
        return;
    }
    if (*pCount == 0) return;
    // Graphics and compute in one family, as Vulkan requires of a device with graphics (and the CTS and vkrunner
    // look for).
    pProps[0].queueFlags = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT | VK_QUEUE_TRANSFER_BIT;
    pProps[0].queueCount = 1;
    pProps[0].timestampValidBits = 64;  // nanoseconds of CLOCK_MONOTONIC
    pProps[0].minImageTransferGranularity = {1, 1, 1};
    *pCount = 1;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceFormatProperties(VkPhysicalDevice, VkFormat format,
                                                                 VkFormatProperties* pFormatProperties) {
    const FormatInfo* f = find_format(format);
    *pFormatProperties = {};
    if (f == nullptr) return;
    pFormatProperties->linearTilingFeatures = VkFormatFeatureFlags(f->linear);
    pFormatProperties->optimalTilingFeatures = VkFormatFeatureFlags(f->optimal);
    pFormatProperties->bufferFeatures = VkFormatFeatureFlags(f->buffer);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceImageFormatProperties(VkPhysicalDevice, VkFormat format,
                                                                          VkImageType type, VkImageTiling tiling,
                                                                          VkImageUsageFlags usage,
                                                                          VkImageCreateFlags flags,
                                                                          VkImageFormatProperties* pProps) {
    *pProps = {};
    const FormatInfo* f = find_format(format);
    if (f == nullptr || !has_image_support(*f)) return VK_ERROR_FORMAT_NOT_SUPPORTED;
    // 1D, 2D and 3D images are implemented (a 1D image is a row of height 1, a 3D image's slices are stored as
    // layers, image.h).
    if (type != VK_IMAGE_TYPE_1D && type != VK_IMAGE_TYPE_2D && type != VK_IMAGE_TYPE_3D)
        return VK_ERROR_FORMAT_NOT_SUPPORTED;
    // 1D as lavapipe (lvp_formats.c: no compressed formats, 1 sample) but only what is implemented and tested for 1D:
    // copies, clears and sampling (sampler1D[Array][Shadow], texelFetch, textureSize); rendering into a 1D view and
    // image1D are not, so no attachment, input attachment or storage usage there, where lavapipe offers them.
    constexpr VkImageUsageFlags kUsage1D =
        VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    if (type == VK_IMAGE_TYPE_1D && (f->layout == format::Layout::kCompressed || (usage & ~kUsage1D) != 0))
        return VK_ERROR_FORMAT_NOT_SUPPORTED;
    // Cube-compatible 2D images are 2D arrays whose layers cube views sample (shader/texture_cube.cpp). A
    // MUTABLE_FORMAT colour image takes views of its size class (image_view.cpp); EXTENDED_USAGE is accepted when
    // the image's own format supports the usage, as checked below, so it widens nothing. No sparse/alias images.
    constexpr VkImageCreateFlags kFlags =
        VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT | VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
    if ((flags & ~kFlags) != 0 || ((flags & VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT) && type != VK_IMAGE_TYPE_2D) ||
        ((flags & VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT) &&
         (f->aspects != VK_IMAGE_ASPECT_COLOR_BIT || f->layout == format::Layout::kCompressed)))
        return VK_ERROR_FORMAT_NOT_SUPPORTED;
    VkFormatFeatureFlags have = tiling == VK_IMAGE_TILING_OPTIMAL  ? VkFormatFeatureFlags(f->optimal)
                                : tiling == VK_IMAGE_TILING_LINEAR ? VkFormatFeatureFlags(f->linear)
                                                                   : 0;
    VkFormatFeatureFlags need = 0;
    if (usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) need |= VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if (usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT) need |= VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    if (usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) need |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
    if (usage & VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT) need |= VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT;
    if (usage & VK_IMAGE_USAGE_SAMPLED_BIT) need |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    if (usage & VK_IMAGE_USAGE_STORAGE_BIT) need |= VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
    // Input attachments are read by subpassLoad as a texel fetch (shader/translate_image.cpp), so they need an
    // attachment format the shader path can read.
    if (usage & VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT) {
        if (!(have & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)) return VK_ERROR_FORMAT_NOT_SUPPORTED;
        if (!(have & (VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)))
            return VK_ERROR_FORMAT_NOT_SUPPORTED;
    }
    if (have == 0 || (have & need) != need) return VK_ERROR_FORMAT_NOT_SUPPORTED;
    const bool is_3d = type == VK_IMAGE_TYPE_3D;
    // 3D images are sampled (sampler3D: shader/texture_3d.cpp), copied and cleared; image3D is not implemented
    // (shader/translate_module.cpp refuses it), so no STORAGE usage, where lavapipe offers it.
    if (is_3d && (usage & VK_IMAGE_USAGE_STORAGE_BIT)) return VK_ERROR_FORMAT_NOT_SUPPORTED;
    // BC blocks are sampled and copied in 2D images and arrays only (format/support.txt); lavapipe also has 3D and
    // cube-compatible ones, which tilevk has not tested.
    if (f->layout == format::Layout::kCompressed && (is_3d || (flags & VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT)))
        return VK_ERROR_FORMAT_NOT_SUPPORTED;
    // 3D as lavapipe (frontends/lavapipe/lvp_formats.c lvp_get_image_format_properties): the 2D width, height and
    // level count, depth up to maxImageDimension3D, one array layer, one sample.
    pProps->maxExtent = {kMaxImageDimension, type == VK_IMAGE_TYPE_1D ? 1 : kMaxImageDimension,
                         is_3d ? kMaxImageDimension3D : 1};
    // LINEAR images have the same levels and layers as OPTIMAL ones, as in lavapipe: tilevk stores both tilings in
    // its one plain layout (image.h), which vkGetImageSubresourceLayout reports for any level and layer.
    pProps->maxMipLevels = kMaxMipLevels;
    pProps->maxArrayLayers = is_3d ? 1 : kMaxArrayLayers;
    const bool attachment =
        (have & (VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)) != 0;
    // Multisampled images can be sampled (texelFetch with a sample index, textureSamples: shader/texture.cpp), as
    // lavapipe's (lvp_formats.c: 4x for optimal 2D attachment formats whatever the usage), but not read as input
    // attachments or used as storage images: subpassInputMS and storage images with samples are refused
    // (shaderStorageImageMultisample is off), where lavapipe offers them. 1D, 3D and cube-compatible images have one
    // sample (lvp_formats.c; Vulkan requires it of cube-compatible ones).
    const bool cube = (flags & VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT) != 0;
    pProps->sampleCounts = tiling == VK_IMAGE_TILING_OPTIMAL && attachment && type == VK_IMAGE_TYPE_2D && !cube &&
                                   !(usage & (VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT))
                               ? VkSampleCountFlags(f->sample_counts) & kSampleCounts
                               : VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT);
    pProps->maxResourceSize = 1ull << 31;
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceSparseImageFormatProperties(VkPhysicalDevice, VkFormat, VkImageType,
                                                                            VkSampleCountFlagBits, VkImageUsageFlags,
                                                                            VkImageTiling, uint32_t* pPropertyCount,
                                                                            VkSparseImageFormatProperties*) {
    *pPropertyCount = 0;  // no sparse resources
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_EnumerateDeviceExtensionProperties(VkPhysicalDevice, const char* pLayerName,
                                                                      uint32_t* pPropertyCount,
                                                                      VkExtensionProperties* pProperties) {
    if (pLayerName != nullptr) return fail(VK_ERROR_LAYER_NOT_PRESENT, "no layer '%s' in tilevk", pLayerName);
    return enumerate_extensions(true, pPropertyCount, pProperties);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_EnumerateDeviceLayerProperties(VkPhysicalDevice, uint32_t* pPropertyCount,
                                                                  VkLayerProperties*) {
    *pPropertyCount = 0;
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
