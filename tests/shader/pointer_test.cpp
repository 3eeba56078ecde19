// PhysicalStorageBuffer pointers in the interpreter (shader/translate_pointer.cpp, exec_pointer.h): OpPtrAccessChain
// (which glslang does not write) with positive and negative elements, the 64-bit address arithmetic glslang writes
// for buffer_reference2 indexing, words outside registered memory, and the 64-bit integer operations refused by name.
// The answers are computed here. (GLSL buffer_reference programs against lavapipe: icd ApiBufferDeviceAddress.)
#include <gtest/gtest.h>

#include <spirv-tools/libspirv.hpp>

#include <algorithm>
#include <cstring>
#include <vector>

#include "compute_harness.h"
#include "glsl.h"

using namespace tilevk::shader;
using namespace tilevk::shader::test;

namespace {

// Invocation i (of 16): w = p[i] through OpPtrAccessChain, v = the same word by ConvertPtrToU + 64-bit IMul/IAdd +
// ConvertUToPtr; p[16 + i] = v + w; p[48 + i] = the word one element before p[33 + i] (element -1 of a pointer
// made by OpPtrAccessChain), so p[32 + i].
const char* const kPtrAccessChain = R"(
               OpCapability Shader
               OpCapability PhysicalStorageBufferAddresses
               OpCapability Int64
               OpMemoryModel PhysicalStorageBuffer64 GLSL450
               OpEntryPoint GLCompute %main "main" %gid %pc
               OpExecutionMode %main LocalSize 16 1 1
               OpDecorate %gid BuiltIn GlobalInvocationId
               OpDecorate %PC Block
               OpMemberDecorate %PC 0 Offset 0
               OpDecorate %ptr ArrayStride 4
       %void = OpTypeVoid
         %fn = OpTypeFunction %void
       %uint = OpTypeInt 32 0
        %int = OpTypeInt 32 1
      %ulong = OpTypeInt 64 0
     %v3uint = OpTypeVector %uint 3
        %ptr = OpTypePointer PhysicalStorageBuffer %uint
         %PC = OpTypeStruct %ptr
      %pc_pt = OpTypePointer PushConstant %PC
     %pcp_pt = OpTypePointer PushConstant %ptr
     %gid_pt = OpTypePointer Input %v3uint
         %pc = OpVariable %pc_pt PushConstant
        %gid = OpVariable %gid_pt Input
      %int_0 = OpConstant %int 0
     %int_m1 = OpConstant %int -1
    %uint_16 = OpConstant %uint 16
    %uint_33 = OpConstant %uint 33
    %uint_48 = OpConstant %uint 48
    %ulong_4 = OpConstant %ulong 4
       %main = OpFunction %void None %fn
      %entry = OpLabel
        %ids = OpLoad %v3uint %gid
          %i = OpCompositeExtract %uint %ids 0
        %ppc = OpAccessChain %pcp_pt %pc %int_0
          %p = OpLoad %ptr %ppc
         %pi = OpPtrAccessChain %ptr %p %i
          %w = OpLoad %uint %pi Aligned 4
         %pu = OpConvertPtrToU %ulong %p
        %i64 = OpUConvert %ulong %i
        %off = OpIMul %ulong %i64 %ulong_4
         %qu = OpIAdd %ulong %pu %off
          %q = OpConvertUToPtr %ptr %qu
          %v = OpLoad %uint %q Aligned 4
        %sum = OpIAdd %uint %v %w
        %i16 = OpIAdd %uint %i %uint_16
        %p16 = OpPtrAccessChain %ptr %p %i16
               OpStore %p16 %sum Aligned 4
        %i33 = OpIAdd %uint %i %uint_33
        %p33 = OpPtrAccessChain %ptr %p %i33
        %p32 = OpPtrAccessChain %ptr %p33 %int_m1
        %x32 = OpLoad %uint %p32 Aligned 4
        %i48 = OpIAdd %uint %i %uint_48
        %p48 = OpPtrAccessChain %ptr %p %i48
               OpStore %p48 %x32 Aligned 4
               OpReturn
               OpFunctionEnd
)";

std::shared_ptr<const Program> assemble(const char* text) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
    std::vector<uint32_t> spv;
    EXPECT_TRUE(tools.Assemble(text, &spv));
    Result r = Program::create(spv, Stage::Compute, "main", {});
    EXPECT_TRUE(r) << r.error;
    return r.program;
}

void run_with_pointer(const Program& p, const void* address) {
    const uint64_t a = uint64_t(reinterpret_cast<uintptr_t>(address));
    std::byte push[8];
    std::memcpy(push, &a, 8);
    Bindings b;
    b.push_constants = push;
    Scratch s;
    dispatch(p, b, 0, 1, 1, s);
}

}  // namespace

TEST(ShaderPointer, PtrAccessChainAndAddressArithmetic) {
    auto p = assemble(kPtrAccessChain);
    ASSERT_TRUE(p);
    EXPECT_FALSE(p->compiled());  // LoadPtr / StorePtr: the interpreter only
    std::vector<uint32_t> words(64);
    for (uint32_t i = 0; i < 64; ++i) words[i] = i < 16 ? 1000 + i * 7 : i < 48 ? 5000 + i : 0xAAAAAAAA;
    register_device_memory(words.data(), words.size() * 4);
    run_with_pointer(*p, words.data());
    unregister_device_memory(words.data());
    for (uint32_t i = 0; i < 16; ++i) {
        EXPECT_EQ(words[i], 1000 + i * 7) << i;
        EXPECT_EQ(words[16 + i], 2 * (1000 + i * 7)) << i;
        EXPECT_EQ(words[32 + i], 5000 + 32 + i) << i;
        EXPECT_EQ(words[48 + i], 5000 + 32 + i) << i;
    }
}

// The same program on memory nobody registered: loads give 0, stores do nothing.
TEST(ShaderPointer, UnregisteredMemoryIsNeitherReadNorWritten) {
    auto p = assemble(kPtrAccessChain);
    ASSERT_TRUE(p);
    std::vector<uint32_t> words(64, 0x12345678u);
    run_with_pointer(*p, words.data());
    for (uint32_t w : words) EXPECT_EQ(w, 0x12345678u);
    // registered only in part: the words past the registered 16 are left alone, those inside are reached
    register_device_memory(words.data(), 16 * 4);
    run_with_pointer(*p, words.data());
    unregister_device_memory(words.data());
    for (uint32_t i = 16; i < 64; ++i) EXPECT_EQ(words[i], 0x12345678u) << i;
}

// 64-bit operations tilevk does not translate name the instruction.
TEST(ShaderPointer, Unsupported64BitIntegerOperationsAreRefusedByName) {
    const char* src = R"(#version 450
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
layout(local_size_x = 16) in;
layout(std430, set = 0, binding = 0) buffer Y { uint y[]; };
void main() {
    uint64_t x = uint64_t(gl_GlobalInvocationID.x) * 3ul;
    y[gl_GlobalInvocationID.x] = uint(ldexp(double(x), 2));
})";
    const std::vector<uint32_t> spv = compile_glsl(Stage::Compute, src);
    Result r = Program::create(spv, Stage::Compute, "main", {});
    EXPECT_FALSE(r);
    EXPECT_NE(r.error.find("unsupported GLSL.std.450 Ldexp on 64-bit values"), std::string::npos) << r.error;
}

// 64-bit integer atomics through a buffer_reference (VK_KHR_shader_atomic_int64 covers PhysicalStorageBuffer):
// adds whose sums carry into the high word, in lane order (so every returned value is known), and a max on the
// high word.
TEST(ShaderPointer, Int64AtomicsThroughPointers) {
    auto p = compute(R"(#version 450
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
layout(local_size_x = 16) in;
layout(buffer_reference, std430, buffer_reference_align = 8) buffer B { uint64_t v[]; };
layout(push_constant) uniform PC { B b; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    b.v[8u + i] = atomicAdd(b.v[i % 4u], 0xFFFFFFFFul + uint64_t(i));
    atomicMax(b.v[4u], uint64_t(i) << 40);
})");
    ASSERT_TRUE(p);
    std::vector<uint64_t> v(24, 0);
    for (uint32_t k = 0; k < 4; ++k) v[k] = uint64_t(k) * 0x80000001ull;
    v[4] = uint64_t(7) << 40;
    const std::vector<uint64_t> before = v;
    register_device_memory(v.data(), v.size() * 8);
    run_with_pointer(*p, v.data());
    unregister_device_memory(v.data());
    std::vector<uint64_t> want = before;
    for (uint32_t i = 0; i < 16; ++i) {
        want[8 + i] = want[i % 4];
        want[i % 4] += 0xFFFFFFFFull + i;
        want[4] = std::max(want[4], uint64_t(i) << 40);
    }
    for (size_t k = 0; k < v.size(); ++k) EXPECT_EQ(v[k], want[k]) << k;
}
