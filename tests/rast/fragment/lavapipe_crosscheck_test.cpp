// The strongest evidence: render on lavapipe itself and compare bit for bit with the kernels: blending (full-screen
// triangle per blend state over random destination bytes), depth conversion/clamping (gl_FragDepth from a buffer)
// and 4x resolves (per-sample colours via sample shading, render-pass resolve). For blending: read the image back
// and compare every pixel with blend_pixel() fed the same source colours, destination bytes and constants.
// Skips (not fails) when no lavapipe device can be created.
#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "buffer_color_frag.h"
#include "buffer_depth_frag.h"
#include "fullscreen_vert.h"
#include "interp_frag.h"
#include "interp_vert.h"
#include "rast/fragment/blend.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/fragment/interp.h"
#include "rast/fragment/msaa.h"
#include "sample_color_frag.h"

using namespace tilevk::rast::fragment;

namespace {

constexpr uint32_t kW = 64, kH = 64;

#define VKC(x)                                                                               \
    do {                                                                                     \
        VkResult r_ = (x);                                                                   \
        if (r_ != VK_SUCCESS) throw std::runtime_error(#x " failed: " + std::to_string(r_)); \
    } while (0)

VkFormat to_vk(ColorFormat f) {
    switch (f) {
        case ColorFormat::R8G8B8A8_UNORM:
            return VK_FORMAT_R8G8B8A8_UNORM;
        case ColorFormat::B8G8R8A8_UNORM:
            return VK_FORMAT_B8G8R8A8_UNORM;
        case ColorFormat::R8G8B8A8_SRGB:
            return VK_FORMAT_R8G8B8A8_SRGB;
        case ColorFormat::B8G8R8A8_SRGB:
            return VK_FORMAT_B8G8R8A8_SRGB;
        case ColorFormat::R8_UNORM:
            return VK_FORMAT_R8_UNORM;
        case ColorFormat::R8G8_UNORM:
            return VK_FORMAT_R8G8_UNORM;
        case ColorFormat::R16G16B16A16_SFLOAT:
            return VK_FORMAT_R16G16B16A16_SFLOAT;
        case ColorFormat::R32_SFLOAT:
            return VK_FORMAT_R32_SFLOAT;
        case ColorFormat::R32G32_SFLOAT:
            return VK_FORMAT_R32G32_SFLOAT;
        case ColorFormat::R32G32B32A32_SFLOAT:
            return VK_FORMAT_R32G32B32A32_SFLOAT;
    }
    return VK_FORMAT_UNDEFINED;
}

struct Lvp {
    VkInstance inst = VK_NULL_HANDLE;
    VkPhysicalDevice phys = VK_NULL_HANDLE;
    VkDevice dev = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t qfam = 0;
    VkPhysicalDeviceMemoryProperties mem{};
    VkCommandPool pool = VK_NULL_HANDLE;

    bool init() {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.apiVersion = VK_API_VERSION_1_0;
        VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ici.pApplicationInfo = &app;
        if (vkCreateInstance(&ici, nullptr, &inst) != VK_SUCCESS) return false;
        uint32_t n = 0;
        vkEnumeratePhysicalDevices(inst, &n, nullptr);
        std::vector<VkPhysicalDevice> devs(n);
        vkEnumeratePhysicalDevices(inst, &n, devs.data());
        for (VkPhysicalDevice d : devs) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(d, &p);
            if (std::string(p.deviceName).find("llvmpipe") != std::string::npos) phys = d;
        }
        if (!phys) return false;
        vkGetPhysicalDeviceMemoryProperties(phys, &mem);
        float prio = 1.0f;
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = 0;
        qci.queueCount = 1;
        qci.pQueuePriorities = &prio;
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        VkPhysicalDeviceFeatures feats{};
        feats.depthClamp = VK_TRUE;
        feats.sampleRateShading = VK_TRUE;
        dci.pEnabledFeatures = &feats;
        if (vkCreateDevice(phys, &dci, nullptr, &dev) != VK_SUCCESS) return false;
        vkGetDeviceQueue(dev, 0, 0, &queue);
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        VKC(vkCreateCommandPool(dev, &pci, nullptr, &pool));
        return true;
    }
    ~Lvp() {
        if (dev) {
            vkDestroyCommandPool(dev, pool, nullptr);
            vkDestroyDevice(dev, nullptr);
        }
        if (inst) vkDestroyInstance(inst, nullptr);
    }
    uint32_t mem_type(uint32_t bits, VkMemoryPropertyFlags want) const {
        for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
            if ((bits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) return i;
        throw std::runtime_error("no memory type");
    }
};

struct Buffer {
    VkBuffer buf = VK_NULL_HANDLE;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    void* map = nullptr;
};

Buffer make_buffer(const Lvp& v, VkDeviceSize size, VkBufferUsageFlags usage) {
    Buffer b;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = size;
    bci.usage = usage;
    VKC(vkCreateBuffer(v.dev, &bci, nullptr, &b.buf));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(v.dev, b.buf, &req);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex =
        v.mem_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VKC(vkAllocateMemory(v.dev, &mai, nullptr, &b.mem));
    VKC(vkBindBufferMemory(v.dev, b.buf, b.mem, 0));
    VKC(vkMapMemory(v.dev, b.mem, 0, VK_WHOLE_SIZE, 0, &b.map));
    return b;
}
void free_buffer(const Lvp& v, Buffer& b) {
    vkDestroyBuffer(v.dev, b.buf, nullptr);
    vkFreeMemory(v.dev, b.mem, nullptr);
}

VkShaderModule make_shader(const Lvp& v, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule m;
    VKC(vkCreateShaderModule(v.dev, &ci, nullptr, &m));
    return m;
}

// Renders src colours over dst bytes with the blend state; returns the image bytes.
std::vector<uint8_t> render(const Lvp& v, ColorFormat f, const BlendAttachment& a, const float consts[4],
                            const std::vector<float>& src, const std::vector<uint8_t>& dst) {
    const uint32_t bpp = format_info(f).bytes;
    const VkFormat vf = to_vk(f);
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = vf;
    ii.extent = {kW, kH, 1};
    ii.mipLevels = ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImage img;
    VKC(vkCreateImage(v.dev, &ii, nullptr, &img));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(v.dev, img, &req);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = v.mem_type(req.memoryTypeBits, 0);
    VkDeviceMemory imem;
    VKC(vkAllocateMemory(v.dev, &mai, nullptr, &imem));
    VKC(vkBindImageMemory(v.dev, img, imem, 0));
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = img;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = vf;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    VKC(vkCreateImageView(v.dev, &vi, nullptr, &view));

    VkAttachmentDescription att{};
    att.format = vf;
    att.samples = VK_SAMPLE_COUNT_1_BIT;
    att.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    att.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpi.attachmentCount = 1;
    rpi.pAttachments = &att;
    rpi.subpassCount = 1;
    rpi.pSubpasses = &sub;
    VkRenderPass rp;
    VKC(vkCreateRenderPass(v.dev, &rpi, nullptr, &rp));
    VkFramebufferCreateInfo fbi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fbi.renderPass = rp;
    fbi.attachmentCount = 1;
    fbi.pAttachments = &view;
    fbi.width = kW;
    fbi.height = kH;
    fbi.layers = 1;
    VkFramebuffer fb;
    VKC(vkCreateFramebuffer(v.dev, &fbi, nullptr, &fb));

    VkDescriptorSetLayoutBinding b0{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo dli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    dli.bindingCount = 1;
    dli.pBindings = &b0;
    VkDescriptorSetLayout dsl;
    VKC(vkCreateDescriptorSetLayout(v.dev, &dli, nullptr, &dsl));
    VkPushConstantRange pcr{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &dsl;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &pcr;
    VkPipelineLayout pl;
    VKC(vkCreatePipelineLayout(v.dev, &pli, nullptr, &pl));

    VkShaderModule vs = make_shader(v, kFullscreenVert, sizeof kFullscreenVert);
    VkShaderModule fs = make_shader(v, kBufferColorFrag, sizeof kBufferColorFrag);
    VkPipelineShaderStageCreateInfo st[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                             {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    st[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    st[0].module = vs;
    st[0].pName = "main";
    st[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    st[1].module = fs;
    st[1].pName = "main";
    VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkViewport vp{0, 0, float(kW), float(kH), 0, 1};
    VkRect2D sc{{0, 0}, {kW, kH}};
    VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vps.viewportCount = 1;
    vps.pViewports = &vp;
    vps.scissorCount = 1;
    vps.pScissors = &sc;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineColorBlendAttachmentState cba{};
    cba.blendEnable = a.blend_enable;
    cba.srcColorBlendFactor = VkBlendFactor(a.src_color);
    cba.dstColorBlendFactor = VkBlendFactor(a.dst_color);
    cba.colorBlendOp = VkBlendOp(a.color_op);
    cba.srcAlphaBlendFactor = VkBlendFactor(a.src_alpha);
    cba.dstAlphaBlendFactor = VkBlendFactor(a.dst_alpha);
    cba.alphaBlendOp = VkBlendOp(a.alpha_op);
    cba.colorWriteMask = a.write_mask;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = 1;
    cb.pAttachments = &cba;
    std::memcpy(cb.blendConstants, consts, 16);
    VkGraphicsPipelineCreateInfo gpi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gpi.stageCount = 2;
    gpi.pStages = st;
    gpi.pVertexInputState = &vin;
    gpi.pInputAssemblyState = &ia;
    gpi.pViewportState = &vps;
    gpi.pRasterizationState = &rs;
    gpi.pMultisampleState = &ms;
    gpi.pColorBlendState = &cb;
    gpi.layout = pl;
    gpi.renderPass = rp;
    VkPipeline pipe;
    VKC(vkCreateGraphicsPipelines(v.dev, VK_NULL_HANDLE, 1, &gpi, nullptr, &pipe));

    VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.maxSets = 1;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &ps;
    VkDescriptorPool dp;
    VKC(vkCreateDescriptorPool(v.dev, &dpi, nullptr, &dp));
    VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    dai.descriptorPool = dp;
    dai.descriptorSetCount = 1;
    dai.pSetLayouts = &dsl;
    VkDescriptorSet ds;
    VKC(vkAllocateDescriptorSets(v.dev, &dai, &ds));

    Buffer colors = make_buffer(v, src.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::memcpy(colors.map, src.data(), src.size() * 4);
    Buffer xfer = make_buffer(v, VkDeviceSize(kW) * kH * bpp,
                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    std::memcpy(xfer.map, dst.data(), dst.size());
    VkDescriptorBufferInfo dbi{colors.buf, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = ds;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &dbi;
    vkUpdateDescriptorSets(v.dev, 1, &w, 0, nullptr);

    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = v.pool;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VKC(vkAllocateCommandBuffers(v.dev, &cai, &cmd));
    VkCommandBufferBeginInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VKC(vkBeginCommandBuffer(cmd, &cbi));
    VkImageMemoryBarrier bar{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    bar.srcQueueFamilyIndex = bar.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    bar.image = img;
    bar.subresourceRange = vi.subresourceRange;
    bar.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    bar.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    bar.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &bar);
    VkBufferImageCopy bic{};
    bic.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    bic.imageExtent = {kW, kH, 1};
    vkCmdCopyBufferToImage(cmd, xfer.buf, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &bic);
    bar.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    bar.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    bar.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    bar.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &bar);
    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = rp;
    rbi.framebuffer = fb;
    rbi.renderArea = sc;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pl, 0, 1, &ds, 0, nullptr);
    const uint32_t width = kW;
    vkCmdPushConstants(cmd, pl, VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4, &width);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    vkCmdCopyImageToBuffer(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, xfer.buf, 1, &bic);
    VKC(vkEndCommandBuffer(cmd));
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VKC(vkQueueSubmit(v.queue, 1, &si, VK_NULL_HANDLE));
    VKC(vkQueueWaitIdle(v.queue));
    std::vector<uint8_t> out(size_t(kW) * kH * bpp);
    std::memcpy(out.data(), xfer.map, out.size());

    vkFreeCommandBuffers(v.dev, v.pool, 1, &cmd);
    free_buffer(v, colors);
    free_buffer(v, xfer);
    vkDestroyDescriptorPool(v.dev, dp, nullptr);
    vkDestroyPipeline(v.dev, pipe, nullptr);
    vkDestroyShaderModule(v.dev, vs, nullptr);
    vkDestroyShaderModule(v.dev, fs, nullptr);
    vkDestroyPipelineLayout(v.dev, pl, nullptr);
    vkDestroyDescriptorSetLayout(v.dev, dsl, nullptr);
    vkDestroyFramebuffer(v.dev, fb, nullptr);
    vkDestroyRenderPass(v.dev, rp, nullptr);
    vkDestroyImageView(v.dev, view, nullptr);
    vkDestroyImage(v.dev, img, nullptr);
    vkFreeMemory(v.dev, imem, nullptr);
    return out;
}

float random_src(std::mt19937& rng, ChannelKind kind) {
    const uint32_t r = rng() % 1000;
    if (kind == ChannelKind::Float32 || kind == ChannelKind::Half) return float(int(rng() % 40001) - 20000) / 7919.0f;
    if (r < 5) return INFINITY;  // the 8-wide conversion clamps +Inf to 1 (the 4-wide one would give 0)
    if (r < 8) return NAN;
    if (r < 10) return 3e9f;
    if (r < 30) return -0.25f;
    if (r < 60) return 1.5f;
    return float(rng() % 1000001) / 1000000.0f;
}

void random_dst(std::mt19937& rng, ColorFormat f, uint8_t* px) {
    const FormatInfo fi = format_info(f);
    if (fi.kind == ChannelKind::Float32) {
        for (int c = 0; c < fi.channels; ++c) {
            const float v = float(int(rng() % 20001) - 10000) / 4999.0f;
            std::memcpy(px + 4 * c, &v, 4);
        }
    } else if (fi.kind == ChannelKind::Half) {
        for (int c = 0; c < fi.channels; ++c) {
            const uint16_t h = uint16_t(rng() % 0x4400u) | uint16_t((rng() & 1) << 15);  // finite, |x| < 4
            std::memcpy(px + 2 * c, &h, 2);
        }
    } else {
        for (int i = 0; i < fi.bytes; ++i) px[i] = uint8_t(rng());
    }
}

struct Case {
    const char* name;
    ColorFormat format;
    BlendAttachment a;
};

BlendAttachment ba(BlendFactor sc, BlendFactor dc, BlendOp co, BlendFactor sa, BlendFactor da, BlendOp ao,
                   uint8_t mask = 0xf) {
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = sc;
    a.dst_color = dc;
    a.color_op = co;
    a.src_alpha = sa;
    a.dst_alpha = da;
    a.alpha_op = ao;
    a.write_mask = mask;
    return a;
}

}  // namespace

using F = BlendFactor;
using O = BlendOp;

TEST(FragmentLavapipe, BlendMatchesLavapipeBitForBit) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    BlendAttachment off;
    const Case cases[] = {
        {"rgba8 no blend", ColorFormat::R8G8B8A8_UNORM, off},
        {"rgba8 alpha", ColorFormat::R8G8B8A8_UNORM,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::OneMinusSrcAlpha, O::Add)},
        {"rgba8 additive", ColorFormat::R8G8B8A8_UNORM, ba(F::One, F::One, O::Add, F::One, F::One, O::Add)},
        {"rgba8 modulate", ColorFormat::R8G8B8A8_UNORM,
         ba(F::DstColor, F::Zero, O::Add, F::DstAlpha, F::SrcColor, O::Subtract)},
        {"rgba8 const", ColorFormat::R8G8B8A8_UNORM,
         ba(F::ConstantColor, F::OneMinusConstantAlpha, O::ReverseSubtract, F::ConstantAlpha, F::OneMinusDstAlpha,
            O::Add, kWriteR | kWriteB | kWriteA)},
        {"rgba8 min max", ColorFormat::R8G8B8A8_UNORM, ba(F::SrcAlpha, F::DstColor, O::Min, F::Zero, F::Zero, O::Max)},
        {"rgba8 saturate", ColorFormat::R8G8B8A8_UNORM,
         ba(F::SrcAlphaSaturate, F::OneMinusSrcColor, O::Add, F::SrcAlphaSaturate, F::OneMinusDstColor, O::Add)},
        {"bgra8 alpha", ColorFormat::B8G8R8A8_UNORM,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Subtract, F::OneMinusDstAlpha, F::One, O::ReverseSubtract)},
        {"r8 lerp quirk", ColorFormat::R8_UNORM,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::SrcAlpha, F::OneMinusSrcAlpha, O::Add)},
        {"r8 dst alpha", ColorFormat::R8_UNORM, ba(F::DstAlpha, F::OneMinusDstColor, O::Add, F::One, F::Zero, O::Add)},
        {"rg8 const", ColorFormat::R8G8_UNORM, ba(F::ConstantAlpha, F::SrcColor, O::Subtract, F::One, F::Zero, O::Add)},
        {"rgba16f alpha", ColorFormat::R16G16B16A16_SFLOAT,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::OneMinusSrcAlpha, O::Add)},
        {"rgba16f shared", ColorFormat::R16G16B16A16_SFLOAT,
         ba(F::ConstantColor, F::ConstantColor, O::Subtract, F::ConstantColor, F::ConstantColor, O::Subtract)},
        {"r32f lerp", ColorFormat::R32_SFLOAT, ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::Zero, O::Add)},
        {"r32f complementary sub", ColorFormat::R32_SFLOAT,
         ba(F::OneMinusSrcColor, F::SrcColor, O::ReverseSubtract, F::One, F::Zero, O::Add)},
        {"rg32f general", ColorFormat::R32G32_SFLOAT,
         ba(F::DstColor, F::ConstantColor, O::Add, F::One, F::Zero, O::Add)},
        {"rgba32f shared", ColorFormat::R32G32B32A32_SFLOAT,
         ba(F::SrcAlpha, F::SrcAlpha, O::Add, F::SrcAlpha, F::SrcAlpha, O::Add)},
        {"rgba32f min", ColorFormat::R32G32B32A32_SFLOAT, ba(F::SrcColor, F::SrcAlpha, O::Min, F::One, F::One, O::Max)},
        {"srgb alpha", ColorFormat::R8G8B8A8_SRGB,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::OneMinusSrcAlpha, O::Add)},
        {"srgb no blend", ColorFormat::B8G8R8A8_SRGB, off},
    };
    std::mt19937 rng(42);
    for (const Case& c : cases) {
        const FormatInfo fi = format_info(c.format);
        std::vector<float> src(size_t(kW) * kH * 4);
        std::vector<uint8_t> dst(size_t(kW) * kH * fi.bytes);
        for (float& s : src) s = random_src(rng, fi.kind);
        for (size_t p = 0; p < size_t(kW) * kH; ++p) random_dst(rng, c.format, &dst[p * fi.bytes]);
        const float consts[4] = {0.2f, 0.71f, 1.0f, 0.4f};
        const std::vector<uint8_t> got = render(v, c.format, c.a, consts, src, dst);
        int bad = 0, changed = 0;
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            changed += std::memcmp(&dst[p * fi.bytes], &got[p * fi.bytes], fi.bytes) != 0;
            uint8_t want[16];
            std::memcpy(want, &dst[p * fi.bytes], fi.bytes);
            blend_pixel(c.a, c.format, consts, &src[p * 4], want);
            if (std::memcmp(want, &got[p * fi.bytes], fi.bytes) != 0) {
                if (bad++ < 3) {
                    std::string w, g;
                    for (int i = 0; i < fi.bytes; ++i) {
                        w += std::to_string(want[i]) + " ";
                        g += std::to_string(got[p * fi.bytes + i]) + " ";
                    }
                    ADD_FAILURE() << c.name << " pixel " << p << " src " << src[p * 4] << "," << src[p * 4 + 1] << ","
                                  << src[p * 4 + 2] << "," << src[p * 4 + 3] << " want " << w << " lavapipe " << g;
                }
            }
        }
        EXPECT_EQ(bad, 0) << c.name;
        // The draw really happened: most pixels changed.
        EXPECT_GT(changed, int(kW * kH) / 2) << c.name;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Depth conversion and clamping, and MSAA resolve, against lavapipe.

namespace {

struct Img {
    VkImage img = VK_NULL_HANDLE;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
};

Img make_image(const Lvp& v, VkFormat f, VkSampleCountFlagBits samples, VkImageUsageFlags usage,
               VkImageAspectFlags aspect) {
    Img r;
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = f;
    ii.extent = {kW, kH, 1};
    ii.mipLevels = ii.arrayLayers = 1;
    ii.samples = samples;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = usage;
    VKC(vkCreateImage(v.dev, &ii, nullptr, &r.img));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(v.dev, r.img, &req);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = v.mem_type(req.memoryTypeBits, 0);
    VKC(vkAllocateMemory(v.dev, &mai, nullptr, &r.mem));
    VKC(vkBindImageMemory(v.dev, r.img, r.mem, 0));
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = r.img;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = f;
    vi.subresourceRange = {aspect, 0, 1, 0, 1};
    VKC(vkCreateImageView(v.dev, &vi, nullptr, &r.view));
    return r;
}
void free_image(const Lvp& v, Img& i) {
    vkDestroyImageView(v.dev, i.view, nullptr);
    vkDestroyImage(v.dev, i.img, nullptr);
    vkFreeMemory(v.dev, i.mem, nullptr);
}

struct PassSpec {
    bool depth = false;  // depth-only pass writing gl_FragDepth, else colour (4x, per-sample) + resolve
    VkFormat format = VK_FORMAT_UNDEFINED;
    bool depth_clamp = false;
    float min_depth = 0.0f, max_depth = 1.0f;
    bool per_pixel_color = false;  // colour pass: one colour per pixel (no sample shading) instead of per sample
    bool alpha_to_coverage = false;
    uint32_t sample_mask = 0xf;
    bool interp = false;  // interp.vert/interp.frag with vertex data in the buffer, `samples` samples
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;
    bool no_draw = false;  // only the render pass clear
    float clear[4] = {};   // colour clear value
};

// Runs one pass and returns the readback (depth aspect, or the resolved colour image).
std::vector<uint8_t> run_pass(const Lvp& v, const PassSpec& spec, const std::vector<float>& data, uint32_t bpp) {
    const VkSampleCountFlagBits samples = spec.depth ? VK_SAMPLE_COUNT_1_BIT : spec.samples;
    const bool resolve = !spec.depth && samples != VK_SAMPLE_COUNT_1_BIT;
    const VkImageAspectFlags aspect = spec.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    Img target =
        make_image(v, spec.format, samples,
                   (spec.depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                   aspect);
    Img resolved;
    if (resolve)
        resolved = make_image(v, spec.format, VK_SAMPLE_COUNT_1_BIT,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, aspect);

    VkAttachmentDescription att[2]{};
    att[0].format = spec.format;
    att[0].samples = samples;
    att[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
    att[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    att[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    att[1] = att[0];
    att[1].samples = VK_SAMPLE_COUNT_1_BIT;
    att[1].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    VkAttachmentReference r0{
        0, spec.depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference r1{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    if (spec.depth) {
        sub.pDepthStencilAttachment = &r0;
    } else {
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &r0;
        if (resolve) sub.pResolveAttachments = &r1;
    }
    VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpi.attachmentCount = resolve ? 2 : 1;
    rpi.pAttachments = att;
    rpi.subpassCount = 1;
    rpi.pSubpasses = &sub;
    VkRenderPass rp;
    VKC(vkCreateRenderPass(v.dev, &rpi, nullptr, &rp));
    VkImageView views[2] = {target.view, resolved.view};
    VkFramebufferCreateInfo fbi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fbi.renderPass = rp;
    fbi.attachmentCount = rpi.attachmentCount;
    fbi.pAttachments = views;
    fbi.width = kW;
    fbi.height = kH;
    fbi.layers = 1;
    VkFramebuffer fb;
    VKC(vkCreateFramebuffer(v.dev, &fbi, nullptr, &fb));

    VkDescriptorSetLayoutBinding b0{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                                    VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_VERTEX_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo dli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    dli.bindingCount = 1;
    dli.pBindings = &b0;
    VkDescriptorSetLayout dsl;
    VKC(vkCreateDescriptorSetLayout(v.dev, &dli, nullptr, &dsl));
    VkPushConstantRange pcr{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &dsl;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &pcr;
    VkPipelineLayout pl;
    VKC(vkCreatePipelineLayout(v.dev, &pli, nullptr, &pl));
    VkShaderModule vs = spec.interp ? make_shader(v, kInterpVert, sizeof kInterpVert)
                                    : make_shader(v, kFullscreenVert, sizeof kFullscreenVert);
    VkShaderModule fs = spec.interp            ? make_shader(v, kInterpFrag, sizeof kInterpFrag)
                        : spec.depth           ? make_shader(v, kBufferDepthFrag, sizeof kBufferDepthFrag)
                        : spec.per_pixel_color ? make_shader(v, kBufferColorFrag, sizeof kBufferColorFrag)
                                               : make_shader(v, kSampleColorFrag, sizeof kSampleColorFrag);
    VkPipelineShaderStageCreateInfo st[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                             {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    st[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    st[0].module = vs;
    st[0].pName = "main";
    st[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    st[1].module = fs;
    st[1].pName = "main";
    VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkViewport vp{0, 0, float(kW), float(kH), spec.min_depth, spec.max_depth};
    VkRect2D sc{{0, 0}, {kW, kH}};
    VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vps.viewportCount = 1;
    vps.pViewports = &vp;
    vps.scissorCount = 1;
    vps.pScissors = &sc;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.lineWidth = 1.0f;
    rs.depthClampEnable = spec.depth_clamp;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = samples;
    ms.sampleShadingEnable = !spec.depth && !spec.per_pixel_color && !spec.interp;
    ms.minSampleShading = 1.0f;
    const VkSampleMask smask = spec.sample_mask;
    ms.pSampleMask = &smask;
    ms.alphaToCoverageEnable = spec.alpha_to_coverage;
    VkPipelineDepthStencilStateCreateInfo dss{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    dss.depthTestEnable = VK_TRUE;
    dss.depthWriteEnable = VK_TRUE;
    dss.depthCompareOp = VK_COMPARE_OP_ALWAYS;
    VkPipelineColorBlendAttachmentState cba{};
    cba.colorWriteMask = 0xf;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = spec.depth ? 0 : 1;
    cb.pAttachments = &cba;
    VkGraphicsPipelineCreateInfo gpi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gpi.stageCount = 2;
    gpi.pStages = st;
    gpi.pVertexInputState = &vin;
    gpi.pInputAssemblyState = &ia;
    gpi.pViewportState = &vps;
    gpi.pRasterizationState = &rs;
    gpi.pMultisampleState = &ms;
    gpi.pDepthStencilState = spec.depth ? &dss : nullptr;
    gpi.pColorBlendState = &cb;
    gpi.layout = pl;
    gpi.renderPass = rp;
    VkPipeline pipe;
    VKC(vkCreateGraphicsPipelines(v.dev, VK_NULL_HANDLE, 1, &gpi, nullptr, &pipe));

    VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.maxSets = 1;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &ps;
    VkDescriptorPool dp;
    VKC(vkCreateDescriptorPool(v.dev, &dpi, nullptr, &dp));
    VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    dai.descriptorPool = dp;
    dai.descriptorSetCount = 1;
    dai.pSetLayouts = &dsl;
    VkDescriptorSet ds;
    VKC(vkAllocateDescriptorSets(v.dev, &dai, &ds));
    Buffer ssbo = make_buffer(v, data.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::memcpy(ssbo.map, data.data(), data.size() * 4);
    Buffer xfer = make_buffer(v, VkDeviceSize(kW) * kH * bpp, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkDescriptorBufferInfo dbi{ssbo.buf, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = ds;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &dbi;
    vkUpdateDescriptorSets(v.dev, 1, &w, 0, nullptr);

    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = v.pool;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VKC(vkAllocateCommandBuffers(v.dev, &cai, &cmd));
    VkCommandBufferBeginInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VKC(vkBeginCommandBuffer(cmd, &cbi));
    VkClearValue clear{};
    std::memcpy(clear.color.float32, spec.clear, 16);
    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = rp;
    rbi.framebuffer = fb;
    rbi.renderArea = sc;
    rbi.clearValueCount = 1;
    rbi.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pl, 0, 1, &ds, 0, nullptr);
    const uint32_t width = kW;
    vkCmdPushConstants(cmd, pl, VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4, &width);
    if (!spec.no_draw) vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    VkBufferImageCopy bic{};
    bic.imageSubresource = {aspect, 0, 0, 1};
    bic.imageExtent = {kW, kH, 1};
    vkCmdCopyImageToBuffer(cmd, resolve ? resolved.img : target.img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, xfer.buf, 1,
                           &bic);
    VKC(vkEndCommandBuffer(cmd));
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VKC(vkQueueSubmit(v.queue, 1, &si, VK_NULL_HANDLE));
    VKC(vkQueueWaitIdle(v.queue));
    std::vector<uint8_t> out(size_t(kW) * kH * bpp);
    std::memcpy(out.data(), xfer.map, out.size());

    vkFreeCommandBuffers(v.dev, v.pool, 1, &cmd);
    free_buffer(v, ssbo);
    free_buffer(v, xfer);
    vkDestroyDescriptorPool(v.dev, dp, nullptr);
    vkDestroyPipeline(v.dev, pipe, nullptr);
    vkDestroyShaderModule(v.dev, vs, nullptr);
    vkDestroyShaderModule(v.dev, fs, nullptr);
    vkDestroyPipelineLayout(v.dev, pl, nullptr);
    vkDestroyDescriptorSetLayout(v.dev, dsl, nullptr);
    vkDestroyFramebuffer(v.dev, fb, nullptr);
    vkDestroyRenderPass(v.dev, rp, nullptr);
    free_image(v, target);
    if (resolve) free_image(v, resolved);
    return out;
}

float bits_f(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

}  // namespace

TEST(FragmentLavapipe, DepthConversionAndClampMatchLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(77);
    std::vector<float> z(size_t(kW) * kH);
    for (size_t i = 0; i < z.size(); ++i) {
        const uint32_t r = rng() % 100;
        if (r < 3)
            z[i] = -0.5f;
        else if (r < 6)
            z[i] = 1.75f;
        else if (r < 8)
            z[i] = NAN;
        else if (r < 40)
            z[i] = float(rng() % 65536) / 65535.0f + float(int(rng() % 3) - 1) * 0x1p-18f;  // near codes
        else
            z[i] = bits_f(rng() % 0x3f800001u);  // any float in [0, 1]
    }
    struct DCase {
        VkFormat vf;
        DepthFormat df;
        uint32_t bpp;
        bool clamp;
    } cases[] = {{VK_FORMAT_D16_UNORM, DepthFormat::D16, 2, false},
                 {VK_FORMAT_D32_SFLOAT, DepthFormat::D32F, 4, false},
                 {VK_FORMAT_X8_D24_UNORM_PACK32, DepthFormat::X8D24, 4, false},
                 {VK_FORMAT_D16_UNORM, DepthFormat::D16, 2, true},
                 {VK_FORMAT_D32_SFLOAT, DepthFormat::D32F, 4, true}};
    for (const DCase& c : cases) {
        PassSpec spec;
        spec.depth = true;
        spec.format = c.vf;
        spec.depth_clamp = c.clamp;
        if (c.clamp) {
            spec.min_depth = 0.8f;  // reversed range: the clamp uses min/max of the two
            spec.max_depth = 0.3f;
        }
        const std::vector<uint8_t> got = run_pass(v, spec, z, c.bpp);
        DepthStencilState s;
        s.depth_test = s.depth_write = true;
        s.depth_compare = CompareOp::Always;
        s.depth_clamp = c.clamp;
        s.min_depth = 0.3f;
        s.max_depth = 0.8f;
        int bad = 0;
        for (size_t i = 0; i < z.size(); ++i) {
            uint32_t g = 0;
            std::memcpy(&g, &got[i * c.bpp], c.bpp);
            if (c.df == DepthFormat::X8D24) g &= 0xffffffu;
            const uint32_t want = depth_to_stored(clamp_depth(z[i], s, c.df), c.df);
            if (g != want && bad++ < 3)
                ADD_FAILURE() << "format " << c.vf << " clamp " << c.clamp << " z " << z[i] << " want " << want
                              << " lavapipe " << g;
        }
        EXPECT_EQ(bad, 0) << c.vf;
    }
}

TEST(FragmentLavapipe, ResolveMatchesLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(9);
    const ColorFormat formats[] = {ColorFormat::R8G8B8A8_UNORM, ColorFormat::R8_UNORM, ColorFormat::R16G16B16A16_SFLOAT,
                                   ColorFormat::R32_SFLOAT, ColorFormat::R8G8B8A8_SRGB};
    for (ColorFormat f : formats) {
        const FormatInfo fi = format_info(f);
        std::vector<float> c(size_t(kW) * kH * 4 * 4);
        for (float& x : c)
            x = fi.kind == ChannelKind::Float32 || fi.kind == ChannelKind::Half
                    ? float(int(rng() % 40001) - 20000) / 7919.0f
                    : float(rng() % 1000001) / 1000000.0f;
        PassSpec spec;
        spec.format = to_vk(f);
        const std::vector<uint8_t> got = run_pass(v, spec, c, fi.bytes);
        int bad = 0;
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            // Each sample's stored value is the shader colour through the format's output conversion.
            uint8_t sp[4][16];
            const BlendAttachment off;
            const float k[4] = {};
            for (int s = 0; s < 4; ++s) blend_pixel(off, f, k, &c[(p * 4 + s) * 4], sp[s]);
            const uint8_t* ptr[4] = {sp[0], sp[1], sp[2], sp[3]};
            uint8_t want[16];
            resolve_pixel(f, ptr, want, true);
            if (std::memcmp(want, &got[p * fi.bytes], fi.bytes) != 0 && bad++ < 3)
                ADD_FAILURE() << "format " << int(f) << " pixel " << p << " want " << int(want[0]) << " lavapipe "
                              << int(got[p * fi.bytes]);
        }
        EXPECT_EQ(bad, 0) << int(f);
    }
}

TEST(FragmentLavapipe, AlphaToCoverageAndSampleMaskMatchLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(21);
    std::vector<float> c(size_t(kW) * kH * 4);
    for (size_t p = 0; p < size_t(kW) * kH; ++p) {
        for (int ch = 0; ch < 3; ++ch) c[p * 4 + ch] = float(rng() % 1000001) / 1000000.0f;
        const uint32_t r = rng() % 100;
        // alphas on and around the thresholds 0, 0.25, 0.5, 0.75, plus NaN and out-of-range values
        const float th[4] = {0.0f, 0.25f, 0.5f, 0.75f};
        if (r < 40)
            c[p * 4 + 3] = std::nextafter(th[r % 4], (r & 4) ? 2.0f : -2.0f);
        else if (r < 60)
            c[p * 4 + 3] = th[r % 4];
        else if (r < 63)
            c[p * 4 + 3] = NAN;
        else if (r < 66)
            c[p * 4 + 3] = 1.5f;
        else
            c[p * 4 + 3] = float(rng() % 1001) / 1000.0f;
    }
    for (uint32_t smask : {0xfu, 0xbu}) {
        for (bool a2c : {true, false}) {
            PassSpec spec;
            spec.format = VK_FORMAT_R8G8B8A8_UNORM;
            spec.per_pixel_color = true;
            spec.alpha_to_coverage = a2c;
            spec.sample_mask = smask;
            const std::vector<uint8_t> got = run_pass(v, spec, c, 4);
            int bad = 0;
            for (size_t p = 0; p < size_t(kW) * kH; ++p) {
                // model: every sample covered; sample mask; alpha to coverage on the raw alpha; the covered samples
                // store the pixel's colour, the others keep the clear value 0; then resolve.
                float alpha[16] = {};
                alpha[0] = c[p * 4 + 3];
                uint16_t m[4] = {1, 1, 1, 1};
                apply_sample_mask(smask, 4, m);
                if (a2c) alpha_to_coverage_4x(alpha, m);
                uint8_t sp[4][4] = {};
                const BlendAttachment off;
                const float k[4] = {};
                for (int s = 0; s < 4; ++s)
                    if (m[s] & 1) blend_pixel(off, ColorFormat::R8G8B8A8_UNORM, k, &c[p * 4], sp[s]);
                const uint8_t* ptr[4] = {sp[0], sp[1], sp[2], sp[3]};
                uint8_t want[4];
                resolve_pixel(ColorFormat::R8G8B8A8_UNORM, ptr, want, true);
                if (std::memcmp(want, &got[p * 4], 4) != 0 && bad++ < 3)
                    ADD_FAILURE() << "smask " << smask << " a2c " << a2c << " alpha " << c[p * 4 + 3] << " want "
                                  << int(want[0]) << "," << int(want[3]) << " lavapipe " << int(got[p * 4]) << ","
                                  << int(got[p * 4 + 3]);
            }
            EXPECT_EQ(bad, 0) << smask << " " << a2c;
        }
    }
}

namespace {

VkStencilOpState to_vk(const StencilFace& f) {
    VkStencilOpState s{};
    s.failOp = VkStencilOp(f.fail_op);
    s.passOp = VkStencilOp(f.pass_op);
    s.depthFailOp = VkStencilOp(f.depth_fail_op);
    s.compareOp = VkCompareOp(f.compare_op);
    s.compareMask = f.compare_mask;
    s.writeMask = f.write_mask;
    s.reference = f.reference;
    return s;
}

// D24S8 pass: initial depth/stencil from buffers, gl_FragDepth from `z`, returns (depth words, stencil bytes).
void run_stencil_pass(const Lvp& v, const DepthStencilState& st, bool front, const std::vector<uint32_t>& d0,
                      const std::vector<uint8_t>& s0, const std::vector<float>& z, std::vector<uint32_t>& d1,
                      std::vector<uint8_t>& s1) {
    const VkFormat vf = VK_FORMAT_D24_UNORM_S8_UINT;
    const VkImageAspectFlags both = VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    Img img = make_image(
        v, vf, VK_SAMPLE_COUNT_1_BIT,
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        both);
    VkAttachmentDescription att{};
    att.format = vf;
    att.samples = VK_SAMPLE_COUNT_1_BIT;
    att.loadOp = att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    att.storeOp = att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
    att.initialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    att.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference r0{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.pDepthStencilAttachment = &r0;
    VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpi.attachmentCount = 1;
    rpi.pAttachments = &att;
    rpi.subpassCount = 1;
    rpi.pSubpasses = &sub;
    VkRenderPass rp;
    VKC(vkCreateRenderPass(v.dev, &rpi, nullptr, &rp));
    VkFramebufferCreateInfo fbi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fbi.renderPass = rp;
    fbi.attachmentCount = 1;
    fbi.pAttachments = &img.view;
    fbi.width = kW;
    fbi.height = kH;
    fbi.layers = 1;
    VkFramebuffer fb;
    VKC(vkCreateFramebuffer(v.dev, &fbi, nullptr, &fb));
    VkDescriptorSetLayoutBinding b0{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo dli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    dli.bindingCount = 1;
    dli.pBindings = &b0;
    VkDescriptorSetLayout dsl;
    VKC(vkCreateDescriptorSetLayout(v.dev, &dli, nullptr, &dsl));
    VkPushConstantRange pcr{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &dsl;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &pcr;
    VkPipelineLayout pl;
    VKC(vkCreatePipelineLayout(v.dev, &pli, nullptr, &pl));
    VkShaderModule vs = make_shader(v, kFullscreenVert, sizeof kFullscreenVert);
    VkShaderModule fs = make_shader(v, kBufferDepthFrag, sizeof kBufferDepthFrag);
    VkPipelineShaderStageCreateInfo stg[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                              {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stg[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stg[0].module = vs;
    stg[0].pName = "main";
    stg[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stg[1].module = fs;
    stg[1].pName = "main";
    VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkViewport vp{0, 0, float(kW), float(kH), 0, 1};
    VkRect2D sc{{0, 0}, {kW, kH}};
    VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vps.viewportCount = 1;
    vps.pViewports = &vp;
    vps.scissorCount = 1;
    vps.pScissors = &sc;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    // The full-screen triangle has negative Vulkan area: it is front-facing with CLOCKWISE.
    rs.frontFace = front ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo dss{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    dss.depthTestEnable = st.depth_test;
    dss.depthWriteEnable = st.depth_write;
    dss.depthCompareOp = VkCompareOp(st.depth_compare);
    dss.stencilTestEnable = st.stencil_test;
    dss.front = to_vk(st.front);
    dss.back = to_vk(st.back);
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    VkGraphicsPipelineCreateInfo gpi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gpi.stageCount = 2;
    gpi.pStages = stg;
    gpi.pVertexInputState = &vin;
    gpi.pInputAssemblyState = &ia;
    gpi.pViewportState = &vps;
    gpi.pRasterizationState = &rs;
    gpi.pMultisampleState = &ms;
    gpi.pDepthStencilState = &dss;
    gpi.pColorBlendState = &cb;
    gpi.layout = pl;
    gpi.renderPass = rp;
    VkPipeline pipe;
    VKC(vkCreateGraphicsPipelines(v.dev, VK_NULL_HANDLE, 1, &gpi, nullptr, &pipe));
    VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.maxSets = 1;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &ps;
    VkDescriptorPool dp;
    VKC(vkCreateDescriptorPool(v.dev, &dpi, nullptr, &dp));
    VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    dai.descriptorPool = dp;
    dai.descriptorSetCount = 1;
    dai.pSetLayouts = &dsl;
    VkDescriptorSet ds;
    VKC(vkAllocateDescriptorSets(v.dev, &dai, &ds));
    const size_t n = size_t(kW) * kH;
    Buffer ssbo = make_buffer(v, n * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::memcpy(ssbo.map, z.data(), n * 4);
    Buffer xfer = make_buffer(v, n * 5, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    std::memcpy(xfer.map, d0.data(), n * 4);
    std::memcpy(static_cast<uint8_t*>(xfer.map) + n * 4, s0.data(), n);
    VkDescriptorBufferInfo dbi{ssbo.buf, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = ds;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &dbi;
    vkUpdateDescriptorSets(v.dev, 1, &w, 0, nullptr);

    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = v.pool;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VKC(vkAllocateCommandBuffers(v.dev, &cai, &cmd));
    VkCommandBufferBeginInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VKC(vkBeginCommandBuffer(cmd, &cbi));
    VkImageMemoryBarrier bar{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    bar.srcQueueFamilyIndex = bar.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    bar.image = img.img;
    bar.subresourceRange = {both, 0, 1, 0, 1};
    bar.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    bar.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    bar.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &bar);
    VkBufferImageCopy bic[2]{};
    bic[0].imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    bic[0].imageExtent = {kW, kH, 1};
    bic[1] = bic[0];
    bic[1].imageSubresource.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
    bic[1].bufferOffset = n * 4;
    vkCmdCopyBufferToImage(cmd, xfer.buf, img.img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 2, bic);
    bar.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    bar.newLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    bar.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    bar.dstAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT, 0, 0, nullptr,
                         0, nullptr, 1, &bar);
    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = rp;
    rbi.framebuffer = fb;
    rbi.renderArea = sc;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pl, 0, 1, &ds, 0, nullptr);
    const uint32_t width = kW;
    vkCmdPushConstants(cmd, pl, VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4, &width);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    vkCmdCopyImageToBuffer(cmd, img.img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, xfer.buf, 2, bic);
    VKC(vkEndCommandBuffer(cmd));
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VKC(vkQueueSubmit(v.queue, 1, &si, VK_NULL_HANDLE));
    VKC(vkQueueWaitIdle(v.queue));
    d1.resize(n);
    s1.resize(n);
    std::memcpy(d1.data(), xfer.map, n * 4);
    std::memcpy(s1.data(), static_cast<uint8_t*>(xfer.map) + n * 4, n);

    vkFreeCommandBuffers(v.dev, v.pool, 1, &cmd);
    free_buffer(v, ssbo);
    free_buffer(v, xfer);
    vkDestroyDescriptorPool(v.dev, dp, nullptr);
    vkDestroyPipeline(v.dev, pipe, nullptr);
    vkDestroyShaderModule(v.dev, vs, nullptr);
    vkDestroyShaderModule(v.dev, fs, nullptr);
    vkDestroyPipelineLayout(v.dev, pl, nullptr);
    vkDestroyDescriptorSetLayout(v.dev, dsl, nullptr);
    vkDestroyFramebuffer(v.dev, fb, nullptr);
    vkDestroyRenderPass(v.dev, rp, nullptr);
    free_image(v, img);
}

}  // namespace

TEST(FragmentLavapipe, StencilAndDepthTestMatchLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(5150);
    const size_t n = size_t(kW) * kH;
    int total_bad = 0, depth_changed = 0, stencil_changed = 0;
    for (int iter = 0; iter < 24; ++iter) {
        DepthStencilState st;
        st.depth_test = iter % 4 != 3;
        st.depth_write = iter % 3 != 2;
        st.depth_compare = CompareOp(rng() % 8);
        st.stencil_test = iter % 6 != 5;
        for (StencilFace* f : {&st.front, &st.back}) {
            f->fail_op = StencilOp(rng() % 8);
            f->pass_op = StencilOp(rng() % 8);
            f->depth_fail_op = StencilOp(rng() % 8);
            f->compare_op = CompareOp(rng() % 8);
            f->compare_mask = uint8_t(rng());
            f->write_mask = uint8_t(rng());
            f->reference = uint8_t(rng() % 4 == 0 ? 0 : (rng() % 4 == 0 ? 255 : rng()));
        }
        const bool front = iter % 2 == 0;
        std::vector<uint32_t> d0(n), d1;
        std::vector<uint8_t> s0(n), s1;
        std::vector<float> z(n);
        for (size_t i = 0; i < n; ++i) {
            d0[i] = uint32_t(rng() % 0x1000000u);
            // stencil near the 0/255 edges and the reference, so clamps and wraps happen
            const uint32_t r = rng() % 4;
            s0[i] = uint8_t(r == 0 ? rng() % 3 : r == 1 ? 253 + rng() % 3 : r == 2 ? st.front.reference : rng());
            // depth equal to the stored value a quarter of the time
            z[i] = rng() % 4 == 0 ? float(double(d0[i]) / 16777215.0) : float(rng() % 1000001) / 1000000.0f;
        }
        run_stencil_pass(v, st, front, d0, s0, z, d1, s1);
        int bad = 0;
        for (size_t i = 0; i < n; ++i) {
            DepthStencilBlock b{};
            b.depth[0] = d0[i];
            b.stencil[0] = s0[i];
            float zz[16] = {z[i]};
            depth_stencil_test(st, DepthFormat::X8D24, front, zz, 1, b);
            depth_changed += (d1[i] & 0xffffffu) != d0[i];
            stencil_changed += s1[i] != s0[i];
            if (((d1[i] & 0xffffffu) != b.depth[0] || s1[i] != b.stencil[0]) && bad++ < 3)
                ADD_FAILURE() << "iter " << iter << " px " << i << " z " << z[i] << " d0 " << d0[i] << " s0 "
                              << int(s0[i]) << " want " << b.depth[0] << "/" << int(b.stencil[0]) << " lavapipe "
                              << (d1[i] & 0xffffffu) << "/" << int(s1[i]);
        }
        total_bad += bad;
    }
    EXPECT_EQ(total_bad, 0);
    // the draws did something
    EXPECT_GT(depth_changed, 5000);
    EXPECT_GT(stencil_changed, 5000);
}

// Interpolation: a triangle inside the viewport (no clipping), planes set up with the notes' §4 formulas in the
// test, evaluated by eval_plane / perspective_divide, compared with lavapipe's RGBA32F output at 1x and 4x.
namespace {

struct SetupPlane {
    // lp_state_setup.c emit_tri_coef with unfused float ops; v are the re-ordered window positions.
    static Plane make(const float vx[3], const float vy[3], const float a[3], float pc) {
        volatile float x0c = vx[0] - pc, y0c = vy[0] - pc;
        volatile float dx01 = vx[0] - vx[1], dy01 = vy[0] - vy[1];
        volatile float dx20 = vx[2] - vx[0], dy20 = vy[2] - vy[0];
        volatile float m1 = dx01 * dy20, m2 = dy01 * dx20;
        volatile float area = m1 - m2;
        volatile float ooa = 1.0f / area;
        volatile float dx20o = dx20 * ooa, dy20o = dy20 * ooa, dx01o = dx01 * ooa, dy01o = dy01 * ooa;
        volatile float da01 = a[0] - a[1], da20 = a[2] - a[0];
        volatile float t1 = da01 * dy20o, t2 = da20 * dy01o;
        volatile float dadx = t1 - t2;
        volatile float t3 = da20 * dx01o, t4 = da01 * dx20o;
        volatile float dady = t3 - t4;
        volatile float u1 = dadx * x0c, u2 = dady * y0c;
        volatile float s = u1 + u2;
        volatile float a0 = a[0] - s;
        return Plane{dadx, dady, a0};
    }
};

}  // namespace

TEST(FragmentLavapipe, InterpolationMatchesLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(31337);
    int fused_only = 0;
    for (int iter = 0; iter < 6; ++iter) {
        const bool msaa = iter % 2 == 1;
        // NDC corners of the lower-left half of the viewport: window (0,0), (64,0), (0,64) exactly.
        const float ndc[3][2] = {{-1, -1}, {1, -1}, {-1, 1}};
        const float ws[3] = {float(1 << (rng() % 3)), float(1 << (rng() % 3)), float(1 << (rng() % 3))};
        float attr_s[3][2], attr_l[3][2];
        std::vector<float> data;
        for (int i = 0; i < 3; ++i) {
            for (int c = 0; c < 2; ++c) {
                attr_s[i][c] = float(int(rng() % 20001) - 10000) / 997.0f;
                attr_l[i][c] = float(int(rng() % 20001) - 10000) / 991.0f;
            }
            const float w = ws[i];
            const float pos[4] = {ndc[i][0] * w, ndc[i][1] * w, 0.5f * w, w};
            data.insert(data.end(), pos, pos + 4);
            data.insert(data.end(), {attr_s[i][0], attr_s[i][1], 0.0f, 0.0f});
            data.insert(data.end(), {attr_l[i][0], attr_l[i][1], 0.0f, 0.0f});
        }
        PassSpec spec;
        spec.interp = true;
        spec.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        spec.samples = msaa ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
        const std::vector<uint8_t> got = run_pass(v, spec, data, 16);

        // Setup model: window coords are exact; the triangle is clockwise in lavapipe's fixed-point test, so the
        // flatshade_first re-order (v0, v2, v1) applies.
        const int order[3] = {0, 2, 1};
        float vx[3], vy[3], oow[3], as[2][3], al[2][3];
        for (int k = 0; k < 3; ++k) {
            const int i = order[k];
            vx[k] = (ndc[i][0] + 1.0f) * 32.0f;
            vy[k] = (ndc[i][1] + 1.0f) * 32.0f;
            oow[k] = 1.0f / ws[i];
            for (int c = 0; c < 2; ++c) {
                volatile float pa = attr_s[i][c] * oow[k];  // perspective inputs are pre-multiplied by 1/w
                as[c][k] = pa;
                al[c][k] = attr_l[i][c];
            }
        }
        const float pc = msaa ? 0.0f : 0.5f;
        const Plane pw = SetupPlane::make(vx, vy, oow, pc);
        Plane ps[2], plin[2];
        for (int c = 0; c < 2; ++c) {
            ps[c] = SetupPlane::make(vx, vy, as[c], pc);
            plin[c] = SetupPlane::make(vx, vy, al[c], pc);
        }
        int bad = 0, compared = 0;
        for (int by = 0; by < int(kH); by += 4)
            for (int bx = 0; bx < int(kW); bx += 4) {
                float want[2][4][16];  // [fused?][channel][lane]
                for (int f = 0; f < 2; ++f) {
                    const EvalOffset off = plane_offset(msaa ? 4 : 1, -1);
                    float w[16], a[16];
                    eval_plane(pw, bx, by, off, f == 0, w);
                    for (int c = 0; c < 2; ++c) {
                        eval_plane(ps[c], bx, by, off, f == 0, a);
                        perspective_divide(a, w, want[f][c]);
                        eval_plane(plin[c], bx, by, off, f == 0, want[f][2 + c]);
                    }
                }
                for (int l = 0; l < 16; ++l) {
                    const int x = bx + lane_x(l), y = by + lane_y(l);
                    if (x + y + 2 > 62) continue;  // strictly inside the triangle: every sample covered
                    ++compared;
                    const float* g = reinterpret_cast<const float*>(&got[(size_t(y) * kW + x) * 16]);
                    for (int c = 0; c < 4; ++c) {
                        float e[2];
                        for (int f = 0; f < 2; ++f) {
                            e[f] = want[f][c][l];
                            if (msaa) {  // four identical samples through the resolve shader
                                volatile float s = 0.0f;
                                for (int k = 0; k < 4; ++k) s = s + e[f];
                                e[f] = s * 0.25f;
                            }
                        }
                        fused_only += e[0] != e[1];
                        if (std::memcmp(&g[c], &e[0], 4) != 0 && bad++ < 3)
                            ADD_FAILURE() << "iter " << iter << " (" << x << "," << y << ") c" << c << " want " << e[0]
                                          << " lavapipe " << g[c];
                    }
                }
            }
        EXPECT_EQ(bad, 0) << iter;
        EXPECT_GT(compared, 1500);
    }
    EXPECT_GT(fused_only, 0);  // the data distinguishes fused from unfused evaluation
}

TEST(FragmentLavapipe, ClearPackingMatchesLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(606);
    const ColorFormat formats[] = {ColorFormat::R8G8B8A8_UNORM, ColorFormat::B8G8R8A8_SRGB, ColorFormat::R8G8B8A8_SRGB,
                                   ColorFormat::R16G16B16A16_SFLOAT};
    for (ColorFormat f : formats) {
        const FormatInfo fi = format_info(f);
        for (int iter = 0; iter < 8; ++iter) {
            PassSpec spec;
            spec.format = to_vk(f);
            spec.samples = VK_SAMPLE_COUNT_1_BIT;
            spec.per_pixel_color = true;
            spec.no_draw = true;
            for (float& c : spec.clear) c = float(int(rng() % 1200001) - 100000) / 1000000.0f;
            if (iter == 0) {
                spec.clear[0] = 0.0031308f;
                spec.clear[1] = 0.5f / 255.0f;
                spec.clear[2] = 1e-5f;
                spec.clear[3] = 127.5f / 255.0f;
            }
            const std::vector<float> dummy(4, 0.0f);
            const std::vector<uint8_t> got = run_pass(v, spec, dummy, fi.bytes);
            uint8_t want[16];
            ASSERT_TRUE(pack_clear_color(f, spec.clear, want));
            EXPECT_EQ(std::memcmp(want, got.data(), fi.bytes), 0)
                << "format " << int(f) << " clear " << spec.clear[0] << "," << spec.clear[1] << "," << spec.clear[2]
                << "," << spec.clear[3] << " want " << int(want[0]) << "," << int(want[1]) << "," << int(want[2]) << ","
                << int(want[3]) << " lavapipe " << int(got[0]) << "," << int(got[1]) << "," << int(got[2]) << ","
                << int(got[3]);
        }
    }
}

TEST(FragmentLavapipe, SingleSampleMaskAndHalfAlphaThreshold) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(8);
    std::vector<float> c(size_t(kW) * kH * 4);
    for (size_t p = 0; p < size_t(kW) * kH; ++p) {
        for (int ch = 0; ch < 3; ++ch) c[p * 4 + ch] = float(rng() % 1000) / 999.0f;
        const uint32_t r = rng() % 10;
        c[p * 4 + 3] = r == 0   ? 0.5f
                       : r == 1 ? std::nextafter(0.5f, 1.0f)
                       : r == 2 ? NAN
                                : float(rng() % 1001) / 1000.0f;
    }
    for (int variant = 0; variant < 6; ++variant) {
        const bool a2c = variant & 1;
        // bit 0 clear still draws at 1x; only an all-zero mask discards
        const uint32_t smask = variant < 2 ? 1u : variant < 4 ? 0xfffffffeu : 0u;
        PassSpec spec;
        spec.format = VK_FORMAT_R8G8B8A8_UNORM;
        spec.samples = VK_SAMPLE_COUNT_1_BIT;
        spec.per_pixel_color = true;
        spec.alpha_to_coverage = a2c;
        spec.sample_mask = smask;
        const std::vector<uint8_t> got = run_pass(v, spec, c, 4);
        int bad = 0;
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            float alpha[16] = {c[p * 4 + 3]};
            uint16_t m[4] = {1, 0, 0, 0};
            apply_sample_mask(smask, 1, m);
            const bool live = m[0] && (!a2c || (alpha_to_coverage_1x(alpha, 1) & 1));
            uint8_t want[4] = {0, 0, 0, 0};
            const BlendAttachment off;
            const float k[4] = {};
            if (live) blend_pixel(off, ColorFormat::R8G8B8A8_UNORM, k, &c[p * 4], want);
            if (std::memcmp(want, &got[p * 4], 4) != 0 && bad++ < 3)
                ADD_FAILURE() << "a2c " << a2c << " alpha " << c[p * 4 + 3] << " want " << int(want[0]) << " lavapipe "
                              << int(got[p * 4]);
        }
        EXPECT_EQ(bad, 0) << a2c;
    }
}
