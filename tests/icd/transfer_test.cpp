// Transfer commands on both drivers (tilevk and lavapipe, through the loader with validation on): each scenario
// runs on both, the read-back bytes must equal each other AND an expectation computed here independently.
#include <gtest/gtest.h>
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "vk_harness.h"
#include "vk_pipeline.h"

namespace {

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::SingleAttachmentPass;
using tilevk::test::transition;
using tilevk::test::TwoDriverSuite;
using Bytes = std::vector<uint8_t>;

constexpr VkImageLayout kDst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
constexpr VkImageLayout kSrc = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
constexpr VkImageUsageFlags kXfer = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

class Transfer : public TwoDriverSuite {
  protected:
    // Runs `scenario` on both drivers; returns tilevk's bytes after checking they equal lavapipe's.
    template <class F>
    Bytes both(F scenario) {
        Bytes t = scenario(*tilevk_), l = scenario(*lavapipe_);
        EXPECT_EQ(t.size(), l.size());
        size_t diffs = 0, first = ~size_t(0);
        for (size_t i = 0; i < std::min(t.size(), l.size()); ++i) {
            if (t[i] != l[i]) {
                if (first == ~size_t(0)) first = i;
                ++diffs;
            }
        }
        EXPECT_EQ(diffs, 0u) << "tilevk and lavapipe differ; first at byte " << first << ": " << int(t[first]) << " vs "
                             << int(l[first]);
        return t;
    }
};

Bytes read(const Device::Buffer& b) {
    const uint8_t* p = static_cast<const uint8_t*>(b.map);
    return Bytes(p, p + b.size);
}

uint8_t pattern(size_t i) {
    return uint8_t(i * 7 + (i >> 8) * 13 + 1);
}

// ---- buffers ----------------------------------------------------------------------------------------------------
TEST_F(Transfer, FillUpdateCopyBuffer) {
    const size_t n = 1024;
    uint8_t update[40];
    for (int i = 0; i < 40; ++i) update[i] = uint8_t(200 - i);
    const uint32_t word = 0xdeadbeef, word2 = 0x01020304;
    auto scenario = [&](Device& d) {
        Device::Buffer a = d.make_buffer(n), b = d.make_buffer(n);
        for (size_t i = 0; i < n; ++i) static_cast<uint8_t*>(a.map)[i] = pattern(i);
        std::memset(b.map, 0xee, n);
        d.run([&](VkCommandBuffer cb) {
            vkCmdFillBuffer(cb, a.buffer, 16, 64, word);
            vkCmdUpdateBuffer(cb, a.buffer, 200, sizeof update, update);
            VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
            mb.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
            vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0,
                                 nullptr, 0, nullptr);
            VkBufferCopy regions[] = {{0, 100, 300}, {600, 0, 50}};
            vkCmdCopyBuffer(cb, a.buffer, b.buffer, 2, regions);
            vkCmdFillBuffer(cb, b.buffer, 900, VK_WHOLE_SIZE, word2);
        });
        Bytes out = read(b);
        d.destroy(a);
        d.destroy(b);
        return out;
    };
    Bytes got = both(scenario);
    // Expected, simulated on plain arrays.
    Bytes a(n), b(n, 0xee);
    for (size_t i = 0; i < n; ++i) a[i] = pattern(i);
    for (size_t i = 16; i < 80; i += 4) std::memcpy(&a[i], &word, 4);
    std::memcpy(&a[200], update, sizeof update);
    std::memcpy(&b[100], &a[0], 300);
    std::memcpy(&b[0], &a[600], 50);
    for (size_t i = 900; i + 4 <= n; i += 4) std::memcpy(&b[i], &word2, 4);
    EXPECT_EQ(got, b);
}

// ---- buffer <-> image and image -> image ------------------------------------------------------------------------
TEST_F(Transfer, BufferImageRoundTripAndImageCopy) {
    const uint32_t w = 13, h = 7, row_len = 16;    // buffer rows padded to 16 texels
    const size_t n = size_t(row_len) * h * 4 * 2;  // two layers
    auto scenario = [&](Device& d) {
        Device::Buffer src = d.make_buffer(n), dst = d.make_buffer(n);
        for (size_t i = 0; i < n; ++i) static_cast<uint8_t*>(src.map)[i] = pattern(i);
        std::memset(dst.map, 0, n);
        Device::Image a = d.make_image(VK_FORMAT_R8G8B8A8_UNORM, w, h, 2, 2, VK_SAMPLE_COUNT_1_BIT, kXfer);
        Device::Image b = d.make_image(VK_FORMAT_R8G8B8A8_UNORM, w, h, 1, 1, VK_SAMPLE_COUNT_1_BIT, kXfer);
        d.run([&](VkCommandBuffer cb) {
            transition(cb, a.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
            transition(cb, b.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
            VkClearColorValue zero{};
            VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(cb, b.image, kDst, &zero, 1, &all);
            VkBufferImageCopy up{0, row_len, h, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 2}, {0, 0, 0}, {w, h, 1}};
            vkCmdCopyBufferToImage(cb, src.buffer, a.image, kDst, 1, &up);
            transition(cb, a.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kSrc);
            transition(cb, b.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kDst);
            // Layer 1, texels (2..9, 1..5) -> b at (4, 2).
            VkImageCopy ic{{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 1},
                           {2, 1, 0},
                           {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                           {4, 2, 0},
                           {8, 5, 1}};
            vkCmdCopyImage(cb, a.image, kSrc, b.image, kDst, 1, &ic);
            transition(cb, b.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kSrc);
            // Read back: a's layer 0 sub-rect (tightly packed at 0) and all of b (after it).
            VkBufferImageCopy down0{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {3, 2, 0}, {5, 4, 1}};
            vkCmdCopyImageToBuffer(cb, a.image, kSrc, dst.buffer, 1, &down0);
            VkBufferImageCopy down1{80, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
            vkCmdCopyImageToBuffer(cb, b.image, kSrc, dst.buffer, 1, &down1);
        });
        Bytes out = read(dst);
        d.destroy(a);
        d.destroy(b);
        d.destroy(src);
        d.destroy(dst);
        return out;
    };
    Bytes got = both(scenario);
    auto src_texel = [&](uint32_t layer, uint32_t x, uint32_t y, int c) {
        return pattern(((size_t(layer) * h + y) * row_len + x) * 4 + c);
    };
    Bytes want(n, 0);
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 5; ++x)
            for (int c = 0; c < 4; ++c) want[(y * 5 + x) * 4 + c] = src_texel(0, 3 + x, 2 + y, c);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c) {
                bool in = x >= 4 && x < 12 && y >= 2 && y < 7;
                want[80 + (y * w + x) * 4 + c] = in ? src_texel(1, x - 4 + 2, y - 2 + 1, c) : 0;
            }
    EXPECT_EQ(got, want);
}

// ---- colour clears ----------------------------------------------------------------------------------------------
const float kClearValues[][4] = {
    {0.5f, 0.25f, 0.75f, 1.0f},
    {1.0f / 255.0f, 2.0f / 255.0f, 0.00196f, 0.0f},
    {0.9999f, 0.5019608f, 0.4980392f, 0.1f},
    {-0.1f, 1.5f, 0.003f, 0.3333333f},
    {0.0031308f, 0.04045f, 0.2140f, 0.7350f},
    {1e-5f, 0.999f, 0.0001f, 0.6f},
};

struct ColorFormat {
    VkFormat format;
    uint32_t bytes;
};
const ColorFormat kColorFormats[] = {
    {VK_FORMAT_R8G8B8A8_UNORM, 4},       {VK_FORMAT_B8G8R8A8_UNORM, 4}, {VK_FORMAT_R8G8B8A8_SRGB, 4},
    {VK_FORMAT_B8G8R8A8_SRGB, 4},        {VK_FORMAT_R8_UNORM, 1},       {VK_FORMAT_R8G8_UNORM, 2},
    {VK_FORMAT_R16G16B16A16_SFLOAT, 8},  {VK_FORMAT_R32_SFLOAT, 4},     {VK_FORMAT_R32G32_SFLOAT, 8},
    {VK_FORMAT_R32G32B32A32_SFLOAT, 16},
};

__attribute__((target("f16c"))) uint16_t f16c_rtz(float f) {
    return uint16_t(_cvtss_sh(f, _MM_FROUND_TO_ZERO));
}

// Independent UNORM8 expectation: Mesa's float_to_ubyte is round-half-even(fl(f*fl(255/256)) * 256) mod 256.
uint8_t expect_unorm8(float f) {
    if (!(f > 0.0f)) return 0;
    if (f >= 1.0f) return 255;
    return uint8_t(int(std::nearbyint(double(f * (255.0f / 256.0f)) * 256.0)) & 0xff);
}

TEST_F(Transfer, ClearColorImageAllFormats) {
    const uint32_t w = 5, h = 3;
    for (const ColorFormat& cf : kColorFormats) {
        for (const auto& v : kClearValues) {
            SCOPED_TRACE(::testing::Message()
                         << "format " << cf.format << " value " << v[0] << "," << v[1] << "," << v[2] << "," << v[3]);
            // Level 1 of layer 1 is cleared; level 0 of layer 1 is filled from a buffer and must stay intact.
            const size_t level0 = size_t(w) * h * cf.bytes, level1 = size_t(w / 2) * (h / 2) * cf.bytes;
            auto scenario = [&](Device& d) {
                Device::Buffer buf = d.make_buffer(level0 + level1);
                for (size_t i = 0; i < buf.size; ++i) static_cast<uint8_t*>(buf.map)[i] = pattern(i) & 0x3f;
                Device::Image img = d.make_image(cf.format, w, h, 2, 2, VK_SAMPLE_COUNT_1_BIT, kXfer);
                d.run([&](VkCommandBuffer cb) {
                    transition(cb, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
                    VkBufferImageCopy up{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 1}, {0, 0, 0}, {w, h, 1}};
                    vkCmdCopyBufferToImage(cb, buf.buffer, img.image, kDst, 1, &up);
                    VkClearColorValue c;
                    std::memcpy(c.float32, v, sizeof c.float32);
                    VkImageSubresourceRange r{VK_IMAGE_ASPECT_COLOR_BIT, 1, 1, 1, 1};
                    vkCmdClearColorImage(cb, img.image, kDst, &c, 1, &r);
                    transition(cb, img.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kSrc);
                    VkBufferImageCopy d0{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 1}, {0, 0, 0}, {w, h, 1}};
                    VkBufferImageCopy d1{level0,           0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 1, 1, 1}, {0, 0, 0},
                                         {w / 2, h / 2, 1}};
                    VkBufferImageCopy downs[] = {d0, d1};
                    vkCmdCopyImageToBuffer(cb, img.image, kSrc, buf.buffer, 2, downs);
                });
                Bytes out = read(buf);
                d.destroy(img);
                d.destroy(buf);
                return out;
            };
            Bytes got = both(scenario);
            ASSERT_EQ(got.size(), level0 + level1);
            for (size_t i = 0; i < level0; ++i) ASSERT_EQ(got[i], pattern(i) & 0x3f) << "level 0 was touched";
            // The cleared level, against expectations computed here for the non-sRGB formats.
            const uint8_t* t = got.data() + level0;
            for (size_t px = 0; px < size_t(w / 2) * (h / 2); ++px, t += cf.bytes) {
                switch (cf.format) {
                    case VK_FORMAT_R8G8B8A8_UNORM:
                    case VK_FORMAT_R8_UNORM:
                    case VK_FORMAT_R8G8_UNORM:
                        for (uint32_t c = 0; c < cf.bytes; ++c) EXPECT_EQ(t[c], expect_unorm8(v[c]));
                        break;
                    case VK_FORMAT_B8G8R8A8_UNORM:
                        EXPECT_EQ(t[0], expect_unorm8(v[2]));
                        EXPECT_EQ(t[1], expect_unorm8(v[1]));
                        EXPECT_EQ(t[2], expect_unorm8(v[0]));
                        EXPECT_EQ(t[3], expect_unorm8(v[3]));
                        break;
                    case VK_FORMAT_R16G16B16A16_SFLOAT:
                        // Mesa packs half clears rounding toward zero; reference: the CPU's F16C instruction.
                        if (__builtin_cpu_supports("f16c")) {
                            for (int c = 0; c < 4; ++c) {
                                uint16_t hv = f16c_rtz(v[c]);
                                EXPECT_EQ(std::memcmp(t + 2 * c, &hv, 2), 0) << "channel " << c;
                            }
                        }
                        break;
                    case VK_FORMAT_R32_SFLOAT:
                    case VK_FORMAT_R32G32_SFLOAT:
                    case VK_FORMAT_R32G32B32A32_SFLOAT:
                        EXPECT_EQ(std::memcmp(t, v, cf.bytes), 0);
                        break;
                    default:  // sRGB: lavapipe (compared above) is the reference
                        EXPECT_EQ(t[3], expect_unorm8(v[3])) << "sRGB alpha is linear";
                        break;
                }
            }
        }
    }
}

// ---- depth/stencil clears ---------------------------------------------------------------------------------------
TEST_F(Transfer, ClearDepthStencilImage) {
    const float depths[] = {0.0f, 1.0f, 0.5f, 0.3f, 1.0f / 3.0f, 0.999999f, 0.123456f};
    const uint32_t w = 4, h = 3;
    struct DF {
        VkFormat format;
        VkImageAspectFlags aspects;
    } formats[] = {{VK_FORMAT_D16_UNORM, VK_IMAGE_ASPECT_DEPTH_BIT},
                   {VK_FORMAT_D32_SFLOAT, VK_IMAGE_ASPECT_DEPTH_BIT},
                   {VK_FORMAT_D32_SFLOAT_S8_UINT, VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT}};
    for (const DF& f : formats) {
        for (float z : depths) {
            SCOPED_TRACE(::testing::Message() << "format " << f.format << " depth " << z);
            const uint32_t stencil = 0xa5;
            const size_t dbytes = f.format == VK_FORMAT_D16_UNORM ? 2 : 4, n = w * h * (dbytes + 1);
            auto scenario = [&](Device& d) {
                Device::Buffer buf = d.make_buffer(n);
                std::memset(buf.map, 0x77, n);
                Device::Image img = d.make_image(f.format, w, h, 1, 1, VK_SAMPLE_COUNT_1_BIT, kXfer);
                d.run([&](VkCommandBuffer cb) {
                    transition(cb, img.image, f.aspects, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
                    VkClearDepthStencilValue v{z, stencil};
                    VkImageSubresourceRange r{f.aspects, 0, 1, 0, 1};
                    vkCmdClearDepthStencilImage(cb, img.image, kDst, &v, 1, &r);
                    transition(cb, img.image, f.aspects, kDst, kSrc);
                    VkBufferImageCopy dd{0, 0, 0, {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
                    vkCmdCopyImageToBuffer(cb, img.image, kSrc, buf.buffer, 1, &dd);
                    if (f.aspects & VK_IMAGE_ASPECT_STENCIL_BIT) {
                        VkBufferImageCopy ds{w * h * dbytes, 0,        0, {VK_IMAGE_ASPECT_STENCIL_BIT, 0, 0, 1},
                                             {0, 0, 0},      {w, h, 1}};
                        vkCmdCopyImageToBuffer(cb, img.image, kSrc, buf.buffer, 1, &ds);
                    }
                });
                Bytes out = read(buf);
                d.destroy(img);
                d.destroy(buf);
                return out;
            };
            Bytes got = both(scenario);
            for (uint32_t i = 0; i < w * h; ++i) {
                if (f.format == VK_FORMAT_D16_UNORM) {
                    // nearest integer to z*65535, ties to even (z*65535 computed exactly enough in double)
                    uint16_t want = uint16_t(std::nearbyint(double(z) * 65535.0)), v;
                    std::memcpy(&v, &got[i * 2], 2);
                    EXPECT_EQ(v, want);
                } else {
                    EXPECT_EQ(std::memcmp(&got[i * 4], &z, 4), 0);
                }
                if (f.aspects & VK_IMAGE_ASPECT_STENCIL_BIT) {
                    EXPECT_EQ(got[w * h * dbytes + i], stencil);
                }
            }
        }
    }
}

// ---- render pass load-op clear and resolve (4x -> 1x) ----------------------------------------------------------
TEST_F(Transfer, RenderPassClearAndResolve) {
    const uint32_t w = 9, h = 6;
    const float colors[][4] = {{0.5f, 0.25f, 0.1f, 1.0f}, {0.7f, 0.3333f, 0.01f, 0.2f}, {0.9f, 0.6f, 0.45f, 0.05f}};
    for (const auto& col : colors) {
        auto scenario = [&](Device& d) {
            VkDevice dev = d.device();
            Device::Buffer buf = d.make_buffer(size_t(w) * h * 4);
            Device::Image ms = d.make_image(VK_FORMAT_R8G8B8A8_UNORM, w, h, 1, 1, VK_SAMPLE_COUNT_4_BIT,
                                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
            Device::Image one = d.make_image(VK_FORMAT_R8G8B8A8_UNORM, w, h, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
            VkAttachmentDescription att[2] = {};
            att[0].format = VK_FORMAT_R8G8B8A8_UNORM;
            att[0].samples = VK_SAMPLE_COUNT_4_BIT;
            att[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            att[0].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            att[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
            att[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            att[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
            att[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            att[1] = att[0];
            att[1].samples = VK_SAMPLE_COUNT_1_BIT;
            att[1].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
            att[1].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            att[1].finalLayout = kSrc;
            VkAttachmentReference cref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
            VkAttachmentReference rref{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
            VkSubpassDescription sp{};
            sp.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
            sp.colorAttachmentCount = 1;
            sp.pColorAttachments = &cref;
            sp.pResolveAttachments = &rref;
            VkSubpassDependency dep{0,
                                    VK_SUBPASS_EXTERNAL,
                                    VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                    VK_PIPELINE_STAGE_TRANSFER_BIT,
                                    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                    VK_ACCESS_TRANSFER_READ_BIT,
                                    0};
            VkRenderPassCreateInfo rpci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
            rpci.attachmentCount = 2;
            rpci.pAttachments = att;
            rpci.subpassCount = 1;
            rpci.pSubpasses = &sp;
            rpci.dependencyCount = 1;
            rpci.pDependencies = &dep;
            VkRenderPass rp;
            EXPECT_EQ(vkCreateRenderPass(dev, &rpci, nullptr, &rp), VK_SUCCESS);
            VkImageView views[2];
            VkImage imgs[2] = {ms.image, one.image};
            for (int i = 0; i < 2; ++i) {
                VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
                vci.image = imgs[i];
                vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
                vci.format = VK_FORMAT_R8G8B8A8_UNORM;
                vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                EXPECT_EQ(vkCreateImageView(dev, &vci, nullptr, &views[i]), VK_SUCCESS);
            }
            VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
            fci.renderPass = rp;
            fci.attachmentCount = 2;
            fci.pAttachments = views;
            fci.width = w;
            fci.height = h;
            fci.layers = 1;
            VkFramebuffer fb;
            EXPECT_EQ(vkCreateFramebuffer(dev, &fci, nullptr, &fb), VK_SUCCESS);
            d.run([&](VkCommandBuffer cb) {
                VkClearValue cv[2] = {};
                std::memcpy(cv[0].color.float32, col, sizeof col);
                VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
                bi.renderPass = rp;
                bi.framebuffer = fb;
                bi.renderArea = {{0, 0}, {w, h}};
                bi.clearValueCount = 2;
                bi.pClearValues = cv;
                vkCmdBeginRenderPass(cb, &bi, VK_SUBPASS_CONTENTS_INLINE);
                vkCmdEndRenderPass(cb);
                VkBufferImageCopy down{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
                vkCmdCopyImageToBuffer(cb, one.image, kSrc, buf.buffer, 1, &down);
            });
            Bytes out = read(buf);
            vkDestroyFramebuffer(dev, fb, nullptr);
            for (VkImageView v : views) vkDestroyImageView(dev, v, nullptr);
            vkDestroyRenderPass(dev, rp, nullptr);
            d.destroy(ms);
            d.destroy(one);
            d.destroy(buf);
            return out;
        };
        Bytes got = both(scenario);
        // Expected: each sample holds u = float_to_ubyte(c); the resolve sums fl(u * fl(1/255)) four times in float,
        // multiplies by 0.25 and converts with round-half-even(x * 255).
        for (int c = 0; c < 4; ++c) {
            const float t = float(expect_unorm8(col[c])) * (1.0f / 255.0f);
            float sum = 0.0f;
            for (int s = 0; s < 4; ++s) sum = sum + t;
            const uint8_t want = uint8_t(std::nearbyint((sum * 0.25f) * 255.0f));
            for (uint32_t p = 0; p < w * h; ++p) ASSERT_EQ(got[p * 4 + c], want) << "channel " << c;
        }
    }
}

// ---- partial render area + vkCmdClearAttachments ----------------------------------------------------------------
TEST_F(Transfer, RenderAreaClearAndClearAttachments) {
    const float c0[4] = {0.1f, 0.2f, 0.3f, 0.4f}, c1[4] = {0.9f, 0.8f, 0.7f, 0.6f}, c2[4] = {0.5f, 0.0f, 1.0f, 0.25f};
    // The second size spans several of tilevk's 64-row clear bands, with a render area starting and ending
    // inside a band (tilevk clears load ops in row bands on its worker threads).
    struct Size {
        uint32_t w, h;
        VkRect2D area, rect;
    };
    for (const Size& size : {Size{10, 7, {{2, 1}, {6, 4}}, {{4, 3}, {3, 2}}},
                             Size{150, 300, {{3, 61}, {140, 200}}, {{10, 70}, {50, 100}}}}) {
        SCOPED_TRACE(size.h);
        const uint32_t w = size.w, h = size.h;
        const VkRect2D area = size.area, rect = size.rect;
        auto scenario = [&](Device& d) {
            VkDevice dev = d.device();
            Device::Buffer buf = d.make_buffer(size_t(w) * h * 4);
            Device::Image img = d.make_image(VK_FORMAT_R8G8B8A8_UNORM, w, h, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                                             kXfer | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
            VkAttachmentDescription att{};
            att.format = VK_FORMAT_R8G8B8A8_UNORM;
            att.samples = VK_SAMPLE_COUNT_1_BIT;
            att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
            att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            att.initialLayout = kDst;
            att.finalLayout = kSrc;
            const std::vector<VkSubpassDependency> deps = {
                {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0},
                {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, 0}};
            SingleAttachmentPass pass(dev, img.image, att, VK_IMAGE_ASPECT_COLOR_BIT, w, h, deps);
            d.run([&](VkCommandBuffer cb) {
                transition(cb, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
                VkClearColorValue cv0;
                std::memcpy(cv0.float32, c0, sizeof c0);
                VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                vkCmdClearColorImage(cb, img.image, kDst, &cv0, 1, &all);
                VkClearValue cv1;
                std::memcpy(cv1.color.float32, c1, sizeof c1);
                VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
                bi.renderPass = pass.pass;
                bi.framebuffer = pass.framebuffer;
                bi.renderArea = area;
                bi.clearValueCount = 1;
                bi.pClearValues = &cv1;
                vkCmdBeginRenderPass(cb, &bi, VK_SUBPASS_CONTENTS_INLINE);
                VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
                std::memcpy(ca.clearValue.color.float32, c2, sizeof c2);
                VkClearRect cr{rect, 0, 1};
                vkCmdClearAttachments(cb, 1, &ca, 1, &cr);
                vkCmdEndRenderPass(cb);
                VkBufferImageCopy down{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
                vkCmdCopyImageToBuffer(cb, img.image, kSrc, buf.buffer, 1, &down);
            });
            Bytes out = read(buf);
            pass.destroy(dev);
            d.destroy(img);
            d.destroy(buf);
            return out;
        };
        Bytes got = both(scenario);
        auto inside = [](const VkRect2D& r, uint32_t x, uint32_t y) {
            return x >= uint32_t(r.offset.x) && x < r.offset.x + r.extent.width && y >= uint32_t(r.offset.y) &&
                   y < r.offset.y + r.extent.height;
        };
        for (uint32_t y = 0; y < h; ++y) {
            for (uint32_t x = 0; x < w; ++x) {
                const float* c = inside(rect, x, y) ? c2 : inside(area, x, y) ? c1 : c0;
                for (int k = 0; k < 4; ++k) ASSERT_EQ(got[(y * w + x) * 4 + k], expect_unorm8(c[k])) << x << "," << y;
            }
        }
    }
}

// ---- depth/stencil load-op clears over a partial render area, and a stencil-only image copy ---------------------
TEST_F(Transfer, DepthStencilRenderAreaClearAndStencilCopy) {
    const uint32_t w = 8, h = 6;
    const VkFormat fmt = VK_FORMAT_D32_SFLOAT_S8_UINT;
    const VkImageAspectFlags ds = VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    const VkRect2D area{{1, 2}, {5, 3}};
    const float z0 = 0.25f, z1 = 0.75f;
    const uint32_t s0 = 7, s1 = 200;
    auto scenario = [&](Device& d) {
        VkDevice dev = d.device();
        Device::Buffer buf = d.make_buffer(size_t(w) * h * 9);  // depth, other depth (4 B each), stencil (1 B)
        Device::Image img =
            d.make_image(fmt, w, h, 1, 1, VK_SAMPLE_COUNT_1_BIT, kXfer | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
        Device::Image other = d.make_image(fmt, w, h, 1, 1, VK_SAMPLE_COUNT_1_BIT, kXfer);
        VkAttachmentDescription att{};
        att.format = fmt;
        att.samples = VK_SAMPLE_COUNT_1_BIT;
        att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
        att.initialLayout = kDst;
        att.finalLayout = kSrc;
        const VkPipelineStageFlags frag =
            VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
        const std::vector<VkSubpassDependency> deps = {
            {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, frag, VK_ACCESS_TRANSFER_WRITE_BIT,
             VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, 0},
            {0, VK_SUBPASS_EXTERNAL, frag, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
             VK_ACCESS_TRANSFER_READ_BIT, 0}};
        SingleAttachmentPass pass(dev, img.image, att, ds, w, h, deps);
        d.run([&](VkCommandBuffer cb) {
            transition(cb, img.image, ds, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
            transition(cb, other.image, ds, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
            VkClearDepthStencilValue v0{z0, s0}, zero{0.0f, 0};
            VkImageSubresourceRange all{ds, 0, 1, 0, 1};
            vkCmdClearDepthStencilImage(cb, img.image, kDst, &v0, 1, &all);
            vkCmdClearDepthStencilImage(cb, other.image, kDst, &zero, 1, &all);
            VkClearValue cv;
            cv.depthStencil = {z1, s1};
            VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
            bi.renderPass = pass.pass;
            bi.framebuffer = pass.framebuffer;
            bi.renderArea = area;
            bi.clearValueCount = 1;
            bi.pClearValues = &cv;
            vkCmdBeginRenderPass(cb, &bi, VK_SUBPASS_CONTENTS_INLINE);
            vkCmdEndRenderPass(cb);
            // Stencil only into `other` (whose depth stays 0).
            VkImageCopy ic{{VK_IMAGE_ASPECT_STENCIL_BIT, 0, 0, 1},
                           {0, 0, 0},
                           {VK_IMAGE_ASPECT_STENCIL_BIT, 0, 0, 1},
                           {0, 0, 0},
                           {w, h, 1}};
            vkCmdCopyImage(cb, img.image, kSrc, other.image, kDst, 1, &ic);
            transition(cb, other.image, ds, kDst, kSrc);
            VkBufferImageCopy dd{0, 0, 0, {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
            vkCmdCopyImageToBuffer(cb, img.image, kSrc, buf.buffer, 1, &dd);
            VkBufferImageCopy od{w * h * 4, 0, 0, {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
            vkCmdCopyImageToBuffer(cb, other.image, kSrc, buf.buffer, 1, &od);
            VkBufferImageCopy os{w * h * 8, 0, 0, {VK_IMAGE_ASPECT_STENCIL_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
            vkCmdCopyImageToBuffer(cb, other.image, kSrc, buf.buffer, 1, &os);
        });
        Bytes out = read(buf);
        pass.destroy(dev);
        d.destroy(img);
        d.destroy(other);
        d.destroy(buf);
        return out;
    };
    // Named difference: lavapipe's vkCmdCopyImage ignores aspectMask for depth/stencil formats (it calls
    // resource_copy_region on whole texels), so its stencil-only copy also copies depth. tilevk follows the spec
    // and copies only the stencil. Everything else must match byte for byte.
    Bytes got = scenario(*tilevk_), lvp = scenario(*lavapipe_);
    ASSERT_EQ(got.size(), lvp.size());
    const size_t other_depth = size_t(w) * h * 4, stencil = size_t(w) * h * 8;
    EXPECT_TRUE(std::equal(got.begin(), got.begin() + other_depth, lvp.begin())) << "depth differs";
    EXPECT_TRUE(std::equal(got.begin() + stencil, got.end(), lvp.begin() + stencil)) << "stencil differs";
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const bool in = x >= 1 && x < 6 && y >= 2 && y < 5;
            const size_t i = y * w + x;
            float z, oz, lvp_oz;
            std::memcpy(&z, &got[i * 4], 4);
            std::memcpy(&oz, &got[other_depth + i * 4], 4);
            std::memcpy(&lvp_oz, &lvp[other_depth + i * 4], 4);
            EXPECT_EQ(z, in ? z1 : z0) << x << "," << y;
            EXPECT_EQ(oz, 0.0f) << "tilevk: a stencil-only copy must not touch depth";
            EXPECT_EQ(lvp_oz, in ? z1 : z0) << "lavapipe's known whole-texel copy changed; revisit the note";
            EXPECT_EQ(got[stencil + i], in ? s1 : s0) << x << "," << y;
        }
    }
}

}  // namespace
