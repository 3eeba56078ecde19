// Vulkan 1.3's required features as they land (suite ApiVulkan13), each through its extension on tilevk and lavapipe
// with the validation layer on, bytes compared, plus the answers computed here: zero-initialized workgroup memory
// (VK_KHR_zero_initialize_workgroup_memory), subgroup size control with full subgroups
// (VK_EXT_subgroup_size_control), integer dot products (VK_KHR_shader_integer_dot_product), the Vulkan memory model
// (VK_KHR_vulkan_memory_model) and inline uniform blocks (VK_EXT_inline_uniform_block); then Vulkan 1.3 itself: the
// version reported with every feature and limit 1.3 requires (ReportsVulkan13WithEverythingItRequires).
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>

#include <spirv-tools/libspirv.hpp>

#include "api_breadth.h"
#include "api_breadth_compute.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

#include "cp_inline_block_comp.h"
#include "cp_memory_model_comp.h"
#include "cp_subgroup_comp.h"
#include "cp_zero_init_comp.h"

using tilevk::test::stderr_of;

class ApiVulkan13 : public ApiBreadth {};

// Null-initialized shared variables (cp_zero_init.comp): only the invocations with odd inputs write their word and
// count themselves, so every other word reads as its initial zero, in each of four workgroups.
TEST_F(ApiVulkan13, ZeroInitializedWorkgroupMemory) {
    VkPhysicalDeviceZeroInitializeWorkgroupMemoryFeatures zf{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ZERO_INITIALIZE_WORKGROUP_MEMORY_FEATURES};
    zf.shaderZeroInitializeWorkgroupMemory = VK_TRUE;
    auto dev = device_pair({VK_KHR_ZERO_INITIALIZE_WORKGROUP_MEMORY_EXTENSION_NAME}, &zf);
    ASSERT_TRUE(dev->ok());
    std::mt19937 rng(13);
    std::vector<uint32_t> x(256);
    for (uint32_t& v : x) v = rng() % 1000;
    const Bytes out = both_on(dev->tilevk, dev->lavapipe,
                              [&x](Kit& k) { return dispatch_two_words_per_input(k, x, SPV(cp_zero_init_comp), 4); });
    ASSERT_EQ(out.size(), x.size() * 8);
    std::vector<uint32_t> y(x.size() * 2);
    std::memcpy(y.data(), out.data(), out.size());
    for (uint32_t g = 0; g < x.size(); ++g) {
        const uint32_t group = g / 64, mirror = group * 64 + 63 - g % 64;
        uint32_t odd = 0;
        for (uint32_t i = group * 64; i < group * 64 + 64; ++i) odd += x[i] & 1;
        EXPECT_EQ(y[2 * g], (x[mirror] & 1) != 0 ? x[mirror] : 0u) << g;
        EXPECT_EQ(y[2 * g + 1], odd) << g;
    }
}

VkPhysicalDeviceSubgroupSizeControlProperties size_control_properties(VkPhysicalDevice pd) {
    VkPhysicalDeviceSubgroupSizeControlProperties sp{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sp};
    vkGetPhysicalDeviceProperties2(pd, &p2);
    return sp;
}

// One subgroup size (8 on both drivers), required by the compute stage or allowed to vary, with full subgroups: the
// records of cp_subgroup.comp equal lavapipe's and the records of the same pipeline without any of it.
TEST_F(ApiVulkan13, SubgroupSizeControlAndFullSubgroups) {
    const auto t = size_control_properties(tilevk_->physical()), l = size_control_properties(lavapipe_->physical());
    EXPECT_EQ(t.minSubgroupSize, 8u);
    EXPECT_EQ(t.maxSubgroupSize, 8u);
    EXPECT_EQ(l.minSubgroupSize, t.minSubgroupSize);
    EXPECT_EQ(l.maxSubgroupSize, t.maxSubgroupSize);
    EXPECT_EQ(t.requiredSubgroupSizeStages, VkShaderStageFlags(VK_SHADER_STAGE_COMPUTE_BIT));
    EXPECT_NE(l.requiredSubgroupSizeStages & VK_SHADER_STAGE_COMPUTE_BIT, 0u);
    EXPECT_GE(t.maxComputeWorkgroupSubgroups * t.maxSubgroupSize, 1024u);  // maxComputeWorkGroupInvocations
    VkPhysicalDeviceSubgroupSizeControlFeatures sf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES};
    sf.subgroupSizeControl = VK_TRUE;
    sf.computeFullSubgroups = VK_TRUE;
    auto dev = device_pair({VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME}, &sf);
    ASSERT_TRUE(dev->ok());
    const VkPipelineShaderStageCreateFlags full = VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT,
                                           varying = VK_PIPELINE_SHADER_STAGE_CREATE_ALLOW_VARYING_SUBGROUP_SIZE_BIT;
    for (uint32_t n : {64u, 24u, 8u}) {
        SCOPED_TRACE(n);
        Bytes plain;
        {
            Kit k(dev->tilevk);
            plain = subgroup_records(k, SPV(cp_subgroup_comp), n);
        }
        const struct {
            VkPipelineShaderStageCreateFlags flags;
            uint32_t required;
        } variants[] = {{full, 0}, {full, 8}, {varying, 0}, {full | varying, 0}, {0, 8}};
        for (const auto& v : variants) {
            SCOPED_TRACE(testing::Message() << "flags " << v.flags << " required " << v.required);
            const Bytes b = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
                return subgroup_records(k, SPV(cp_subgroup_comp), n, v.flags, v.required);
            });
            EXPECT_TRUE(b == plain);
        }
    }
}

// What no valid pipeline asks for is refused by name, not run with another size: a required size other than 8, and
// full subgroups of a local size x that is not a multiple of 8 (tilevk alone, no validation layer: invalid usage).
TEST_F(ApiVulkan13, SubgroupSizesTilevkCannotGiveAreRefusedByName) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    VkPhysicalDeviceSubgroupSizeControlFeatures sf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES};
    sf.subgroupSizeControl = VK_TRUE;
    sf.computeFullSubgroups = VK_TRUE;
    Device dev(plain.find_device("tilevk"), nullptr, {VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME}, &sf);
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    Device::Buffer a = k.buffer(64, kStorage), b = k.buffer(64, kStorage);
    StorageSet s = storage_set(k, {&a, &b});
    VkPipelineShaderStageRequiredSubgroupSizeCreateInfo required{
        VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_REQUIRED_SUBGROUP_SIZE_CREATE_INFO};
    required.requiredSubgroupSize = 16;
    const uint32_t thirteen = 13;
    const VkSpecializationMapEntry entry{0, 0, 4};
    const VkSpecializationInfo spec{1, &entry, 4, &thirteen};
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = k.shader(SPV(cp_subgroup_comp));
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = &spec;
    ci.layout = s.layout;
    const auto refused = [&](const char* name) {
        VkPipeline p = VK_NULL_HANDLE;
        const std::string err = stderr_of([&] {
            EXPECT_EQ(vkCreateComputePipelines(k.d, VK_NULL_HANDLE, 1, &ci, nullptr, &p),
                      VK_ERROR_INITIALIZATION_FAILED);
        });
        EXPECT_NE(err.find(name), std::string::npos) << err;
        EXPECT_EQ(p, VkPipeline(VK_NULL_HANDLE));
    };
    ci.stage.pNext = &required;
    refused("VkPipelineShaderStageRequiredSubgroupSizeCreateInfo::requiredSubgroupSize 16");
    ci.stage.pNext = nullptr;
    ci.stage.flags = VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT;
    refused("VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT with local size x = 13");
}

// cp_dot: every integer dot product (SPV_KHR_integer_dot_product, assembled here: glslang 12 has no GLSL for them) of
// invocation i's uvec4 a = x[3i], b = x[3i + 1] and accumulator x[3i + 2].x, twelve words per invocation: the
// vector forms OpSDot/OpUDot/OpSUDot of a and b, the packed 4x8-bit forms of a.x and b.x with and without the
// accumulator, and the vector AccSat forms of a and b shifted right by 17 (so that their sums cannot overflow,
// which would leave the result undefined).
std::string dot_module() {
    std::string t = R"(OpCapability Shader
OpCapability DotProduct
OpCapability DotProductInputAll
OpCapability DotProductInput4x8BitPacked
OpExtension "SPV_KHR_integer_dot_product"
OpMemoryModel Logical GLSL450
OpEntryPoint GLCompute %main "main" %gid
OpExecutionMode %main LocalSize 64 1 1
OpDecorate %gid BuiltIn GlobalInvocationId
OpDecorate %arr4 ArrayStride 16
OpDecorate %arr1 ArrayStride 4
OpDecorate %In Block
OpMemberDecorate %In 0 Offset 0
OpDecorate %Out Block
OpMemberDecorate %Out 0 Offset 0
OpDecorate %in DescriptorSet 0
OpDecorate %in Binding 0
OpDecorate %out DescriptorSet 0
OpDecorate %out Binding 1
%void = OpTypeVoid
%fn = OpTypeFunction %void
%uint = OpTypeInt 32 0
%v3 = OpTypeVector %uint 3
%v4 = OpTypeVector %uint 4
%arr4 = OpTypeRuntimeArray %v4
%arr1 = OpTypeRuntimeArray %uint
%In = OpTypeStruct %arr4
%Out = OpTypeStruct %arr1
%p_in = OpTypePointer StorageBuffer %In
%p_out = OpTypePointer StorageBuffer %Out
%p_v4 = OpTypePointer StorageBuffer %v4
%p_uint = OpTypePointer StorageBuffer %uint
%p_gid = OpTypePointer Input %v3
%c17 = OpConstant %uint 17
%s17 = OpConstantComposite %v4 %c17 %c17 %c17 %c17
%in = OpVariable %p_in StorageBuffer
%out = OpVariable %p_out StorageBuffer
%gid = OpVariable %p_gid Input
)";
    for (int k = 0; k <= 12; ++k) t += "%c" + std::to_string(k) + " = OpConstant %uint " + std::to_string(k) + "\n";
    t += R"(%main = OpFunction %void None %fn
%entry = OpLabel
%g = OpLoad %v3 %gid
%i = OpCompositeExtract %uint %g 0
%ia = OpIMul %uint %i %c3
%ib = OpIAdd %uint %ia %c1
%ic = OpIAdd %uint %ia %c2
%pa = OpAccessChain %p_v4 %in %c0 %ia
%pb = OpAccessChain %p_v4 %in %c0 %ib
%pc = OpAccessChain %p_v4 %in %c0 %ic
%a = OpLoad %v4 %pa
%b = OpLoad %v4 %pb
%cv = OpLoad %v4 %pc
%acc = OpCompositeExtract %uint %cv 0
%ax = OpCompositeExtract %uint %a 0
%bx = OpCompositeExtract %uint %b 0
%as = OpShiftRightArithmetic %v4 %a %s17
%bs = OpShiftRightArithmetic %v4 %b %s17
%au = OpShiftRightLogical %v4 %a %s17
%bu = OpShiftRightLogical %v4 %b %s17
%r0 = OpSDot %uint %a %b
%r1 = OpUDot %uint %a %b
%r2 = OpSUDot %uint %a %b
%r3 = OpSDot %uint %ax %bx PackedVectorFormat4x8Bit
%r4 = OpUDot %uint %ax %bx PackedVectorFormat4x8Bit
%r5 = OpSUDot %uint %ax %bx PackedVectorFormat4x8Bit
%r6 = OpSDotAccSat %uint %ax %bx %acc PackedVectorFormat4x8Bit
%r7 = OpUDotAccSat %uint %ax %bx %acc PackedVectorFormat4x8Bit
%r8 = OpSUDotAccSat %uint %ax %bx %acc PackedVectorFormat4x8Bit
%r9 = OpSDotAccSat %uint %as %bs %acc
%r10 = OpUDotAccSat %uint %au %bu %acc
%r11 = OpSUDotAccSat %uint %as %bu %acc
%o = OpIMul %uint %i %c12
)";
    for (int k = 0; k < 12; ++k) {
        const std::string n = std::to_string(k);
        t += "%o" + n + " = OpIAdd %uint %o %c" + n + "\n%po" + n + " = OpAccessChain %p_uint %out %c0 %o" + n +
             "\nOpStore %po" + n + " %r" + n + "\n";
    }
    return t + "OpReturn\nOpFunctionEnd\n";
}

int64_t lane(uint32_t v, bool is_signed) {
    return is_signed ? int64_t(int32_t(v)) : int64_t(v);
}
int64_t packed_lane(uint32_t v, int k, bool is_signed) {
    const uint32_t byte = v >> (8 * k) & 0xffu;
    return is_signed ? int64_t(int8_t(byte)) : int64_t(byte);
}
// The exact sum, saturated to the 32-bit signed or unsigned range.
uint32_t saturate(int64_t v, bool is_signed) {
    if (is_signed) return uint32_t(int32_t(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX)));
    return uint32_t(std::clamp<int64_t>(v, 0, UINT32_MAX));
}

// The twelve words cp_dot writes for one invocation, from the definitions (exact sums, low 32 bits or saturated).
std::array<uint32_t, 12> dot_model(const uint32_t* a, const uint32_t* b, uint32_t acc) {
    std::array<uint32_t, 12> r{};
    const bool sign1[3] = {true, false, true}, sign2[3] = {true, false, false};
    for (int f = 0; f < 3; ++f) {
        // The 32-bit vectors' sum is only kept modulo 2^32 (two unsigned lanes' product overflows int64): it is
        // summed modulo 2^64, where unsigned arithmetic wraps.
        uint64_t vec = 0;
        int64_t packed = 0, shifted = 0;
        for (int k = 0; k < 4; ++k) {
            vec += uint64_t(lane(a[k], sign1[f])) * uint64_t(lane(b[k], sign2[f]));
            packed += packed_lane(a[0], k, sign1[f]) * packed_lane(b[0], k, sign2[f]);
            const auto shift = [](uint32_t v, bool s) { return s ? int64_t(int32_t(v) >> 17) : int64_t(v >> 17); };
            shifted += shift(a[k], sign1[f]) * shift(b[k], sign2[f]);
        }
        r[f] = uint32_t(vec);
        r[3 + f] = uint32_t(packed);
        r[6 + f] = saturate(lane(acc, sign1[f]) + packed, sign1[f]);
        r[9 + f] = saturate(lane(acc, sign1[f]) + shifted, sign1[f]);
    }
    return r;
}

// VK_KHR_shader_integer_dot_product: cp_dot over 128 invocations with random operands and accumulators at the edges
// of both ranges; equal to lavapipe and to dot_model.
TEST_F(ApiVulkan13, IntegerDotProducts) {
    VkPhysicalDeviceShaderIntegerDotProductFeatures df{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_INTEGER_DOT_PRODUCT_FEATURES};
    df.shaderIntegerDotProduct = VK_TRUE;
    auto dev = device_pair({VK_KHR_SHADER_INTEGER_DOT_PRODUCT_EXTENSION_NAME}, &df);
    ASSERT_TRUE(dev->ok());
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_1);
    std::vector<uint32_t> code;
    ASSERT_TRUE(tools.Assemble(dot_module(), &code));
    std::mt19937 rng(1303);
    const uint32_t edges[] = {0x7ffffff0u, 0x80000008u, 0xfffffff0u, 5u, 0x7fffffffu, 0x80000000u};
    std::vector<uint32_t> x(128 * 12);
    for (uint32_t i = 0; i < 128; ++i) {
        for (uint32_t k = 0; k < 8; ++k) x[12 * i + k] = rng();
        x[12 * i + 8] = i % 2 == 0 ? edges[i / 2 % 6] : uint32_t(rng());
    }
    const Bytes out = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
        Device::Buffer in = k.buffer_of(x, kStorage);
        Device::Buffer res = k.buffer(128 * 48, kStorage);
        std::memset(res.map, 0xAD, 128 * 48);
        StorageSet s = storage_set(k, {&in, &res});
        VkPipeline p = compute_pipeline(k, Spv{code.data(), code.size() * 4}, s.layout);
        if (p == VK_NULL_HANDLE) return Bytes{};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &s.set, 0, nullptr);
            vkCmdDispatch(c, 2, 1, 1);
        }),
                  VK_SUCCESS);
        return Kit::bytes(res);
    });
    ASSERT_EQ(out.size(), 128u * 48);
    for (uint32_t i = 0; i < 128; ++i) {
        const std::array<uint32_t, 12> want = dot_model(&x[12 * i], &x[12 * i + 4], x[12 * i + 8]);
        for (uint32_t w = 0; w < 12; ++w) {
            uint32_t got;
            std::memcpy(&got, &out[(12 * i + w) * 4], 4);
            EXPECT_EQ(got, want[w]) << "invocation " << i << " word " << w;
        }
    }
}

// VK_KHR_vulkan_memory_model (vulkanMemoryModel, vulkanMemoryModelDeviceScope): cp_memory_model.comp over four
// workgroups of 64, its coherent buffer and r32ui storage image accesses with availability / visibility operands, its
// atomics and barriers at Workgroup, Device and QueueFamily scope. The buffer and the image equal lavapipe's and
// what the shader computes: v = x[mirror] + x[g], r = (v, 3v + 1, 4v), texel g = v.
TEST_F(ApiVulkan13, VulkanMemoryModel) {
    VkPhysicalDeviceVulkanMemoryModelFeatures mf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_MEMORY_MODEL_FEATURES};
    mf.vulkanMemoryModel = VK_TRUE;
    mf.vulkanMemoryModelDeviceScope = VK_TRUE;
    auto dev = device_pair({VK_KHR_VULKAN_MEMORY_MODEL_EXTENSION_NAME}, &mf);
    ASSERT_TRUE(dev->ok());
    std::mt19937 rng(1305);
    std::vector<uint32_t> x(256);
    for (uint32_t& v : x) v = rng();
    const Bytes out = both_on(dev->tilevk, dev->lavapipe, [&x](Kit& k) {
        Device::Buffer in = k.buffer_of(x, kStorage);
        Device::Buffer res = k.buffer(768 * 4, kStorage);
        std::memset(res.map, 0xAD, 768 * 4);
        Device::Image img =
            k.image(VK_FORMAT_R32_UINT, 16, 16, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        const VkImageView view = k.view(img.image, VK_FORMAT_R32_UINT, VK_IMAGE_ASPECT_COLOR_BIT);
        const VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT},
                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT},
                          {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT}});
        const VkPipelineLayout layout = k.pipeline_layout({dsl});
        const VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorBufferInfo bi = whole(in), br = whole(res);
        const VkDescriptorImageInfo ii{VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bi, nullptr);
        k.write(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &br, nullptr);
        k.write(set, 2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &ii);
        VkPipeline p = compute_pipeline(k, SPV(cp_memory_model_comp), layout);
        if (p == VK_NULL_HANDLE) return Bytes{};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            transition(c, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
            vkCmdDispatch(c, 4, 1, 1);
            transition(c, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        }),
                  VK_SUCCESS);
        return concat({Kit::bytes(res), k.read(img.image, 16, 16, 4)});
    });
    ASSERT_EQ(out.size(), 1024u * 4);
    std::vector<uint32_t> y(1024);
    std::memcpy(y.data(), out.data(), out.size());
    for (uint32_t g = 0; g < 256; ++g) {
        const uint32_t v = x[g / 64 * 64 + 63 - g % 64] + x[g];
        EXPECT_EQ(y[g], v) << g;
        EXPECT_EQ(y[256 + g], 3 * v + 1) << g;
        EXPECT_EQ(y[512 + g], 4 * v) << g;
        EXPECT_EQ(y[768 + g], v) << g;
    }
}

// An inline uniform block binding's bytes, written at `offset` (the array element of the write).
void write_inline(Kit& k, VkDescriptorSet set, uint32_t binding, uint32_t offset, const std::vector<uint32_t>& words) {
    VkWriteDescriptorSetInlineUniformBlock data{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_INLINE_UNIFORM_BLOCK};
    data.dataSize = uint32_t(words.size() * 4);
    data.pData = words.data();
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, &data};
    w.dstSet = set;
    w.dstBinding = binding;
    w.dstArrayElement = offset;
    w.descriptorCount = data.dataSize;
    w.descriptorType = VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK;
    vkUpdateDescriptorSets(k.d, 1, &w, 0, nullptr);
}

// cp_inline_block.comp reading two inline uniform blocks of one set (48 and 32 bytes) filled by every way there is:
// block a by two writes (bytes 0-15 and 16-47), block b by a descriptor update template (its 32 bytes from 8 bytes
// into the template's data) and then its bytes 16-31 by a copy from bytes 0-15 of another set's block. The words
// equal lavapipe's and what was written.
TEST_F(ApiVulkan13, InlineUniformBlocks) {
    VkPhysicalDeviceInlineUniformBlockFeatures bf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_INLINE_UNIFORM_BLOCK_FEATURES};
    bf.inlineUniformBlock = VK_TRUE;
    auto dev = device_pair({VK_EXT_INLINE_UNIFORM_BLOCK_EXTENSION_NAME}, &bf);
    ASSERT_TRUE(dev->ok());
    std::vector<uint32_t> a(12), tpl(10), other(8);
    for (uint32_t i = 0; i < 12; ++i) a[i] = 0x1000u + i * 7u;
    for (uint32_t i = 0; i < 10; ++i) tpl[i] = 0x2000u + i * 5u;
    for (uint32_t i = 0; i < 8; ++i) other[i] = 0x3000u + i * 3u;
    const Bytes out = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
        Device::Buffer res = k.buffer(20 * 4, kStorage);
        std::memset(res.map, 0xAD, 20 * 4);
        const VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK, 48, VK_SHADER_STAGE_COMPUTE_BIT},
                          {1, VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK, 32, VK_SHADER_STAGE_COMPUTE_BIT},
                          {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT}});
        const VkPipelineLayout layout = k.pipeline_layout({dsl});
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK, 160},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
        VkDescriptorPoolInlineUniformBlockCreateInfo blocks{
            VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_INLINE_UNIFORM_BLOCK_CREATE_INFO};
        blocks.maxInlineUniformBlockBindings = 4;
        VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, &blocks};
        pci.maxSets = 2;
        pci.poolSizeCount = 2;
        pci.pPoolSizes = sizes;
        VkDescriptorPool pool = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateDescriptorPool(k.d, &pci, nullptr, &pool), VK_SUCCESS);
        k.undo(VK_OBJECT_TYPE_DESCRIPTOR_POOL, pool, [&k, pool] { vkDestroyDescriptorPool(k.d, pool, nullptr); });
        const VkDescriptorSetLayout layouts[2] = {dsl, dsl};
        VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        ai.descriptorPool = pool;
        ai.descriptorSetCount = 2;
        ai.pSetLayouts = layouts;
        VkDescriptorSet sets[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
        EXPECT_EQ(vkAllocateDescriptorSets(k.d, &ai, sets), VK_SUCCESS);
        write_inline(k, sets[0], 0, 0, {a.begin(), a.begin() + 4});
        write_inline(k, sets[0], 0, 16, {a.begin() + 4, a.end()});
        const VkDescriptorUpdateTemplateEntry entry{1, 0, 32, VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK, 8, 0};
        VkDescriptorUpdateTemplateCreateInfo tci{VK_STRUCTURE_TYPE_DESCRIPTOR_UPDATE_TEMPLATE_CREATE_INFO};
        tci.descriptorUpdateEntryCount = 1;
        tci.pDescriptorUpdateEntries = &entry;
        tci.templateType = VK_DESCRIPTOR_UPDATE_TEMPLATE_TYPE_DESCRIPTOR_SET;
        tci.descriptorSetLayout = dsl;
        VkDescriptorUpdateTemplate t = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateDescriptorUpdateTemplate(k.d, &tci, nullptr, &t), VK_SUCCESS);
        vkUpdateDescriptorSetWithTemplate(k.d, sets[0], t, tpl.data());
        vkDestroyDescriptorUpdateTemplate(k.d, t, nullptr);
        write_inline(k, sets[1], 1, 0, other);
        VkCopyDescriptorSet copy{VK_STRUCTURE_TYPE_COPY_DESCRIPTOR_SET};
        copy.srcSet = sets[1];
        copy.srcBinding = 1;
        copy.dstSet = sets[0];
        copy.dstBinding = 1;
        copy.dstArrayElement = 16;
        copy.descriptorCount = 16;
        vkUpdateDescriptorSets(k.d, 0, nullptr, 1, &copy);
        const VkDescriptorBufferInfo br = whole(res);
        k.write(sets[0], 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &br, nullptr);
        VkPipeline p = compute_pipeline(k, SPV(cp_inline_block_comp), layout);
        if (p == VK_NULL_HANDLE) return Bytes{};
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &sets[0], 0, nullptr);
            vkCmdDispatch(c, 1, 1, 1);
        }),
                  VK_SUCCESS);
        return Kit::bytes(res);
    });
    ASSERT_EQ(out.size(), 20u * 4);
    std::vector<uint32_t> want(a);
    want.insert(want.end(), tpl.begin() + 2, tpl.begin() + 6);  // template bytes 8-23 -> b bytes 0-15
    want.insert(want.end(), other.begin(), other.begin() + 4);  // the copy -> b bytes 16-31
    std::vector<uint32_t> got(20);
    std::memcpy(got.data(), out.data(), out.size());
    EXPECT_EQ(got, want);
}

// The features and limits the Vulkan 1.3 spec requires ("Feature Requirements", "Required Limits"), on one driver.
// Where each works: robustImageAccess ApiStorageImage.RobustImageAccessFeature; inlineUniformBlock, the memory
// model, zero-initialized workgroup memory, subgroup size control, integer dot products above; bufferDeviceAddress
// ApiBufferDeviceAddress; dynamicRendering ApiDynamicRendering; synchronization2, privateData,
// pipelineCreationCacheControl, maintenance4, demote and terminate: their suites (icd/README.md "Extensions").
void expect_required_13(VkPhysicalDevice pd, const char* who) {
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f11};
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, &f12};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
    vkGetPhysicalDeviceFeatures2(pd, &f2);
    EXPECT_TRUE(f2.features.robustBufferAccess) << who;
    EXPECT_TRUE(f11.multiview) << who;
    for (const VkBool32 v :
         {f12.uniformBufferStandardLayout, f12.subgroupBroadcastDynamicId, f12.imagelessFramebuffer,
          f12.separateDepthStencilLayouts, f12.hostQueryReset, f12.timelineSemaphore, f12.shaderSubgroupExtendedTypes,
          f12.vulkanMemoryModel, f12.vulkanMemoryModelDeviceScope, f12.bufferDeviceAddress})
        EXPECT_TRUE(v) << who << ": a VkPhysicalDeviceVulkan12Features member";
    EXPECT_TRUE(f13.robustImageAccess) << who;
    EXPECT_TRUE(f13.inlineUniformBlock) << who;
    EXPECT_TRUE(f13.pipelineCreationCacheControl) << who;
    EXPECT_TRUE(f13.privateData) << who;
    EXPECT_TRUE(f13.shaderDemoteToHelperInvocation) << who;
    EXPECT_TRUE(f13.shaderTerminateInvocation) << who;
    EXPECT_TRUE(f13.subgroupSizeControl) << who;
    EXPECT_TRUE(f13.computeFullSubgroups) << who;
    EXPECT_TRUE(f13.synchronization2) << who;
    EXPECT_TRUE(f13.shaderZeroInitializeWorkgroupMemory) << who;
    EXPECT_TRUE(f13.dynamicRendering) << who;
    EXPECT_TRUE(f13.shaderIntegerDotProduct) << who;
    EXPECT_TRUE(f13.maintenance4) << who;
    // descriptorBindingInlineUniformBlockUpdateAfterBind: required only with descriptorIndexing
    if (f12.descriptorIndexing) {
        EXPECT_TRUE(f13.descriptorBindingInlineUniformBlockUpdateAfterBind) << who;
    }

    VkPhysicalDeviceVulkan13Properties p13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
    VkPhysicalDeviceMaintenance4Properties m4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES, &p13};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &m4};
    vkGetPhysicalDeviceProperties2(pd, &p2);
    EXPECT_EQ(VK_API_VERSION_MAJOR(p2.properties.apiVersion), 1u) << who;
    EXPECT_EQ(VK_API_VERSION_MINOR(p2.properties.apiVersion), 3u) << who;  // icd/meson.build icd_api_minor
    EXPECT_GE(p13.maxInlineUniformBlockSize, 256u) << who;
    EXPECT_GE(p13.maxPerStageDescriptorInlineUniformBlocks, 4u) << who;
    EXPECT_GE(p13.maxPerStageDescriptorUpdateAfterBindInlineUniformBlocks, 4u) << who;
    EXPECT_GE(p13.maxDescriptorSetInlineUniformBlocks, 4u) << who;
    EXPECT_GE(p13.maxDescriptorSetUpdateAfterBindInlineUniformBlocks, 4u) << who;
    EXPECT_GE(p13.maxInlineUniformTotalSize, 256u) << who;
    EXPECT_GE(p13.maxBufferSize, VkDeviceSize(1) << 30) << who;
    EXPECT_EQ(m4.maxBufferSize, p13.maxBufferSize) << who;  // the promoted struct says the same
    EXPECT_GE(p13.minSubgroupSize, 1u) << who;
    EXPECT_GE(p13.maxSubgroupSize, p13.minSubgroupSize) << who;
}

// tilevk reports Vulkan 1.3 and everything 1.3 requires (lavapipe, a 1.3 driver, proves the list holds), and a
// device can be made with every required 1.3 feature enabled through VkPhysicalDeviceVulkan1{1,2,3}Features (the
// validation layer checks the chain against the reported features and the 1.3 device's rules).
TEST_F(ApiVulkan13, ReportsVulkan13WithEverythingItRequires) {
    // an instance of Vulkan 1.3, where the Vulkan13 structs are valid (the suite's instance asks for 1.2)
    Harness h13(true, {}, VK_API_VERSION_1_3);
    ASSERT_TRUE(h13.ok());
    const VkPhysicalDevice t = h13.find_device("tilevk"), l = h13.find_device("llvmpipe");
    ASSERT_TRUE(t != VK_NULL_HANDLE && l != VK_NULL_HANDLE);
    expect_required_13(t, "tilevk");
    expect_required_13(l, "lavapipe");
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    f11.multiview = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f11};
    f12.bufferDeviceAddress = f12.vulkanMemoryModel = f12.vulkanMemoryModelDeviceScope = VK_TRUE;
    f12.timelineSemaphore = f12.hostQueryReset = f12.imagelessFramebuffer = VK_TRUE;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, &f12};
    f13.robustImageAccess = f13.inlineUniformBlock = f13.pipelineCreationCacheControl = f13.privateData = VK_TRUE;
    f13.shaderDemoteToHelperInvocation = f13.shaderTerminateInvocation = VK_TRUE;
    f13.subgroupSizeControl = f13.computeFullSubgroups = f13.synchronization2 = VK_TRUE;
    f13.shaderZeroInitializeWorkgroupMemory = f13.dynamicRendering = f13.shaderIntegerDotProduct = VK_TRUE;
    f13.maintenance4 = VK_TRUE;
    for (const VkPhysicalDevice pd : {t, l}) {
        Device d(pd, nullptr, {}, &f13);
        EXPECT_TRUE(d.ok());
    }
    EXPECT_EQ(h13.message_count(), 0) << h13.message_report();
}

}  // namespace
}  // namespace tilevk::test::breadth
