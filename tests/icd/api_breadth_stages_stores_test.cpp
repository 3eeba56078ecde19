// Side effects outside compute and out-of-bounds buffer accesses through the API, on tilevk and lavapipe with the
// validation layer, bytes compared, plus every result checked against values computed here:
// - suite ApiStagesStores (vertexPipelineStoresAndAtomics, fragmentStoresAndAtomics): storage-buffer stores and
//   atomics from vertex shaders, storage-buffer atomics, storage-image stores and image atomics from fragment
//   shaders, with
//   discards, helper lanes at triangle edges and a depth test that fails, with and without EarlyFragmentTests.
//   Only results that do not depend on the order (or, for vertices, the number) of invocations are used: counters
//   of fragments, bits per pixel and draw, per-pixel and per-vertex values, the largest vertex index.
// - suite ApiImageAtomics: every 32-bit image atomic on R32_UINT and R32_SINT storage images from compute, and
//   outside the image.
// - suite ApiStorageTexelBuffers: imageLoad / imageStore / imageSize / atomics on storage texel buffers, past
//   their ranges too.
// - suite ApiRobustBufferAccess (robustBufferAccess): uniform, storage and uniform texel buffer reads past the
//   bound range, stores and atomics past it; a vertex attribute past the end of its vertex buffer.
#include <algorithm>
#include <bit>
#include <cstring>
#include <vector>

#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

#include "ia_ops_comp.h"
#include "rb_access_comp.h"
#include "ss_store_early_frag.h"
#include "ss_store_frag.h"
#include "ss_store_vert.h"
#include "tb_ops_comp.h"

constexpr uint32_t kSize = 32;  // every target here is 32x32
constexpr uint32_t kBlocks = kSize / 4;  // ss_store.frag's per-block counters
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

class ApiStagesStores : public ApiBreadth {
  protected:
    // Both drivers with `features` enabled; runs `scene` on each, expects the same bytes and returns tilevk's.
    Bytes both_with(const VkPhysicalDeviceFeatures& features, const std::function<Bytes(Kit&)>& scene) {
        Device t(tilevk_->physical(), &features), l(lavapipe_->physical(), &features);
        EXPECT_TRUE(t.ok() && l.ok());
        if (!t.ok() || !l.ok()) return {};
        return both_on(t, l, scene);
    }
};
class ApiRobustBufferAccess : public ApiStagesStores {};

// ss_store.frag's discard: every fourth diagonal.
bool discarded(uint32_t x, uint32_t y) {
    return ((x ^ y) & 3) == 0;
}

// The push constants of ss_store.vert / ss_store.frag.
struct StorePush {
    uint32_t draw_id;
    float z;
    uint32_t partial;
};

// The sections of stores_scene's bytes.
struct StoreResult {
    Bytes colour, depth, frag, vert, image, blocks;
};
StoreResult split(const Bytes& b, bool depth) {
    StoreResult r;
    size_t at = 0;
    auto take = [&](size_t n, Bytes& out) {
        if (at + n <= b.size()) out.assign(b.begin() + long(at), b.begin() + long(at + n));
        at += n;
    };
    take(kSize * kSize * 4, r.colour);
    if (depth) take(kSize * kSize * 4, r.depth);
    take(4 + kSize * kSize * 4, r.frag);
    take(8 + 6 * 4, r.vert);
    take(kSize * kSize * 4, r.image);
    take(kBlocks * kBlocks * 4, r.blocks);
    return r;
}
uint32_t word(const Bytes& b, size_t i) {
    uint32_t v = 0;
    if (i * 4 + 4 <= b.size()) std::memcpy(&v, b.data() + i * 4, 4);
    return v;
}

// Draws `draws` triangles with ss_store.vert and `fs` (draw d: vertices 3d..3d+2, push constants {d, z[d],
// partial}) into a cleared RGBA8 target (and a D32 depth target cleared to 1 with test LESS, when `depth`), the
// fragment shader's buffer, the vertex shader's buffer and two r32ui storage images (per pixel, per 4x4 block) all
// zero at the start. Returns colour, depth (if any), the fragment buffer, the vertex buffer and the two images.
Bytes stores_scene(Kit& k, Spv fs, bool depth, bool partial, const std::vector<float>& z) {
    const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM, D = VK_FORMAT_D32_SFLOAT;
    Device::Buffer frag = k.buffer(4 + kSize * kSize * 4, kStorage);
    Device::Buffer vert = k.buffer(8 + 6 * 4, kStorage);
    Device::Image img =
        k.image(VK_FORMAT_R32_UINT, kSize, kSize,
                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const VkImageView img_view = k.view(img.image, VK_FORMAT_R32_UINT, VK_IMAGE_ASPECT_COLOR_BIT);
    Device::Image blocks =
        k.image(VK_FORMAT_R32_UINT, kBlocks, kBlocks,
                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const VkImageView blocks_view = k.view(blocks.image, VK_FORMAT_R32_UINT, VK_IMAGE_ASPECT_COLOR_BIT);
    Target tg{};
    DepthTarget dt{};
    if (depth)
        dt = depth_target(k, D);
    else
        tg = target(k, C);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkDescriptorSetLayout dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages},
                                                    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stages},
                                                    {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages},
                                                    {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stages}});
    const VkPipelineLayout layout = k.pipeline_layout({dsl}, {{stages, 0, sizeof(StorePush)}});
    const VkDescriptorSet set = k.descriptor_set(dsl);
    const VkDescriptorBufferInfo fb_info{frag.buffer, 0, VK_WHOLE_SIZE}, vb_info{vert.buffer, 0, VK_WHOLE_SIZE};
    const VkDescriptorImageInfo ii{VK_NULL_HANDLE, img_view, VK_IMAGE_LAYOUT_GENERAL},
        bi{VK_NULL_HANDLE, blocks_view, VK_IMAGE_LAYOUT_GENERAL};
    k.write(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &fb_info, nullptr);
    k.write(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &ii);
    k.write(set, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &vb_info, nullptr);
    k.write(set, 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &bi);

    Pipe p;
    p.vs = SPV(ss_store_vert);
    p.fs = fs;
    p.bindings = {};
    p.attrs = {};
    p.rp = depth ? dt.rp : tg.rp;
    p.layout = layout;
    const VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
    if (depth) p.ds = &ds;
    const VkPipeline pipe = k.pipeline(p);

    auto image_barrier = [&](VkCommandBuffer c, VkImageLayout from, VkImageLayout to, VkImage image) {
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr,
                             0, nullptr, 1, &b);
    };
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        const VkClearColorValue zero{};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        for (VkImage i : {img.image, blocks.image}) {
            image_barrier(c, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, i);
            vkCmdClearColorImage(c, i, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
            image_barrier(c, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL, i);
        }
        if (depth)
            begin_pass(c, dt.rp, dt.fb, kSize, kSize, {clear_color(0, 0, 0, 0), clear_depth(1.0f)});
        else
            begin_pass(c, tg.rp, tg.fb, kSize, kSize, {clear_color(0, 0, 0, 0)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
        for (uint32_t d = 0; d < z.size(); ++d) {
            const StorePush push{d, z[d], partial ? 1u : 0u};
            vkCmdPushConstants(c, layout, stages, 0, sizeof push, &push);
            vkCmdDraw(c, 3, 1, 3 * d, 0);
        }
        vkCmdEndRenderPass(c);
        for (VkImage i : {img.image, blocks.image})
            image_barrier(c, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, i);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                             VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr, 0, nullptr);
    }),
              VK_SUCCESS);
    Bytes out = k.read(depth ? dt.col.image : tg.image.image, kSize, kSize, 4);
    if (depth) out = concat({out, k.read(dt.dep.image, kSize, kSize, 4, VK_IMAGE_ASPECT_DEPTH_BIT)});
    return concat({out, Kit::bytes(frag), Kit::bytes(vert), k.read(img.image, kSize, kSize, 4),
                   k.read(blocks.image, kBlocks, kBlocks, 4)});
}

VkPhysicalDeviceFeatures stores_features() {
    VkPhysicalDeviceFeatures f{};
    f.vertexPipelineStoresAndAtomics = VK_TRUE;
    f.fragmentStoresAndAtomics = VK_TRUE;
    return f;
}

// The vertex shader's buffer after draws of vertices 0 .. n-1: however often each vertex ran.
void expect_vertices(const Bytes& vert, uint32_t n) {
    EXPECT_EQ(word(vert, 0), n);               // largest index + 1
    EXPECT_EQ(word(vert, 1), (1u << n) - 1u);  // a bit per index
    for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(word(vert, 2 + i), i * 7u + 3u) << "vertex " << i;
    for (uint32_t i = n; i < 6; ++i) EXPECT_EQ(word(vert, 2 + i), 0u) << "vertex " << i;
}

// A triangle over part of the target, no depth test: the fragments that stored are exactly the pixels whose colour
// was written (covered, not discarded); helper lanes of the edge quads (the shader takes a derivative) store nothing.
TEST_F(ApiStagesStores, FragmentSideEffectsFollowCoverageAndDiscard) {
    const Bytes b =
        both_with(stores_features(), [](Kit& k) { return stores_scene(k, SPV(ss_store_frag), false, true, {0.5f}); });
    const StoreResult r = split(b, false);
    ASSERT_EQ(r.image.size(), size_t(kSize * kSize * 4));
    uint32_t written = 0;
    std::vector<uint32_t> per_block(kBlocks * kBlocks, 0);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool coloured = r.colour[(y * kSize + x) * 4] == 255;
            written += coloured;
            per_block[(y / 4) * kBlocks + x / 4] += coloured;
            EXPECT_FALSE(coloured && discarded(x, y)) << x << "," << y;
            EXPECT_EQ(word(r.frag, 1 + y * kSize + x), coloured ? 1u : 0u) << x << "," << y;
            EXPECT_EQ(word(r.image, y * kSize + x), coloured ? x + kSize * y + 1 : 0u) << x << "," << y;
        }
    EXPECT_EQ(word(r.frag, 0), written);
    for (uint32_t i = 0; i < kBlocks * kBlocks; ++i) EXPECT_EQ(word(r.blocks, i), per_block[i]) << "block " << i;
    EXPECT_GT(written, 100u);  // a partial triangle: some pixels in, many out
    EXPECT_LT(written, 700u);
    expect_vertices(r.vert, 3);
}

// Two full-target draws, the second behind the first (depth LESS fails everywhere). Without EarlyFragmentTests the
// shader writes memory, so the depth test comes after it (lavapipe's LATE depth mode; the spec's order) and the
// second draw's fragments store too; with them, the test comes first: the second draw stores nothing, and discarded
// fragments of the first still wrote their depth.
TEST_F(ApiStagesStores, DepthTestOrdersSideEffectsByEarlyFragmentTests) {
    for (const bool early : {false, true}) {
        SCOPED_TRACE(early ? "early_fragment_tests" : "late depth test");
        const Bytes b = both_with(stores_features(), [early](Kit& k) {
            return stores_scene(k, early ? SPV(ss_store_early_frag) : SPV(ss_store_frag), true, false, {0.5f, 0.7f});
        });
        const StoreResult r = split(b, true);
        ASSERT_EQ(r.image.size(), size_t(kSize * kSize * 4));
        uint32_t count = 0;
        std::vector<uint32_t> per_block(kBlocks * kBlocks, 0);
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const uint32_t i = y * kSize + x;
                const bool kept = !discarded(x, y);
                const uint32_t bits = kept ? (early ? 1u : 3u) : 0u;
                count += std::popcount(bits);
                per_block[(y / 4) * kBlocks + x / 4] += (bits & 1) + (bits & 2 ? 0x100u : 0u);
                EXPECT_EQ(word(r.frag, 1 + i), bits) << x << "," << y;
                EXPECT_EQ(word(r.image, i), kept ? x + kSize * y + 1 : 0u) << x << "," << y;
                EXPECT_EQ(r.colour[i * 4], kept ? 255 : 0) << x << "," << y;
                const float z = std::bit_cast<float>(word(r.depth, i));
                EXPECT_EQ(z, kept || early ? 0.5f : 1.0f) << x << "," << y;
            }
        EXPECT_EQ(word(r.frag, 0), count);
        for (uint32_t i = 0; i < kBlocks * kBlocks; ++i) EXPECT_EQ(word(r.blocks, i), per_block[i]) << "block " << i;
        expect_vertices(r.vert, 6);
    }
}

// ---- Image atomics ---------------------------------------------------------------------------------------------

class ApiImageAtomics : public ApiStagesStores {};

constexpr uint32_t kIaW = 16, kIaH = 8;  // ia_ops.comp's images (it uses columns 0..7)

// The images' starting texels: u row 2 (min) and row 4 (and) all ones, row 6 (exchange) 77 + x, row 7
// (compare-exchange) 3x for even x and 3x + 1 for odd; s row 2 (add) 1000, row 3 (compare-exchange) -x for even x
// and 5 - x for odd; everything else 0.
std::vector<uint32_t> ia_start(bool sint) {
    std::vector<uint32_t> t(kIaW * kIaH, 0);
    for (uint32_t x = 0; x < kIaW; ++x) {
        auto at = [&](uint32_t y) -> uint32_t& { return t[y * kIaW + x]; };
        if (!sint) {
            at(2) = at(4) = ~0u;
            at(6) = 77 + x;
            at(7) = 3 * x + (x & 1);
        } else {
            at(2) = 1000;
            at(3) = uint32_t(-int32_t(x) + ((x & 1) ? 5 : 0));
        }
    }
    return t;
}

// ia_ops.comp over 16x8 invocations; returns the r32ui image, the r32i image and the returned values.
Bytes image_atomics_scene(Kit& k) {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const VkFormat fmts[2] = {VK_FORMAT_R32_UINT, VK_FORMAT_R32_SINT};
    Device::Image imgs[2] = {k.image(fmts[0], kIaW, kIaH, usage), k.image(fmts[1], kIaW, kIaH, usage)};
    Device::Buffer starts[2] = {k.buffer_of(ia_start(false), 0), k.buffer_of(ia_start(true), 0)};
    Device::Buffer out = k.buffer(27 * 4, kStorage);
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const VkDescriptorSetLayout dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs},
                                                    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs},
                                                    {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs}});
    const VkPipelineLayout layout = k.pipeline_layout({dsl});
    const VkDescriptorSet set = k.descriptor_set(dsl);
    for (uint32_t i = 0; i < 2; ++i) {
        const VkDescriptorImageInfo ii{VK_NULL_HANDLE, k.view(imgs[i].image, fmts[i], VK_IMAGE_ASPECT_COLOR_BIT),
                                       VK_IMAGE_LAYOUT_GENERAL};
        k.write(set, i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &ii);
    }
    const VkDescriptorBufferInfo oi{out.buffer, 0, VK_WHOLE_SIZE};
    k.write(set, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &oi, nullptr);
    const VkPipeline p = compute_pipeline(k, SPV(ia_ops_comp), layout);
    auto barrier = [](VkCommandBuffer c, VkImage img, VkImageLayout from, VkImageLayout to) {
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr,
                             0, nullptr, 1, &b);
    };
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        for (uint32_t i = 0; i < 2; ++i) {
            barrier(c, imgs[i].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy r{};
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            r.imageExtent = {kIaW, kIaH, 1};
            vkCmdCopyBufferToImage(c, starts[i].buffer, imgs[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
            barrier(c, imgs[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        }
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdDispatch(c, 2, 2, 1);
        for (uint32_t i = 0; i < 2; ++i)
            barrier(c, imgs[i].image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr,
                             0, nullptr);
    }),
              VK_SUCCESS);
    return concat({k.read(imgs[0].image, kIaW, kIaH, 4), k.read(imgs[1].image, kIaW, kIaH, 4), Kit::bytes(out)});
}

// Every image atomic's result, computed here from the 16 operands each texel takes (ia_ops.comp).
TEST_F(ApiImageAtomics, EveryAtomicOnR32UintAndSint) {
    for (const VkFormat f : {VK_FORMAT_R32_UINT, VK_FORMAT_R32_SINT}) {
        VkFormatProperties tp, lp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &tp);
        vkGetPhysicalDeviceFormatProperties(lavapipe_->physical(), f, &lp);
        EXPECT_TRUE(tp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_ATOMIC_BIT) << f;
        EXPECT_TRUE(lp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_ATOMIC_BIT) << f;
    }
    const Bytes b = both(image_atomics_scene);
    ASSERT_EQ(b.size(), size_t(2 * kIaW * kIaH + 27) * 4);
    std::vector<uint32_t> u = ia_start(false), s = ia_start(true), o(27, 0);
    for (uint32_t t = 0; t < 8; ++t) {
        auto us = [&](uint32_t row) -> uint32_t& { return u[row * kIaW + t]; };
        auto ss = [&](uint32_t row) -> uint32_t& { return s[row * kIaW + t]; };
        for (uint32_t gy = 0; gy < kIaH; ++gy)
            for (const uint32_t gx : {t, t + 8}) {
                const uint32_t i = gx + 16 * gy;
                us(0) += i + 1;
                us(1) = std::max(us(1), i * 2654435761u);
                us(2) = std::min(us(2), i * 2654435761u);
                us(3) |= 1u << (i % 32);
                us(4) &= ~(1u << ((i * 7) % 32));
                us(5) ^= i * 0x01010101u;
                ss(0) = uint32_t(std::min(int32_t(ss(0)), int32_t(i) * 40503 - 2000000));
                ss(1) = uint32_t(std::max(int32_t(ss(1)), int32_t(i) * -40503 + 100));
                ss(2) -= i;
            }
        o[t] = us(6);  // the one exchange of texel t, by invocation i = t
        us(6) = t + 1000;
        o[8 + t] = us(7);
        if (us(7) == 3 * t) us(7) = 500 + t;
        o[16 + t] = ss(3);
        if (int32_t(ss(3)) == -int32_t(t)) ss(3) = uint32_t(int32_t(t) - 50);
    }
    for (uint32_t i = 0; i < kIaW * kIaH; ++i) {
        EXPECT_EQ(word(b, i), u[i]) << "r32ui texel " << i % kIaW << "," << i / kIaW;
        EXPECT_EQ(word(b, kIaW * kIaH + i), s[i]) << "r32i texel " << i % kIaW << "," << i / kIaW;
    }
    for (uint32_t i = 0; i < 27; ++i) EXPECT_EQ(word(b, 2 * kIaW * kIaH + i), o[i]) << "returned value " << i;
}

// ---- Storage texel buffers ---------------------------------------------------------------------------------------

class ApiStorageTexelBuffers : public ApiStagesStores {};

constexpr uint32_t kTexelOffset = 256;                          // the rgba8 and rgba32f views start here
constexpr uint8_t kUntouchedByte = 0x7f;                        // the rgba32f buffer's bytes before the dispatch
constexpr uint32_t kSrc = 20, kDst = 24, kCnt = 8, kFsrc = 10;  // the views' texels

uint8_t src_byte(uint32_t i) {
    return uint8_t(i * 37 + 11);
}
float fsrc_value(uint32_t i) {
    return float(i) * 1.5f - 3.0f;
}

// A buffer view of `b` (kit-owned).
VkBufferView buffer_view(Kit& k, const Device::Buffer& b, VkFormat f, VkDeviceSize offset, VkDeviceSize range) {
    VkBufferViewCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    ci.buffer = b.buffer;
    ci.format = f;
    ci.offset = offset;
    ci.range = range;
    VkBufferView v = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateBufferView(k.d, &ci, nullptr, &v), VK_SUCCESS) << f;
    k.undo(VK_OBJECT_TYPE_BUFFER_VIEW, v, [&k, v] { vkDestroyBufferView(k.d, v, nullptr); });
    return v;
}

// tb_ops.comp over 32 invocations; returns the rgba32f buffer (all of it), the r32ui buffer and `o`.
Bytes texel_buffers_scene(Kit& k) {
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT;
    std::vector<uint8_t> src(kTexelOffset + 64 * 4);
    for (uint32_t i = 0; i < src.size(); ++i) src[i] = src_byte(i);
    std::vector<float> fsrc(64);
    for (uint32_t i = 0; i < fsrc.size(); ++i) fsrc[i] = fsrc_value(i);
    Device::Buffer sb = k.buffer_of(src, usage), fb = k.buffer_of(fsrc, usage);
    Device::Buffer db = k.buffer_of(std::vector<uint8_t>(kTexelOffset + 32 * 16, kUntouchedByte), usage);
    Device::Buffer cb = k.buffer(kCnt * 4 + 64, usage);
    Device::Buffer out = k.buffer(163 * 4, kStorage);
    const VkBufferView views[4] = {buffer_view(k, sb, VK_FORMAT_R8G8B8A8_UNORM, kTexelOffset, kSrc * 4),
                                   buffer_view(k, db, VK_FORMAT_R32G32B32A32_SFLOAT, kTexelOffset, kDst * 16),
                                   buffer_view(k, cb, VK_FORMAT_R32_UINT, 0, kCnt * 4),
                                   buffer_view(k, fb, VK_FORMAT_R32_SFLOAT, 0, kFsrc * 4)};
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (uint32_t i = 0; i < 4; ++i) bindings.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 1, cs});
    bindings.push_back({4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs});
    const VkDescriptorSetLayout dsl = k.set_layout(bindings);
    const VkPipelineLayout layout = k.pipeline_layout({dsl});
    const VkDescriptorSet set = k.descriptor_set(dsl);
    for (uint32_t i = 0; i < 4; ++i) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set;
        w.dstBinding = i;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
        w.pTexelBufferView = &views[i];
        vkUpdateDescriptorSets(k.d, 1, &w, 0, nullptr);
    }
    const VkDescriptorBufferInfo oi{out.buffer, 0, VK_WHOLE_SIZE};
    k.write(set, 4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &oi, nullptr);
    const VkPipeline p = compute_pipeline(k, SPV(tb_ops_comp), layout);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdDispatch(c, 2, 1, 1);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr,
                             0, nullptr);
    }),
              VK_SUCCESS);
    return concat({Kit::bytes(db), Kit::bytes(cb), Kit::bytes(out)});
}

// Loads convert as texel fetches do (UNORM8: c * fl(1/255)), stores as image stores, atomics as on images; past a
// view's range loads give (0, 0, 0, 0) (alpha 1 for R32_SFLOAT), stores and atomics do nothing (atomics return 0).
TEST_F(ApiStorageTexelBuffers, LoadStoreAtomicsAndSizes) {
    const Bytes b = both(texel_buffers_scene);
    const size_t db_size = kTexelOffset + 32 * 16, cb_size = kCnt * 4 + 64;
    ASSERT_EQ(b.size(), db_size + cb_size + 163 * 4);
    for (uint32_t byte = 0; byte < db_size; ++byte) {
        const uint32_t rel = byte - kTexelOffset, texel = rel / 16;
        if (byte < kTexelOffset || texel >= kDst) {
            EXPECT_EQ(b[byte], kUntouchedByte) << "byte " << byte;
            continue;
        }
        if (rel % 4 != 0) continue;
        const uint32_t c = (rel % 16) / 4;
        const float loaded = texel < kSrc ? float(src_byte(kTexelOffset + texel * 4 + c)) * (1.0f / 255.0f) : 0.0f;
        const float want = loaded * 2.0f + 0.25f;
        EXPECT_EQ(std::bit_cast<float>(word(b, byte / 4)), want) << "texel " << texel << "." << c;
    }
    for (uint32_t t = 0; t < kCnt + 16; ++t) {
        uint32_t sum = 0;
        for (uint32_t i = t; t < kCnt && i < 32; i += 10) sum += i + 1;
        EXPECT_EQ(word(b, db_size / 4 + t), sum) << "counter " << t;
    }
    const size_t o = (db_size + cb_size) / 4;
    for (uint32_t i = 0; i < 32; ++i) {
        const uint32_t want[5] = {i < kFsrc ? std::bit_cast<uint32_t>(fsrc_value(i)) : 0u, 0, 0,
                                  std::bit_cast<uint32_t>(1.0f), 0};
        for (uint32_t c = 0; c < 5; ++c) EXPECT_EQ(word(b, o + i * 5 + c), want[c]) << i << "." << c;
    }
    EXPECT_EQ(word(b, o + 160), kSrc);
    EXPECT_EQ(word(b, o + 161), kDst);
    EXPECT_EQ(word(b, o + 162), kCnt);
}

// ---- robustBufferAccess ------------------------------------------------------------------------------------------

constexpr uint32_t kInvocations = 32;  // rb_access.comp: 2 workgroups of 16
constexpr VkDeviceSize kOffset = 256;  // every binding starts here (a multiple of any minimum offset alignment)
constexpr uint32_t kOut = 12;          // result words per invocation

float ubo_value(uint32_t word_index) {
    return 1000.0f + float(word_index);
}
uint32_t ssbo_value(uint32_t word_index) {
    return 0x5000u + word_index;
}
constexpr uint32_t kUntouched = 0x11111111u;  // the store and atomic buffers' words before the dispatch

// rb_access.comp with its buffers bound at kOffset: the uniform buffer's range 56 bytes (vec4 3 straddles the end:
// 2 words in), the read storage buffer's 44 (uvec2 5: 1 word in), the stored one's 40 (10 words), the atomic one's
// 24 (6 words), the R32_SFLOAT texel buffer's 20 texels. Returns the results, then the stored and atomic buffers.
Bytes robust_scene(Kit& k) {
    std::vector<float> u(kOffset / 4 + 256);
    for (uint32_t i = 0; i < u.size(); ++i) u[i] = ubo_value(i);
    std::vector<uint32_t> s(kOffset / 4 + 256), untouched(kOffset / 4 + 64, kUntouched), a(kOffset / 4 + 64);
    for (uint32_t i = 0; i < s.size(); ++i) s[i] = ssbo_value(i);
    for (uint32_t i = 0; i < a.size(); ++i) a[i] = i;
    Device::Buffer ub = k.buffer_of(u, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    Device::Buffer sb = k.buffer_of(s, kStorage);
    Device::Buffer wb = k.buffer_of(untouched, kStorage);
    Device::Buffer ab = k.buffer_of(a, kStorage);
    Device::Buffer ob = k.buffer(kInvocations * kOut * 4, kStorage);
    VkBufferViewCreateInfo bvci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    bvci.buffer = ub.buffer;
    bvci.format = VK_FORMAT_R32_SFLOAT;
    bvci.offset = kOffset;
    bvci.range = 20 * 4;
    VkBufferView view = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateBufferView(k.d, &bvci, nullptr, &view), VK_SUCCESS);
    k.undo(VK_OBJECT_TYPE_BUFFER_VIEW, view, [&k, view] { vkDestroyBufferView(k.d, view, nullptr); });

    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const VkDescriptorSetLayout dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, cs},
                                                    {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs},
                                                    {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs},
                                                    {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs},
                                                    {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs},
                                                    {5, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1, cs}});
    const VkPipelineLayout layout = k.pipeline_layout({dsl});
    const VkDescriptorSet set = k.descriptor_set(dsl);
    const VkDescriptorBufferInfo infos[5] = {{ub.buffer, kOffset, 56},
                                             {sb.buffer, kOffset, 44},
                                             {wb.buffer, kOffset, 40},
                                             {ab.buffer, kOffset, 24},
                                             {ob.buffer, 0, VK_WHOLE_SIZE}};
    k.write(set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &infos[0], nullptr);
    for (uint32_t i = 1; i < 5; ++i) k.write(set, i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &infos[i], nullptr);
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = 5;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    w.pTexelBufferView = &view;
    vkUpdateDescriptorSets(k.d, 1, &w, 0, nullptr);
    const VkPipeline p = compute_pipeline(k, SPV(rb_access_comp), layout);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdDispatch(c, kInvocations / 16, 1, 1);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr,
                             0, nullptr);
    }),
              VK_SUCCESS);
    return concat({Kit::bytes(ob), Kit::bytes(wb), Kit::bytes(ab)});
}

// Out of the bound range: loads give 0 per 32-bit word (a vec4 or uvec2 straddling the end keeps its words inside),
// texel fetches (0, 0, 0, 1), stores and atomics change nothing (an atomic returns 0); inside it everything works.
// Nothing outside the ranges (before the offset or past the end) is touched.
TEST_F(ApiRobustBufferAccess, OutOfRangeReadsGiveZeroWritesAndAtomicsAreDropped) {
    VkPhysicalDeviceFeatures f{};
    f.robustBufferAccess = VK_TRUE;
    const Bytes b = both_with(f, robust_scene);
    const size_t out_words = kInvocations * kOut, w_words = kOffset / 4 + 64;
    ASSERT_EQ(b.size(), (out_words + 2 * w_words) * 4);
    const uint32_t base = kOffset / 4;
    auto f32 = [](float v) { return std::bit_cast<uint32_t>(v); };
    for (uint32_t i = 0; i < kInvocations; ++i) {
        SCOPED_TRACE("invocation " + std::to_string(i));
        const size_t o = size_t(i) * kOut;
        for (uint32_t c = 0; c < 4; ++c) {  // ub.u[i]: words 4i + c, 14 of them in range
            const uint32_t wi = 4 * i + c;
            EXPECT_EQ(word(b, o + c), wi < 14 ? f32(ubo_value(base + wi)) : 0u) << "ub.u[i]." << c;
        }
        EXPECT_EQ(word(b, o + 4), f32(ubo_value(base + 13)));  // ub.u[3].y: the last word in range
        for (uint32_t c = 0; c < 2; ++c) {                     // sb.s[i]: words 2i + c, 11 in range
            const uint32_t wi = 2 * i + c;
            EXPECT_EQ(word(b, o + 5 + c), wi < 11 ? ssbo_value(base + wi) : 0u) << "sb.s[i]." << c;
        }
        EXPECT_EQ(word(b, o + 7), i < 6 ? base + i : 0u);  // the atomic's old value
        const uint32_t texel[4] = {i < 20 ? f32(ubo_value(base + i)) : 0u, 0, 0, f32(1.0f)};
        for (uint32_t c = 0; c < 4; ++c) EXPECT_EQ(word(b, o + 8 + c), texel[c]) << "texelFetch." << c;
    }
    for (uint32_t j = 0; j < w_words; ++j) {
        const bool stored = j >= base && j < base + 10;
        EXPECT_EQ(word(b, out_words + j), stored ? 0xAB000000u + (j - base) : kUntouched) << "stored word " << j;
        const bool added = j >= base && j < base + 6;
        EXPECT_EQ(word(b, out_words + w_words + j), added ? j + 0x100u : j) << "atomic word " << j;
    }
}

// A triangle whose third vertex's colour attribute lies past the end of the vertex buffer (the buffer ends after
// its position) draws as the same triangle with that colour written as (0, 0, 0, 0) in a whole buffer.
TEST_F(ApiRobustBufferAccess, VertexAttributesPastTheBufferReadZero) {
    VkPhysicalDeviceFeatures f{};
    f.robustBufferAccess = VK_TRUE;
    auto draw = [](bool truncated) {
        return [truncated](Kit& k) {
            std::vector<Vertex> vs = kTriangle;
            vs[2].color[0] = vs[2].color[1] = vs[2].color[2] = vs[2].color[3] = 0.0f;
            std::vector<uint8_t> bytes(sizeof(Vertex) * 3);
            std::memcpy(bytes.data(), vs.data(), bytes.size());
            if (truncated) bytes.resize(sizeof(Vertex) * 2 + sizeof(Vertex::pos));
            Device::Buffer vb = k.buffer_of(bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
            Target tg = target(k);
            Pipe p;
            p.rp = tg.rp;
            const VkPipeline pipe = k.pipeline(p);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                begin_pass(c, tg.rp, tg.fb, kSize, kSize, {clear_color(0.2f, 0.4f, 0.6f, 0.8f)});
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                bind_vertices(c, vb);
                vkCmdDraw(c, 3, 1, 0, 0);
                vkCmdEndRenderPass(c);
            }),
                      VK_SUCCESS);
            return k.read(tg.image.image, kSize, kSize, 4);
        };
    };
    const Bytes cut = both_with(f, draw(true)), whole = both_with(f, draw(false));
    EXPECT_EQ(cut, whole);
    EXPECT_NE(cut, Bytes(cut.size(), 0));
}

}  // namespace
}  // namespace tilevk::test::breadth
