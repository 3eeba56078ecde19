// Buffer device addresses (suite ApiBufferDeviceAddress; VK_KHR_buffer_device_address, Vulkan 1.2's
// bufferDeviceAddress, required by Vulkan 1.3): cp_bda.comp on tilevk and lavapipe, results compared with each other
// and with the answers computed here; then what tilevk does with addresses outside every buffer (tilevk alone: the
// application's bug, where lavapipe would crash).
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "api_breadth.h"
#include "api_breadth_compute.h"

namespace tilevk::test::breadth {
namespace {

#include "cp_bda_comp.h"
#include "cp_bda_wild_comp.h"

class ApiBufferDeviceAddress : public ApiBreadth {
  protected:
    static VkPhysicalDeviceBufferDeviceAddressFeatures features() {
        VkPhysicalDeviceBufferDeviceAddressFeatures f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
        f.bufferDeviceAddress = VK_TRUE;
        return f;
    }
};

constexpr VkBufferUsageFlags kAddressed =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
constexpr uint32_t kInvocations = 64, kNodes = 200;

VkDeviceAddress address_of(Kit& k, const Device::Buffer& b) {
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = b.buffer;
    return vkGetBufferDeviceAddress(k.d, &info);
}

// The scene's inputs: node k's successor (-1: none; always a lower node, so every list ends) and value, each
// invocation's first node (-1: an empty list), and the Pairs' (a.x, a.y, b).
struct Lists {
    std::vector<int> next, head;
    std::vector<uint32_t> value, pairs;
};

Lists make_lists() {
    Lists l;
    std::mt19937 rng(1302);
    for (uint32_t k = 0; k < kNodes; ++k) {
        l.next.push_back(k == 0 || rng() % 6 == 0 ? -1 : int(rng() % k));
        l.value.push_back(rng() % 1000);
    }
    for (uint32_t i = 0; i < kInvocations; ++i) l.head.push_back(rng() % 9 == 0 ? -1 : int(rng() % kNodes));
    for (uint32_t i = 0; i < kInvocations * 3; ++i) l.pairs.push_back(rng() % 100000);
    return l;
}

// Runs cp_bda.comp; returns the results, the nodes' visit counts, the Pairs and the counters (addresses left out:
// they differ between the drivers).
Bytes run_bda(Kit& k, const Lists& l) {
    Device::Buffer nodes = k.buffer(kNodes * 16, kAddressed);
    Device::Buffer heads = k.buffer(kInvocations * 8, kAddressed);
    Device::Buffer pairs = k.buffer(kInvocations * 16, kAddressed);
    Device::Buffer params = k.buffer(16, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    Device::Buffer out = k.buffer(kInvocations * 16, kAddressed);
    Device::Buffer counters = k.buffer(8, kAddressed);
    const VkDeviceAddress node0 = address_of(k, nodes);
    EXPECT_NE(node0, 0u);
    auto put64 = [](void* map, size_t at, uint64_t v) { std::memcpy(static_cast<uint8_t*>(map) + at, &v, 8); };
    for (uint32_t n = 0; n < kNodes; ++n) {
        put64(nodes.map, n * 16, l.next[n] < 0 ? 0 : node0 + uint64_t(l.next[n]) * 16);
        std::memcpy(static_cast<uint8_t*>(nodes.map) + n * 16 + 8, &l.value[n], 4);
    }
    for (uint32_t i = 0; i < kInvocations; ++i) {
        put64(heads.map, i * 8, l.head[i] < 0 ? 0 : node0 + uint64_t(l.head[i]) * 16);
        std::memcpy(static_cast<uint8_t*>(pairs.map) + i * 16, &l.pairs[i * 3], 12);
    }
    put64(params.map, 0, address_of(k, pairs));
    const uint32_t n = kInvocations;
    std::memcpy(static_cast<uint8_t*>(params.map) + 8, &n, 4);
    const VkDeviceAddress push[2] = {address_of(k, out), address_of(k, counters)};

    const VkDescriptorSetLayout dsl =
        k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT},
                      {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT}});
    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push};
    const VkPipelineLayout layout = k.pipeline_layout({dsl}, {range});
    const VkDescriptorSet set = k.descriptor_set(dsl);
    const VkDescriptorBufferInfo bh = whole(heads), bp = whole(params);
    k.write(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bh, nullptr);
    k.write(set, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &bp, nullptr);
    const VkPipeline p = compute_pipeline(k, SPV(cp_bda_comp), layout);
    if (p == VK_NULL_HANDLE) return {};
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(c, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, push);
        vkCmdDispatch(c, 1, 1, 1);
    }),
              VK_SUCCESS);
    Bytes visits;
    for (uint32_t v = 0; v < kNodes; ++v) {
        const auto* w = static_cast<const uint8_t*>(nodes.map) + v * 16 + 12;
        visits.insert(visits.end(), w, w + 4);
    }
    return concat({Kit::bytes(out), visits, Kit::bytes(pairs), Kit::bytes(counters)});
}

// cp_bda.comp's answers: per invocation (sum of value * position in its list, length, 2 * Pair b, head is null),
// each node's visits, the Pairs with c = 3 a.x + a.y + i + 7, the counters (total length, largest sum).
std::vector<uint32_t> expected(const Lists& l) {
    std::vector<uint32_t> res(kInvocations * 4), visits(kNodes), pairs(kInvocations * 4), counters(2);
    for (uint32_t i = 0; i < kInvocations; ++i) {
        uint32_t sum = 0, len = 0;
        for (int node = l.head[i]; node >= 0; node = l.next[size_t(node)]) {
            sum += l.value[size_t(node)] * ++len;
            ++visits[size_t(node)];
        }
        res[i * 4] = sum;
        res[i * 4 + 1] = len;
        res[i * 4 + 2] = 2 * l.pairs[i * 3 + 2];
        res[i * 4 + 3] = l.head[i] < 0 ? 1 : 0;
        for (uint32_t c = 0; c < 3; ++c) pairs[i * 4 + c] = l.pairs[i * 3 + c];
        pairs[i * 4 + 3] = 3 * l.pairs[i * 3] + l.pairs[i * 3 + 1] + i + 7;
        counters[0] += len;
        counters[1] = std::max(counters[1], sum);
    }
    res.insert(res.end(), visits.begin(), visits.end());
    res.insert(res.end(), pairs.begin(), pairs.end());
    res.insert(res.end(), counters.begin(), counters.end());
    return res;
}

// A linked list walk with pointers from a storage buffer and from the nodes, atomics through pointers, uvec2 address
// arithmetic with a carry, pointers in a uniform buffer and in push constants: the same bytes as lavapipe and as
// computed here. (OpPtrAccessChain and buffer_reference2's 64-bit indexing, which needs shaderInt64:
// tests/shader/pointer_test.cpp.)
TEST_F(ApiBufferDeviceAddress, ListsPointerArithmeticAndAtomics) {
    auto f = features();
    auto dev = device_pair({VK_KHR_BUFFER_DEVICE_ADDRESS_EXTENSION_NAME}, &f);
    ASSERT_TRUE(dev->ok());
    const Lists l = make_lists();
    const Bytes got = both_on(dev->tilevk, dev->lavapipe, [&l](Kit& k) { return run_bda(k, l); });
    const std::vector<uint32_t> want = expected(l);
    ASSERT_EQ(got.size(), want.size() * 4);
    for (size_t w = 0; w < want.size(); ++w) {
        uint32_t v = 0;
        std::memcpy(&v, &got[w * 4], 4);
        EXPECT_EQ(v, want[w]) << "word " << w;
    }
}

// The features tilevk reports for addresses: bufferDeviceAddress only (addresses are where malloc puts the memory:
// nothing to capture and replay; one device per group).
TEST_F(ApiBufferDeviceAddress, ReportedFeatures) {
    VkPhysicalDeviceBufferDeviceAddressFeatures f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f};
    vkGetPhysicalDeviceFeatures2(tilevk_->physical(), &f2);
    EXPECT_EQ(f.bufferDeviceAddress, VK_TRUE);
    EXPECT_EQ(f.bufferDeviceAddressCaptureReplay, VK_FALSE);
    EXPECT_EQ(f.bufferDeviceAddressMultiDevice, VK_FALSE);
}

// Addresses outside the memory allocated with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT are the application's bug (a GPU
// would fault or read garbage, lavapipe would crash: tilevk alone). tilevk looks every word up in those allocations
// (shader/exec_pointer.h): a word 16 bytes into the address space, a word straddling the end of an allocation, and
// a word of a buffer whose memory was allocated without the flag all load 0, are not stored to, and their atomics
// do nothing and return 0.
TEST_F(ApiBufferDeviceAddress, AddressesOutsideEveryBuffer) {
    auto f = features();
    auto dev = device_pair({VK_KHR_BUFFER_DEVICE_ADDRESS_EXTENSION_NAME}, &f);
    ASSERT_TRUE(dev->ok());
    Kit k(dev->tilevk);
    Device::Buffer out = k.buffer(64, kAddressed);
    Device::Buffer edge = k.buffer(64, kAddressed);  // its allocation is its 64 bytes (icd kBufferAlignment)
    Device::Buffer plain = k.buffer(64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::memset(out.map, 0xAD, 64);
    std::memset(edge.map, 0x5A, 64);
    std::memset(plain.map, 0x3C, 64);
    const VkDeviceAddress plain_at = VkDeviceAddress(reinterpret_cast<uintptr_t>(plain.map));  // host = device
    const VkDeviceAddress push[4] = {address_of(k, out), 16, address_of(k, edge) + 62, plain_at};
    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push};
    const VkPipelineLayout layout = k.pipeline_layout({}, {range});
    const VkPipeline p = compute_pipeline(k, SPV(cp_bda_wild_comp), layout);
    ASSERT_NE(p, VK_NULL_HANDLE);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdPushConstants(c, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, push);
        vkCmdDispatch(c, 1, 1, 1);
    }),
              VK_SUCCESS);
    const auto* o = static_cast<const uint32_t*>(out.map);
    for (int w = 0; w < 6; ++w) EXPECT_EQ(o[w], 0u) << "word " << w;
    for (int w = 6; w < 16; ++w) EXPECT_EQ(o[w], 0xADADADADu) << "word " << w;
    const auto* e = static_cast<const uint8_t*>(edge.map);
    const auto* q = static_cast<const uint8_t*>(plain.map);
    for (int b = 0; b < 64; ++b) {
        EXPECT_EQ(e[b], 0x5A) << "byte " << b;
        EXPECT_EQ(q[b], 0x3C) << "byte " << b;
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
