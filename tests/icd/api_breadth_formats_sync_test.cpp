// API breadth (api_breadth.h): format honesty (every reported format works, image format properties match
// the features) and synchronisation / error paths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "api_breadth.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {

#include "ab_sample_mips_frag.h"  // only this file's test samples with it

namespace {

// ---- Format honesty --------------------------------------------------------------------------------------------

struct FormatCounts {
    int colour = 0, depth = 0, sampled = 0;
};
// Runs a scene on tilevk and lavapipe and expects the same bytes (ApiBreadth::both, or both_on on devices of a test).
using BothDrivers = std::function<void(const std::function<Bytes(Kit&)>&)>;

// Format `f`, whose optimal-tiling features on tilevk are `t`, renders (COLOR_ATTACHMENT, + BLEND,
// DEPTH_STENCIL_ATTACHMENT), samples and filters exactly as on lavapipe.
void expect_format_works(VkFormat f, VkFormatFeatureFlags t, const BothDrivers& both, FormatCounts& n) {
    if (t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) {
        ++n.colour;
        SCOPED_TRACE("colour attachment");
        const bool blend = t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
        both([&](Kit& k) {
            Target tg = target(k, f);
            Pipe p;
            p.rp = tg.rp;
            p.blend = {blend ? alpha_over() : opaque()};
            if (is_uint_format(f)) p.fs = SPV(ab_color_uint_frag);
            if (is_sint_format(f)) p.fs = SPV(ab_color_sint_frag);
            VkPipeline pipe = k.pipeline(p);
            Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                draw_vertices(c, tg, pipe, vb, 6, clear_color(0.1f, 0.2f, 0.3f, 0.4f));
            }),
                      VK_SUCCESS);
            return k.read(tg.image.image, 32, 32, texel_bytes(f, VK_IMAGE_ASPECT_COLOR_BIT));
        });
    }
    if (t & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
        ++n.depth;
        SCOPED_TRACE("depth/stencil attachment");
        both([&](Kit& k) {
            const auto [col, dep, rp, fb] = depth_target(k, f);
            VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
            ds.stencilTestEnable = has_stencil(f);
            ds.front = ds.back = {VK_STENCIL_OP_KEEP,
                                  VK_STENCIL_OP_REPLACE,
                                  VK_STENCIL_OP_INCREMENT_AND_CLAMP,
                                  VK_COMPARE_OP_ALWAYS,
                                  0xff,
                                  0xff,
                                  0x5a};
            Pipe p;
            p.rp = rp;
            p.ds = &ds;
            VkPipeline pipe = k.pipeline(p);
            Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(0.7f, 3)});
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                bind_vertices(c, vb);
                vkCmdDraw(c, 6, 1, 0, 0);
                vkCmdEndRenderPass(c);
            }),
                      VK_SUCCESS);
            Bytes out = k.read(col.image, 32, 32, 4);
            if (f != VK_FORMAT_S8_UINT)
                out = concat({out, k.read(dep.image, 32, 32, texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT),
                                          VK_IMAGE_ASPECT_DEPTH_BIT)});
            if (has_stencil(f)) out = concat({out, k.read(dep.image, 32, 32, 1, VK_IMAGE_ASPECT_STENCIL_BIT)});
            return out;
        });
    }
    if (t & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) {
        ++n.sampled;
        SCOPED_TRACE("sampled image");
        both([&](Kit& k) {
            return sample_4x4(k, f,
                              is_uint_format(f)   ? SPV(ab_sample_uint_frag)
                              : is_sint_format(f) ? SPV(ab_sample_sint_frag)
                                                  : SPV(ab_sample_frag));
        });
    }
    if (t & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) {
        SCOPED_TRACE("linear filtering");
        both([&](Kit& k) {  // bilinear footprints near and past the edges (REPEAT and CLAMP_TO_EDGE)
            Bytes out;
            for (VkSamplerAddressMode mode : {VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE}) {
                Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 8, 8);
                Device::Image tex = k.image(f, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
                Device::Buffer src = k.buffer_of(texel_data(f, 16, uint32_t(f) + 77), 0);
                upload(k, src, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, 4, 4);
                const auto [dsl, layout, set] = sampler_set(k);
                VkDescriptorImageInfo ii{k.sampler(VK_FILTER_LINEAR, mode),
                                         k.view(tex.image, f, VK_IMAGE_ASPECT_COLOR_BIT),
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
                k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
                const Pipe p = fullscreen_pipe(SPV(ab_sample_edges_frag), tg, layout);
                VkPipeline pipe = k.pipeline(p);
                EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
                out = concat({out, k.read(tg.image.image, 8, 8, 16)});
            }
            return out;
        });
    }
}

// Every format tilevk reports as COLOR_ATTACHMENT (+BLEND), DEPTH_STENCIL_ATTACHMENT or SAMPLED_IMAGE renders /
// samples exactly as on lavapipe; lavapipe must report the same feature (else the test could not compare).
TEST_F(ApiBreadth, EveryReportedImageFormatWorks) {
    FormatCounts n;
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        const VkFormat f = VkFormat(fi);
        VkFormatProperties tp, lp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &tp);
        vkGetPhysicalDeviceFormatProperties(lavapipe_->physical(), f, &lp);
        const VkFormatFeatureFlags t = tp.optimalTilingFeatures;
        if (t == 0) continue;
        // BC blocks are not texels this test can render or upload: cts texture.bc.* samples them and TransferBc
        // copies them against lavapipe; only the feature subset is checked here
        if (f >= VK_FORMAT_BC1_RGB_UNORM_BLOCK && f <= VK_FORMAT_BC7_SRGB_BLOCK) {
            EXPECT_EQ(t & ~lp.optimalTilingFeatures, 0u) << "tilevk reports features lavapipe lacks, format " << fi;
            continue;
        }
        SCOPED_TRACE("format " + std::to_string(fi));
        EXPECT_EQ(t & ~lp.optimalTilingFeatures, 0u) << "tilevk reports features lavapipe lacks";
        ASSERT_NE(texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT), 0u) << "the test does not know this format";
        expect_format_works(
            f, t, [this](const std::function<Bytes(Kit&)>& scene) { both(scene); }, n);
    }
    EXPECT_GT(n.colour, 0);
    EXPECT_GT(n.depth, 0);
    EXPECT_GT(n.sampled, 0);
}

// VK_EXT_4444_formats: both drivers offer it with both features; on devices that enable them, A4R4G4B4 and
// A4B4G4R4_UNORM_PACK16 report lavapipe's image features (no buffer features) and render, blend, sample and filter as
// on lavapipe.
TEST_F(ApiBreadth, Formats4444WorkLikeLavapipe) {
    VkPhysicalDevice4444FormatsFeaturesEXT want{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_4444_FORMATS_FEATURES_EXT};
    for (Device* dev : {tilevk_.get(), lavapipe_.get()}) {
        VkPhysicalDevice4444FormatsFeaturesEXT got{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_4444_FORMATS_FEATURES_EXT};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &got};
        vkGetPhysicalDeviceFeatures2(dev->physical(), &f2);
        EXPECT_EQ(got.formatA4R4G4B4, VK_TRUE);
        EXPECT_EQ(got.formatA4B4G4R4, VK_TRUE);
    }
    want.formatA4R4G4B4 = want.formatA4B4G4R4 = VK_TRUE;
    auto d = device_pair({VK_EXT_4444_FORMATS_EXTENSION_NAME}, &want);
    ASSERT_TRUE(d->ok());
    FormatCounts n;
    for (VkFormat f : {VK_FORMAT_A4R4G4B4_UNORM_PACK16, VK_FORMAT_A4B4G4R4_UNORM_PACK16}) {
        SCOPED_TRACE("format " + std::to_string(int(f)));
        VkFormatProperties tp, lp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &tp);
        vkGetPhysicalDeviceFormatProperties(lavapipe_->physical(), f, &lp);
        EXPECT_EQ(tp.optimalTilingFeatures, lp.optimalTilingFeatures);
        EXPECT_EQ(tp.linearTilingFeatures, lp.linearTilingFeatures);
        // lavapipe also offers uniform texel and vertex buffers of them, which tilevk does not report (yet)
        EXPECT_EQ(tp.bufferFeatures, 0u);
        expect_format_works(
            f, tp.optimalTilingFeatures,
            [&](const std::function<Bytes(Kit&)>& scene) { both_on(d->tilevk, d->lavapipe, scene); }, n);
    }
    EXPECT_EQ(n.colour, 2);
    EXPECT_EQ(n.sampled, 2);
}

// Half-float texels that are NaN (signalling and quiet, with payloads), infinite, zero or denormal, sampled into an
// RGBA32F target: lavapipe converts them as VCVTPH2PS does (signalling NaNs quieted, payload kept), and so must
// tilevk's texel codec; the bytes of the float target carry every NaN payload bit. (-0 is left out: the shader's
// `texture(...) + v_color * 0.0` is folded away by NIR's inexact algebraic rules in lavapipe, keeping -0, while
// tilevk evaluates it, giving +0 — a shader-arithmetic difference, not a texel conversion.)
TEST_F(ApiBreadth, HalfTexelSpecialsSampleLikeLavapipe) {
    const uint16_t specials[] = {0x7c01, 0x7d55, 0xfc01, 0xfdff, 0x7e00, 0x7e01, 0x7fff, 0xffff,
                                 0x7c00, 0xfc00, 0x0000, 0x8001, 0x0001, 0x03ff, 0x83ff, 0x7bff};
    const Bytes data = half_specials(specials);
    const VkFormat f = VK_FORMAT_R16G16B16A16_SFLOAT;
    const Bytes out = both([&](Kit& k) {
        Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
        Device::Image tex = k.image(f, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        Device::Buffer src = k.buffer_of(data, 0);
        upload(k, src, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, 4, 4);
        const auto [dsl, layout, set] = sampler_set(k);
        VkDescriptorImageInfo ii{k.sampler(), k.view(tex.image, f, VK_IMAGE_ASPECT_COLOR_BIT),
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        const Pipe p = fullscreen_pipe(SPV(ab_sample_frag), tg, layout);
        VkPipeline pipe = k.pipeline(p);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
        return k.read(tg.image.image, 4, 4, 16);
    });
    expect_signalling_half_nan_quieted(data, out);
}

// Bilinear CLAMP_TO_EDGE sampling near and past the edges of a float texture holding infinities: lavapipe clamps
// the scaled coordinate to [0.5, n - 0.5] before the filter (lp_bld_sample_soa.c lp_build_sample_wrap_linear), so
// next to an edge it lerps texels 0 and 1 with weight 0 — an infinite texel 1 then makes the result NaN — where
// clamping the two texel indices instead would read texel 0 twice.
TEST_F(ApiBreadth, LinearClampToEdgeNearInfinitiesLikeLavapipe) {
    const VkFormat f = VK_FORMAT_R32G32B32A32_SFLOAT;
    std::vector<uint8_t> data(16 * 16);
    for (size_t i = 0; i < 64; ++i) {
        const float x = float(int(i * 37 % 41) - 20) / 8.0f;
        std::memcpy(&data[4 * i], &x, 4);
    }
    const float inf = INFINITY;
    for (size_t texel : {1u, 4u, 7u, 13u}) std::memcpy(&data[16 * texel + 4 * (texel % 4)], &inf, 4);
    both([&](Kit& k) {
        Target tg = target(k, f, 8, 8);
        Device::Image tex = k.image(f, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        Device::Buffer src = k.buffer_of(data, 0);
        upload(k, src, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, 4, 4);
        const auto [dsl, layout, set] = sampler_set(k);
        VkDescriptorImageInfo ii{k.sampler(VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
                                 k.view(tex.image, f, VK_IMAGE_ASPECT_COLOR_BIT),
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        const Pipe p = fullscreen_pipe(SPV(ab_sample_edges_frag), tg, layout);
        VkPipeline pipe = k.pipeline(p);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
        return k.read(tg.image.image, 8, 8, 16);
    });
}

// A w x h image of `f` with `levels` mip levels, every level filled with distinct bytes, left SHADER_READ_ONLY.
Device::Image mip_texture(Kit& k, VkFormat f, uint32_t w, uint32_t h, uint32_t levels, uint32_t seed) {
    Device::Image tex = k.image(f, w, h, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, levels);
    std::vector<VkBufferImageCopy> regions;
    VkDeviceSize size = 0;
    for (uint32_t l = 0; l < levels; ++l) {
        VkBufferImageCopy r{};
        r.bufferOffset = size;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
        r.imageExtent = {std::max(1u, w >> l), std::max(1u, h >> l), 1};
        regions.push_back(r);
        size += VkDeviceSize(r.imageExtent.width) * r.imageExtent.height * 4;
    }
    Device::Buffer src = k.buffer(size);
    auto* p = static_cast<uint8_t*>(src.map);
    for (size_t i = 0; i < size; ++i) p[i] = uint8_t((i * 29 + seed * 83 + (i >> 6) * 7) & 255);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        transition(c, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(c, src.buffer, tex.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()),
                               regions.data());
        transition(c, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }),
              VK_SUCCESS);
    return tex;
}

// Trilinear RGBA8/BGRA8 sampling (the compiled tier's RGBA8 sampler, whose per-level table each image view keeps)
// with descriptor sets that alternate draw by draw in one render pass: views of other sizes, level counts and
// formats, a view of the same image from its third level, the same sizes in another image, REPEAT and
// CLAMP_TO_EDGE with a LOD bias; then a set rewritten to another view between two submissions. Each draw fills one
// quadrant (dynamic scissor), the LOD varies across it (ab_sample_mips.frag). Bytes equal to lavapipe's.
TEST_F(ApiBreadth, Rgba8ViewsAlternateBetweenDrawsLikeLavapipe) {
    both([&](Kit& k) {
        Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 64, 64);
        const VkFormat rgba = VK_FORMAT_R8G8B8A8_UNORM, bgra = VK_FORMAT_B8G8R8A8_UNORM;
        Device::Image a = mip_texture(k, rgba, 64, 64, 7, 1), b = mip_texture(k, bgra, 32, 16, 4, 2),
                      c = mip_texture(k, rgba, 64, 64, 3, 3);
        const VkImageAspectFlags col = VK_IMAGE_ASPECT_COLOR_BIT;
        const VkImageView views[4] = {k.view(a.image, rgba, col, VK_IMAGE_VIEW_TYPE_2D, 0, 7),
                                      k.view(b.image, bgra, col, VK_IMAGE_VIEW_TYPE_2D, 0, 4),
                                      k.view(a.image, rgba, col, VK_IMAGE_VIEW_TYPE_2D, 2, 5),
                                      k.view(c.image, rgba, col, VK_IMAGE_VIEW_TYPE_2D, 0, 3)};
        VkSampler samplers[2];
        for (int i = 0; i < 2; ++i) {
            VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
            ci.magFilter = ci.minFilter = VK_FILTER_LINEAR;
            ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
            ci.addressModeU = ci.addressModeV = ci.addressModeW =
                i == 0 ? VK_SAMPLER_ADDRESS_MODE_REPEAT : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
            ci.mipLodBias = i == 0 ? 0.0f : 0.6f;
            ci.maxLod = 16.0f;
            EXPECT_EQ(vkCreateSampler(k.d, &ci, nullptr, &samplers[i]), VK_SUCCESS);
            k.undo(VK_OBJECT_TYPE_SAMPLER, samplers[i], [&k, s = samplers[i]] { vkDestroySampler(k.d, s, nullptr); });
        }
        const VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
        const VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet sets[4];
        for (int i = 0; i < 4; ++i) {
            sets[i] = k.descriptor_set(dsl);
            VkDescriptorImageInfo ii{samplers[(i + i / 2) % 2], views[i], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            k.write(sets[i], 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        }
        Pipe p = fullscreen_pipe(SPV(ab_sample_mips_frag), tg, layout);
        p.dynamic = {VK_DYNAMIC_STATE_SCISSOR};
        VkPipeline pipe = k.pipeline(p);
        auto frame = [&] {
            EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
                begin_pass(cb, tg.rp, tg.fb, tg.w, tg.h, {clear_color(-1, -1, -1, -1)});
                vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                for (int d = 0; d < 8; ++d) {  // quadrants in two rounds, the sets in another order each round
                    const int q = d % 4, set = d < 4 ? d : 3 - q;
                    const VkRect2D r{{int32_t(q % 2) * 32, int32_t(q / 2) * 32 + (d < 4 ? 0 : 16)}, {32, 16}};
                    vkCmdSetScissor(cb, 0, 1, &r);
                    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &sets[set], 0, nullptr);
                    vkCmdDraw(cb, 3, 1, 0, 0);
                }
                vkCmdEndRenderPass(cb);
            }),
                      VK_SUCCESS);
            return k.read(tg.image.image, 64, 64, 16);
        };
        const Bytes first = frame();
        VkDescriptorImageInfo ii{samplers[1], views[2], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(sets[0], 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        return concat({first, frame()});
    });
}

// vkGetPhysicalDeviceImageFormatProperties says VK_ERROR_FORMAT_NOT_SUPPORTED for every usage whose format feature
// is not reported (and for formats with no features at all), and what it accepts, vkCreateImage makes.
TEST_F(ApiBreadth, ImageFormatPropertiesMatchFeatures) {
    VkPhysicalDevice pd = tilevk_->physical();
    const std::pair<VkImageUsageFlags, VkFormatFeatureFlags> usages[] = {
        {VK_IMAGE_USAGE_SAMPLED_BIT, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT},
        {VK_IMAGE_USAGE_STORAGE_BIT, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT},
        {VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT},
        {VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT},
        {VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_FORMAT_FEATURE_TRANSFER_SRC_BIT},
        {VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_FORMAT_FEATURE_TRANSFER_DST_BIT}};
    int accepted = 0;
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        const VkFormat f = VkFormat(fi);
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, f, &fp);
        for (auto [usage, feature] : usages) {
            VkImageFormatProperties ip;
            const VkResult r = vkGetPhysicalDeviceImageFormatProperties(pd, f, VK_IMAGE_TYPE_2D,
                                                                        VK_IMAGE_TILING_OPTIMAL, usage, 0, &ip);
            if (!(fp.optimalTilingFeatures & feature)) {
                EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << "format " << fi << " usage " << usage;
                continue;
            }
            EXPECT_EQ(r, VK_SUCCESS) << "format " << fi << " usage " << usage;
            if (r != VK_SUCCESS) continue;
            ++accepted;
            Device::Image img = tilevk_->make_image(f, 16, 8, 1, 1, VK_SAMPLE_COUNT_1_BIT, usage);
            EXPECT_NE(img.image, VK_NULL_HANDLE) << "format " << fi << " usage " << usage;
            if (img.image) tilevk_->destroy(img);
        }
    }
    EXPECT_GT(accepted, 20);
    // LINEAR tiling: what the linear features do not have is refused too.
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, VkFormat(fi), &fp);
        for (auto [usage, feature] : usages) {
            VkImageFormatProperties ip;
            const VkResult r = vkGetPhysicalDeviceImageFormatProperties(pd, VkFormat(fi), VK_IMAGE_TYPE_2D,
                                                                        VK_IMAGE_TILING_LINEAR, usage, 0, &ip);
            if (!(fp.linearTilingFeatures & feature))
                EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << "linear format " << fi << " usage " << usage;
            else
                EXPECT_EQ(r, VK_SUCCESS) << "linear format " << fi << " usage " << usage;
        }
    }
    // Input attachments: every colour-attachment format may be one (it is read by a texel fetch); a depth format
    // only when it is also sampled; never multisampled. What is accepted, vkCreateImage makes.
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        const VkFormat f = VkFormat(fi);
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, f, &fp);
        const VkFormatFeatureFlags t = fp.optimalTilingFeatures;
        const VkImageUsageFlags att = (t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT)
                                          ? VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT
                                          : VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        const VkImageUsageFlags usage = att | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
        VkImageFormatProperties ip;
        const VkResult r =
            vkGetPhysicalDeviceImageFormatProperties(pd, f, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, usage, 0, &ip);
        const bool attachment =
            t & (VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT);
        if (!attachment) {
            EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << "format " << fi;
            continue;
        }
        if (t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) {
            EXPECT_EQ(r, VK_SUCCESS) << "colour format " << fi;
        }
        if (r != VK_SUCCESS) continue;
        EXPECT_EQ(ip.sampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT)) << "format " << fi;
        Device::Image img = tilevk_->make_image(f, 16, 8, 1, 1, VK_SAMPLE_COUNT_1_BIT, usage);
        EXPECT_NE(img.image, VK_NULL_HANDLE) << "format " << fi;
        if (img.image) tilevk_->destroy(img);
    }
}

// ---- Synchronisation and error paths ---------------------------------------------------------------------------

// Fences (signalled at creation, reset, waited with and without timeout), a semaphore between two submissions,
// events set by the host and by a command buffer, vkCmdWaitEvents, queue/device idle: same results on both.
TEST_F(ApiBreadth, FencesSemaphoresEvents) {
    both([](Kit& k) {
        Bytes log;
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        VkFence fence;
        EXPECT_EQ(vkCreateFence(k.d, &fci, nullptr, &fence), VK_SUCCESS);
        log.push_back(uint8_t(vkGetFenceStatus(k.d, fence)));  // VK_SUCCESS
        EXPECT_EQ(vkResetFences(k.d, 1, &fence), VK_SUCCESS);
        log.push_back(uint8_t(vkGetFenceStatus(k.d, fence)));                 // VK_NOT_READY
        log.push_back(uint8_t(vkWaitForFences(k.d, 1, &fence, VK_TRUE, 0)));  // VK_TIMEOUT
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore sem;
        EXPECT_EQ(vkCreateSemaphore(k.d, &sci, nullptr, &sem), VK_SUCCESS);
        VkEventCreateInfo eci{VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
        VkEvent host_ev, dev_ev;
        EXPECT_EQ(vkCreateEvent(k.d, &eci, nullptr, &host_ev), VK_SUCCESS);
        EXPECT_EQ(vkCreateEvent(k.d, &eci, nullptr, &dev_ev), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, host_ev)));  // VK_EVENT_RESET
        EXPECT_EQ(vkSetEvent(k.d, host_ev), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, host_ev)));  // VK_EVENT_SET
        Device::Buffer buf = k.buffer(256);
        VkCommandBuffer a = k.command_buffer(), b = k.command_buffer();
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(a, &bi);
        vkCmdFillBuffer(a, buf.buffer, 0, 64, 0x01020304u);
        vkCmdSetEvent(a, dev_ev, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkEndCommandBuffer(a);
        vkBeginCommandBuffer(b, &bi);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_HOST_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        VkEvent evs[2] = {host_ev, dev_ev};
        vkCmdWaitEvents(b, 2, evs, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, 1, &mb, 0, nullptr, 0, nullptr);
        VkBufferCopy region{0, 128, 64};
        vkCmdCopyBuffer(b, buf.buffer, buf.buffer, 1, &region);
        vkCmdResetEvent(b, host_ev, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkEndCommandBuffer(b);
        VkSubmitInfo s1{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        s1.commandBufferCount = 1;
        s1.pCommandBuffers = &a;
        s1.signalSemaphoreCount = 1;
        s1.pSignalSemaphores = &sem;
        VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        VkSubmitInfo s2{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        s2.waitSemaphoreCount = 1;
        s2.pWaitSemaphores = &sem;
        s2.pWaitDstStageMask = &wait_stage;
        s2.commandBufferCount = 1;
        s2.pCommandBuffers = &b;
        EXPECT_EQ(vkQueueSubmit(k.queue, 1, &s1, VK_NULL_HANDLE), VK_SUCCESS);
        EXPECT_EQ(vkQueueSubmit(k.queue, 1, &s2, fence), VK_SUCCESS);
        log.push_back(uint8_t(vkWaitForFences(k.d, 1, &fence, VK_TRUE, UINT64_MAX)));
        log.push_back(uint8_t(vkGetFenceStatus(k.d, fence)));
        EXPECT_EQ(vkQueueWaitIdle(k.queue), VK_SUCCESS);
        EXPECT_EQ(vkDeviceWaitIdle(k.d), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, dev_ev)));   // set by command buffer a
        log.push_back(uint8_t(vkGetEventStatus(k.d, host_ev)));  // reset by command buffer b
        EXPECT_EQ(vkResetEvent(k.d, dev_ev), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, dev_ev)));
        // An empty submission only signals its fence.
        EXPECT_EQ(vkResetFences(k.d, 1, &fence), VK_SUCCESS);
        EXPECT_EQ(vkQueueSubmit(k.queue, 0, nullptr, fence), VK_SUCCESS);
        log.push_back(uint8_t(vkWaitForFences(k.d, 1, &fence, VK_TRUE, UINT64_MAX)));
        vkDestroyEvent(k.d, host_ev, nullptr);
        vkDestroyEvent(k.d, dev_ev, nullptr);
        vkDestroySemaphore(k.d, sem, nullptr);
        vkDestroyFence(k.d, fence, nullptr);
        const Bytes data = Kit::bytes(buf);
        EXPECT_EQ(data[128], 4);  // the copy after the wait saw the fill
        EXPECT_EQ(log[1], uint8_t(VK_NOT_READY));
        EXPECT_EQ(log[2], uint8_t(VK_TIMEOUT));
        EXPECT_EQ(log[7], uint8_t(VK_EVENT_SET));
        EXPECT_EQ(log[8], uint8_t(VK_EVENT_RESET));
        return concat({log, data});
    });
}

// Error paths on tilevk without the validation layer (these calls are valid but must fail cleanly): an allocation
// larger than the heap, a geometry stage, a compute pipeline whose workgroup is larger than
// maxComputeWorkGroupInvocations; each returns an error code and a null handle, and the device keeps working.
TEST_F(ApiBreadth, ErrorPathsFailCleanly) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    Device dev(plain.find_device("tilevk"));
    ASSERT_TRUE(dev.ok());
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(dev.physical(), &mp);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = mp.memoryHeaps[0].size + 4096;
    ai.memoryTypeIndex = 0;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateMemory(dev.device(), &ai, nullptr, &mem), VK_ERROR_OUT_OF_DEVICE_MEMORY);
    ai.allocationSize = uint64_t(1) << 62;
    EXPECT_EQ(vkAllocateMemory(dev.device(), &ai, nullptr, &mem), VK_ERROR_OUT_OF_DEVICE_MEMORY);
    {
        Kit k(dev);
        Target t = target(k);
        // Compute pipeline past the workgroup limits: refused.
        VkResult cr = VK_SUCCESS;
        VkPipeline cp = compute_pipeline(k, SPV(ab_compute_comp), k.empty_layout(), nullptr, &cr);
        EXPECT_NE(cr, VK_SUCCESS);
        EXPECT_EQ(cp, VK_NULL_HANDLE);
        // A geometry stage (the feature is not reported; without the layer nothing stops the call): refused.
        {
            VkPipelineShaderStageCreateInfo st[3] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                     {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                     {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
            const VkShaderStageFlagBits stages[3] = {VK_SHADER_STAGE_VERTEX_BIT, VK_SHADER_STAGE_GEOMETRY_BIT,
                                                     VK_SHADER_STAGE_FRAGMENT_BIT};
            const Spv code[3] = {SPV(draw_vert), SPV(ab_passthrough_geom), SPV(color_frag)};
            for (int i = 0; i < 3; ++i) {
                st[i].stage = stages[i];
                st[i].module = k.shader(code[i]);
                st[i].pName = "main";
            }
            VkVertexInputBindingDescription vb{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
            VkVertexInputAttributeDescription va[2] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                                       {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16}};
            VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
            vi.vertexBindingDescriptionCount = 1;
            vi.pVertexBindingDescriptions = &vb;
            vi.vertexAttributeDescriptionCount = 2;
            vi.pVertexAttributeDescriptions = va;
            VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
            ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
            VkViewport vp{0, 0, 32, 32, 0, 1};
            VkRect2D sc{{0, 0}, {32, 32}};
            VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
            vps.viewportCount = vps.scissorCount = 1;
            vps.pViewports = &vp;
            vps.pScissors = &sc;
            VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
            rs.lineWidth = 1.0f;
            VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
            ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
            VkPipelineColorBlendAttachmentState cba = opaque();
            VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
            cb.attachmentCount = 1;
            cb.pAttachments = &cba;
            VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
            gci.stageCount = 3;
            gci.pStages = st;
            gci.pVertexInputState = &vi;
            gci.pInputAssemblyState = &ia;
            gci.pViewportState = &vps;
            gci.pRasterizationState = &rs;
            gci.pMultisampleState = &ms;
            gci.pColorBlendState = &cb;
            gci.layout = k.empty_layout();
            gci.renderPass = t.rp;
            VkPipeline gp = VK_NULL_HANDLE;
            EXPECT_NE(vkCreateGraphicsPipelines(k.d, VK_NULL_HANDLE, 1, &gci, nullptr, &gp), VK_SUCCESS);
            EXPECT_EQ(gp, VK_NULL_HANDLE);
        }
        // The device still draws.
        Pipe ok;
        ok.rp = t.rp;
        VkPipeline good = k.pipeline(ok);
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_vertices(c, t, good, vb, 3, clear_color(0, 0, 0.25f, 1)); }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(px(b, 10, 12)[2], 64);
    }
    EXPECT_EQ(vkDeviceWaitIdle(dev.device()), VK_SUCCESS);
}

// What the issue found accepted silently, refused now (no validation layer: invalid usage on purpose): a pipeline
// for dynamic rendering (no render pass, VkPipelineRenderingCreateInfo) on a device without the dynamicRendering
// feature enabled (ApiDynamicRendering.RefusalsWithoutTheFeatures checks its message), and a
// buffer view on a STORAGE_TEXEL_BUFFER buffer in a format without the feature (R5G6B5_UNORM_PACK16). The same requests
// with a render pass / a UNIFORM_TEXEL_BUFFER buffer succeed.
TEST_F(ApiBreadth, DynamicRenderingPipelinesAndStorageTexelViewsAreRefused) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    Device dev(plain.find_device("tilevk"));
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    Target t = target(k);
    const VkFormat color = VK_FORMAT_R8G8B8A8_UNORM;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &color;
    Pipe p;
    p.pnext = &rendering;
    VkResult r = VK_SUCCESS;
    EXPECT_EQ(k.pipeline(p, &r), VkPipeline(VK_NULL_HANDLE));
    EXPECT_EQ(r, VK_ERROR_INITIALIZATION_FAILED);
    p.pnext = nullptr;
    p.rp = t.rp;
    EXPECT_NE(k.pipeline(p, &r), VkPipeline(VK_NULL_HANDLE));
    EXPECT_EQ(r, VK_SUCCESS);

    for (VkBufferUsageFlags usage : {VkBufferUsageFlags(VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT),
                                     VkBufferUsageFlags(VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT)}) {
        Device::Buffer b = dev.make_buffer(256, usage);
        VkBufferViewCreateInfo vci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
        vci.buffer = b.buffer;
        vci.format = VK_FORMAT_R5G6B5_UNORM_PACK16;
        vci.range = VK_WHOLE_SIZE;
        VkBufferView view = VK_NULL_HANDLE;
        const VkResult vr = vkCreateBufferView(dev.device(), &vci, nullptr, &view);
        if (usage == VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT) {
            EXPECT_EQ(vr, VK_ERROR_FORMAT_NOT_SUPPORTED);
        } else {
            EXPECT_EQ(vr, VK_SUCCESS);
            vkDestroyBufferView(dev.device(), view, nullptr);
        }
        dev.destroy(b);
    }
}

// maxFragmentDualSrcAttachments is 1 (as lavapipe): a VK_BLEND_FACTOR_SRC1_* factor blends with the fragment output
// of Location 0, Index 1, which only attachment 0 can use. The same blend state on attachment 1 of a two-colour
// pass is refused by name (no validation layer: invalid usage on purpose), on attachment 0 it is accepted.
TEST_F(ApiBreadth, DualSourceFactorsOnlyOnAttachmentZero) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    VkPhysicalDeviceFeatures features{};
    features.dualSrcBlend = VK_TRUE;
    Device dev(plain.find_device("tilevk"), &features);
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    const VkAttachmentDescription colour =
        attachment(VK_FORMAT_R8G8B8A8_UNORM, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE);
    const VkAttachmentReference refs[2] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                           {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 2;
    sub.pColorAttachments = refs;
    Pipe p;
    p.rp = k.render_pass({colour, colour}, {sub});
    p.color_count = 2;
    const VkPipelineColorBlendAttachmentState dual = blend_add(
        VK_BLEND_FACTOR_SRC1_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ZERO);
    for (uint32_t on : {1u, 0u}) {
        p.blend = {opaque(), opaque()};
        p.blend[on] = dual;
        StderrCapture capture;
        VkResult r = VK_SUCCESS;
        const VkPipeline pipe = k.pipeline(p, &r);
        if (on == 1) {
            EXPECT_EQ(pipe, VkPipeline(VK_NULL_HANDLE));
            EXPECT_NE(r, VK_SUCCESS);
            EXPECT_NE(capture.text().find("pColorBlendAttachments[1]"), std::string::npos) << capture.text();
            EXPECT_NE(capture.text().find("maxFragmentDualSrcAttachments"), std::string::npos) << capture.text();
        } else {
            EXPECT_NE(pipe, VkPipeline(VK_NULL_HANDLE));
            EXPECT_EQ(r, VK_SUCCESS) << capture.text();
        }
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
