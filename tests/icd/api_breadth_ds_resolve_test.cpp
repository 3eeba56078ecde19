// VK_KHR_depth_stencil_resolve (suite ApiDepthStencilResolve): a 4x depth/stencil attachment whose four samples hold
// four known values (four full-screen draws, each with pSampleMask = one sample, depth compare ALWAYS, stencil
// REPLACE with its own reference) and a partial triangle on top (edge pixels with mixed coverage), resolved at the
// end of the subpass (VkSubpassDescriptionDepthStencilResolve) with SAMPLE_ZERO, read back: tilevk's bytes equal
// lavapipe's (validation layer on), and at a pixel the triangle misses each equals sample 0's value, which the test
// checks is not the average. AVERAGE is not offered (lavapipe 22.3's returns sample 0: icd/physical_device.h).
// The refusals (tilevk alone): invalid mode combinations and what tilevk does not resolve, by name.
#include "api_breadth.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

using tilevk::test::stderr_of;

const std::vector<const char*> kExtensions = {
    VK_KHR_MULTIVIEW_EXTENSION_NAME, VK_KHR_MAINTENANCE_2_EXTENSION_NAME, VK_KHR_CREATE_RENDERPASS_2_EXTENSION_NAME,
    VK_KHR_DEPTH_STENCIL_RESOLVE_EXTENSION_NAME, VK_KHR_SEPARATE_DEPTH_STENCIL_LAYOUTS_EXTENSION_NAME};

// The four samples' depths (each times 2^16-1 and 2^24-1 an integer, so D16 and D24 store them without rounding
// questions) and stencil references. Their average, 0.5, is no sample's.
constexpr float kSampleDepth[4] = {0.2f, 0.4f, 0.6f, 0.8f};
constexpr uint32_t kSampleStencil[4] = {3, 70, 141, 250};
constexpr uint32_t kSize = 32;

VkImageAspectFlags aspects_of(VkFormat f) {
    if (f == VK_FORMAT_S8_UINT) return VK_IMAGE_ASPECT_STENCIL_BIT;
    if (f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT)
        return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    return VK_IMAGE_ASPECT_DEPTH_BIT;
}

// A render pass of one subpass: attachment 0 the 4x depth/stencil attachment (load op CLEAR), attachment 1 its 1x
// resolve attachment (DONT_CARE, or LOAD from DEPTH_STENCIL_ATTACHMENT_OPTIMAL with `load_resolve`), resolved with
// `ds` (its pDepthStencilResolveAttachment set here when null). With `separate_layouts` (Vulkan 1.2
// separateDepthStencilLayouts) the attachments and references use DEPTH_ATTACHMENT_OPTIMAL and, through
// VkAttachmentDescriptionStencilLayout / VkAttachmentReferenceStencilLayout, STENCIL_ATTACHMENT_OPTIMAL.
VkRenderPass ds_pass(Kit& k, VkFormat f, VkSubpassDescriptionDepthStencilResolve ds, VkResult* result = nullptr,
                     VkFormat resolve_format = VK_FORMAT_UNDEFINED,
                     VkSampleCountFlagBits resolve_samples = VK_SAMPLE_COUNT_1_BIT, bool load_resolve = false,
                     uint32_t view_mask = 0, bool separate_layouts = false) {
    VkAttachmentDescription2 att[2] = {{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2},
                                       {VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2}};
    att[0].format = f;
    att[0].samples = VK_SAMPLE_COUNT_4_BIT;
    att[0].loadOp = att[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[0].storeOp = att[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[0].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    att[1].format = resolve_format != VK_FORMAT_UNDEFINED ? resolve_format : f;
    att[1].samples = resolve_samples;
    att[1].loadOp = att[1].stencilLoadOp = load_resolve ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    if (load_resolve) att[1].initialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    att[1].storeOp = att[1].stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
    att[1].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const VkImageAspectFlags a = aspects_of(f);
    VkImageLayout ref_layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    const VkAttachmentReferenceStencilLayout stencil_ref{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_STENCIL_LAYOUT, nullptr,
                                                         VK_IMAGE_LAYOUT_STENCIL_ATTACHMENT_OPTIMAL};
    VkAttachmentDescriptionStencilLayout stencil_att[2] = {
        {VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_STENCIL_LAYOUT, nullptr, VK_IMAGE_LAYOUT_UNDEFINED,
         VK_IMAGE_LAYOUT_STENCIL_ATTACHMENT_OPTIMAL},
        {VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_STENCIL_LAYOUT, nullptr, VK_IMAGE_LAYOUT_UNDEFINED,
         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL}};
    const void* ref_chain = nullptr;
    if (separate_layouts) {
        const bool both = a == (VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT);
        ref_layout = a == VK_IMAGE_ASPECT_STENCIL_BIT ? VK_IMAGE_LAYOUT_STENCIL_ATTACHMENT_OPTIMAL
                                                      : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        att[0].finalLayout = ref_layout;
        if (load_resolve) {
            att[1].initialLayout = ref_layout;
            stencil_att[1].stencilInitialLayout = VK_IMAGE_LAYOUT_STENCIL_ATTACHMENT_OPTIMAL;
        }
        if (both) {  // the stencil aspect's own layouts (VUID-VkAttachmentReference2-attachment-04755)
            ref_chain = &stencil_ref;
            att[0].pNext = &stencil_att[0];
            att[1].pNext = &stencil_att[1];
        }
    }
    const VkAttachmentReference2 depth{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, ref_chain, 0, ref_layout, a};
    const VkAttachmentReference2 resolve{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, ref_chain, 1, ref_layout, a};
    if (ds.pDepthStencilResolveAttachment == nullptr) ds.pDepthStencilResolveAttachment = &resolve;
    VkSubpassDescription2 sub{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2};
    sub.pNext = &ds;
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.pDepthStencilAttachment = &depth;
    sub.viewMask = view_mask;
    const VkSubpassDependency2 dep{
        VK_STRUCTURE_TYPE_SUBPASS_DEPENDENCY_2,
        nullptr,
        0,
        VK_SUBPASS_EXTERNAL,
        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
        VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
        VK_ACCESS_TRANSFER_READ_BIT,
        0,
        0};
    VkRenderPassCreateInfo2 ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
    ci.attachmentCount = 2;
    ci.pAttachments = att;
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    ci.dependencyCount = 1;
    ci.pDependencies = &dep;
    auto create = reinterpret_cast<PFN_vkCreateRenderPass2KHR>(vkGetDeviceProcAddr(k.d, "vkCreateRenderPass2KHR"));
    EXPECT_NE(create, nullptr);
    VkRenderPass rp = VK_NULL_HANDLE;
    const VkResult r = create(k.d, &ci, nullptr, &rp);
    if (result != nullptr)
        *result = r;
    else
        EXPECT_EQ(r, VK_SUCCESS);
    if (rp != VK_NULL_HANDLE) {
        VkDevice d = k.d;
        k.undo(VK_OBJECT_TYPE_RENDER_PASS, rp, [d, rp] { vkDestroyRenderPass(d, rp, nullptr); });
    }
    return rp;
}

VkSubpassDescriptionDepthStencilResolve modes(VkResolveModeFlagBits depth, VkResolveModeFlagBits stencil) {
    VkSubpassDescriptionDepthStencilResolve ds{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_DEPTH_STENCIL_RESOLVE};
    ds.depthResolveMode = depth;
    ds.stencilResolveMode = stencil;
    return ds;
}

// Depth test `compare` with writes, stencil ALWAYS / REPLACE with `reference`.
VkPipelineDepthStencilStateCreateInfo ds_state(VkCompareOp compare, uint32_t reference) {
    VkPipelineDepthStencilStateCreateInfo ds = depth_state(compare);
    ds.stencilTestEnable = VK_TRUE;
    ds.front = {VK_STENCIL_OP_KEEP, VK_STENCIL_OP_REPLACE, VK_STENCIL_OP_KEEP, VK_COMPARE_OP_ALWAYS, 0xff, 0xff,
                reference};
    ds.back = ds.front;
    return ds;
}

// What resolve_scene varies.
struct Scene {
    float clear_z = 1.0f;            // the 4x attachment's load-op clear depth (stencil 0)
    uint32_t first_drawn = 0;        // the samples below it are not drawn: they keep the clear
    const VkRect2D* area = nullptr;  // the render area (null: all), the resolve image then cleared to depth 0.5,
                                     // stencil 9 before the pass and loaded
    uint32_t view_mask = 0;          // multiview: the subpass's views, one layer each of two-layer images; no
                                     // triangle then (icd/README.md: multiview draws differ at triangle edges)
    bool separate_layouts = false;   // ds_pass's separate depth and stencil layouts
};

// The scene (see the top of the file) on format `f` with `depth_mode` / `stencil_mode`; returns the resolve
// attachment's depth bytes then its stencil bytes (each aspect the format has), layer after layer, read through a
// buffer.
Bytes resolve_scene(Kit& k, VkFormat f, VkResolveModeFlagBits depth_mode, VkResolveModeFlagBits stencil_mode,
                    const Scene& sc = {}) {
    const uint32_t layers = sc.view_mask != 0 ? 2 : 1;
    const VkImageViewType type = sc.view_mask != 0 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    const VkImageAspectFlags a = aspects_of(f);
    Device::Image ms = k.dev().make_image(f, kSize, kSize, 1, layers, VK_SAMPLE_COUNT_4_BIT,
                                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    EXPECT_NE(ms.image, VK_NULL_HANDLE);
    k.undo(VK_OBJECT_TYPE_IMAGE, ms.image, [&k, ms]() mutable { k.dev().destroy(ms); });
    Device::Image res = k.image(
        f, kSize, kSize,
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        1, layers);
    VkRenderPass rp = ds_pass(k, f, modes(depth_mode, stencil_mode), nullptr, VK_FORMAT_UNDEFINED,
                              VK_SAMPLE_COUNT_1_BIT, sc.area != nullptr, sc.view_mask, sc.separate_layouts);
    VkFramebuffer fb = k.framebuffer(
        rp, {k.view(ms.image, f, a, type, 0, 1, 0, layers), k.view(res.image, f, a, type, 0, 1, 0, layers)}, kSize,
        kSize);
    VkPipeline sample_pipes[4];
    VkPipelineDepthStencilStateCreateInfo states[4];
    VkSampleMask masks[4];
    for (int s = 0; s < 4; ++s) {
        states[s] = ds_state(VK_COMPARE_OP_ALWAYS, kSampleStencil[s]);
        masks[s] = 1u << s;
        Pipe p;
        p.rp = rp;
        p.color_count = 0;
        p.no_fragment_stage = true;
        p.samples = VK_SAMPLE_COUNT_4_BIT;
        p.ds = &states[s];
        p.sample_mask = &masks[s];
        sample_pipes[s] = k.pipeline(p);
    }
    const VkPipelineDepthStencilStateCreateInfo tri_state = ds_state(VK_COMPARE_OP_LESS, 99);
    Pipe tp;
    tp.rp = rp;
    tp.color_count = 0;
    tp.no_fragment_stage = true;
    tp.samples = VK_SAMPLE_COUNT_4_BIT;
    tp.ds = &tri_state;
    VkPipeline tri_pipe = k.pipeline(tp);
    std::vector<Vertex> verts;
    for (float z : kSampleDepth) {
        verts.push_back(v(-1, -1, z, 0, 0, 0));
        verts.push_back(v(3, -1, z, 0, 0, 0));
        verts.push_back(v(-1, 3, z, 0, 0, 0));
    }
    // A sloped triangle right of x = -0.5 (pixel 8): nearer than some samples, farther than others.
    verts.push_back(v(-0.2f, -0.9f, 0.05f, 0, 0, 0));
    verts.push_back(v(0.9f, 0.1f, 0.9f, 0, 0, 0));
    verts.push_back(v(-0.5f, 0.8f, 0.3f, 0, 0, 0));
    Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        const std::vector<VkClearValue> clears = {clear_depth(sc.clear_z, 0), clear_depth(0, 0)};
        if (sc.area != nullptr) {
            transition(c, res.image, a, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            const VkClearDepthStencilValue before{0.5f, 9};
            const VkImageSubresourceRange range{a, 0, 1, 0, 1};
            vkCmdClearDepthStencilImage(c, res.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &before, 1, &range);
            transition(c, res.image, a, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
            VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
            bi.renderPass = rp;
            bi.framebuffer = fb;
            bi.renderArea = *sc.area;
            bi.clearValueCount = uint32_t(clears.size());
            bi.pClearValues = clears.data();
            vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
        } else {
            begin_pass(c, rp, fb, kSize, kSize, clears);
        }
        bind_vertices(c, vb);
        for (uint32_t s = sc.first_drawn; s < 4; ++s) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, sample_pipes[s]);
            vkCmdDraw(c, 3, 1, 3 * s, 0);
        }
        if (sc.view_mask == 0) {
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, tri_pipe);
            vkCmdDraw(c, 3, 1, 12, 0);
        }
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    Bytes out;
    for (uint32_t l = 0; l < layers; ++l) {
        if (a & VK_IMAGE_ASPECT_DEPTH_BIT) {
            const Bytes d = k.read(res.image, kSize, kSize, texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT),
                                   VK_IMAGE_ASPECT_DEPTH_BIT, 0, l);
            out.insert(out.end(), d.begin(), d.end());
        }
        if (a & VK_IMAGE_ASPECT_STENCIL_BIT) {
            const Bytes st = k.read(res.image, kSize, kSize, 1, VK_IMAGE_ASPECT_STENCIL_BIT, 0, l);
            out.insert(out.end(), st.begin(), st.end());
        }
    }
    return out;
}

// The test's own expectation at pixel (x, y), which the triangle does not reach: sample 0's depth (as the format
// stores 0.2: D16 13107, D24 3355443, D32F the float) and stencil.
void expect_sample0(const Bytes& out, VkFormat f, uint32_t x, uint32_t y) {
    const VkImageAspectFlags a = aspects_of(f);
    size_t stencil_at = 0;
    if (a & VK_IMAGE_ASPECT_DEPTH_BIT) {
        const uint32_t tb = texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT);
        stencil_at = size_t(kSize) * kSize * tb;
        uint32_t bits = 0;
        std::memcpy(&bits, out.data() + (size_t(y) * kSize + x) * tb, tb);
        if (f == VK_FORMAT_D16_UNORM) {
            EXPECT_EQ(bits, 13107u) << "D16 sample 0 (0.2 * 65535); the average would be 32767 or 32768";
        } else if (f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D32_SFLOAT_S8_UINT) {
            float z = 0;
            std::memcpy(&z, &bits, 4);
            EXPECT_EQ(z, kSampleDepth[0]) << "D32 sample 0; the average would be 0.5";
        } else {
            EXPECT_EQ(bits & 0xffffffu, 3355443u) << "D24 sample 0 (0.2 * 16777215)";
        }
    }
    if (a & VK_IMAGE_ASPECT_STENCIL_BIT) {
        EXPECT_EQ(out[stencil_at + size_t(y) * kSize + x], kSampleStencil[0]) << "stencil sample 0";
    }
}

class ApiDepthStencilResolve : public ApiBreadth {
  protected:
    // resolve_scene on both drivers (equal bytes), on devices with multiview enabled (for MultiviewResolvesEachView);
    // tilevk's.
    Bytes scene(VkFormat f, VkResolveModeFlagBits depth_mode, VkResolveModeFlagBits stencil_mode,
                const Scene& sc = {}) {
        VkPhysicalDeviceSeparateDepthStencilLayoutsFeatures layouts{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SEPARATE_DEPTH_STENCIL_LAYOUTS_FEATURES};
        layouts.separateDepthStencilLayouts = VK_TRUE;
        VkPhysicalDeviceMultiviewFeatures mv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES, &layouts};
        mv.multiview = VK_TRUE;
        DevicePair d(tilevk_->physical(), lavapipe_->physical(), kExtensions, &mv);
        EXPECT_TRUE(d.tilevk.ok() && d.lavapipe.ok());
        return both_on(d.tilevk, d.lavapipe, [&](Kit& k) { return resolve_scene(k, f, depth_mode, stencil_mode, sc); });
    }
    void run(VkFormat f, VkResolveModeFlagBits depth_mode, VkResolveModeFlagBits stencil_mode) {
        const Bytes out = scene(f, depth_mode, stencil_mode);
        expect_sample0(out, f, 2, 2);
        expect_sample0(out, f, 1, 30);
    }
    static uint32_t word_at(const Bytes& out, uint32_t x, uint32_t y) {
        uint32_t w = 0;
        std::memcpy(&w, out.data() + (size_t(y) * kSize + x) * 4, 4);
        return w;
    }
};

TEST_F(ApiDepthStencilResolve, PropertiesAreLavapipesWithoutAverage) {
    VkPhysicalDeviceDepthStencilResolveProperties p[2] = {
        {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_STENCIL_RESOLVE_PROPERTIES},
        {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_STENCIL_RESOLVE_PROPERTIES}};
    const VkPhysicalDevice devs[2] = {tilevk_->physical(), lavapipe_->physical()};
    for (int i = 0; i < 2; ++i) {
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p[i]};
        vkGetPhysicalDeviceProperties2(devs[i], &p2);
    }
    EXPECT_EQ(p[0].supportedDepthResolveModes, VkResolveModeFlags(VK_RESOLVE_MODE_SAMPLE_ZERO_BIT));
    EXPECT_EQ(p[0].supportedStencilResolveModes, VkResolveModeFlags(VK_RESOLVE_MODE_SAMPLE_ZERO_BIT));
    EXPECT_EQ(p[0].independentResolveNone, VK_FALSE);
    EXPECT_EQ(p[0].independentResolve, VK_FALSE);
    // lavapipe also reports depth AVERAGE, which it computes as SAMPLE_ZERO (icd/physical_device.h)
    EXPECT_EQ(p[1].supportedDepthResolveModes, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT | VK_RESOLVE_MODE_AVERAGE_BIT);
    EXPECT_EQ(p[0].supportedStencilResolveModes, p[1].supportedStencilResolveModes);
    EXPECT_EQ(p[0].independentResolveNone, p[1].independentResolveNone);
    EXPECT_EQ(p[0].independentResolve, p[1].independentResolve);
}

TEST_F(ApiDepthStencilResolve, D32SampleZero) {
    run(VK_FORMAT_D32_SFLOAT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_NONE);
}
TEST_F(ApiDepthStencilResolve, D16SampleZero) {
    run(VK_FORMAT_D16_UNORM, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_NONE);
}
// A stencil mode on a depth-only format is ignored (VUID-03184/03185 bind formats with a stencil aspect only).
TEST_F(ApiDepthStencilResolve, D16WithAnIgnoredStencilMode) {
    run(VK_FORMAT_D16_UNORM, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_MAX_BIT);
}
TEST_F(ApiDepthStencilResolve, X8D24SampleZero) {
    run(VK_FORMAT_X8_D24_UNORM_PACK32, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_NONE);
}
// A render area of (5, 3) 20x17: only it is resolved; outside, the resolve image keeps what it was cleared to before
// the pass (depth 0.5: D24 lrint(0.5 * (2^24-1)) = 8388608, D16 32768; stencil 9).
TEST_F(ApiDepthStencilResolve, OnlyTheRenderAreaIsResolved) {
    const VkRect2D area{{5, 3}, {20, 17}};
    Scene sc;
    sc.area = &area;
    const Bytes ds =
        scene(VK_FORMAT_D24_UNORM_S8_UINT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, sc);
    expect_sample0(ds, VK_FORMAT_D24_UNORM_S8_UINT, 6, 4);
    EXPECT_EQ(word_at(ds, 2, 2) & 0xffffffu, 8388608u);
    EXPECT_EQ(word_at(ds, 6, 20) & 0xffffffu, 8388608u);  // the row below the area
    EXPECT_EQ(ds[size_t(kSize) * kSize * 4 + 2 * kSize + 2], 9);
    const Bytes d16 = scene(VK_FORMAT_D16_UNORM, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_NONE, sc);
    expect_sample0(d16, VK_FORMAT_D16_UNORM, 6, 4);
    uint16_t outside = 0;
    std::memcpy(&outside, d16.data() + (2 * kSize + 25) * 2, 2);  // (25, 2): right of and above the area
    EXPECT_EQ(outside, 32768);
}
// Multiview (views 0 and 1 of two-layer images): each view is resolved into its layer, sample 0 in both. On tilevk
// alone (validation layer on): lavapipe 22.3 differs in layer 1 — its SAMPLE_ZERO (util_resource_copy_region of a
// layered 4x image) writes zeros there; not analysed further (icd/README.md, VK_KHR_depth_stencil_resolve).
TEST_F(ApiDepthStencilResolve, MultiviewResolvesEachViewOnTilevk) {
    VkPhysicalDeviceMultiviewFeatures mv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
    mv.multiview = VK_TRUE;
    Device dev(tilevk_->physical(), nullptr, kExtensions, &mv);
    ASSERT_TRUE(dev.ok());
    Scene sc;
    sc.view_mask = 0b11;
    for (const auto& [f, depth_mode] : {std::pair{VK_FORMAT_D32_SFLOAT_S8_UINT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT},
                                        std::pair{VK_FORMAT_D16_UNORM, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT}}) {
        Bytes out;
        {
            Kit k(dev);
            out = resolve_scene(k, f, depth_mode, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, sc);
        }
        const uint32_t tb =
            (aspects_of(f) & VK_IMAGE_ASPECT_STENCIL_BIT ? 1 : 0) + texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT);
        const size_t layer_bytes = size_t(kSize) * kSize * tb;
        ASSERT_EQ(out.size(), 2 * layer_bytes);
        for (size_t l = 0; l < 2; ++l) {
            const Bytes layer(out.begin() + long(l * layer_bytes), out.begin() + long((l + 1) * layer_bytes));
            expect_sample0(layer, f, 2, 2);
            expect_sample0(layer, f, 20, 30);
        }
    }
}
TEST_F(ApiDepthStencilResolve, D24S8SampleZero) {
    run(VK_FORMAT_D24_UNORM_S8_UINT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT);
}
TEST_F(ApiDepthStencilResolve, D32S8SampleZero) {
    run(VK_FORMAT_D32_SFLOAT_S8_UINT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT);
}
TEST_F(ApiDepthStencilResolve, S8SampleZero) {
    run(VK_FORMAT_S8_UINT, VK_RESOLVE_MODE_NONE, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT);
}

// Vulkan 1.2 separateDepthStencilLayouts (VK_KHR_separate_depth_stencil_layouts): the same scenes with depth-only and
// stencil-only layouts (and the stencil aspect's own through the 1.2 structs) give the bytes of the combined layout,
// on tilevk as on lavapipe (validation layer on: the layer checks the layouts are used as the spec says).
TEST_F(ApiDepthStencilResolve, SeparateDepthStencilLayoutsChangeNothing) {
    Scene separate;
    separate.separate_layouts = true;
    for (const VkFormat f :
         {VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D16_UNORM, VK_FORMAT_S8_UINT}) {
        const bool has_depth = (aspects_of(f) & VK_IMAGE_ASPECT_DEPTH_BIT) != 0;
        const VkResolveModeFlagBits depth_mode = has_depth ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_NONE;
        const VkResolveModeFlagBits stencil_mode =
            has_stencil(f) ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_NONE;
        const Bytes combined = scene(f, depth_mode, stencil_mode);
        const Bytes split = scene(f, depth_mode, stencil_mode, separate);
        EXPECT_EQ(split, combined) << "VkFormat " << int(f);
        expect_sample0(split, f, 2, 2);
    }
}

// tilevk alone, without the validation layer (each is invalid usage or what tilevk does not resolve): refused with
// VK_ERROR_FEATURE_NOT_PRESENT and a message naming the struct and the member.
TEST_F(ApiDepthStencilResolve, Refusals) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    Device dev(plain.find_device("tilevk"), nullptr, kExtensions, nullptr);
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    const auto refused = [&](VkFormat f, VkSubpassDescriptionDepthStencilResolve ds, const char* name,
                             VkFormat resolve_format = VK_FORMAT_UNDEFINED,
                             VkSampleCountFlagBits resolve_samples = VK_SAMPLE_COUNT_1_BIT) {
        VkResult r = VK_SUCCESS;
        VkRenderPass rp = VK_NULL_HANDLE;
        const std::string err = stderr_of([&] { rp = ds_pass(k, f, ds, &r, resolve_format, resolve_samples); });
        EXPECT_EQ(r, VK_ERROR_FEATURE_NOT_PRESENT) << name;
        EXPECT_NE(err.find("VkSubpassDescriptionDepthStencilResolve::"), std::string::npos) << err;
        EXPECT_NE(err.find(name), std::string::npos) << name << ": " << err;
        EXPECT_EQ(rp, VkRenderPass(VK_NULL_HANDLE)) << name;
    };
    const VkResolveModeFlagBits kNone = VK_RESOLVE_MODE_NONE, kZero = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT,
                                kAverage = VK_RESOLVE_MODE_AVERAGE_BIT;
    // Combined formats: the two modes must be identical (independentResolve and independentResolveNone false).
    refused(VK_FORMAT_D24_UNORM_S8_UINT, modes(kZero, kNone), "independentResolveNone");
    refused(VK_FORMAT_D32_SFLOAT_S8_UINT, modes(kNone, kZero), "independentResolveNone");
    // AVERAGE (lavapipe's is sample 0), MIN and MAX are not offered; stencil cannot average.
    refused(VK_FORMAT_D32_SFLOAT, modes(kAverage, kNone), "depthResolveMode");
    refused(VK_FORMAT_D16_UNORM, modes(kAverage, kNone), "depthResolveMode");
    refused(VK_FORMAT_D24_UNORM_S8_UINT, modes(kAverage, kAverage), "depthResolveMode");
    refused(VK_FORMAT_S8_UINT, modes(kNone, kAverage), "stencilResolveMode");
    refused(VK_FORMAT_D32_SFLOAT, modes(VK_RESOLVE_MODE_MIN_BIT, kNone), "depthResolveMode");
    refused(VK_FORMAT_D16_UNORM, modes(VK_RESOLVE_MODE_MAX_BIT, kNone), "depthResolveMode");
    refused(VK_FORMAT_D16_UNORM, modes(VkResolveModeFlagBits(kZero | kAverage), kNone), "depthResolveMode");
    refused(VK_FORMAT_D32_SFLOAT, modes(kNone, kNone), "both VK_RESOLVE_MODE_NONE");
    // Another resolve format (valid when the aspects match; tilevk does not convert) and a 4x resolve attachment.
    refused(VK_FORMAT_D24_UNORM_S8_UINT, modes(kZero, kZero), "pDepthStencilResolveAttachment: format",
            VK_FORMAT_X8_D24_UNORM_PACK32);
    refused(VK_FORMAT_D32_SFLOAT, modes(kZero, kNone), "pDepthStencilResolveAttachment: the depth/stencil",
            VK_FORMAT_UNDEFINED, VK_SAMPLE_COUNT_4_BIT);
    // An attachment index past attachmentCount.
    const VkAttachmentReference2 past{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, 7,
                                      VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_IMAGE_ASPECT_DEPTH_BIT};
    VkSubpassDescriptionDepthStencilResolve ds = modes(kZero, kNone);
    ds.pDepthStencilResolveAttachment = &past;
    refused(VK_FORMAT_D32_SFLOAT, ds, "pDepthStencilResolveAttachment->attachment = 7");
    // Accepted: identical modes on a combined format, a depth mode with the stencil mode ignored on a depth-only one,
    // and an unused resolve attachment (modes ignored).
    VkResult r = VK_ERROR_UNKNOWN;
    EXPECT_NE(ds_pass(k, VK_FORMAT_D24_UNORM_S8_UINT, modes(kZero, kZero), &r), VkRenderPass(VK_NULL_HANDLE));
    EXPECT_EQ(r, VK_SUCCESS);
    EXPECT_NE(ds_pass(k, VK_FORMAT_D32_SFLOAT, modes(kZero, kAverage), &r), VkRenderPass(VK_NULL_HANDLE));
    EXPECT_EQ(r, VK_SUCCESS);
    const VkAttachmentReference2 unused{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, VK_ATTACHMENT_UNUSED,
                                        VK_IMAGE_LAYOUT_UNDEFINED, 0};
    ds = modes(VK_RESOLVE_MODE_MIN_BIT, VK_RESOLVE_MODE_MAX_BIT);
    ds.pDepthStencilResolveAttachment = &unused;
    EXPECT_NE(ds_pass(k, VK_FORMAT_D32_SFLOAT, ds, &r), VkRenderPass(VK_NULL_HANDLE));
    EXPECT_EQ(r, VK_SUCCESS);
}

}  // namespace
}  // namespace tilevk::test::breadth
