#include "compute.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "glsl.hpp"
#include "render_objects.hpp"
#include "vk_context.hpp"
#include "vk_names.hpp"

namespace tilevk::cts {

using frame::Buffer;
using frame::Cleanup;
using Kind = ComputeStep::Kind;

namespace {
// A copy between two of the program's buffers or images (its indices).
ComputeStep transfer(Kind kind, uint32_t src, uint32_t dst) {
    ComputeStep s;
    s.kind = kind;
    s.src = src;
    s.dst = dst;
    return s;
}
}  // namespace

ComputeStep dispatch(uint32_t shader, uint32_t x, uint32_t y, uint32_t z) {
    ComputeStep s;
    s.shader = shader;
    s.groups[0] = x;
    s.groups[1] = y;
    s.groups[2] = z;
    return s;
}
ComputeStep dispatch_indirect(uint32_t shader, uint32_t buffer, uint32_t offset) {
    ComputeStep s;
    s.kind = Kind::kDispatchIndirect;
    s.shader = shader;
    s.src = buffer;
    s.dst = offset;
    return s;
}
ComputeStep dispatch_base(uint32_t shader, const uint32_t base[3], const uint32_t groups[3]) {
    ComputeStep s = dispatch(shader, groups[0], groups[1], groups[2]);
    s.kind = Kind::kDispatchBase;
    std::copy(base, base + 3, s.base);
    return s;
}
ComputeStep fill(uint32_t buffer, uint32_t value) {
    ComputeStep s;
    s.kind = Kind::kFill;
    s.dst = buffer;
    s.value = value;
    return s;
}
ComputeStep copy_buffer(uint32_t src, uint32_t dst) {
    return transfer(Kind::kCopyBuffer, src, dst);
}
ComputeStep copy_buffer_to_image(uint32_t buffer, uint32_t image) {
    return transfer(Kind::kCopyBufferToImage, buffer, image);
}
ComputeStep copy_image_to_buffer(uint32_t image, uint32_t buffer) {
    return transfer(Kind::kCopyImageToBuffer, image, buffer);
}
ComputeStep draw() {
    ComputeStep s;
    s.kind = Kind::kDraw;
    return s;
}

namespace {

constexpr VkShaderStageFlags kAllStages =
    VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

uint32_t storage_texel_bytes(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R16G16B16A16_UINT:
        case VK_FORMAT_R16G16B16A16_SINT:
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_UINT:
        case VK_FORMAT_R32G32_SINT:
        case VK_FORMAT_R32G32_SFLOAT:
        case VK_FORMAT_R16G16B16A16_UNORM:
        case VK_FORMAT_R16G16B16A16_SNORM:
            return 8;
        case VK_FORMAT_R8G8_UNORM:
        case VK_FORMAT_R8G8_SNORM:
        case VK_FORMAT_R8G8_UINT:
        case VK_FORMAT_R8G8_SINT:
        case VK_FORMAT_R16_UNORM:
        case VK_FORMAT_R16_SNORM:
        case VK_FORMAT_R16_UINT:
        case VK_FORMAT_R16_SINT:
        case VK_FORMAT_R16_SFLOAT:
            return 2;
        case VK_FORMAT_R8_UNORM:
        case VK_FORMAT_R8_SNORM:
        case VK_FORMAT_R8_UINT:
        case VK_FORMAT_R8_SINT:
            return 1;
        case VK_FORMAT_R32G32B32A32_UINT:
        case VK_FORMAT_R32G32B32A32_SINT:
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return 16;
        default:
            return 4;  // the 8-bit RGBA formats, the R32 ones and the other 32-bit texels (RG16, packed)
    }
}

// Whether a step runs under conditional rendering (ComputeStep::condition).
bool has_condition(const ComputeSpec& s) {
    return std::any_of(s.steps.begin(), s.steps.end(), [](const ComputeStep& st) { return st.condition >= 0; });
}

// The stages and accesses of a step, as the source (its writes) and the destination (its reads and writes) of the
// barrier that separates it from its neighbour.
struct Sync {
    VkPipelineStageFlags stage;
    VkAccessFlags src_access, dst_access;
};
Sync sync_of(Kind k) {
    switch (k) {
        case Kind::kDispatch:
        case Kind::kDispatchBase:
            return {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT};
        case Kind::kDispatchIndirect:
            return {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                    VK_ACCESS_SHADER_WRITE_BIT,
                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT |
                        VK_ACCESS_INDIRECT_COMMAND_READ_BIT};
        case Kind::kDraw:  // the attachment, and storage writes of the vertex and fragment shaders
            return {VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                    VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT |
                        VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
        default:
            return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT};
    }
}
// A draw's destination stages: every stage that reads what an earlier step wrote.
VkPipelineStageFlags dst_stages(Kind k) {
    if (k != Kind::kDraw) return sync_of(k).stage;
    return VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
           VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
}

// One global memory barrier from step kind `a` to step kind `b` (the images stay in GENERAL, so no layout changes).
void barrier(VkCommandBuffer cb, Sync a, VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, a.src_access, dst_access};
    vkCmdPipelineBarrier(cb, a.stage, dst_stage, 0, 1, &mb, 0, nullptr, 0, nullptr);
}
void barrier(VkCommandBuffer cb, Kind a, Kind b) {
    barrier(cb, sync_of(a), dst_stages(b), sync_of(b).dst_access);
}

// A layout transition of a whole single-level image: the copies use the TRANSFER_*_OPTIMAL layouts (the validation
// layer warns about copies in GENERAL), everything else GENERAL.
void transition(VkCommandBuffer cb, VkImage image, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags src_stage,
                VkAccessFlags src_access, VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}
constexpr VkPipelineStageFlags kTransfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
constexpr VkAccessFlags kTransferRW = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;

// Copies between buffer `buf` and image `img` of the spec, in the transfer layout, GENERAL before and after (the
// steps' own barriers order them against the neighbouring steps).
void copy_image(VkCommandBuffer cb, VkBuffer buf, VkImage img, const ComputeImage& im, bool to_image) {
    const VkImageLayout l = to_image ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    transition(cb, img, VK_IMAGE_LAYOUT_GENERAL, l, kTransfer, kTransferRW, kTransfer, kTransferRW);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {im.width, im.height, 1};
    if (to_image)
        vkCmdCopyBufferToImage(cb, buf, img, l, 1, &r);
    else
        vkCmdCopyImageToBuffer(cb, img, l, buf, 1, &r);
    transition(cb, img, l, VK_IMAGE_LAYOUT_GENERAL, kTransfer, kTransferRW, kTransfer, kTransferRW);
}

struct Img {
    VkImage image;
    VkImageView view;
    Buffer staging;  // upload, then read-back
    VkDeviceSize bytes;
};

// The device objects of a spec: buffers, images, descriptors, pipelines.
struct Objects {
    const DeviceContext& c;
    Cleanup gc;
    std::vector<Buffer> buffers;
    std::vector<VkDeviceSize> sizes;
    std::vector<VkBufferView> texel_views;  // per buffer: its storage texel buffer view, or null
    std::vector<Img> images;
    VkDescriptorSetLayout dsl = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    std::vector<VkPipeline> pipelines;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkPipeline graphics = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;  // of the multisampled images' descriptors
    int attachment = -1;

    explicit Objects(const DeviceContext& ctx) : c(ctx) {}
    ~Objects() {
        // Before Cleanup destroys anything: nothing may still run (an exception can leave a submission in flight).
        vkQueueWaitIdle(c.queue);
    }
    template <typename F>
    void later(F f) {
        gc.add(std::move(f));
    }
    void make_resources(const ComputeSpec& s);
    void make_descriptors(const ComputeSpec& s);
    VkShaderModule module(Stage stage, const std::string& glsl);
    void make_pipelines(const ComputeSpec& s);
    void make_graphics(const ComputeSpec& s);
};

void Objects::make_resources(const ComputeSpec& s) {
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    for (const ComputeBuffer& b : s.buffers) {
        const VkDeviceSize bytes = std::max<VkDeviceSize>(4, b.words.size() * 4);
        const bool texel = b.texel_format != VK_FORMAT_UNDEFINED;
        Buffer buf = frame::make_buffer(c, gc, bytes,
                                        (texel ? usage | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT : usage) |
                                            (has_condition(s) ? VK_BUFFER_USAGE_CONDITIONAL_RENDERING_BIT_EXT : 0));
        std::memset(buf.mapped, 0, bytes);
        if (!b.words.empty()) std::memcpy(buf.mapped, b.words.data(), b.words.size() * 4);
        VkBufferView view = VK_NULL_HANDLE;
        if (texel) {
            VkBufferViewCreateInfo vci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
            vci.buffer = buf.buffer;
            vci.format = b.texel_format;
            vci.range = VK_WHOLE_SIZE;
            vk_check(vkCreateBufferView(c.device, &vci, nullptr, &view), "vkCreateBufferView");
            later([dev = c.device, view] { vkDestroyBufferView(dev, view, nullptr); });
        }
        buffers.push_back(buf);
        sizes.push_back(bytes);
        texel_views.push_back(view);
    }
    for (size_t j = 0; j < s.images.size(); ++j) {
        const ComputeImage& im = s.images[j];
        const bool ms = im.samples != VK_SAMPLE_COUNT_1_BIT;
        if (ms && !im.attachment) throw std::runtime_error("harness: a multisampled image must be the attachment");
        VkImageUsageFlags u =
            ms ? VK_IMAGE_USAGE_SAMPLED_BIT
               : VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        if (im.sampled) u |= VK_IMAGE_USAGE_SAMPLED_BIT;
        if ((ms || im.sampled) && sampler == VK_NULL_HANDLE) {
            VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};  // nearest, repeat
            vk_check(vkCreateSampler(c.device, &sci, nullptr, &sampler), "vkCreateSampler");
            later([dev = c.device, smp = sampler] { vkDestroySampler(dev, smp, nullptr); });
        }
        if (im.attachment) {
            u |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
            attachment = int(j);
        }
        Img img;
        if (im.linear && (ms || im.attachment))
            throw std::runtime_error("harness: a linear image is single-sample and not the attachment");
        img.image = frame::make_image(c, gc, im.format, im.width, im.height, 1, im.samples, u, 1, false, 1, 0,
                                      im.linear ? VK_IMAGE_TILING_LINEAR : VK_IMAGE_TILING_OPTIMAL);
        img.view = frame::make_view(c, gc, img.image, im.format, VK_IMAGE_ASPECT_COLOR_BIT, 1);
        if (ms) {
            img.bytes = 0;
            images.push_back(img);
            continue;
        }
        img.bytes = VkDeviceSize(im.width) * im.height * storage_texel_bytes(im.format);
        img.staging =
            frame::make_buffer(c, gc, img.bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        std::memset(img.staging.mapped, 0, img.bytes);
        if (!im.init.empty())  // data() of an empty vector may be null, which memcpy must not get
            std::memcpy(img.staging.mapped, im.init.data(), std::min<size_t>(im.init.size(), img.bytes));
        images.push_back(img);
    }
}

void Objects::make_descriptors(const ComputeSpec& s) {
    VkDevice dev = c.device;
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    uint32_t nstorage = 0, nuniform = 0, ntexel = 0;
    for (const ComputeBuffer& b : s.buffers) {
        const bool texel = b.texel_format != VK_FORMAT_UNDEFINED;
        const VkDescriptorType t = texel       ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER
                                   : b.uniform ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                               : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        (texel ? ntexel : b.uniform ? nuniform : nstorage)++;
        bindings.push_back({uint32_t(bindings.size()), t, 1, kAllStages, nullptr});
    }
    uint32_t nstorage_images = 0;
    for (const ComputeImage& im : s.images) {
        const bool combined = im.samples != VK_SAMPLE_COUNT_1_BIT || im.sampled;
        nstorage_images += combined ? 0 : 1;
        bindings.push_back({uint32_t(bindings.size()),
                            combined ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1,
                            kAllStages, nullptr});
    }
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = uint32_t(bindings.size());
    lci.pBindings = bindings.data();
    vk_check(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &dsl), "vkCreateDescriptorSetLayout");
    later([dev, l = dsl] { vkDestroyDescriptorSetLayout(dev, l, nullptr); });
    VkPushConstantRange range{kAllStages, 0, uint32_t(s.push.size() * 4)};
    VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pci.setLayoutCount = 1;
    pci.pSetLayouts = &dsl;
    pci.pushConstantRangeCount = s.push.empty() ? 0 : 1;
    pci.pPushConstantRanges = &range;
    vk_check(vkCreatePipelineLayout(dev, &pci, nullptr, &layout), "vkCreatePipelineLayout");
    later([dev, l = layout] { vkDestroyPipelineLayout(dev, l, nullptr); });

    std::vector<VkDescriptorPoolSize> sizes_;
    if (nstorage) sizes_.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nstorage});
    if (nuniform) sizes_.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nuniform});
    if (ntexel) sizes_.push_back({VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, ntexel});
    if (nstorage_images) sizes_.push_back({VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nstorage_images});
    if (nstorage_images < s.images.size())
        sizes_.push_back({VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(s.images.size()) - nstorage_images});
    if (sizes_.empty()) sizes_.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1});
    VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpci.maxSets = 1;
    dpci.poolSizeCount = uint32_t(sizes_.size());
    dpci.pPoolSizes = sizes_.data();
    VkDescriptorPool pool;
    vk_check(vkCreateDescriptorPool(dev, &dpci, nullptr, &pool), "vkCreateDescriptorPool");
    later([dev, pool] { vkDestroyDescriptorPool(dev, pool, nullptr); });
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &dsl;
    vk_check(vkAllocateDescriptorSets(dev, &ai, &set), "vkAllocateDescriptorSets");

    std::vector<VkDescriptorBufferInfo> binfo(s.buffers.size());
    std::vector<VkDescriptorImageInfo> iinfo(s.images.size());
    std::vector<VkWriteDescriptorSet> writes;
    static const VkBufferView kNullView = VK_NULL_HANDLE;
    for (size_t i = 0; i < bindings.size(); ++i) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set;
        w.dstBinding = uint32_t(i);
        w.descriptorCount = 1;
        w.descriptorType = bindings[i].descriptorType;
        if (i < s.buffers.size() && texel_views[i] != VK_NULL_HANDLE) {
            w.pTexelBufferView = s.buffers[i].null_descriptor ? &kNullView : &texel_views[i];
        } else if (i < s.buffers.size()) {
            const ComputeBuffer& b = s.buffers[i];
            // a null buffer's offset is 0 and its range VK_WHOLE_SIZE (VUID-VkDescriptorBufferInfo-buffer-02999)
            binfo[i] = {b.null_descriptor ? VK_NULL_HANDLE : buffers[i].buffer, 0,
                        b.range != 0 && !b.null_descriptor ? VkDeviceSize(b.range) : VK_WHOLE_SIZE};
            w.pBufferInfo = &binfo[i];
        } else {
            const size_t j = i - s.buffers.size();
            const bool combined = bindings[i].descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            iinfo[j] = {combined ? sampler : VK_NULL_HANDLE,
                        s.images[j].null_descriptor ? VK_NULL_HANDLE : images[j].view, VK_IMAGE_LAYOUT_GENERAL};
            w.pImageInfo = &iinfo[j];
        }
        writes.push_back(w);
    }
    vkUpdateDescriptorSets(dev, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

VkShaderModule Objects::module(Stage stage, const std::string& glsl) {
    const std::vector<uint32_t>& spirv = compile_glsl(stage, glsl);
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = spirv.size() * 4;
    ci.pCode = spirv.data();
    VkShaderModule m;
    vk_check(vkCreateShaderModule(c.device, &ci, nullptr, &m), "vkCreateShaderModule");
    later([dev = c.device, m] { vkDestroyShaderModule(dev, m, nullptr); });
    return m;
}

void Objects::make_pipelines(const ComputeSpec& s) {
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t i = 0; i < s.spec_values.size(); ++i) entries.push_back({i, i * 4, 4});
    VkSpecializationInfo si{uint32_t(entries.size()), entries.data(), s.spec_values.size() * 4, s.spec_values.data()};
    for (const std::string& glsl : s.shaders) {
        VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        ci.stage.module = module(Stage::kCompute, glsl);
        ci.stage.pName = "main";
        ci.stage.pSpecializationInfo = entries.empty() ? nullptr : &si;
        if (std::any_of(s.steps.begin(), s.steps.end(),
                        [](const ComputeStep& st) { return st.kind == Kind::kDispatchBase; }))
            ci.flags = VK_PIPELINE_CREATE_DISPATCH_BASE_KHR;
        ci.layout = layout;
        VkPipeline p;
        vk_check(vkCreateComputePipelines(c.device, VK_NULL_HANDLE, 1, &ci, nullptr, &p), "vkCreateComputePipelines");
        later([dev = c.device, p] { vkDestroyPipeline(dev, p, nullptr); });
        pipelines.push_back(p);
    }
}

// The spec's draw: a render pass over the attachment image (loaded, stored, GENERAL throughout), its framebuffer
// and a triangle-list pipeline, vertex input from a buffer when the spec names one.
void Objects::make_graphics(const ComputeSpec& s) {
    if (attachment < 0) throw std::runtime_error("harness: a draw step needs an image with `attachment` set");
    VkDevice dev = c.device;
    const ComputeImage& t = s.images[attachment];
    VkAttachmentDescription ad{};
    ad.format = t.format;
    ad.samples = t.samples;
    ad.loadOp = t.samples != VK_SAMPLE_COUNT_1_BIT ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    ad.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    ad.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    ad.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    ad.initialLayout = ad.finalLayout = VK_IMAGE_LAYOUT_GENERAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_GENERAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkRenderPassCreateInfo rpci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpci.attachmentCount = 1;
    rpci.pAttachments = &ad;
    rpci.subpassCount = 1;
    rpci.pSubpasses = &sub;
    vk_check(vkCreateRenderPass(dev, &rpci, nullptr, &render_pass), "vkCreateRenderPass");
    later([dev, rp = render_pass] { vkDestroyRenderPass(dev, rp, nullptr); });
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = render_pass;
    fci.attachmentCount = 1;
    fci.pAttachments = &images[attachment].view;
    fci.width = t.width;
    fci.height = t.height;
    fci.layers = 1;
    vk_check(vkCreateFramebuffer(dev, &fci, nullptr, &framebuffer), "vkCreateFramebuffer");
    later([dev, fb = framebuffer] { vkDestroyFramebuffer(dev, fb, nullptr); });

    VkPipelineShaderStageCreateInfo st[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                             {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    st[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    st[0].module = module(Stage::kVertex, s.draw.vertex_glsl);
    st[0].pName = "main";
    st[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    st[1].module = module(Stage::kFragment, s.draw.fragment_glsl);
    st[1].pName = "main";
    VkVertexInputBindingDescription vb{0, 16, VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription va{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0};
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    if (s.draw.vertex_buffer >= 0) {
        vi.vertexBindingDescriptionCount = vi.vertexAttributeDescriptionCount = 1;
        vi.pVertexBindingDescriptions = &vb;
        vi.pVertexAttributeDescriptions = &va;
    }
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkViewport vp{0, 0, float(t.width), float(t.height), 0, 1};
    VkRect2D sc{{0, 0}, {t.width, t.height}};
    VkPipelineViewportStateCreateInfo vs{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vs.viewportCount = vs.scissorCount = 1;
    vs.pViewports = &vp;
    vs.pScissors = &sc;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = t.samples;
    ms.sampleShadingEnable = s.draw.min_sample_shading >= 0.0f;
    ms.minSampleShading = ms.sampleShadingEnable ? s.draw.min_sample_shading : 0.0f;
    ms.alphaToCoverageEnable = s.draw.alpha_to_coverage;
    VkPipelineColorBlendAttachmentState cba{};
    cba.colorWriteMask = 0xF;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = 1;
    cb.pAttachments = &cba;
    VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gci.stageCount = 2;
    gci.pStages = st;
    gci.pVertexInputState = &vi;
    gci.pInputAssemblyState = &ia;
    gci.pViewportState = &vs;
    gci.pRasterizationState = &rs;
    gci.pMultisampleState = &ms;
    gci.pColorBlendState = &cb;
    gci.layout = layout;
    gci.renderPass = render_pass;
    vk_check(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gci, nullptr, &graphics), "vkCreateGraphicsPipelines");
    later([dev, p = graphics] { vkDestroyPipeline(dev, p, nullptr); });
}

void record_draw(VkCommandBuffer cb, const Objects& o, const ComputeSpec& s) {
    const ComputeImage& t = s.images[o.attachment];
    VkRenderPassBeginInfo rb{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rb.renderPass = o.render_pass;
    rb.framebuffer = o.framebuffer;
    rb.renderArea = {{0, 0}, {t.width, t.height}};
    const VkClearValue zero{};  // a multisampled attachment is cleared (make_graphics), the others loaded
    rb.clearValueCount = 1;
    rb.pClearValues = &zero;
    vkCmdBeginRenderPass(cb, &rb, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, o.graphics);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, o.layout, 0, 1, &o.set, 0, nullptr);
    if (!s.push.empty()) vkCmdPushConstants(cb, o.layout, kAllStages, 0, uint32_t(s.push.size() * 4), s.push.data());
    if (s.draw.vertex_buffer >= 0) {
        VkDeviceSize off = 0;
        const VkBuffer vb = s.buffers.at(size_t(s.draw.vertex_buffer)).null_descriptor
                                ? VK_NULL_HANDLE
                                : o.buffers.at(size_t(s.draw.vertex_buffer)).buffer;
        vkCmdBindVertexBuffers(cb, 0, 1, &vb, &off);
    }
    vkCmdDraw(cb, s.draw.vertex_count, 1, 0, 0);
    vkCmdEndRenderPass(cb);
}

void record_step(VkCommandBuffer cb, const Objects& o, const ComputeSpec& s, const ComputeStep& st) {
    switch (st.kind) {
        case Kind::kDispatch:
        case Kind::kDispatchIndirect:
        case Kind::kDispatchBase:
            vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, o.pipelines.at(st.shader));
            vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, o.layout, 0, 1, &o.set, 0, nullptr);
            if (!s.push.empty())
                vkCmdPushConstants(cb, o.layout, kAllStages, 0, uint32_t(s.push.size() * 4), s.push.data());
            if (st.condition >= 0) {
                VkConditionalRenderingBeginInfoEXT info{VK_STRUCTURE_TYPE_CONDITIONAL_RENDERING_BEGIN_INFO_EXT};
                info.buffer = o.buffers.at(size_t(st.condition)).buffer;
                info.offset = st.condition_offset;
                info.flags = st.condition_inverted ? VK_CONDITIONAL_RENDERING_INVERTED_BIT_EXT : 0;
                o.c.cmd.begin_conditional(cb, &info);
            }
            if (st.kind == Kind::kDispatch) {
                vkCmdDispatch(cb, st.groups[0], st.groups[1], st.groups[2]);
            } else if (st.kind == Kind::kDispatchBase) {
                const auto base =
                    reinterpret_cast<PFN_vkCmdDispatchBaseKHR>(vkGetDeviceProcAddr(o.c.device, "vkCmdDispatchBaseKHR"));
                if (base == nullptr) throw VkError("vkCmdDispatchBaseKHR is not available");
                base(cb, st.base[0], st.base[1], st.base[2], st.groups[0], st.groups[1], st.groups[2]);
            } else {
                vkCmdDispatchIndirect(cb, o.buffers.at(st.src).buffer, st.dst);
            }
            if (st.condition >= 0) o.c.cmd.end_conditional(cb);
            return;
        case Kind::kFill:
            vkCmdFillBuffer(cb, o.buffers.at(st.dst).buffer, 0, VK_WHOLE_SIZE, st.value);
            return;
        case Kind::kCopyBuffer: {
            VkBufferCopy r{0, 0, std::min(o.sizes.at(st.src), o.sizes.at(st.dst))};
            vkCmdCopyBuffer(cb, o.buffers[st.src].buffer, o.buffers[st.dst].buffer, 1, &r);
            return;
        }
        case Kind::kCopyBufferToImage:
            copy_image(cb, o.buffers.at(st.src).buffer, o.images.at(st.dst).image, s.images[st.dst], true);
            return;
        case Kind::kCopyImageToBuffer:
            copy_image(cb, o.buffers.at(st.dst).buffer, o.images.at(st.src).image, s.images[st.src], false);
            return;
        case Kind::kDraw:
            record_draw(cb, o, s);
            return;
    }
}

void record(VkCommandBuffer cb, const Objects& o, const ComputeSpec& s, const std::vector<ComputeStep>& steps) {
    // Images: UNDEFINED -> GENERAL, then their initial texels from the staging buffers.
    for (size_t j = 0; j < o.images.size(); ++j) {
        transition(cb, o.images[j].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                   VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, kTransfer, kTransferRW);
        if (s.images[j].samples == VK_SAMPLE_COUNT_1_BIT)
            copy_image(cb, o.images[j].staging.buffer, o.images[j].image, s.images[j], true);
    }
    Kind prev = Kind::kFill;  // the uploads are transfers
    for (const ComputeStep& st : steps) {
        barrier(cb, prev, st.kind);
        if (st.condition >= 0)  // the predicate an earlier step wrote
            barrier(cb, sync_of(prev), VK_PIPELINE_STAGE_CONDITIONAL_RENDERING_BIT_EXT,
                    VK_ACCESS_CONDITIONAL_RENDERING_READ_BIT_EXT);
        record_step(cb, o, s, st);
        prev = st.kind;
    }
    // Read-back: every image into its staging buffer, then everything to the host.
    barrier(cb, prev, Kind::kFill);
    for (size_t j = 0; j < o.images.size(); ++j)
        if (s.images[j].samples == VK_SAMPLE_COUNT_1_BIT)
            copy_image(cb, o.images[j].staging.buffer, o.images[j].image, s.images[j], false);
    Sync all = sync_of(prev);
    all.stage |= VK_PIPELINE_STAGE_TRANSFER_BIT;
    all.src_access |= VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier(cb, all, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

}  // namespace

std::vector<Plane> run_compute(const DeviceContext& c, const ComputeSpec& s) {
    Objects o(c);
    o.make_resources(s);
    o.make_descriptors(s);
    o.make_pipelines(s);
    std::vector<ComputeStep> steps = s.steps.empty() ? std::vector<ComputeStep>{dispatch(0, 1)} : s.steps;
    if (std::any_of(steps.begin(), steps.end(), [](const ComputeStep& st) { return st.kind == Kind::kDraw; }))
        o.make_graphics(s);

    VkDevice dev = c.device;
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = c.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb;
    vk_check(vkAllocateCommandBuffers(dev, &ai, &cb), "vkAllocateCommandBuffers");
    o.later([dev, pool = c.pool, cb] { vkFreeCommandBuffers(dev, pool, 1, &cb); });
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vk_check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
    record(cb, o, s, steps);
    vk_check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    vk_check(vkCreateFence(dev, &fi, nullptr, &fence), "vkCreateFence");
    o.later([dev, fence] { vkDestroyFence(dev, fence, nullptr); });
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    vk_check(vkQueueSubmit(c.queue, 1, &si, fence), "vkQueueSubmit");
    vk_check(vkWaitForFences(dev, 1, &fence, VK_TRUE, 60ull * 1000 * 1000 * 1000), "vkWaitForFences");

    std::vector<Plane> planes;
    for (size_t i = 0; i < s.buffers.size(); ++i) {
        if (!s.buffers[i].read_back) continue;
        Plane p{"buffer" + std::to_string(i), VK_FORMAT_R32_UINT, uint32_t(o.sizes[i] / 4), 1, 4, {}};
        const auto* bytes = static_cast<const uint8_t*>(o.buffers[i].mapped);
        p.data.assign(bytes, bytes + o.sizes[i]);
        planes.push_back(std::move(p));
    }
    for (size_t j = 0; j < s.images.size(); ++j) {
        const ComputeImage& im = s.images[j];
        if (im.samples != VK_SAMPLE_COUNT_1_BIT) continue;
        Plane p{"image" + std::to_string(j), im.format, im.width, im.height, storage_texel_bytes(im.format), {}};
        const auto* bytes = static_cast<const uint8_t*>(o.images[j].staging.mapped);
        p.data.assign(bytes, bytes + o.images[j].bytes);
        planes.push_back(std::move(p));
    }
    return planes;
}

namespace {

// The spec's buffers against the device's descriptor limits: every binding is visible to the compute stage.
std::string buffer_limits_unsupported(const VkPhysicalDeviceLimits& l, const ComputeSpec& s) {
    uint32_t storage = 0, uniform = 0;
    for (const ComputeBuffer& b : s.buffers) {
        if (b.texel_format != VK_FORMAT_UNDEFINED) continue;
        (b.uniform ? uniform : storage)++;
        if (b.uniform && b.words.size() * 4 > l.maxUniformBufferRange)
            return "a uniform buffer of " + std::to_string(b.words.size() * 4) +
                   " bytes: more than VkPhysicalDeviceLimits::maxUniformBufferRange";
    }
    if (storage > std::min(l.maxPerStageDescriptorStorageBuffers, l.maxDescriptorSetStorageBuffers))
        return std::to_string(storage) +
               " storage buffers in one stage and set: more than VkPhysicalDeviceLimits::"
               "maxPerStageDescriptorStorageBuffers or maxDescriptorSetStorageBuffers";
    if (uniform > std::min(l.maxPerStageDescriptorUniformBuffers, l.maxDescriptorSetUniformBuffers))
        return std::to_string(uniform) +
               " uniform buffers in one stage and set: more than VkPhysicalDeviceLimits::"
               "maxPerStageDescriptorUniformBuffers or maxDescriptorSetUniformBuffers";
    if (s.images.size() > l.maxDescriptorSetStorageImages)
        return std::to_string(s.images.size()) +
               " storage images in one set: more than VkPhysicalDeviceLimits::maxDescriptorSetStorageImages";
    return {};
}

}  // namespace

std::string compute_unsupported(const DeviceContext& c, const ComputeSpec& s) {
    if (has_condition(s) && !c.conditional_rendering.conditionalRendering)
        return "VK_EXT_conditional_rendering conditionalRendering";
    if (std::any_of(s.steps.begin(), s.steps.end(),
                    [](const ComputeStep& st) { return st.kind == Kind::kDispatchBase; }) &&
        !c.has_extension(VK_KHR_DEVICE_GROUP_EXTENSION_NAME))
        return "vkCmdDispatchBaseKHR needs VK_KHR_device_group";
    if (s.draw.min_sample_shading >= 0.0f && !c.features.sampleRateShading) return "feature sampleRateShading";
    if (s.atomic_float) {
        const VkPhysicalDeviceShaderAtomicFloatFeaturesEXT& f = c.atomic_float;
        if (!c.has_extension(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME)) return "VK_EXT_shader_atomic_float";
        if (!f.shaderBufferFloat32Atomics || !f.shaderBufferFloat32AtomicAdd || !f.shaderSharedFloat32Atomics ||
            !f.shaderSharedFloat32AtomicAdd || !f.shaderImageFloat32Atomics || !f.shaderImageFloat32AtomicAdd)
            return "a 32-bit member of VkPhysicalDeviceShaderAtomicFloatFeaturesEXT";
    }
    if (s.atomic_float_min_max) {
        const VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT& f = c.atomic_float2;
        if (!c.has_extension(VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME)) return "VK_EXT_shader_atomic_float2";
        if (!f.shaderBufferFloat32AtomicMinMax || !f.shaderSharedFloat32AtomicMinMax ||
            !f.shaderImageFloat32AtomicMinMax)
            return "a Float32AtomicMinMax member of VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT";
    }
    if (s.atomic_int64) {
        if (!c.has_extension(VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME)) return "VK_KHR_shader_atomic_int64";
        if (!c.features.shaderInt64) return "feature shaderInt64";
        if (!c.atomic_int64.shaderBufferInt64Atomics || !c.atomic_int64.shaderSharedInt64Atomics)
            return "feature shaderBufferInt64Atomics or shaderSharedInt64Atomics";
    }
    if (std::string why = buffer_limits_unsupported(c.props.limits, s); !why.empty()) return why;
    if ((std::any_of(s.buffers.begin(), s.buffers.end(), [](const ComputeBuffer& b) { return b.null_descriptor; }) ||
         std::any_of(s.images.begin(), s.images.end(), [](const ComputeImage& im) { return im.null_descriptor; })) &&
        !c.robustness2.nullDescriptor)
        return "VK_EXT_robustness2 nullDescriptor";
    for (const ComputeBuffer& b : s.buffers) {
        if (b.texel_format == VK_FORMAT_UNDEFINED) continue;
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(c.physical, b.texel_format, &fp);
        if (!(fp.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT))
            return std::string("format ") + format_name(b.texel_format) +
                   " lacks VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT";
    }
    for (const ComputeImage& im : s.images) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(c.physical, im.format, &fp);
        const bool ms = im.samples != VK_SAMPLE_COUNT_1_BIT;
        VkFormatFeatureFlags need = ms ? VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT : VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
        if (im.sampled) need |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
        if (im.attachment) need |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
        const VkFormatFeatureFlags have = im.linear ? fp.linearTilingFeatures : fp.optimalTilingFeatures;
        if ((have & need) != need)
            return std::string("format ") + format_name(im.format) + " lacks " + format_features_name(need & ~have) +
                   (im.linear ? " (linear tiling)" : "");
        VkImageFormatProperties ip{};
        if (ms && (vkGetPhysicalDeviceImageFormatProperties(
                       c.physical, im.format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0, &ip) != VK_SUCCESS ||
                   !(ip.sampleCounts & im.samples)))
            return std::string("format ") + format_name(im.format) +
                   ": no sampled multisampled image of that count (VkImageFormatProperties::sampleCounts)";
    }
    if (s.images.size() > c.props.limits.maxPerStageDescriptorStorageImages)
        return std::to_string(s.images.size()) +
               " storage images in one stage: more than "
               "VkPhysicalDeviceLimits::maxPerStageDescriptorStorageImages";
    return {};
}

Scene compute_scene(ComputeSpec s) {
    auto spec = std::make_shared<ComputeSpec>(std::move(s));
    Scene sc;
    sc.run = [spec](const DeviceContext& ctx) { return run_compute(ctx, *spec); };
    sc.unsupported = [spec](const DeviceContext& ctx) { return compute_unsupported(ctx, *spec); };
    return sc;
}

std::vector<uint32_t> buffer_words(const std::vector<Plane>& planes, uint32_t i) {
    const std::string name = "buffer" + std::to_string(i);
    for (const Plane& p : planes) {
        if (p.name != name) continue;
        std::vector<uint32_t> w(p.data.size() / 4);
        if (!w.empty()) std::memcpy(w.data(), p.data.data(), w.size() * 4);
        return w;
    }
    return {};
}

}  // namespace tilevk::cts
