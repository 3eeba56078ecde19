// End-to-end cross-check with lavapipe: triangles (many clipped, with perspective) are rendered through Vulkan on
// lavapipe into R8G8B8A8_UNORM at 1x, and every pixel is compared with a model made of this folder's
// prepare_vertex / clip_triangle / setup_triangle_planes plus the notes' snap, edge (§2), interpolation (§4) and
// colour (§5) rules written out below. Skips when lavapipe is not available.
#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "rast/geometry/clip.h"
#include "rast/geometry/line_point_setup.h"
#include "rast/geometry/planes.h"
#include "rast/geometry/primitive_assembly.h"
#include "rast/geometry/vertex_fetch.h"
#include "rast/geometry/viewport.h"
#include "xcheck_frag.spv.h"
#include "xcheck_vert.spv.h"

using namespace tilevk::rast::geometry;

namespace {

constexpr int kSize = 64;
constexpr size_t kIndexOffset = 1 << 19;  // index data lives in the upper half of the vertex buffer

struct InVertex {
    float pos[4];
    float col[4];
};

// Less common state for a draw (pipeline key, plus an optional 32-bit index buffer).
struct Extra {
    bool depth_clamp = false;
    VkCullModeFlags cull = VK_CULL_MODE_NONE;
    VkFrontFace front = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool restart = false;
    const std::vector<uint32_t>* indices = nullptr;
    float vp[4] = {0, 0, kSize, kSize};  // x, y, width, height
};

#define VK_OK(x)                                      \
    do {                                              \
        VkResult r_ = (x);                            \
        if (r_ != VK_SUCCESS) {                       \
            ADD_FAILURE() << #x << " failed: " << r_; \
            return {};                                \
        }                                             \
    } while (0)

// Minimal Vulkan renderer on lavapipe: one pipeline, one 64x64 RGBA8 target, draws a triangle list.
class Lavapipe {
  public:
    bool init() {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.apiVersion = VK_API_VERSION_1_0;
        VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ici.pApplicationInfo = &app;
        if (vkCreateInstance(&ici, nullptr, &inst_) != VK_SUCCESS) return false;
        uint32_t n = 0;
        vkEnumeratePhysicalDevices(inst_, &n, nullptr);
        std::vector<VkPhysicalDevice> pds(n);
        vkEnumeratePhysicalDevices(inst_, &n, pds.data());
        for (auto pd : pds) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(pd, &p);
            if (std::strstr(p.deviceName, "llvmpipe")) pd_ = pd;
        }
        if (!pd_) return false;
        float prio = 1.0f;
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = 0;
        qci.queueCount = 1;
        qci.pQueuePriorities = &prio;
        VkPhysicalDeviceFeatures feats{};
        feats.wideLines = VK_TRUE;
        feats.largePoints = VK_TRUE;
        feats.depthBiasClamp = VK_TRUE;
        feats.depthClamp = VK_TRUE;
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        dci.pEnabledFeatures = &feats;
        VkPhysicalDeviceLineRasterizationFeaturesEXT line_feats{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
        line_feats.bresenhamLines = VK_TRUE;
        const char* ext = VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME;
        uint32_t next = 0;
        vkEnumerateDeviceExtensionProperties(pd_, nullptr, &next, nullptr);
        std::vector<VkExtensionProperties> exts(next);
        vkEnumerateDeviceExtensionProperties(pd_, nullptr, &next, exts.data());
        for (const auto& e : exts)
            if (std::strcmp(e.extensionName, ext) == 0) has_line_ext_ = true;
        if (has_line_ext_) {
            dci.enabledExtensionCount = 1;
            dci.ppEnabledExtensionNames = &ext;
            dci.pNext = &line_feats;
        }
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        if (vkCreateDevice(pd_, &dci, nullptr, &dev_) != VK_SUCCESS) return false;
        vkGetDeviceQueue(dev_, 0, 0, &queue_);
        return setup();
    }
    ~Lavapipe() {
        if (dev_) vkDeviceWaitIdle(dev_), vkDestroyDevice(dev_, nullptr);  // objects die with the device in lvp
        if (inst_) vkDestroyInstance(inst_, nullptr);
    }

    bool has_line_ext() const { return has_line_ext_; }

    // Renders `verts` as a triangle list with the given fragment mode; returns RGBA8 pixels.
    std::vector<uint8_t> render(const std::vector<InVertex>& verts, int mode,
                                VkPrimitiveTopology topo = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, float line_width = 1,
                                bool bresenham = false, VkFormat col_format = VK_FORMAT_R32G32B32A32_SFLOAT,
                                const DepthBias* bias = nullptr, const Extra& extra = Extra{}) {
        const VkPipeline pipe = pipeline(topo, line_width, bresenham, col_format, bias, extra);
        if (pipe == VK_NULL_HANDLE) return {};
        std::memcpy(vb_map_, verts.data(), verts.size() * sizeof(InVertex));
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        VK_OK(vkResetCommandBuffer(cmd_, 0));
        VK_OK(vkBeginCommandBuffer(cmd_, &bi));
        VkClearValue clear{};
        VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rp.renderPass = pass_;
        rp.framebuffer = fb_;
        rp.renderArea.extent = {kSize, kSize};
        rp.clearValueCount = 1;
        rp.pClearValues = &clear;
        vkCmdBeginRenderPass(cmd_, &rp, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        VkDeviceSize off = 0;
        vkCmdBindVertexBuffers(cmd_, 0, 1, &vb_, &off);
        vkCmdPushConstants(cmd_, layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4, &mode);
        if (extra.indices) {
            std::memcpy(static_cast<char*>(vb_map_) + kIndexOffset, extra.indices->data(), extra.indices->size() * 4);
            vkCmdBindIndexBuffer(cmd_, vb_, kIndexOffset, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(cmd_, static_cast<uint32_t>(extra.indices->size()), 1, 0, 0, 0);
        } else {
            vkCmdDraw(cmd_, static_cast<uint32_t>(verts.size()), 1, 0, 0);
        }
        vkCmdEndRenderPass(cmd_);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {kSize, kSize, 1};
        vkCmdCopyImageToBuffer(cmd_, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, rb_, 1, &copy);
        VK_OK(vkEndCommandBuffer(cmd_));
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd_;
        VK_OK(vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE));
        VK_OK(vkQueueWaitIdle(queue_));
        std::vector<uint8_t> px(kSize * kSize * 4);
        std::memcpy(px.data(), rb_map_, px.size());
        return px;
    }

  private:
    uint32_t host_memory_type(uint32_t bits) {
        VkPhysicalDeviceMemoryProperties mp;
        vkGetPhysicalDeviceMemoryProperties(pd_, &mp);
        for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
            if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)) return i;
        return 0;
    }
    bool buffer(VkDeviceSize size, VkBufferUsageFlags usage, VkBuffer* b, void** map) {
        VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        ci.size = size;
        ci.usage = usage;
        if (vkCreateBuffer(dev_, &ci, nullptr, b) != VK_SUCCESS) return false;
        VkMemoryRequirements mr;
        vkGetBufferMemoryRequirements(dev_, *b, &mr);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = mr.size;
        ai.memoryTypeIndex = host_memory_type(mr.memoryTypeBits);
        VkDeviceMemory m;
        if (vkAllocateMemory(dev_, &ai, nullptr, &m) != VK_SUCCESS) return false;
        vkBindBufferMemory(dev_, *b, m, 0);
        return vkMapMemory(dev_, m, 0, VK_WHOLE_SIZE, 0, map) == VK_SUCCESS;
    }
    VkPipeline pipeline(VkPrimitiveTopology topo, float line_width, bool bresenham, VkFormat col_format,
                        const DepthBias* bias, const Extra& x) {
        const DepthBias b = bias ? *bias : DepthBias{};
        for (const auto& p : pipes_)
            if (p.topo == topo && p.width == line_width && p.bresenham == bresenham && p.format == col_format &&
                p.bias.constant_factor == b.constant_factor && p.bias.slope_factor == b.slope_factor &&
                p.bias.clamp == b.clamp && p.x.depth_clamp == x.depth_clamp && p.x.cull == x.cull &&
                p.x.front == x.front && p.x.restart == x.restart && std::memcmp(p.x.vp, x.vp, sizeof(x.vp)) == 0)
                return p.pipe;
        VkPipelineShaderStageCreateInfo st[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
        st[0].stage = VK_SHADER_STAGE_VERTEX_BIT, st[0].module = vs_, st[0].pName = "main";
        st[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT, st[1].module = fs_, st[1].pName = "main";
        VkVertexInputBindingDescription bind{0, sizeof(InVertex), VK_VERTEX_INPUT_RATE_VERTEX};
        VkVertexInputAttributeDescription attrs[2] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0}, {1, 0, col_format, 16}};
        VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        vin.vertexBindingDescriptionCount = 1;
        vin.pVertexBindingDescriptions = &bind;
        vin.vertexAttributeDescriptionCount = 2;
        vin.pVertexAttributeDescriptions = attrs;
        VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        ia.topology = topo;
        ia.primitiveRestartEnable = x.restart;
        VkViewport vp{x.vp[0], x.vp[1], x.vp[2], x.vp[3], 0, 1};
        VkRect2D sc{{0, 0}, {kSize, kSize}};
        VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        vps.viewportCount = vps.scissorCount = 1;
        vps.pViewports = &vp;
        vps.pScissors = &sc;
        VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        rs.polygonMode = VK_POLYGON_MODE_FILL;
        rs.cullMode = x.cull;
        rs.frontFace = x.front;
        rs.depthClampEnable = x.depth_clamp;
        rs.lineWidth = line_width;
        rs.depthBiasEnable = bias != nullptr;
        rs.depthBiasConstantFactor = b.constant_factor;
        rs.depthBiasSlopeFactor = b.slope_factor;
        rs.depthBiasClamp = b.clamp;
        VkPipelineRasterizationLineStateCreateInfoEXT ls{
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
        ls.lineRasterizationMode = VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
        if (bresenham) rs.pNext = &ls;
        VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        VkPipelineColorBlendAttachmentState cba{};
        cba.colorWriteMask = 0xF;
        VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        cb.attachmentCount = 1;
        cb.pAttachments = &cba;
        VkGraphicsPipelineCreateInfo gi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
        gi.stageCount = 2;
        gi.pStages = st;
        gi.pVertexInputState = &vin;
        gi.pInputAssemblyState = &ia;
        gi.pViewportState = &vps;
        gi.pRasterizationState = &rs;
        gi.pMultisampleState = &ms;
        gi.pColorBlendState = &cb;
        gi.layout = layout_;
        gi.renderPass = pass_;
        VkPipeline pipe = VK_NULL_HANDLE;
        if (vkCreateGraphicsPipelines(dev_, VK_NULL_HANDLE, 1, &gi, nullptr, &pipe) != VK_SUCCESS) return pipe;
        pipes_.push_back({topo, line_width, bresenham, col_format, b, x, pipe});
        return pipe;
    }
    bool setup() {
        if (!buffer(1 << 20, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &vb_, &vb_map_))
            return false;
        if (!buffer(kSize * kSize * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &rb_, &rb_map_)) return false;
        VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ii.imageType = VK_IMAGE_TYPE_2D;
        ii.format = VK_FORMAT_R8G8B8A8_UNORM;
        ii.extent = {kSize, kSize, 1};
        ii.mipLevels = ii.arrayLayers = 1;
        ii.samples = VK_SAMPLE_COUNT_1_BIT;
        ii.tiling = VK_IMAGE_TILING_OPTIMAL;
        ii.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        if (vkCreateImage(dev_, &ii, nullptr, &image_) != VK_SUCCESS) return false;
        VkMemoryRequirements mr;
        vkGetImageMemoryRequirements(dev_, image_, &mr);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = mr.size;
        ai.memoryTypeIndex = host_memory_type(mr.memoryTypeBits);
        VkDeviceMemory m;
        if (vkAllocateMemory(dev_, &ai, nullptr, &m) != VK_SUCCESS) return false;
        vkBindImageMemory(dev_, image_, m, 0);
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = image_;
        vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vi.format = ii.format;
        vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view;
        if (vkCreateImageView(dev_, &vi, nullptr, &view) != VK_SUCCESS) return false;
        VkAttachmentDescription att{};
        att.format = ii.format;
        att.samples = VK_SAMPLE_COUNT_1_BIT;
        att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        att.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &ref;
        VkSubpassDependency dep{};
        dep.srcSubpass = 0;
        dep.dstSubpass = VK_SUBPASS_EXTERNAL;
        dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        dep.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
        dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        dep.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        rpi.attachmentCount = 1;
        rpi.pAttachments = &att;
        rpi.subpassCount = 1;
        rpi.pSubpasses = &sub;
        rpi.dependencyCount = 1;
        rpi.pDependencies = &dep;
        if (vkCreateRenderPass(dev_, &rpi, nullptr, &pass_) != VK_SUCCESS) return false;
        VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fi.renderPass = pass_;
        fi.attachmentCount = 1;
        fi.pAttachments = &view;
        fi.width = fi.height = kSize;
        fi.layers = 1;
        if (vkCreateFramebuffer(dev_, &fi, nullptr, &fb_) != VK_SUCCESS) return false;
        VkShaderModuleCreateInfo smi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        smi.codeSize = sizeof(kXcheck_vert);
        smi.pCode = kXcheck_vert;
        if (vkCreateShaderModule(dev_, &smi, nullptr, &vs_) != VK_SUCCESS) return false;
        smi.codeSize = sizeof(kXcheck_frag);
        smi.pCode = kXcheck_frag;
        if (vkCreateShaderModule(dev_, &smi, nullptr, &fs_) != VK_SUCCESS) return false;
        VkPushConstantRange pcr{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};
        VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        li.pushConstantRangeCount = 1;
        li.pPushConstantRanges = &pcr;
        if (vkCreatePipelineLayout(dev_, &li, nullptr, &layout_) != VK_SUCCESS) return false;
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        VkCommandPool pool;
        if (vkCreateCommandPool(dev_, &pi, nullptr, &pool) != VK_SUCCESS) return false;
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        return vkAllocateCommandBuffers(dev_, &cai, &cmd_) == VK_SUCCESS;
    }

    VkInstance inst_ = VK_NULL_HANDLE;
    VkPhysicalDevice pd_ = VK_NULL_HANDLE;
    VkDevice dev_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkBuffer vb_ = VK_NULL_HANDLE, rb_ = VK_NULL_HANDLE;
    void* vb_map_ = nullptr;
    void* rb_map_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE;
    VkRenderPass pass_ = VK_NULL_HANDLE;
    VkFramebuffer fb_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkShaderModule vs_ = VK_NULL_HANDLE, fs_ = VK_NULL_HANDLE;
    struct Pipe {
        VkPrimitiveTopology topo;
        float width;
        bool bresenham;
        VkFormat format;
        DepthBias bias;
        Extra x;
        VkPipeline pipe;
    };
    std::vector<Pipe> pipes_;
    bool has_line_ext_ = false;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

// ---- The model ----
constexpr uint32_t kFloats = 8 + 4 * 3;
const Interp kModes[3] = {Interp::kPerspective, Interp::kNoPerspective, Interp::kFlat};

// u8 = sat(rne(fl(x*255))), NaN -> 0 (notes §5)
uint8_t to_unorm8(float x) {
    const float s = x * 255.0f;
    if (!(s > 0.0f)) return 0;
    if (s >= 255.0f) return 255;
    return static_cast<uint8_t>(std::nearbyint(s));
}

// wrong_divide: a/oow instead of a*(1/oow), a deliberately wrong rule for the negative test.
struct ModelExtra {
    bool clip_z = true;  // !depthClampEnable
    bool cull_front = false, cull_back = false;
    bool front_ccw = true;
    float vp[4] = {0, 0, kSize, kSize};
};

Viewport model_viewport(const ModelExtra& mx) {
    return make_viewport(mx.vp[0], mx.vp[1], mx.vp[2], mx.vp[3], 0, 1);
}

// Every primitive is limited to the viewport's whole-pixel rectangle (and the framebuffer).
bool in_rect(const PixelRect& r, int px, int py) {
    return px >= r.x0 && px < r.x1 && py >= r.y0 && py < r.y1;
}

std::vector<uint8_t> model(const std::vector<InVertex>& verts, int mode, bool fma, bool wrong_divide = false,
                           const DepthBias* bias = nullptr, const ModelExtra& mx = ModelExtra{}) {
    std::vector<uint8_t> img(kSize * kSize * 4, 0);
    ClipMaskConfig cm{};
    cm.clip_z = mx.clip_z;
    // draw runs its pipeline (clip, then float cull when a cull mode is set) for a whole vertex batch as soon as
    // one vertex has a clip mask; these scenes are one batch each.
    bool pipeline_path = false;
    for (const auto& v : verts) pipeline_path = pipeline_path || compute_clipmask(cm, v.pos) != 0;
    const FloatCull fcull{mx.cull_front, mx.cull_back, mx.front_ccw};
    ViewportConfig vc;
    vc.vp = model_viewport(mx);
    const PixelRect rect = viewport_pixel_rect(vc.vp);
    vc.fused = fma;
    ClipConfig cc;
    cc.layout = {3, kModes};
    cc.vp = vc.vp;
    PlaneSetupConfig pc;
    pc.layout = cc.layout;
    if (bias) pc.bias = *bias;  // no depth attachment: lavapipe's default mrd is D24's
    std::vector<float> scratch(kClipScratchVertices * kFloats);
    auto mad = [fma](float a, float b, float c) { return fma ? std::fma(a, b, c) : a * b + c; };
    for (size_t t = 0; t + 2 < verts.size(); t += 3) {
        float rec[3][kFloats];
        uint32_t mask[3];
        for (int k = 0; k < 3; ++k) {
            std::memcpy(rec[k], verts[t + k].pos, 16);
            for (int a = 0; a < 3; ++a) std::memcpy(rec[k] + 8 + 4 * a, verts[t + k].col, 16);
            mask[k] = prepare_vertex(cm, vc, rec[k]);
        }
        ClippedTriangle tris[kMaxClippedTriangles];
        const uint32_t n = clip_triangle(cc, rec[0], rec[1], rec[2], mask[0], mask[1], mask[2], scratch.data(), tris);
        for (uint32_t i = 0; i < n; ++i) {
            const float* v[3] = {tris[i].v[0], tris[i].v[1], tris[i].v[2]};
            if (pipeline_path && (mx.cull_front || mx.cull_back) &&
                !float_cull_keep(fcull, v[0] + 4, v[1] + 4, v[2] + 4))
                continue;
            // snap: rne(fl(x - 0.5) * 256)
            int64_t X[3], Y[3];
            for (int k = 0; k < 3; ++k) {
                X[k] = static_cast<int64_t>(std::nearbyint((v[k][4] - 0.5f) * 256.0f));
                Y[k] = static_cast<int64_t>(std::nearbyint((v[k][5] - 0.5f) * 256.0f));
            }
            const int64_t area = (X[0] - X[1]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[0] - Y[1]);
            if (area == 0) continue;
            // llvmpipe's own cull on the exact fixed-point area: area > 0 is "ccw"
            const bool front = (area > 0) == mx.front_ccw;
            if ((front && mx.cull_front) || (!front && mx.cull_back)) continue;
            if (area < 0) {  // CW -> CCW with flatshade_first: swap v1, v2
                std::swap(v[1], v[2]);
                std::swap(X[1], X[2]);
                std::swap(Y[1], Y[2]);
            }
            TrianglePlanes tp;
            AttribPlane ap[3];
            setup_triangle_planes(pc, v[0], v[1], v[2], &tp, ap);
            for (int py = 0; py < kSize; ++py)
                for (int px = 0; px < kSize; ++px) {
                    if (!in_rect(rect, px, py)) continue;
                    bool in = true;
                    for (int e = 0; e < 3; ++e) {
                        const int j = (e + 1) % 3;
                        const int64_t dy = Y[e] - Y[j], dx = X[e] - X[j];
                        const int64_t bias = (dy < 0 || (dy == 0 && dx > 0)) ? 1 : 0;
                        in = in && dy * (X[e] - px * 256) - dx * (Y[e] - py * 256) + bias > 0;
                    }
                    if (!in) continue;
                    const float fx = static_cast<float>(px), fy = static_cast<float>(py);
                    if (mode & 8) {
                        // gl_FragCoord.z = fmuladd(dzdy, py, fmuladd(dzdx, px, z0)) + offset (plain add)
                        const float zi = mad(tp.pos.dady[2], fy, mad(tp.pos.dadx[2], fx, tp.pos.a0[2]));
                        const float z = zi + tp.depth_offset;
                        const float big = z * 65536.0f, mid = z * 256.0f, huge = z * 16777216.0f;
                        const float ch[4] = {big - std::floor(big), mid - std::floor(mid), z, huge - std::floor(huge)};
                        for (int c = 0; c < 4; ++c) img[(py * kSize + px) * 4 + c] = to_unorm8(ch[c]);
                        continue;
                    }
                    const AttribPlane& a = ap[mode & 3];
                    const float oow = mad(tp.pos.dady[3], fy, mad(tp.pos.dadx[3], fx, tp.pos.a0[3]));
                    const float rw = 1.0f / oow;
                    for (int c = 0; c < 4; ++c) {
                        float val = mad(a.dady[c], fy, mad(a.dadx[c], fx, a.a0[c]));
                        if ((mode & 3) == 0) val = wrong_divide ? val / oow : val * rw;
                        if (mode & 4) {
                            const float big = val * 65536.0f;  // exact
                            val = big - std::floor(big);
                        }
                        img[(py * kSize + px) * 4 + c] = to_unorm8(val);
                    }
                }
        }
    }
    return img;
}

// Fragment evaluation (notes §4): a = fmuladd(dady, py, fmuladd(dadx, px, a0)); perspective a *= 1/(1/w plane).
void shade(std::vector<uint8_t>& img, int px, int py, const AttribPlane& pos, const AttribPlane& a, int mode,
           bool fma) {
    auto mad = [fma](float x, float y, float z) { return fma ? std::fma(x, y, z) : x * y + z; };
    const float fx = static_cast<float>(px), fy = static_cast<float>(py);
    const float oow = mad(pos.dady[3], fy, mad(pos.dadx[3], fx, pos.a0[3]));
    const float rw = 1.0f / oow;
    for (int c = 0; c < 4; ++c) {
        float val = mad(a.dady[c], fy, mad(a.dadx[c], fx, a.a0[c]));
        if ((mode & 3) == 0) val = val * rw;
        if (mode & 4) {
            const float big = val * 65536.0f;  // exact
            val = big - std::floor(big);
        }
        img[(py * kSize + px) * 4 + c] = to_unorm8(val);
    }
}

struct ModelState {
    ClipMaskConfig cm{};
    ViewportConfig vc;
    ClipConfig cc;
    std::vector<float> scratch = std::vector<float>(kClipScratchVertices * kFloats);
    PixelRect rect;
    ModelState(bool fma, const ModelExtra& mx) {
        vc.vp = model_viewport(mx);
        rect = viewport_pixel_rect(vc.vp);
        vc.fused = fma;
        cc.layout = {3, kModes};
        cc.vp = vc.vp;
    }
    uint32_t record(const InVertex& in, float* rec) const {
        std::memcpy(rec, in.pos, 16);
        for (int a = 0; a < 3; ++a) std::memcpy(rec + 8 + 4 * a, in.col, 16);
        return prepare_vertex(cm, vc, rec);
    }
};

std::vector<uint8_t> model_lines(const std::vector<InVertex>& verts, int mode, bool fma, float width,
                                 bool bresenham = false, const ModelExtra& mx = ModelExtra{}) {
    std::vector<uint8_t> img(kSize * kSize * 4, 0);
    ModelState st(fma, mx);
    LineSetupConfig lc;
    lc.layout = st.cc.layout;
    lc.width = width;
    lc.mode = bresenham ? LineMode::kBresenham : LineMode::kRectangular;
    for (size_t i = 0; i + 1 < verts.size(); i += 2) {
        float r0[kFloats], r1[kFloats];
        const uint32_t m0 = st.record(verts[i], r0), m1 = st.record(verts[i + 1], r1);
        const float* a;
        const float* b;
        if (!clip_line(st.cc, r0, r1, m0, m1, st.scratch.data(), &a, &b)) continue;
        LineSetup ls;
        AttribPlane ap[3];
        if (setup_line(lc, a, b, &ls, ap) != PrimSetupStatus::kOk) continue;
        for (int py = 0; py < kSize; ++py)
            for (int px = 0; px < kSize; ++px) {
                bool in = in_rect(st.rect, px, py);
                for (const auto& pl : ls.planes)
                    in = in && pl.c + int64_t{pl.a} * (px * 256) + int64_t{pl.b} * (py * 256) > 0;
                if (in) shade(img, px, py, ls.pos, ap[mode & 3], mode, fma);
            }
    }
    return img;
}

// col_format: the colour bytes of each InVertex are an element of this format, converted by vertex_fetch.
std::vector<uint8_t> model_points(const std::vector<InVertex>& verts, int mode, bool fma,
                                  VertexFormat col_format = VertexFormat::kR32G32B32A32Float,
                                  const ModelExtra& mx = ModelExtra{}) {
    std::vector<uint8_t> img(kSize * kSize * 4, 0);
    ModelState st(fma, mx);
    PointSetupConfig pc;
    pc.layout = st.cc.layout;
    for (const auto& raw : verts) {
        InVertex v = raw;
        const FetchedAttrib f = convert_element(col_format, reinterpret_cast<const uint8_t*>(raw.col));
        std::memcpy(v.col, f.w, 16);
        float r[kFloats];
        const uint32_t m = st.record(v, r);
        if (!clip_point_keep(r, m)) continue;
        PointSetup ps;
        AttribPlane ap[3];
        if (setup_point(pc, r, v.col[3] * 8.0f, &ps, ap) != PrimSetupStatus::kOk) continue;
        for (int py = 0; py < kSize; ++py)
            for (int px = 0; px < kSize; ++px)
                if (in_rect(st.rect, px, py) && ps.x0 <= px * 256 && px * 256 < ps.x1 && ps.y0 <= py * 256 &&
                    py * 256 < ps.y1)
                    shade(img, px, py, ps.pos, ap[mode & 3], mode, fma);
    }
    return img;
}

InVertex iv(float x, float y, float z, float w, float r, float g, float b, float a = 1.0f) {
    return InVertex{{x, y, z, w}, {r, g, b, a}};
}

}  // namespace

std::vector<std::vector<InVertex>> make_scenes() {
    std::vector<std::vector<InVertex>> scenes;
    // crosses right and bottom, w = 1
    scenes.push_back(
        {iv(-0.7f, -0.6f, 0.5f, 1, 1, 0, 0), iv(1.9f, 0.1f, 0.5f, 1, 0, 1, 0), iv(0.2f, 1.7f, 0.5f, 1, 0, 0, 1)});
    // perspective, crosses left and top
    scenes.push_back({iv(-3.1f, -0.2f, 0.3f, 2.0f, 1, 0.5f, 0), iv(0.4f, -1.9f, 0.6f, 0.7f, 0, 1, 0.25f),
                      iv(0.6f, 0.8f, 0.2f, 1.3f, 0.1f, 0.2f, 1)});
    // crosses the near plane (z < 0) and the far plane
    scenes.push_back({iv(-0.5f, -0.5f, -0.8f, 1.5f, 1, 1, 0), iv(0.9f, -0.2f, 0.7f, 1.0f, 0, 1, 1),
                      iv(-0.1f, 0.9f, 1.9f, 1.2f, 1, 0, 1)});
    // covers the whole viewport, crosses all four sides
    scenes.push_back({iv(-5, -5, 0.5f, 1, 0.2f, 0.9f, 0.4f), iv(9, -5, 0.5f, 3, 0.8f, 0.1f, 0.6f),
                      iv(-5, 9, 0.5f, 2, 0.5f, 0.5f, 0.0f)});
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int s = 0; s < 24; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 3 * 4; ++k) {
            const float w = 0.4f + 2.5f * u(rng);
            sc.push_back(iv((u(rng) * 3.4f - 1.7f) * w, (u(rng) * 3.4f - 1.7f) * w, (u(rng) * 1.4f - 0.2f) * w, w,
                            u(rng), u(rng), u(rng), u(rng)));
        }
        scenes.push_back(sc);
    }
    return scenes;
}

TEST(LavapipeCrossCheck, ClippedPerspectiveTrianglesMatchPixelForPixel) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const auto scenes = make_scenes();
    const bool fma = host_has_fma();
    int compared = 0, clipped_scenes = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        for (int mode : {0, 1, 2, 4, 5, 6}) {
            const auto got = lvp.render(scenes[s], mode);
            ASSERT_EQ(got.size(), static_cast<size_t>(kSize * kSize * 4));
            const auto want = model(scenes[s], mode, fma);
            int diff = 0, first = -1;
            for (size_t i = 0; i < got.size(); ++i)
                if (got[i] != want[i]) {
                    if (first < 0) first = static_cast<int>(i);
                    ++diff;
                }
            EXPECT_EQ(diff, 0) << "scene " << s << " mode " << mode << " first diff at pixel " << first / 4
                               << " channel " << first % 4 << ": lavapipe " << int(got[first < 0 ? 0 : first])
                               << " model " << int(want[first < 0 ? 0 : first]);
            int lit = 0;
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            compared += lit;
        }
        (void)clipped_scenes;
    }
    std::printf("compared %zu scenes x 6 modes, %d lit pixels in total\n", scenes.size(), compared);
    EXPECT_GT(compared, 10000);  // the scenes really drew something
}

TEST(LavapipeCrossCheck, WrongRulesAreDetected) {
    // The comparison can fail: deliberately wrong rules (the other FMA choice, a/w for a*(1/w)) must differ.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const auto scenes = make_scenes();
    int diff_fma = 0, diff_div = 0;
    for (const auto& sc : scenes) {
        for (int mode : {4, 5}) {
            const auto got = lvp.render(sc, mode);
            const auto wrong_fma = model(sc, mode, !host_has_fma());
            const auto wrong_div = model(sc, mode, host_has_fma(), true);
            for (size_t i = 0; i < got.size(); ++i) {
                diff_fma += got[i] != wrong_fma[i];
                diff_div += got[i] != wrong_div[i];
            }
        }
    }
    std::printf("wrong-rule channel mismatches: other FMA choice %d, a/w %d\n", diff_fma, diff_div);
    EXPECT_GT(diff_fma, 0);
    EXPECT_GT(diff_div, 0);
}

namespace {

int count_diff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int* first) {
    int diff = 0;
    *first = -1;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
        if (a[i] != b[i]) {
            if (*first < 0) *first = static_cast<int>(i);
            ++diff;
        }
    return diff + static_cast<int>(a.size() != b.size());
}

}  // namespace

TEST(LavapipeCrossCheck, LinesIncludingClippedAndWide) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = host_has_fma();
    int lit = 0;
    for (int s = 0; s < 16; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 2 * 6; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            sc.push_back(iv((u(rng) * 3.0f - 1.5f) * w, (u(rng) * 3.0f - 1.5f) * w, (u(rng) * 1.2f - 0.1f) * w, w,
                            u(rng), u(rng), u(rng), u(rng)));
        }
        for (float width : {1.0f, 3.0f, 2.5f}) {
            for (int mode : {0, 1, 2, 4, 5}) {
                const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, width);
                const auto want = model_lines(sc, mode, fma, width);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "scene " << s << " width " << width << " mode " << mode << " first diff pixel "
                                   << first / 4 << " (x " << (first / 4) % kSize << ", y " << (first / 4) / kSize
                                   << ") lavapipe " << int(got[first < 0 ? 0 : first]) << " model "
                                   << int(want[first < 0 ? 0 : first]);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("lines: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, PointsIncludingOffscreenCentres) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = host_has_fma();
    int lit = 0;
    for (int s = 0; s < 16; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 24; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            sc.push_back(iv((u(rng) * 2.4f - 1.2f) * w, (u(rng) * 2.4f - 1.2f) * w, (u(rng) * 1.2f - 0.1f) * w, w,
                            u(rng), u(rng), u(rng), u(rng)));
        }
        for (int mode : {0, 1, 2, 4, 5}) {
            const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_POINT_LIST);
            const auto want = model_points(sc, mode, fma);
            int first;
            const int diff = count_diff(got, want, &first);
            EXPECT_EQ(diff, 0) << "scene " << s << " mode " << mode << " first diff pixel " << first / 4 << " (x "
                               << (first / 4) % kSize << ", y " << (first / 4) / kSize << ") lavapipe "
                               << int(got[first < 0 ? 0 : first]) << " model " << int(want[first < 0 ? 0 : first]);
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
        }
    }
    std::printf("points: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, BresenhamLines) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    if (!lvp.has_line_ext()) GTEST_SKIP() << "no VK_EXT_line_rasterization";
    std::mt19937 rng(78);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = host_has_fma();
    int lit = 0, differs_from_rect = 0;
    for (int s = 0; s < 16; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 2 * 6; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            // a quarter of the endpoints on pixel centres / edges, where the diamond rule has its special cases
            float x = u(rng) * 2.4f - 1.2f, y = u(rng) * 2.4f - 1.2f;
            if (k % 4 == 0) x = (std::floor((x + 1) * 32) + 0.5f) / 32 - 1, y = std::floor((y + 1) * 32) / 32 - 1;
            sc.push_back(iv(x * w, y * w, 0.5f * w, w, u(rng), u(rng), u(rng), u(rng)));
        }
        for (float width : {1.0f, 3.0f}) {
            for (int mode : {0, 1, 4}) {
                const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, width, true);
                const auto want = model_lines(sc, mode, fma, width, true);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "scene " << s << " width " << width << " mode " << mode << " first diff pixel "
                                   << first / 4 << " (x " << (first / 4) % kSize << ", y " << (first / 4) / kSize
                                   << ") lavapipe " << int(got[first < 0 ? 0 : first]) << " model "
                                   << int(want[first < 0 ? 0 : first]);
                int f2;
                differs_from_rect += count_diff(got, model_lines(sc, mode, fma, width, false), &f2);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("bresenham lines: %d lit pixels compared, %d channels differ from the rectangular model\n", lit,
                differs_from_rect);
    EXPECT_GT(lit, 2000);
    EXPECT_GT(differs_from_rect, 0);  // the two line modes are really different
}

TEST(LavapipeCrossCheck, VertexFormatConversions) {
    // Points with constant colours fetched from each format; the amplified mode (fract(x*65536)) exposes the low
    // bits of every converted value in the u8 output.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const struct {
        VkFormat vk;
        VertexFormat ours;
    } formats[] = {
        {VK_FORMAT_R8G8B8A8_UNORM, VertexFormat::kR8G8B8A8Unorm},
        {VK_FORMAT_R8G8B8A8_SNORM, VertexFormat::kR8G8B8A8Snorm},
        {VK_FORMAT_B8G8R8A8_UNORM, VertexFormat::kB8G8R8A8Unorm},
        {VK_FORMAT_R8G8_UNORM, VertexFormat::kR8G8Unorm},
        {VK_FORMAT_R8G8B8_SNORM, VertexFormat::kR8G8B8Snorm},
        {VK_FORMAT_R16G16B16A16_UNORM, VertexFormat::kR16G16B16A16Unorm},
        {VK_FORMAT_R16G16B16A16_SNORM, VertexFormat::kR16G16B16A16Snorm},
        {VK_FORMAT_R16G16_SNORM, VertexFormat::kR16G16Snorm},
        {VK_FORMAT_R16G16B16A16_SFLOAT, VertexFormat::kR16G16B16A16Float},
        {VK_FORMAT_R32G32B32_SFLOAT, VertexFormat::kR32G32B32Float},
        {VK_FORMAT_R32_SFLOAT, VertexFormat::kR32Float},
    };
    std::mt19937 rng(404);
    const bool fma = host_has_fma();
    int lit = 0;
    for (const auto& f : formats) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 64; ++k) {
            InVertex v = iv(((k % 8) + 0.5f) / 4 - 1, ((k / 8) + 0.5f) / 4 - 1, 0.5f, 1, 0, 0, 0);
            uint8_t bytes[16];
            for (auto& b : bytes) b = static_cast<uint8_t>(rng());
            if (k < 4) std::memset(bytes, k == 0 ? 0x00 : k == 1 ? 0xFF : k == 2 ? 0x80 : 0x7F, 16);  // extremes
            if (f.ours == VertexFormat::kR16G16B16A16Float || f.ours == VertexFormat::kR32G32B32Float ||
                f.ours == VertexFormat::kR32Float) {
                // finite values in [0, 1): random mantissa bits
                for (int c = 0; c < 4; ++c) {
                    const float x = static_cast<float>(rng() % 1000000) / 1000000.0f;
                    if (f.ours == VertexFormat::kR16G16B16A16Float) {
                        const uint16_t h = static_cast<uint16_t>(0x3800 | (rng() & 0x3FF));  // [0.5, 1)
                        std::memcpy(bytes + 2 * c, &h, 2);
                    } else {
                        std::memcpy(bytes + 4 * c, &x, 4);
                    }
                }
            }
            std::memcpy(v.col, bytes, 16);
            sc.push_back(v);
        }
        for (int mode : {1, 5}) {
            const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 1, false, f.vk);
            const auto want = model_points(sc, mode, fma, f.ours);
            int first;
            const int diff = count_diff(got, want, &first);
            EXPECT_EQ(diff, 0) << "format " << f.vk << " mode " << mode << " first diff pixel " << first / 4
                               << " channel " << first % 4 << " lavapipe " << int(got[first < 0 ? 0 : first])
                               << " model " << int(want[first < 0 ? 0 : first]);
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
        }
    }
    std::printf("vertex formats: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 500);
}

TEST(LavapipeCrossCheck, DepthPlaneAndDepthBias) {
    // gl_FragCoord.z carries the z plane plus lavapipe's depth offset (unorm24 units without a depth attachment).
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const auto scenes = make_scenes();
    const bool fma = host_has_fma();
    DepthBias cases[4];
    cases[0] = DepthBias{};
    cases[1].constant_factor = 3.0f;
    cases[2].constant_factor = 1.5f, cases[2].slope_factor = 0.75f;
    cases[3].constant_factor = -200.0f, cases[3].slope_factor = -2.0f, cases[3].clamp = -0.0004f;
    int lit = 0, unbiased_diff = 0, no_factor2_diff = 0;
    for (int b = 0; b < 4; ++b) {
        for (size_t s = 0; s < 12; ++s) {
            const auto got = lvp.render(scenes[s], 8, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                        VK_FORMAT_R32G32B32A32_SFLOAT, b == 0 ? nullptr : &cases[b]);
            const auto want = model(scenes[s], 8, fma, false, b == 0 ? nullptr : &cases[b]);
            int first;
            const int diff = count_diff(got, want, &first);
            EXPECT_EQ(diff, 0) << "bias case " << b << " scene " << s << " first diff pixel " << first / 4
                               << " channel " << first % 4 << " lavapipe " << int(got[first < 0 ? 0 : first])
                               << " model " << int(want[first < 0 ? 0 : first]);
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            if (b != 0) {
                // negative control: the same scene without the bias (or without the factor 2) must differ
                int f2;
                unbiased_diff += count_diff(got, model(scenes[s], 8, fma), &f2);
                DepthBias half = cases[b];
                half.constant_factor *= 0.5f;
                no_factor2_diff += count_diff(got, model(scenes[s], 8, fma, false, &half), &f2);
            }
        }
    }
    std::printf("depth: %d lit pixels compared; controls differ: no bias %d, no factor 2 %d\n", lit, unbiased_diff,
                no_factor2_diff);
    EXPECT_GT(unbiased_diff, 0);
    EXPECT_GT(no_factor2_diff, 0);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, DepthClampNegativeWAndCulling) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    auto scenes = make_scenes();
    std::mt19937 rng(909);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int s = 0; s < 12; ++s) {  // vertices behind the eye (w < 0) and far outside z
        std::vector<InVertex> sc;
        for (int k = 0; k < 3 * 4; ++k) {
            const float w = -1.0f + 4.0f * u(rng);
            sc.push_back(iv((u(rng) * 3 - 1.5f) * 1.5f, (u(rng) * 3 - 1.5f) * 1.5f, (u(rng) * 3 - 1) * 1.5f, w, u(rng),
                            u(rng), u(rng), u(rng)));
        }
        scenes.push_back(sc);
    }
    const bool fma = host_has_fma();
    int lit = 0;
    for (int variant = 0; variant < 4; ++variant) {
        Extra x;
        ModelExtra mx;
        x.depth_clamp = variant == 1;
        mx.clip_z = !x.depth_clamp;
        if (variant == 2) x.cull = VK_CULL_MODE_BACK_BIT, mx.cull_back = true;
        if (variant == 3) {
            x.cull = VK_CULL_MODE_FRONT_BIT, mx.cull_front = true;
            x.front = VK_FRONT_FACE_CLOCKWISE, mx.front_ccw = false;
        }
        for (size_t s = 0; s < scenes.size(); ++s) {
            for (int mode : {0, 4}) {
                const auto got = lvp.render(scenes[s], mode, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                            VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                const auto want = model(scenes[s], mode, fma, false, nullptr, mx);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "variant " << variant << " scene " << s << " mode " << mode
                                   << " first diff pixel " << first / 4 << " lavapipe "
                                   << int(got[first < 0 ? 0 : first]) << " model " << int(want[first < 0 ? 0 : first]);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("depth clamp / w<0 / cull: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 5000);
}

TEST(LavapipeCrossCheck, StripsFansAndRestartOrders) {
    // Indexed strips and fans with primitive restart: assemble_primitives' order (and thus each triangle's plane
    // rounding and provoking vertex) must reproduce lavapipe's pixels, in the amplified and flat modes.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(1717);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = host_has_fma();
    int lit = 0, wrong_diff = 0;
    for (int s = 0; s < 12; ++s) {
        std::vector<InVertex> verts;
        for (int k = 0; k < 16; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            verts.push_back(iv((u(rng) * 2.8f - 1.4f) * w, (u(rng) * 2.8f - 1.4f) * w, 0.5f * w, w, u(rng), u(rng),
                               u(rng), u(rng)));
        }
        std::vector<uint32_t> idx;
        for (int k = 0; k < 14; ++k) idx.push_back(rng() % 16);
        idx[6] = 0xFFFFFFFFu;  // restart in the middle
        for (auto topo : {VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN}) {
            IndexSource src;
            src.indices = reinterpret_cast<const uint8_t*>(idx.data());
            src.index_size = 4;
            src.index_count_total = static_cast<uint32_t>(idx.size());
            src.count = src.index_count_total;
            src.primitive_restart = true;
            const Topology t =
                topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP ? Topology::kTriangleStrip : Topology::kTriangleFan;
            std::vector<uint32_t> order(assembled_index_capacity(t, src.count));
            const uint32_t prims = assemble_primitives(src, t, true, order.data(), order.size());
            std::vector<InVertex> list, wrong;
            for (uint32_t i = 0; i < prims * 3; ++i) list.push_back(verts[order[i]]);
            // negative control: the last-vertex-provoking order
            std::vector<uint32_t> order_last(order.size());
            assemble_primitives(src, t, false, order_last.data(), order_last.size());
            for (uint32_t i = 0; i < prims * 3; ++i) wrong.push_back(verts[order_last[i]]);
            Extra x;
            x.restart = true;
            x.indices = &idx;
            for (int mode : {2, 4, 5}) {
                const auto got = lvp.render(verts, mode, topo, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                const auto want = model(list, mode, fma);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "topology " << topo << " scene " << s << " mode " << mode << " first diff pixel "
                                   << first / 4 << " lavapipe " << int(got[first < 0 ? 0 : first]) << " model "
                                   << int(want[first < 0 ? 0 : first]);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
                wrong_diff += count_diff(got, model(wrong, mode, fma), &first);
            }
        }
    }
    std::printf("strips/fans: %d lit pixels compared; last-vertex order differs in %d channels\n", lit, wrong_diff);
    EXPECT_GT(wrong_diff, 0);
    EXPECT_GT(lit, 5000);
}

TEST(LavapipeCrossCheck, FractionalViewportLimitsEveryPrimitive) {
    // A fractional viewport smaller than the target: clipped triangles and lines, and points (never x/y clipped,
    // limited only by the viewport's whole-pixel rectangle).
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = host_has_fma();
    const float vps[3][4] = {{10.25f, 5.75f, 40.5f, 30.25f}, {3.6f, 50.4f, 52.3f, -41.7f}, {0.5f, 0.5f, 62, 62}};
    int lit = 0;
    for (const auto& vpv : vps) {
        Extra x;
        ModelExtra mx;
        std::memcpy(x.vp, vpv, sizeof(x.vp));
        std::memcpy(mx.vp, vpv, sizeof(mx.vp));
        for (int s = 0; s < 6; ++s) {
            std::vector<InVertex> sc;
            for (int k = 0; k < 12; ++k) {
                const float w = 0.5f + 2.0f * u(rng);
                sc.push_back(iv((u(rng) * 3.0f - 1.5f) * w, (u(rng) * 3.0f - 1.5f) * w, 0.5f * w, w, u(rng), u(rng),
                                u(rng), u(rng)));
            }
            for (int mode : {0, 4}) {
                int first;
                auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                      VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                EXPECT_EQ(count_diff(got, model(sc, mode, fma, false, nullptr, mx), &first), 0)
                    << "triangles vp " << vpv[0] << " scene " << s << " mode " << mode << " pixel " << first / 4;
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
                got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 2.0f, false, VK_FORMAT_R32G32B32A32_SFLOAT,
                                 nullptr, x);
                EXPECT_EQ(count_diff(got, model_lines(sc, mode, fma, 2.0f, false, mx), &first), 0)
                    << "lines vp " << vpv[0] << " scene " << s << " mode " << mode << " pixel " << first / 4;
                got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT,
                                 nullptr, x);
                EXPECT_EQ(count_diff(got, model_points(sc, mode, fma, VertexFormat::kR32G32B32A32Float, mx), &first), 0)
                    << "points vp " << vpv[0] << " scene " << s << " mode " << mode << " pixel " << first / 4;
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("fractional viewports: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 2000);
}
