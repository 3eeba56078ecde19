// VK_KHR_maintenance4 (suite ApiMaintenance4), on tilevk and lavapipe with the extension and the feature enabled and
// the validation layer on: the memory requirements of buffers and images not yet made equal those of the made
// objects (a walk of formats, usages, sizes, levels, layers, samples and tilings, checked on each driver), sparse
// requirements are none, maxBufferSize is reported, and the behavioural rules hold with the bytes compared between the
// drivers: a pipeline layout destroyed right after the pipeline was made, a vertex output wider than the fragment
// input at its location, and a compute shader whose workgroup size is LocalSizeId of a specialization constant.
#include <spirv-tools/libspirv.hpp>

#include "api_breadth.h"
// After api_breadth.h (<cstdint>): the generated SPIR-V arrays include nothing themselves.
#include "ab_narrow_in_frag.h"

namespace tilevk::test::breadth {
namespace {

const std::vector<const char*> kExtensions = {VK_KHR_MAINTENANCE_4_EXTENSION_NAME};

class ApiMaintenance4 : public ApiBreadth {
  protected:
    std::unique_ptr<DevicePair> devices() {
        m4_.maintenance4 = VK_TRUE;
        return device_pair(kExtensions, &m4_);
    }
    VkPhysicalDeviceMaintenance4Features m4_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
};

void expect_equal(const VkMemoryRequirements& made, const VkMemoryRequirements& asked, const std::string& what) {
    EXPECT_EQ(made.size, asked.size) << what;
    EXPECT_EQ(made.alignment, asked.alignment) << what;
    EXPECT_EQ(made.memoryTypeBits, asked.memoryTypeBits) << what;
}

// Every buffer size and usage of the walk: vkGetDeviceBufferMemoryRequirementsKHR = vkGetBufferMemoryRequirements of
// the made buffer, and the size is at most the create size aligned to the alignment.
void buffer_walk(Device& dev) {
    const VkDevice d = dev.device();
    auto query = device_proc<PFN_vkGetDeviceBufferMemoryRequirementsKHR>(d, "vkGetDeviceBufferMemoryRequirementsKHR");
    const VkBufferUsageFlags usages[] = {VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                         VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                         VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                                         VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT};
    for (VkDeviceSize size : {1ull, 3ull, 15ull, 16ull, 17ull, 255ull, 4096ull, 65537ull, 1000003ull})
        for (VkBufferUsageFlags usage : usages) {
            VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
            ci.size = size;
            ci.usage = usage;
            VkBuffer b = VK_NULL_HANDLE;
            ASSERT_EQ(vkCreateBuffer(d, &ci, nullptr, &b), VK_SUCCESS);
            VkMemoryRequirements made{};
            vkGetBufferMemoryRequirements(d, b, &made);
            vkDestroyBuffer(d, b, nullptr);
            VkDeviceBufferMemoryRequirements info{VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS};
            info.pCreateInfo = &ci;
            VkMemoryRequirements2 asked{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
            query(d, &info, &asked);
            const std::string what = "buffer of " + std::to_string(size) + " bytes, usage " + std::to_string(usage);
            expect_equal(made, asked.memoryRequirements, what);
            EXPECT_LE(made.size, (size + made.alignment - 1) / made.alignment * made.alignment) << what;
        }
}

// Every supported image of the walk: vkGetDeviceImageMemoryRequirementsKHR = vkGetImageMemoryRequirements of the
// made image. Returns how many images were compared.
int image_walk(Device& dev) {
    const VkDevice d = dev.device();
    auto query = device_proc<PFN_vkGetDeviceImageMemoryRequirementsKHR>(d, "vkGetDeviceImageMemoryRequirementsKHR");
    const VkFormat formats[] = {VK_FORMAT_R8G8B8A8_UNORM,
                                VK_FORMAT_R8_UNORM,
                                VK_FORMAT_B8G8R8A8_SRGB,
                                VK_FORMAT_R16G16B16A16_SFLOAT,
                                VK_FORMAT_R32G32B32A32_SFLOAT,
                                VK_FORMAT_R5G6B5_UNORM_PACK16,
                                VK_FORMAT_D16_UNORM,
                                VK_FORMAT_D32_SFLOAT,
                                VK_FORMAT_D24_UNORM_S8_UINT,
                                VK_FORMAT_D32_SFLOAT_S8_UINT,
                                VK_FORMAT_S8_UINT};
    const VkExtent2D extents[] = {{1, 1}, {17, 33}, {256, 256}, {1000, 3}};
    int compared = 0;
    for (VkFormat f : formats)
        for (VkImageTiling tiling : {VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_TILING_LINEAR})
            for (bool attachment : {false, true})
                for (VkExtent2D e : extents)
                    for (uint32_t levels : {1u, 3u})
                        for (uint32_t layers : {1u, 4u})
                            for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT}) {
                                const bool depth = is_depth(f) || f == VK_FORMAT_S8_UINT;
                                VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
                                ci.imageType = VK_IMAGE_TYPE_2D;
                                ci.format = f;
                                ci.extent = {e.width, e.height, 1};
                                ci.mipLevels = levels;
                                ci.arrayLayers = layers;
                                ci.samples = samples;
                                ci.tiling = tiling;
                                ci.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
                                if (attachment)
                                    ci.usage |= depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                                      : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
                                else if (samples == VK_SAMPLE_COUNT_1_BIT)
                                    ci.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
                                // Valid create infos only: levels within the full chain, 4x images with one level.
                                const uint32_t chain = 32 - uint32_t(__builtin_clz(std::max(e.width, e.height)));
                                if (levels > chain || (samples != VK_SAMPLE_COUNT_1_BIT && levels != 1)) continue;
                                VkImageFormatProperties props{};
                                if (vkGetPhysicalDeviceImageFormatProperties(dev.physical(), f, ci.imageType, tiling,
                                                                             ci.usage, 0, &props) != VK_SUCCESS ||
                                    levels > props.maxMipLevels || layers > props.maxArrayLayers ||
                                    !(props.sampleCounts & samples) || e.width > props.maxExtent.width ||
                                    e.height > props.maxExtent.height)
                                    continue;
                                VkImage img = VK_NULL_HANDLE;
                                if (vkCreateImage(d, &ci, nullptr, &img) != VK_SUCCESS) {
                                    ADD_FAILURE() << "vkCreateImage of a supported image, format " << f;
                                    continue;
                                }
                                VkMemoryRequirements made{};
                                vkGetImageMemoryRequirements(d, img, &made);
                                vkDestroyImage(d, img, nullptr);
                                VkDeviceImageMemoryRequirements info{
                                    VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
                                info.pCreateInfo = &ci;
                                VkMemoryRequirements2 asked{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
                                query(d, &info, &asked);
                                expect_equal(made, asked.memoryRequirements,
                                             "format " + std::to_string(f) + " " + std::to_string(e.width) + "x" +
                                                 std::to_string(e.height) + " levels " + std::to_string(levels) +
                                                 " layers " + std::to_string(layers) + " samples " +
                                                 std::to_string(samples) + " tiling " + std::to_string(tiling));
                                ++compared;
                            }
    return compared;
}

// "The size memory requirement of a buffer or image is never greater than that of another buffer or image created
// with a greater or equal size": RGBA8 and D32 images of growing extents, buffers of growing sizes.
void sizes_grow(Device& dev) {
    const VkDevice d = dev.device();
    auto image_query =
        device_proc<PFN_vkGetDeviceImageMemoryRequirementsKHR>(d, "vkGetDeviceImageMemoryRequirementsKHR");
    auto buffer_query =
        device_proc<PFN_vkGetDeviceBufferMemoryRequirementsKHR>(d, "vkGetDeviceBufferMemoryRequirementsKHR");
    for (VkFormat f : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT}) {
        VkDeviceSize last = 0;
        for (uint32_t e : {1u, 2u, 3u, 17u, 64u, 65u, 255u, 256u}) {
            VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
            ci.imageType = VK_IMAGE_TYPE_2D;
            ci.format = f;
            ci.extent = {e, e / 2 + 1, 1};
            ci.mipLevels = ci.arrayLayers = 1;
            ci.samples = VK_SAMPLE_COUNT_1_BIT;
            ci.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
            VkDeviceImageMemoryRequirements info{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
            info.pCreateInfo = &ci;
            VkMemoryRequirements2 r{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
            image_query(d, &info, &r);
            EXPECT_GE(r.memoryRequirements.size, last) << "format " << f << " extent " << e;
            last = r.memoryRequirements.size;
        }
    }
    VkDeviceSize last = 0;
    for (VkDeviceSize size = 1; size < 5000; size = size * 3 / 2 + 1) {
        VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        ci.size = size;
        ci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        VkDeviceBufferMemoryRequirements info{VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS};
        info.pCreateInfo = &ci;
        VkMemoryRequirements2 r{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
        buffer_query(d, &info, &r);
        EXPECT_GE(r.memoryRequirements.size, last) << size;
        last = r.memoryRequirements.size;
    }
}

// vkGetDeviceImageSparseMemoryRequirementsKHR for an image without sparse flags: no requirements. Named difference:
// lavapipe 22.3's is a stub (lvp_device.c "FINISHME: stub lvp_GetDeviceImageSparseMemoryRequirements") that writes
// nothing, so the count keeps whatever the application put there (99 here); tilevk writes 0, as the spec asks.
uint32_t sparse_count(Device& dev) {
    const VkDevice d = dev.device();
    auto sparse =
        device_proc<PFN_vkGetDeviceImageSparseMemoryRequirementsKHR>(d, "vkGetDeviceImageSparseMemoryRequirementsKHR");
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = VK_FORMAT_R8G8B8A8_UNORM;
    ci.extent = {16, 16, 1};
    ci.mipLevels = ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    VkDeviceImageMemoryRequirements info{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
    info.pCreateInfo = &ci;
    uint32_t count = 99;
    sparse(d, &info, &count, nullptr);
    return count;
}

TEST_F(ApiMaintenance4, RequirementsOfObjectsNotMadeEqualThoseOfMadeObjects) {
    auto dev = devices();
    for (Device* d : {&dev->tilevk, &dev->lavapipe}) {
        buffer_walk(*d);
        EXPECT_GT(image_walk(*d), 100);
        sizes_grow(*d);
    }
    EXPECT_EQ(sparse_count(dev->tilevk), 0u);
    EXPECT_EQ(sparse_count(dev->lavapipe), 99u);  // the stub: nothing written
}

// The feature and maxBufferSize (at least the 2^30 the spec requires, the same in both property structs) on both.
TEST_F(ApiMaintenance4, FeatureAndMaxBufferSizeReported) {
    for (VkPhysicalDevice pd : {tilevk_->physical(), lavapipe_->physical()}) {
        VkPhysicalDeviceMaintenance4Features f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f};
        vkGetPhysicalDeviceFeatures2(pd, &f2);
        EXPECT_EQ(f.maintenance4, VK_TRUE);
        VkPhysicalDeviceMaintenance4Properties p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p};
        vkGetPhysicalDeviceProperties2(pd, &p2);
        EXPECT_GE(p.maxBufferSize, VkDeviceSize(1) << 30);
    }
}

// The pipeline layout is destroyed as soon as the pipeline is made; the draw binds push constants through another
// layout of the same shape. Bytes = lavapipe's.
TEST_F(ApiMaintenance4, PipelineLayoutDestroyedRightAfterPipelineCreation) {
    auto dev = devices();
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Target t = target(k);
        const std::vector<VkPushConstantRange> ranges = {{VK_SHADER_STAGE_VERTEX_BIT, 0, 16},
                                                         {VK_SHADER_STAGE_FRAGMENT_BIT, 16, 32}};
        VkPipelineLayout gone = k.pipeline_layout({}, ranges);
        Pipe pp;
        pp.vs = SPV(ab_push_vert);
        pp.fs = SPV(ab_push_frag);
        pp.rp = t.rp;
        pp.layout = gone;
        VkPipeline pipe = k.pipeline(pp);
        k.destroy_now(VK_OBJECT_TYPE_PIPELINE_LAYOUT, gone);
        VkPipelineLayout layout = k.pipeline_layout({}, ranges);
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        const float offset[4] = {0.125f, -0.25f, 0, 0}, fragment[8] = {0.5f, 1, 0.25f, 1, 0.1f, 0, 0.2f, 0};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, 16, offset);
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_FRAGMENT_BIT, 16, 32, fragment);
            bind_vertices(c, vb);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_NEAR(px(b, 16, 16)[3], 255, 1);
        return b;
    });
}

// draw.vert writes a vec4 at location 0, ab_narrow_in.frag reads a vec2 there: the extra components are dropped.
TEST_F(ApiMaintenance4, WiderVertexOutputThanFragmentInput) {
    auto dev = devices();
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        Target t = target(k);
        Pipe pp;
        pp.fs = SPV(ab_narrow_in_frag);
        pp.rp = t.rp;
        VkPipeline pipe = k.pipeline(pp);
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_vertices(c, t, pipe, vb, 3, clear_color(0, 0, 0, 0)); }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_NEAR(px(b, 16, 16)[2], 63.75, 1.0);  // 0.25 from the shader, not the vertex colour's blue
        return b;
    });
}

// LocalSizeId (SPIR-V 1.2+, allowed by maintenance4): the workgroup's x size is specialization constant 0 (8 here,
// default 4); each invocation writes its LocalInvocationIndex at its GlobalInvocationId.x, so out[i] = i % 8.
constexpr const char* kLocalSizeIdComp = R"(
OpCapability Shader
OpMemoryModel Logical GLSL450
OpEntryPoint GLCompute %main "main" %gid %lid
OpExecutionModeId %main LocalSizeId %sx %c1 %c1
OpDecorate %sx SpecId 0
OpDecorate %gid BuiltIn GlobalInvocationId
OpDecorate %lid BuiltIn LocalInvocationIndex
OpDecorate %rta ArrayStride 4
OpDecorate %Out Block
OpMemberDecorate %Out 0 Offset 0
OpDecorate %out DescriptorSet 0
OpDecorate %out Binding 0
%void = OpTypeVoid
%fn = OpTypeFunction %void
%uint = OpTypeInt 32 0
%v3 = OpTypeVector %uint 3
%sx = OpSpecConstant %uint 4
%c0 = OpConstant %uint 0
%c1 = OpConstant %uint 1
%rta = OpTypeRuntimeArray %uint
%Out = OpTypeStruct %rta
%p_out = OpTypePointer StorageBuffer %Out
%p_u = OpTypePointer StorageBuffer %uint
%p_in_v3 = OpTypePointer Input %v3
%p_in_u = OpTypePointer Input %uint
%gid = OpVariable %p_in_v3 Input
%lid = OpVariable %p_in_u Input
%out = OpVariable %p_out StorageBuffer
%main = OpFunction %void None %fn
%entry = OpLabel
%g = OpLoad %v3 %gid
%gx = OpCompositeExtract %uint %g 0
%l = OpLoad %uint %lid
%p = OpAccessChain %p_u %out %c0 %gx
OpStore %p %l
OpReturn
OpFunctionEnd
)";

TEST_F(ApiMaintenance4, LocalSizeIdWorkgroupSize) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_1);
    std::vector<uint32_t> code;
    ASSERT_TRUE(tools.Assemble(kLocalSizeIdComp, &code));
    auto dev = devices();
    const Bytes b = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
        Device::Buffer out = k.buffer(24 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        std::memset(out.map, 0xAB, out.size);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorBufferInfo bi{out.buffer, 0, VK_WHOLE_SIZE};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bi, nullptr);
        const uint32_t eight = 8;
        const VkSpecializationMapEntry entry{0, 0, 4};
        const VkSpecializationInfo spec{1, &entry, 4, &eight};
        VkPipeline p = compute_pipeline(k, Spv{code.data(), code.size() * 4}, layout, &spec);
        if (p == VK_NULL_HANDLE) return Bytes{};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
            vkCmdDispatch(c, 3, 1, 1);
        }),
                  VK_SUCCESS);
        return Kit::bytes(out);
    });
    ASSERT_EQ(b.size(), 96u);
    for (uint32_t i = 0; i < 24; ++i) {
        uint32_t v = 0;
        std::memcpy(&v, b.data() + i * 4, 4);
        EXPECT_EQ(v, i % 8) << i;
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
