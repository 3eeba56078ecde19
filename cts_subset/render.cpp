#include "render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "glsl.hpp"

namespace tilevk::cts {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

bool has_stencil(VkFormat f) {
    return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D16_UNORM_S8_UINT ||
           f == VK_FORMAT_S8_UINT;
}
bool has_depth(VkFormat f) {
    return f != VK_FORMAT_S8_UINT && f != VK_FORMAT_UNDEFINED;
}
uint32_t depth_copy_bytes(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D16_UNORM_S8_UINT ? 2 : 4;
}
// Bytes per texel of a colour target as copied to a buffer.
uint32_t color_bytes(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R8_UNORM:
            return 1;
        case VK_FORMAT_R8G8_UNORM:
        case VK_FORMAT_R5G6B5_UNORM_PACK16:
            return 2;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
            return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return 16;
        default:
            return 4;
    }
}

// A vertex colour packed into `f` (Draw::color_format): bytes appended to `out`; false for a format not handled.
bool pack_color(VkFormat f, const float c[4], std::vector<uint8_t>& out) {
    auto put = [&](const void* p, size_t n) {
        out.insert(out.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
    };
    auto unorm = [](float v, double max) { return std::lround(std::clamp(double(v), 0.0, 1.0) * max); };
    auto snorm = [](float v, double max) { return std::lround(std::clamp(double(v), -1.0, 1.0) * max); };
    switch (f) {
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8_UNORM:
            for (int i = 0; i < (f == VK_FORMAT_R8G8_UNORM ? 2 : 4); ++i) out.push_back(uint8_t(unorm(c[i], 255)));
            return true;
        case VK_FORMAT_R8G8B8A8_SNORM:
            for (int i = 0; i < 4; ++i) out.push_back(uint8_t(int8_t(snorm(c[i], 127))));
            return true;
        case VK_FORMAT_R16G16B16A16_UNORM:
            for (int i = 0; i < 4; ++i) {
                uint16_t v = uint16_t(unorm(c[i], 65535));
                put(&v, 2);
            }
            return true;
        case VK_FORMAT_R16G16B16A16_SNORM:
        case VK_FORMAT_R16G16_SNORM:
            for (int i = 0; i < (f == VK_FORMAT_R16G16_SNORM ? 2 : 4); ++i) {
                int16_t v = int16_t(snorm(c[i], 32767));
                put(&v, 2);
            }
            return true;
        case VK_FORMAT_R32G32B32_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
        case VK_FORMAT_R32_SFLOAT:
            put(c, 4 * (f == VK_FORMAT_R32G32B32_SFLOAT ? 3 : f == VK_FORMAT_R32G32_SFLOAT ? 2 : 1));
            return true;
        default:
            return false;
    }
}
uint32_t packed_color_bytes(VkFormat f) {
    std::vector<uint8_t> b;
    const float zero[4] = {};
    if (!pack_color(f, zero, b)) throw std::runtime_error("Draw::color_format: unsupported vertex format");
    return uint32_t(b.size());
}

// Destroys what was created, in reverse order, whether the scene finished or threw.
struct Cleanup {
    std::vector<std::function<void()>> steps;
    ~Cleanup() {
        for (auto it = steps.rbegin(); it != steps.rend(); ++it) (*it)();
    }
    void add(std::function<void()> f) { steps.push_back(std::move(f)); }
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
};

Buffer make_buffer(const DeviceContext& c, Cleanup& gc, VkDeviceSize size, VkBufferUsageFlags usage) {
    Buffer b;
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size;
    ci.usage = usage;
    vk_check(vkCreateBuffer(c.device, &ci, nullptr, &b.buffer), "vkCreateBuffer");
    VkDevice dev = c.device;
    // Cleanup runs in reverse: the buffer is destroyed before its memory is freed (the layer's best-practices
    // check warns about the other order). Until the memory exists, a failure destroys the buffer here.
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(c.device, b.buffer, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    try {
        ai.memoryTypeIndex = c.memory_type(req.memoryTypeBits,
                                           VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        vk_check(vkAllocateMemory(c.device, &ai, nullptr, &b.memory), "vkAllocateMemory");
    } catch (...) {
        vkDestroyBuffer(dev, b.buffer, nullptr);
        throw;
    }
    gc.add([dev, mem = b.memory] { vkFreeMemory(dev, mem, nullptr); });
    gc.add([dev, buf = b.buffer] { vkDestroyBuffer(dev, buf, nullptr); });
    vk_check(vkBindBufferMemory(c.device, b.buffer, b.memory, 0), "vkBindBufferMemory");
    vk_check(vkMapMemory(c.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    return b;
}

VkImage make_image(const DeviceContext& c, Cleanup& gc, VkFormat format, uint32_t w, uint32_t h, uint32_t mips,
                   VkSampleCountFlagBits samples, VkImageUsageFlags usage) {
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {w, h, 1};
    ci.mipLevels = mips;
    ci.arrayLayers = 1;
    ci.samples = samples;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = usage;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage img;
    vk_check(vkCreateImage(c.device, &ci, nullptr, &img), "vkCreateImage");
    VkDevice dev = c.device;
    // As make_buffer: the image is destroyed before its memory is freed.
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(c.device, img, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    VkDeviceMemory mem;
    try {
        ai.memoryTypeIndex = c.memory_type(req.memoryTypeBits, 0);
        vk_check(vkAllocateMemory(c.device, &ai, nullptr, &mem), "vkAllocateMemory(image)");
    } catch (...) {
        vkDestroyImage(dev, img, nullptr);
        throw;
    }
    gc.add([dev, mem] { vkFreeMemory(dev, mem, nullptr); });
    gc.add([dev, img] { vkDestroyImage(dev, img, nullptr); });
    vk_check(vkBindImageMemory(c.device, img, mem, 0), "vkBindImageMemory");
    return img;
}

VkImageView make_view(const DeviceContext& c, Cleanup& gc, VkImage img, VkFormat f, VkImageAspectFlags aspect,
                      uint32_t mips) {
    VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    ci.image = img;
    ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    ci.format = f;
    ci.subresourceRange = {aspect, 0, mips, 0, 1};
    VkImageView v;
    vk_check(vkCreateImageView(c.device, &ci, nullptr, &v), "vkCreateImageView");
    VkDevice dev = c.device;
    gc.add([dev, v] { vkDestroyImageView(dev, v, nullptr); });
    return v;
}

void barrier(VkCommandBuffer cb, VkImage img, VkImageAspectFlags aspect, uint32_t mips, VkImageLayout from,
             VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
             VkPipelineStageFlags dst_stage) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img;
    b.subresourceRange = {aspect, 0, mips, 0, 1};
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

// Texel of mip `level` at (x,y): every level has its own tint so that mip selection shows in the image.
void texel(const TextureSpec& t, uint32_t level, uint32_t x, uint32_t y, uint32_t w, uint32_t h, uint8_t out[4]) {
    static const uint8_t kTint[8][3] = {{255, 255, 255}, {255, 64, 64},  {64, 255, 64},  {64, 64, 255},
                                        {255, 255, 64},  {255, 64, 255}, {64, 255, 255}, {128, 128, 128}};
    const uint8_t* tint = kTint[level % 8];
    if (t.pattern == TexPattern::kChecker) {
        bool on = ((x / std::max(1u, w / 4)) + (y / std::max(1u, h / 4))) % 2 == 0;
        for (int i = 0; i < 3; ++i) out[i] = on ? tint[i] : static_cast<uint8_t>(tint[i] / 4);
    } else {
        out[0] = static_cast<uint8_t>(x * 255 / std::max(1u, w - 1) * tint[0] / 255);
        out[1] = static_cast<uint8_t>(y * 255 / std::max(1u, h - 1) * tint[1] / 255);
        out[2] = static_cast<uint8_t>((x + y) * 127 / std::max(1u, w + h - 2) * tint[2] / 255);
    }
    out[3] = 255;
}

struct Texture {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    Buffer staging;
    std::vector<VkBufferImageCopy> copies;
    uint32_t mips = 1;
};

Texture make_texture(const DeviceContext& c, Cleanup& gc, const TextureSpec& t) {
    Texture tex;
    tex.mips = t.mip_levels;
    VkFormat f = VK_FORMAT_R8G8B8A8_UNORM;
    tex.image = make_image(c, gc, f, t.width, t.height, t.mip_levels, VK_SAMPLE_COUNT_1_BIT,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    tex.view = make_view(c, gc, tex.image, f, VK_IMAGE_ASPECT_COLOR_BIT, t.mip_levels);
    VkDeviceSize total = 0;
    for (uint32_t l = 0, w = t.width, h = t.height; l < t.mip_levels;
         ++l, w = std::max(1u, w / 2), h = std::max(1u, h / 2))
        total += VkDeviceSize(w) * h * 4;
    tex.staging = make_buffer(c, gc, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    auto* bytes = static_cast<uint8_t*>(tex.staging.mapped);
    VkDeviceSize offset = 0;
    for (uint32_t l = 0, w = t.width, h = t.height; l < t.mip_levels;
         ++l, w = std::max(1u, w / 2), h = std::max(1u, h / 2)) {
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) texel(t, l, x, y, w, h, bytes + offset + (VkDeviceSize(y) * w + x) * 4);
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
        r.imageExtent = {w, h, 1};
        tex.copies.push_back(r);
        offset += VkDeviceSize(w) * h * 4;
    }
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = t.mag;
    si.minFilter = t.min;
    si.mipmapMode = t.mip_mode;
    si.addressModeU = si.addressModeV = si.addressModeW = t.wrap;
    si.maxLod = t.max_lod;
    si.borderColor = t.border;
    vk_check(vkCreateSampler(c.device, &si, nullptr, &tex.sampler), "vkCreateSampler");
    VkDevice dev = c.device;
    gc.add([dev, s = tex.sampler] { vkDestroySampler(dev, s, nullptr); });
    return tex;
}

VkShaderModule make_module(const DeviceContext& c, Cleanup& gc, const std::vector<uint32_t>& spirv) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = spirv.size() * 4;
    ci.pCode = spirv.data();
    VkShaderModule m;
    vk_check(vkCreateShaderModule(c.device, &ci, nullptr, &m), "vkCreateShaderModule");
    VkDevice dev = c.device;
    gc.add([dev, m] { vkDestroyShaderModule(dev, m, nullptr); });
    return m;
}

VkPipeline make_pipeline(const DeviceContext& c, Cleanup& gc, const Scene& s, const Draw& d, VkRenderPass rp,
                         VkPipelineLayout layout, double& pipeline_ms) {
    VkShaderModule vs = make_module(c, gc, compile_glsl(Stage::kVertex, vertex_source(d)));
    VkShaderModule fs =
        make_module(c, gc, compile_glsl(Stage::kFragment, fragment_source(d, s.target.color != VK_FORMAT_UNDEFINED)));
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;
    stages[1].pName = "main";

    const bool packed = d.color_format != VK_FORMAT_R32G32B32A32_SFLOAT;
    VkVertexInputBindingDescription bindings[2] = {
        {0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX},
        {1, packed ? packed_color_bytes(d.color_format) : 0, VK_VERTEX_INPUT_RATE_VERTEX}};
    VkVertexInputAttributeDescription attrs[4] = {
        {0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, pos)},
        {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
        {3, 0, VK_FORMAT_R32_SFLOAT, offsetof(Vertex, point_size)},
    };
    if (packed) attrs[1] = {1, 1, d.color_format, 0};
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = packed ? 2 : 1;
    vi.pVertexBindingDescriptions = bindings;
    vi.vertexAttributeDescriptionCount = 4;
    vi.pVertexAttributeDescriptions = attrs;
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = d.topology;
    ia.primitiveRestartEnable = d.primitive_restart;

    const Target& t = s.target;
    VkViewport vp = d.viewport.value_or(VkViewport{0, 0, float(t.width), float(t.height), 0, 1});
    VkRect2D sc = d.scissor.value_or(VkRect2D{{0, 0}, {t.width, t.height}});
    VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vps.viewportCount = 1;
    vps.pViewports = &vp;
    vps.scissorCount = 1;
    vps.pScissors = &sc;

    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.depthClampEnable = d.depth_clamp;
    rs.polygonMode = d.polygon_mode;
    rs.cullMode = d.cull;
    rs.frontFace = d.front_face;
    rs.depthBiasEnable = d.depth_bias;
    rs.depthBiasConstantFactor = d.bias_constant;
    rs.depthBiasSlopeFactor = d.bias_slope;
    rs.depthBiasClamp = d.bias_clamp;
    rs.lineWidth = d.line_width;

    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = t.samples;
    VkSampleMask mask = d.sample_mask;
    ms.pSampleMask = &mask;
    ms.alphaToCoverageEnable = d.alpha_to_coverage;

    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = d.depth_test;
    ds.depthWriteEnable = d.depth_write;
    ds.depthCompareOp = d.depth_op;
    ds.stencilTestEnable = d.stencil_test;
    ds.front = d.stencil_front;
    ds.back = d.stencil_back;
    ds.maxDepthBounds = 1.0f;

    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = t.color != VK_FORMAT_UNDEFINED ? 1 : 0;
    cb.pAttachments = &d.blend;
    std::memcpy(cb.blendConstants, d.blend_constants, sizeof cb.blendConstants);

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vps;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = t.depth != VK_FORMAT_UNDEFINED ? &ds : nullptr;
    ci.pColorBlendState = &cb;
    ci.layout = layout;
    ci.renderPass = rp;
    VkPipeline p;
    auto t0 = Clock::now();
    vk_check(vkCreateGraphicsPipelines(c.device, VK_NULL_HANDLE, 1, &ci, nullptr, &p), "vkCreateGraphicsPipelines");
    pipeline_ms += ms_since(t0);
    VkDevice dev = c.device;
    gc.add([dev, p] { vkDestroyPipeline(dev, p, nullptr); });
    return p;
}

VkRenderPass make_render_pass(const DeviceContext& c, Cleanup& gc, const Target& t) {
    std::vector<VkAttachmentDescription> att;
    VkAttachmentReference color_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depth_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkAttachmentReference resolve_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    bool resolve = t.samples != VK_SAMPLE_COUNT_1_BIT && t.color != VK_FORMAT_UNDEFINED;
    if (t.color != VK_FORMAT_UNDEFINED) {
        color_ref.attachment = uint32_t(att.size());
        att.push_back({0, t.color, t.samples, VK_ATTACHMENT_LOAD_OP_CLEAR,
                       resolve ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
                       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
                       resolve ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL});
    }
    if (t.depth != VK_FORMAT_UNDEFINED) {
        depth_ref.attachment = uint32_t(att.size());
        att.push_back({0, t.depth, t.samples, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE,
                       VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL});
    }
    if (resolve) {
        resolve_ref.attachment = uint32_t(att.size());
        att.push_back({0, t.color, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE,
                       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL});
    }
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = t.color != VK_FORMAT_UNDEFINED ? 1 : 0;
    sub.pColorAttachments = &color_ref;
    sub.pResolveAttachments = resolve ? &resolve_ref : nullptr;
    sub.pDepthStencilAttachment = t.depth != VK_FORMAT_UNDEFINED ? &depth_ref : nullptr;
    // The copies after the pass wait for every attachment write.
    VkSubpassDependency dep{0,
                            VK_SUBPASS_EXTERNAL,
                            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT,
                            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                            VK_ACCESS_TRANSFER_READ_BIT,
                            0};
    VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    ci.attachmentCount = uint32_t(att.size());
    ci.pAttachments = att.data();
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    ci.dependencyCount = 1;
    ci.pDependencies = &dep;
    VkRenderPass rp;
    vk_check(vkCreateRenderPass(c.device, &ci, nullptr, &rp), "vkCreateRenderPass");
    VkDevice dev = c.device;
    gc.add([dev, rp] { vkDestroyRenderPass(dev, rp, nullptr); });
    return rp;
}

struct Readback {
    VkImage image;
    VkImageAspectFlags aspect;
    Plane plane;
    Buffer buffer;
};

}  // namespace

struct Frame::Impl {
    Cleanup gc;  // first member: destroyed last, after the queue is idle
    const DeviceContext* c = nullptr;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    std::vector<Readback> reads;
    Buffer query_results{};  // QueryMode != kNone: 16 bytes per query (64-bit value, 64-bit availability)
    uint32_t num_queries = 0;
    double pipeline_ms = 0;
    std::function<std::vector<Plane>(const DeviceContext&)> run;  // a scene that runs its own commands
    std::vector<Plane> run_planes;
    ~Impl() {
        if (c) vkQueueWaitIdle(c->queue);
    }
};

Frame::~Frame() = default;
double Frame::pipeline_ms() const {
    return impl_->pipeline_ms;
}

Frame::Frame(const DeviceContext& c, const Scene& s, bool selftest_bad_command) : impl_(std::make_unique<Impl>()) {
    impl_->c = &c;
    if (s.run) {
        impl_->run = s.run;
        return;
    }
    Cleanup& gc = impl_->gc;
    auto& reads = impl_->reads;
    VkDevice dev = c.device;
    const Target& t = s.target;
    struct {
        double& pipeline_ms;
    } out{impl_->pipeline_ms};

    // Vertices of every draw, back to back.
    size_t nverts = 0;
    for (const Draw& d : s.draws) nverts += d.vertices.size();
    Buffer vb = make_buffer(c, gc, std::max<size_t>(1, nverts) * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    size_t at = 0;
    for (const Draw& d : s.draws) {
        std::memcpy(static_cast<uint8_t*>(vb.mapped) + at * sizeof(Vertex), d.vertices.data(),
                    d.vertices.size() * sizeof(Vertex));
        at += d.vertices.size();
    }

    // Attachments, in render-pass order.
    std::vector<VkImageView> views;
    const VkImageUsageFlags copy_src = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    bool resolve = t.samples != VK_SAMPLE_COUNT_1_BIT && t.color != VK_FORMAT_UNDEFINED;
    if (t.color != VK_FORMAT_UNDEFINED) {
        VkImage img = make_image(c, gc, t.color, t.width, t.height, 1, t.samples,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (resolve ? 0 : copy_src));
        views.push_back(make_view(c, gc, img, t.color, VK_IMAGE_ASPECT_COLOR_BIT, 1));
        if (!resolve)
            reads.push_back(
                {img, VK_IMAGE_ASPECT_COLOR_BIT, {"color", t.color, t.width, t.height, color_bytes(t.color)}, {}});
    }
    VkImage depth_img = VK_NULL_HANDLE;
    if (t.depth != VK_FORMAT_UNDEFINED) {
        depth_img = make_image(c, gc, t.depth, t.width, t.height, 1, t.samples,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | copy_src);
        VkImageAspectFlags aspects = (has_depth(t.depth) ? VK_IMAGE_ASPECT_DEPTH_BIT : 0) |
                                     (has_stencil(t.depth) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
        views.push_back(make_view(c, gc, depth_img, t.depth, aspects, 1));
    }
    if (resolve) {
        VkImage img = make_image(c, gc, t.color, t.width, t.height, 1, VK_SAMPLE_COUNT_1_BIT,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | copy_src);
        views.push_back(make_view(c, gc, img, t.color, VK_IMAGE_ASPECT_COLOR_BIT, 1));
        reads.insert(reads.begin(),
                     {img, VK_IMAGE_ASPECT_COLOR_BIT, {"color", t.color, t.width, t.height, color_bytes(t.color)}, {}});
    }
    // Multisampled depth cannot be copied to a buffer; only single-sampled depth/stencil is judged.
    if (depth_img && t.samples == VK_SAMPLE_COUNT_1_BIT) {
        if (has_depth(t.depth))
            reads.push_back({depth_img,
                             VK_IMAGE_ASPECT_DEPTH_BIT,
                             {"depth", t.depth, t.width, t.height, depth_copy_bytes(t.depth)},
                             {}});
        if (has_stencil(t.depth))
            reads.push_back({depth_img, VK_IMAGE_ASPECT_STENCIL_BIT, {"stencil", t.depth, t.width, t.height, 1}, {}});
    }
    for (Readback& r : reads)
        r.buffer = make_buffer(c, gc, VkDeviceSize(t.width) * t.height * r.plane.texel_bytes,
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT);

    VkRenderPass rp = make_render_pass(c, gc, t);
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = rp;
    fci.attachmentCount = uint32_t(views.size());
    fci.pAttachments = views.data();
    fci.width = t.width;
    fci.height = t.height;
    fci.layers = 1;
    VkFramebuffer fb;
    vk_check(vkCreateFramebuffer(dev, &fci, nullptr, &fb), "vkCreateFramebuffer");
    gc.add([dev, fb] { vkDestroyFramebuffer(dev, fb, nullptr); });

    // Per-draw texture, uniform buffer, descriptor sets and pipeline. The texture is set 0, the uniform buffer set 1:
    // a set with an unwritten combined-image-sampler binding crashes lavapipe 22.3 when bound (valid Vulkan when
    // the shader does not use it; found by cases_random.cpp), so a draw binds only sets whose every binding it
    // writes. Set 1 and the push-constant range exist only when a draw uses them, so the scenes without them
    // record exactly what they always did.
    bool any_uniforms = false, any_push = false;
    for (const Draw& d : s.draws) {
        any_uniforms |= !d.uniforms.empty();
        any_push |= !d.push_constants.empty();
    }
    const VkShaderStageFlags vf = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkDescriptorSetLayoutBinding dslb[2] = {
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, vf, nullptr}};
    VkDescriptorSetLayout dsl[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    for (uint32_t k = 0; k < (any_uniforms ? 2u : 1u); ++k) {
        VkDescriptorSetLayoutCreateInfo dslci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        dslci.bindingCount = 1;
        dslci.pBindings = &dslb[k];
        vk_check(vkCreateDescriptorSetLayout(dev, &dslci, nullptr, &dsl[k]), "vkCreateDescriptorSetLayout");
        gc.add([dev, l = dsl[k]] { vkDestroyDescriptorSetLayout(dev, l, nullptr); });
    }
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = any_uniforms ? 2 : 1;
    plci.pSetLayouts = dsl;
    const VkPushConstantRange push_range{vf, 0, 128};
    plci.pushConstantRangeCount = any_push ? 1 : 0;
    plci.pPushConstantRanges = &push_range;
    VkPipelineLayout layout;
    vk_check(vkCreatePipelineLayout(dev, &plci, nullptr, &layout), "vkCreatePipelineLayout");
    gc.add([dev, layout] { vkDestroyPipelineLayout(dev, layout, nullptr); });

    uint32_t ntex = 0, nubo = 0;
    for (const Draw& d : s.draws) {
        ntex += d.texture ? 1 : 0;
        nubo += d.uniforms.empty() ? 0 : 1;
    }
    VkDescriptorPool dpool = VK_NULL_HANDLE;
    if (ntex + nubo) {
        VkDescriptorPoolSize sizes[2];
        uint32_t nsizes = 0;
        if (ntex) sizes[nsizes++] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, ntex};
        if (nubo) sizes[nsizes++] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nubo};
        VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpci.maxSets = ntex + nubo;
        dpci.poolSizeCount = nsizes;
        dpci.pPoolSizes = sizes;
        vk_check(vkCreateDescriptorPool(dev, &dpci, nullptr, &dpool), "vkCreateDescriptorPool");
        gc.add([dev, dpool] { vkDestroyDescriptorPool(dev, dpool, nullptr); });
    }
    auto allocate_set = [&](VkDescriptorSetLayout l) {
        VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        dsai.descriptorPool = dpool;
        dsai.descriptorSetCount = 1;
        dsai.pSetLayouts = &l;
        VkDescriptorSet set;
        vk_check(vkAllocateDescriptorSets(dev, &dsai, &set), "vkAllocateDescriptorSets");
        return set;
    };
    std::vector<VkPipeline> pipes;
    std::vector<Texture> textures(s.draws.size());
    std::vector<VkDescriptorSet> sets(s.draws.size(), VK_NULL_HANDLE), ubo_sets(s.draws.size(), VK_NULL_HANDLE);
    for (size_t i = 0; i < s.draws.size(); ++i) {
        const Draw& d = s.draws[i];
        pipes.push_back(make_pipeline(c, gc, s, d, rp, layout, out.pipeline_ms));
        if (d.texture) {
            sets[i] = allocate_set(dsl[0]);
            textures[i] = make_texture(c, gc, *d.texture);
            VkDescriptorImageInfo ii{textures[i].sampler, textures[i].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = sets[i];
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            w.pImageInfo = &ii;
            vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
        }
        if (!d.uniforms.empty()) {
            ubo_sets[i] = allocate_set(dsl[1]);
            const VkDeviceSize bytes = (d.uniforms.size() * 4 + 15) / 16 * 16;  // whole vec4s (std140 arrays)
            Buffer ubo = make_buffer(c, gc, bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
            std::memset(ubo.mapped, 0, bytes);
            std::memcpy(ubo.mapped, d.uniforms.data(), d.uniforms.size() * 4);
            VkDescriptorBufferInfo bi{ubo.buffer, 0, bytes};
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = ubo_sets[i];
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            w.pBufferInfo = &bi;
            vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
        }
    }
    // Indexed draws and packed colour attributes: one buffer each per draw that has them.
    std::vector<VkBuffer> index_buffers(s.draws.size(), VK_NULL_HANDLE), color_buffers(s.draws.size(), VK_NULL_HANDLE);
    for (size_t i = 0; i < s.draws.size(); ++i) {
        const Draw& d = s.draws[i];
        if (!d.indices.empty()) {
            const bool u16 = d.index_type == VK_INDEX_TYPE_UINT16;
            Buffer ib = make_buffer(c, gc, d.indices.size() * (u16 ? 2 : 4), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
            for (size_t k = 0; k < d.indices.size(); ++k) {
                if (u16) {
                    const uint16_t v = uint16_t(d.indices[k]);
                    std::memcpy(static_cast<uint8_t*>(ib.mapped) + 2 * k, &v, 2);
                } else {
                    std::memcpy(static_cast<uint8_t*>(ib.mapped) + 4 * k, &d.indices[k], 4);
                }
            }
            index_buffers[i] = ib.buffer;
        }
        if (d.color_format != VK_FORMAT_R32G32B32A32_SFLOAT && !d.vertices.empty()) {
            std::vector<uint8_t> bytes;
            for (const Vertex& v : d.vertices) pack_color(d.color_format, v.color, bytes);
            Buffer cbuf = make_buffer(c, gc, bytes.size(), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
            std::memcpy(cbuf.mapped, bytes.data(), bytes.size());
            color_buffers[i] = cbuf.buffer;
        }
    }

    // One command buffer: uploads, the pass, the read-back copies.
    VkCommandBufferAllocateInfo cbai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cbai.commandPool = c.pool;
    cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cbai.commandBufferCount = 1;
    VkCommandBuffer cb;
    vk_check(vkAllocateCommandBuffers(dev, &cbai, &cb), "vkAllocateCommandBuffers");
    gc.add([dev, pool = c.pool, cb] { vkFreeCommandBuffers(dev, pool, 1, &cb); });
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vk_check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
    for (Texture& tex : textures) {
        if (!tex.image) continue;
        barrier(cb, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, tex.mips, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkCmdCopyBufferToImage(cb, tex.staging.buffer, tex.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(tex.copies.size()), tex.copies.data());
        barrier(cb, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, tex.mips, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    }
    // Occlusion queries: reset at the start of every submission (the frame is submitted again for timing).
    VkQueryPool qpool = VK_NULL_HANDLE;
    const uint32_t nqueries = s.queries == QueryMode::kPerDraw      ? uint32_t(s.draws.size())
                              : s.queries == QueryMode::kAcrossPass ? 1u
                                                                    : 0u;
    if (nqueries) {
        VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qci.queryType = VK_QUERY_TYPE_OCCLUSION;
        qci.queryCount = nqueries;
        vk_check(vkCreateQueryPool(dev, &qci, nullptr, &qpool), "vkCreateQueryPool");
        gc.add([dev, qpool] { vkDestroyQueryPool(dev, qpool, nullptr); });
        impl_->query_results = make_buffer(c, gc, VkDeviceSize(16) * nqueries, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        impl_->num_queries = nqueries;
        vkCmdResetQueryPool(cb, qpool, 0, nqueries);
    }
    // PRECISE asks for exact counts; both drivers report occlusionQueryPrecise (requirements.cpp checks it).
    const VkQueryControlFlags qflags = VK_QUERY_CONTROL_PRECISE_BIT;
    if (s.queries == QueryMode::kAcrossPass) vkCmdBeginQuery(cb, qpool, 0, qflags);
    VkClearValue clears[3];
    uint32_t nclear = 0;
    if (t.color != VK_FORMAT_UNDEFINED) std::memcpy(clears[nclear++].color.float32, t.clear_color, 16);
    if (t.depth != VK_FORMAT_UNDEFINED) clears[nclear++].depthStencil = {t.clear_depth, t.clear_stencil};
    if (resolve) clears[nclear++] = clears[0];
    VkRenderPassBeginInfo rpbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rpbi.renderPass = rp;
    rpbi.framebuffer = fb;
    rpbi.renderArea = {{0, 0}, {t.width, t.height}};
    rpbi.clearValueCount = nclear;
    rpbi.pClearValues = clears;
    vkCmdBeginRenderPass(cb, &rpbi, VK_SUBPASS_CONTENTS_INLINE);
    VkDeviceSize first = 0;
    for (size_t i = 0; i < s.draws.size(); ++i) {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes[i]);
        if (sets[i]) vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &sets[i], 0, nullptr);
        if (ubo_sets[i])
            vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &ubo_sets[i], 0, nullptr);
        VkDeviceSize offset = first * sizeof(Vertex);
        vkCmdBindVertexBuffers(cb, 0, 1, &vb.buffer, &offset);
        const Draw& d = s.draws[i];
        if (color_buffers[i]) {
            const VkDeviceSize zero = 0;
            vkCmdBindVertexBuffers(cb, 1, 1, &color_buffers[i], &zero);
        }
        if (!d.push_constants.empty())
            vkCmdPushConstants(cb, layout, vf, 0, uint32_t(d.push_constants.size() * 4), d.push_constants.data());
        if (s.queries == QueryMode::kPerDraw) vkCmdBeginQuery(cb, qpool, uint32_t(i), qflags);
        if (index_buffers[i]) {
            vkCmdBindIndexBuffer(cb, index_buffers[i], 0, d.index_type);
            vkCmdDrawIndexed(cb, uint32_t(d.indices.size()), d.instances, 0, 0, 0);
        } else if (!d.vertices.empty()) {
            vkCmdDraw(cb, uint32_t(d.vertices.size()), d.instances, 0, 0);
        }
        if (s.queries == QueryMode::kPerDraw) vkCmdEndQuery(cb, qpool, uint32_t(i));
        first += s.draws[i].vertices.size();
    }
    vkCmdEndRenderPass(cb);
    if (s.queries == QueryMode::kAcrossPass) vkCmdEndQuery(cb, qpool, 0);
    if (nqueries) {
        vkCmdFillBuffer(cb, impl_->query_results.buffer, 0, VK_WHOLE_SIZE, 0xDEADBEEFu);  // unwritten words show
        VkMemoryBarrier fill{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                             VK_ACCESS_TRANSFER_WRITE_BIT};
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &fill, 0,
                             nullptr, 0, nullptr);
        vkCmdCopyQueryPoolResults(
            cb, qpool, 0, nqueries, impl_->query_results.buffer, 0, 16,
            VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
    }
    if (selftest_bad_command) {
        // SHADER_WRITE is not an access of the TRANSFER stage (VUID-vkCmdPipelineBarrier-srcAccessMask-02815);
        // drivers ignore access masks, so only the layer notices.
        VkMemoryBarrier bad{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_ACCESS_TRANSFER_READ_BIT};
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &bad, 0, nullptr,
                             0, nullptr);
    }
    for (Readback& r : reads) {
        VkBufferImageCopy region{};
        region.imageSubresource = {r.aspect, 0, 0, 1};
        region.imageExtent = {t.width, t.height, 1};
        vkCmdCopyImageToBuffer(cb, r.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.buffer.buffer, 1, &region);
    }
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0,
                         nullptr);
    vk_check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");

    VkFenceCreateInfo fci2{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    vk_check(vkCreateFence(dev, &fci2, nullptr, &fence), "vkCreateFence");
    gc.add([dev, fence] { vkDestroyFence(dev, fence, nullptr); });
    impl_->cb = cb;
    impl_->fence = fence;
}

double Frame::submit() {
    const DeviceContext& c = *impl_->c;
    if (impl_->run) {
        auto t0 = Clock::now();
        impl_->run_planes = impl_->run(c);
        return ms_since(t0);
    }
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &impl_->cb;
    auto t0 = Clock::now();
    vk_check(vkQueueSubmit(c.queue, 1, &si, impl_->fence), "vkQueueSubmit");
    vk_check(vkWaitForFences(c.device, 1, &impl_->fence, VK_TRUE, 60ull * 1000 * 1000 * 1000), "vkWaitForFences");
    double ms = ms_since(t0);
    vk_check(vkResetFences(c.device, 1, &impl_->fence), "vkResetFences");
    return ms;
}

std::vector<Plane> Frame::planes() const {
    if (impl_->run) return impl_->run_planes;
    std::vector<Plane> out;
    for (const Readback& r : impl_->reads) {
        Plane p = r.plane;
        p.data.resize(size_t(p.width) * p.height * p.texel_bytes);
        std::memcpy(p.data.data(), r.buffer.mapped, p.data.size());
        out.push_back(std::move(p));
    }
    if (impl_->num_queries) {
        Plane p{"queries", VK_FORMAT_UNDEFINED, impl_->num_queries, 1, 16, {}};
        p.data.resize(size_t(16) * impl_->num_queries);
        std::memcpy(p.data.data(), impl_->query_results.mapped, p.data.size());
        out.push_back(std::move(p));
    }
    return out;
}

RenderResult render(const DeviceContext& c, const Scene& s, int timing_reps, bool selftest_bad_command) {
    Frame f(c, s, selftest_bad_command);
    RenderResult out;
    f.submit();
    out.planes = f.planes();
    out.pipeline_ms = f.pipeline_ms();
    for (int i = 0; i < timing_reps; ++i) out.frame_ms.push_back(f.submit());
    return out;
}

}  // namespace tilevk::cts
