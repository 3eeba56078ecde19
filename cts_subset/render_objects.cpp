#include "render_objects.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <stdexcept>

#include "glsl.hpp"

namespace tilevk::cts::frame {

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
// Bytes per texel of a colour target as copied to a buffer: the spec's block sizes of the core uncompressed colour
// formats, by VkFormat ranges (R4G4 = 1 ... R32G32B32A32 = 109; B10G11R11 and E5B9G9R9 take 4).
uint32_t color_bytes(VkFormat f) {
    const int v = int(f);
    if (v == 1 || (v >= 9 && v <= 15)) return 1;
    if ((v >= 2 && v <= 8) || (v >= 16 && v <= 22) || (v >= 70 && v <= 76)) return 2;
    if (v >= 23 && v <= 36) return 3;
    if (f == VK_FORMAT_A4R4G4B4_UNORM_PACK16 || f == VK_FORMAT_A4B4G4R4_UNORM_PACK16) return 2;
    if (v >= 84 && v <= 90) return 6;
    if ((v >= 91 && v <= 97) || (v >= 101 && v <= 103)) return 8;
    if (v >= 104 && v <= 106) return 12;
    if (v >= 107 && v <= 109) return 16;
    return 4;
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
                   VkSampleCountFlagBits samples, VkImageUsageFlags usage, uint32_t depth, bool one_d, uint32_t layers,
                   VkImageCreateFlags flags, VkImageTiling tiling) {
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.flags = flags;
    ci.imageType = one_d ? VK_IMAGE_TYPE_1D : depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {w, one_d ? 1 : h, depth};
    ci.mipLevels = mips;
    ci.arrayLayers = layers;
    ci.samples = samples;
    ci.tiling = tiling;
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
                      uint32_t mips, VkImageViewType view_type, uint32_t layers) {
    VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    ci.image = img;
    ci.viewType = view_type;
    ci.format = f;
    ci.subresourceRange = {aspect, 0, mips, 0, layers};
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
    b.subresourceRange = {aspect, 0, mips, 0, VK_REMAINING_ARRAY_LAYERS};
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

// Texel of mip `level` at (x,y): every level has its own tint so that mip selection shows in the image.
static void texel(const TextureSpec& t, uint32_t level, uint32_t x, uint32_t y, uint32_t w, uint32_t h, uint8_t out[4]) {
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

// A 3D texel encodes its coordinates (red x, green y, blue z, over the level's extent) and alpha its level, so that
// every filter weight, wrap and level choice shows in the result.
static void texel_3d(uint32_t level, uint32_t x, uint32_t y, uint32_t z, uint32_t w, uint32_t h, uint32_t d,
                     uint8_t out[4]) {
    out[0] = static_cast<uint8_t>(x * 255 / std::max(1u, w - 1));
    out[1] = static_cast<uint8_t>(y * 255 / std::max(1u, h - 1));
    out[2] = static_cast<uint8_t>(z * 255 / std::max(1u, d - 1));
    out[3] = static_cast<uint8_t>(255 - 29 * std::min(level, 8u));
}

// A cube or cube-array texture (TextureSpec::cube_layers): every layer and level its own values, RGBA8 gradients
// tinted by layer and level, or D32_SFLOAT depths, so that a wrong face, orientation or level shows.
static Texture make_cube_texture(const DeviceContext& c, Cleanup& gc, const TextureSpec& t) {
    Texture tex;
    tex.mips = t.mip_levels;
    const bool depth = t.format == VK_FORMAT_D32_SFLOAT;
    tex.aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    tex.image = make_image(c, gc, t.format, t.width, t.width, t.mip_levels, VK_SAMPLE_COUNT_1_BIT,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 1, false, t.cube_layers,
                           VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT);
    tex.view = make_view(c, gc, tex.image, t.format, tex.aspect, t.mip_levels,
                         t.cube_layers == 6 ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, t.cube_layers);
    VkDeviceSize total = 0;
    for (uint32_t l = 0, w = t.width; l < t.mip_levels; ++l, w = std::max(1u, w / 2))
        total += VkDeviceSize(w) * w * 4 * t.cube_layers;
    tex.staging = make_buffer(c, gc, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    auto* bytes = static_cast<uint8_t*>(tex.staging.mapped);
    VkDeviceSize offset = 0;
    for (uint32_t l = 0, w = t.width; l < t.mip_levels; ++l, w = std::max(1u, w / 2)) {
        for (uint32_t k = 0; k < t.cube_layers; ++k)
            for (uint32_t y = 0; y < w; ++y)
                for (uint32_t x = 0; x < w; ++x) {
                    uint8_t* o = bytes + offset + ((VkDeviceSize(k) * w + y) * w + x) * 4;
                    if (depth) {
                        const float d = float((x * 7 + y * 13 + k * 29 + l * 5) % 64) / 63.0f;
                        std::memcpy(o, &d, 4);
                        continue;
                    }
                    o[0] = uint8_t(x * 255 / std::max(1u, w - 1));
                    o[1] = uint8_t(y * 255 / std::max(1u, w - 1));
                    o[2] = uint8_t(k * 40 + l * 23);
                    o[3] = uint8_t(255 - k * 17 - l * 9);
                }
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {tex.aspect, l, 0, t.cube_layers};
        r.imageExtent = {w, w, 1};
        tex.copies.push_back(r);
        offset += VkDeviceSize(w) * w * 4 * t.cube_layers;
    }
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = t.mag;
    si.minFilter = t.min;
    si.mipmapMode = t.mip_mode;
    si.addressModeU = si.addressModeV = si.addressModeW = t.wrap;
    si.maxLod = t.max_lod;
    si.mipLodBias = t.lod_bias;
    si.compareEnable = t.compare ? VK_TRUE : VK_FALSE;
    si.compareOp = t.compare_op;
    if (t.non_seamless) si.flags = VK_SAMPLER_CREATE_NON_SEAMLESS_CUBE_MAP_BIT_EXT;
    vk_check(vkCreateSampler(c.device, &si, nullptr, &tex.sampler), "vkCreateSampler");
    VkDevice dev = c.device;
    gc.add([dev, s = tex.sampler] { vkDestroySampler(dev, s, nullptr); });
    return tex;
}

Texture make_texture(const DeviceContext& c, Cleanup& gc, const TextureSpec& t) {
    if (t.cube_layers != 0) return make_cube_texture(c, gc, t);
    if (is_bc_format(t.format)) return make_bc_texture(c, gc, t);
    Texture tex;
    tex.mips = t.mip_levels;
    // RGBA8, or R8_UNORM (the pattern's red) for the cases that need a single-channel format
    const VkFormat f = t.format == VK_FORMAT_R8_UNORM ? VK_FORMAT_R8_UNORM : VK_FORMAT_R8G8B8A8_UNORM;
    const uint32_t bpp = f == VK_FORMAT_R8_UNORM ? 1 : 4;
    tex.image = make_image(c, gc, f, t.width, t.height, t.mip_levels, VK_SAMPLE_COUNT_1_BIT,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, t.depth, t.one_d, t.layers);
    const VkImageViewType view_type = t.one_d ? (t.layers > 1 ? VK_IMAGE_VIEW_TYPE_1D_ARRAY : VK_IMAGE_VIEW_TYPE_1D)
                                      : t.depth > 1 ? VK_IMAGE_VIEW_TYPE_3D
                                                    : VK_IMAGE_VIEW_TYPE_2D;
    tex.view = make_view(c, gc, tex.image, f, VK_IMAGE_ASPECT_COLOR_BIT, t.mip_levels, view_type, t.layers);
    const auto half = [](uint32_t n, uint32_t l) { return std::max(1u, n >> l); };
    VkDeviceSize total = 0;
    // a 1D image's layers take the place of its rows
    const uint32_t rows = t.one_d ? t.layers : t.height;
    for (uint32_t l = 0; l < t.mip_levels; ++l)
        total += VkDeviceSize(half(t.width, l)) * (t.one_d ? rows : half(rows, l)) * half(t.depth, l) * bpp;
    tex.staging = make_buffer(c, gc, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    auto* bytes = static_cast<uint8_t*>(tex.staging.mapped);
    VkDeviceSize offset = 0;
    for (uint32_t l = 0; l < t.mip_levels; ++l) {
        const uint32_t w = half(t.width, l), h = t.one_d ? rows : half(rows, l), d = half(t.depth, l);
        for (uint32_t z = 0; z < d; ++z)
            for (uint32_t y = 0; y < h; ++y)
                for (uint32_t x = 0; x < w; ++x) {
                    uint8_t p[4];
                    if (t.one_d) {
                        texel_3d(l, x, y, 0, w, 5, 1, p);  // green: the layer, by 255 / 4
                    } else if (t.depth > 1) {
                        texel_3d(l, x, y, z, w, h, d, p);
                    } else {
                        texel(t, l, x, y, w, h, p);
                    }
                    std::memcpy(bytes + offset + ((VkDeviceSize(z) * h + y) * w + x) * bpp, p, bpp);
                }
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, t.one_d ? t.layers : 1};
        r.imageExtent = {w, t.one_d ? 1 : h, d};
        tex.copies.push_back(r);
        offset += VkDeviceSize(w) * h * d * bpp;
    }
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    VkSamplerCustomBorderColorCreateInfoEXT cb{VK_STRUCTURE_TYPE_SAMPLER_CUSTOM_BORDER_COLOR_CREATE_INFO_EXT};
    VkSamplerReductionModeCreateInfo rm{VK_STRUCTURE_TYPE_SAMPLER_REDUCTION_MODE_CREATE_INFO};
    if (t.custom_border) {
        cb.customBorderColor = *t.custom_border;
        cb.format = f;
        si.pNext = &cb;
    }
    if (t.reduction != VK_SAMPLER_REDUCTION_MODE_WEIGHTED_AVERAGE) {
        rm.reductionMode = t.reduction;
        rm.pNext = si.pNext;
        si.pNext = &rm;
    }
    si.magFilter = t.mag;
    si.minFilter = t.min;
    si.mipmapMode = t.mip_mode;
    si.addressModeU = si.addressModeV = si.addressModeW = t.wrap;
    si.addressModeW = t.wrap_w.value_or(t.wrap);
    si.maxLod = t.max_lod;
    si.mipLodBias = t.lod_bias;
    si.borderColor = t.border;
    si.anisotropyEnable = t.max_anisotropy > 0.0f ? VK_TRUE : VK_FALSE;
    si.maxAnisotropy = t.max_anisotropy;
    vk_check(vkCreateSampler(c.device, &si, nullptr, &tex.sampler), "vkCreateSampler");
    VkDevice dev = c.device;
    gc.add([dev, s = tex.sampler] { vkDestroySampler(dev, s, nullptr); });
    return tex;
}

static VkShaderModule make_module(const DeviceContext& c, Cleanup& gc, const std::vector<uint32_t>& spirv) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = spirv.size() * 4;
    ci.pCode = spirv.data();
    VkShaderModule m;
    vk_check(vkCreateShaderModule(c.device, &ci, nullptr, &m), "vkCreateShaderModule");
    VkDevice dev = c.device;
    gc.add([dev, m] { vkDestroyShaderModule(dev, m, nullptr); });
    return m;
}

// Draw::dynamic: the pipeline is created with other values than the draw's (another topology of the same class,
// the opposite cull mode and front face, no viewports, stride 0, the depth/stencil/bias/restart/discard enables
// inverted, other compare and stencil ops, another logic op); render.cpp's record_dynamic_state sets the draw's
// with vkCmdSet*.
const VkDynamicState kDynamicStates[] = {VK_DYNAMIC_STATE_CULL_MODE,
                                         VK_DYNAMIC_STATE_FRONT_FACE,
                                         VK_DYNAMIC_STATE_PRIMITIVE_TOPOLOGY,
                                         VK_DYNAMIC_STATE_VIEWPORT_WITH_COUNT,
                                         VK_DYNAMIC_STATE_SCISSOR_WITH_COUNT,
                                         VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE,
                                         VK_DYNAMIC_STATE_DEPTH_TEST_ENABLE,
                                         VK_DYNAMIC_STATE_DEPTH_WRITE_ENABLE,
                                         VK_DYNAMIC_STATE_DEPTH_COMPARE_OP,
                                         VK_DYNAMIC_STATE_DEPTH_BOUNDS_TEST_ENABLE,
                                         VK_DYNAMIC_STATE_STENCIL_TEST_ENABLE,
                                         VK_DYNAMIC_STATE_STENCIL_OP,
                                         VK_DYNAMIC_STATE_RASTERIZER_DISCARD_ENABLE,
                                         VK_DYNAMIC_STATE_DEPTH_BIAS_ENABLE,
                                         VK_DYNAMIC_STATE_PRIMITIVE_RESTART_ENABLE,
                                         VK_DYNAMIC_STATE_LOGIC_OP_EXT};

static VkPrimitiveTopology other_of_class(VkPrimitiveTopology t) {
    switch (t) {
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST:
            return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP:
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN:
            return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        case VK_PRIMITIVE_TOPOLOGY_LINE_LIST:
            return VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
        case VK_PRIMITIVE_TOPOLOGY_LINE_STRIP:
            return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        default:
            return t;
    }
}

static VkStencilOpState other_ops(const VkStencilOpState& s) {
    VkStencilOpState o = s;
    o.failOp = VkStencilOp((s.failOp + 3) % 8);
    o.passOp = VkStencilOp((s.passOp + 5) % 8);
    o.depthFailOp = VkStencilOp((s.depthFailOp + 1) % 8);
    o.compareOp = VkCompareOp((s.compareOp + 4) % 8);
    return o;
}

VertexInputLayout vertex_input_of(const Draw& d) {
    VertexInputLayout l;
    const bool packed = d.color_format != VK_FORMAT_R32G32B32A32_SFLOAT;
    l.binding_count = packed ? 2 : 1;
    l.bindings[0] = {0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    l.bindings[1] = {1, packed ? packed_color_bytes(d.color_format) : 0, VK_VERTEX_INPUT_RATE_VERTEX};
    l.attributes[0] = {0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, pos)};
    l.attributes[1] = {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)};
    l.attributes[2] = {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)};
    l.attributes[3] = {3, 0, VK_FORMAT_R32_SFLOAT, offsetof(Vertex, point_size)};
    if (packed) l.attributes[1] = {1, 1, d.color_format, 0};
    return l;
}

namespace {

// The rasterization state of a draw with its extension structs (provoking vertex, depth clip, line mode) chained
// in; a dynamic draw bakes the opposite of what its dynamic state will set.
struct RasterizationChain {
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    VkPipelineRasterizationProvokingVertexStateCreateInfoEXT provoking{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_PROVOKING_VERTEX_STATE_CREATE_INFO_EXT};
    VkPipelineRasterizationDepthClipStateCreateInfoEXT depth_clip{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_DEPTH_CLIP_STATE_CREATE_INFO_EXT};
    VkPipelineRasterizationLineStateCreateInfoEXT line{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
};

void fill_rasterization(const Draw& d, RasterizationChain& r) {
    r.rs.depthClampEnable = d.depth_clamp;
    r.rs.polygonMode = d.polygon_mode;
    r.rs.cullMode = d.cull;
    r.rs.frontFace = d.front_face;
    r.rs.depthBiasEnable = d.depth_bias;
    r.rs.depthBiasConstantFactor = d.bias_constant;
    r.rs.depthBiasSlopeFactor = d.bias_slope;
    r.rs.depthBiasClamp = d.bias_clamp;
    r.rs.lineWidth = d.line_width;
    r.provoking.provokingVertexMode = VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT;
    r.depth_clip.depthClipEnable = d.depth_clip_enable.value_or(false);
    r.line.lineRasterizationMode = d.line_mode.value_or(VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT);
    auto chain_rs = [&r](auto& ext) {
        ext.pNext = r.rs.pNext;
        r.rs.pNext = &ext;
    };
    if (d.provoking_last) chain_rs(r.provoking);
    if (d.depth_clip_enable) chain_rs(r.depth_clip);
    if (d.line_mode) chain_rs(r.line);
    if (d.dynamic) {
        r.rs.cullMode =
            d.cull == VK_CULL_MODE_NONE ? VkCullModeFlags{VK_CULL_MODE_FRONT_AND_BACK} : VkCullModeFlags(~d.cull & 3);
        r.rs.frontFace =
            d.front_face == VK_FRONT_FACE_CLOCKWISE ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE;
        r.rs.depthBiasEnable = !d.depth_bias;
        r.rs.rasterizerDiscardEnable = VK_TRUE;
    }
}

// The pipeline state Draw::dynamic3 bakes with other values than the draw's (render.cpp sets the draw's).
struct Dynamic3Parts {
    VkPipelineInputAssemblyStateCreateInfo& ia;
    RasterizationChain& raster;
    VkPipelineMultisampleStateCreateInfo& ms;
    VkPipelineColorBlendAttachmentState& blend;
    VkPipelineColorBlendStateCreateInfo& cb;
    VkPipelineViewportStateCreateInfo& vps;
    VkPipelineViewportDepthClipControlCreateInfoEXT& clip_control;
    std::vector<VkDynamicState>& dynamic_states;
};

// Extended dynamic state 3: the states Draw::dynamic3 sets (DEPTH_CLIP_ENABLE only for draws that chain the
// depth clip struct, so that the others see depth clipping follow the dynamic depth clamp).
const VkDynamicState kDynamicStates3[] = {VK_DYNAMIC_STATE_VERTEX_INPUT_EXT,
                                          VK_DYNAMIC_STATE_POLYGON_MODE_EXT,
                                          VK_DYNAMIC_STATE_DEPTH_CLAMP_ENABLE_EXT,
                                          VK_DYNAMIC_STATE_DEPTH_CLIP_NEGATIVE_ONE_TO_ONE_EXT,
                                          VK_DYNAMIC_STATE_LOGIC_OP_ENABLE_EXT,
                                          VK_DYNAMIC_STATE_SAMPLE_MASK_EXT,
                                          VK_DYNAMIC_STATE_ALPHA_TO_COVERAGE_ENABLE_EXT,
                                          VK_DYNAMIC_STATE_LINE_RASTERIZATION_MODE_EXT,
                                          VK_DYNAMIC_STATE_LINE_STIPPLE_ENABLE_EXT,
                                          VK_DYNAMIC_STATE_PROVOKING_VERTEX_MODE_EXT,
                                          VK_DYNAMIC_STATE_COLOR_BLEND_ENABLE_EXT,
                                          VK_DYNAMIC_STATE_COLOR_BLEND_EQUATION_EXT,
                                          VK_DYNAMIC_STATE_COLOR_WRITE_MASK_EXT};

// Another topology class (dynamicPrimitiveTopologyUnrestricted), every enable inverted (alpha to one stays static:
// tilevk does not report it dynamic), LAST/FIRST vertex and
// BRESENHAM/RECTANGULAR swapped, another blend equation and write mask, and (make_pipeline) sample mask ~mask.
void bake_dynamic3(const Draw& d, const Dynamic3Parts& p) {
    const bool triangles = d.topology >= VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    p.ia.topology = triangles ? VK_PRIMITIVE_TOPOLOGY_LINE_STRIP : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    RasterizationChain& r = p.raster;
    auto chain_rs = [&r](auto& ext) {
        ext.pNext = r.rs.pNext;
        r.rs.pNext = &ext;
    };
    r.rs.polygonMode = d.polygon_mode == VK_POLYGON_MODE_FILL ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
    r.rs.depthClampEnable = !d.depth_clamp;
    r.provoking.provokingVertexMode =
        d.provoking_last ? VK_PROVOKING_VERTEX_MODE_FIRST_VERTEX_EXT : VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT;
    if (!d.provoking_last) chain_rs(r.provoking);
    r.line.lineRasterizationMode =
        d.line_mode == VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT ? VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT
                                                                : VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
    if (!d.line_mode) chain_rs(r.line);
    if (d.depth_clip_enable) r.depth_clip.depthClipEnable = !*d.depth_clip_enable;
    p.ms.alphaToCoverageEnable = !d.alpha_to_coverage;
    p.blend = {!d.blend.blendEnable,       VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR, VK_BLEND_FACTOR_SRC_ALPHA,
               VK_BLEND_OP_REVERSE_SUBTRACT, VK_BLEND_FACTOR_ZERO,              VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
               VK_BLEND_OP_SUBTRACT,         ~d.blend.colorWriteMask & 0xFu};
    p.cb.logicOpEnable = !d.logic_op.has_value();
    p.vps.pNext = d.negative_one_to_one ? nullptr : &p.clip_control;
    // VERTEX_INPUT_BINDING_STRIDE must not be dynamic with VERTEX_INPUT_EXT (vkCmdSetVertexInputEXT sets strides).
    std::erase(p.dynamic_states, VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE);
    p.dynamic_states.insert(p.dynamic_states.end(), std::begin(kDynamicStates3), std::end(kDynamicStates3));
    if (d.depth_clip_enable) p.dynamic_states.push_back(VK_DYNAMIC_STATE_DEPTH_CLIP_ENABLE_EXT);
}

}  // namespace

VkPipeline make_pipeline(const DeviceContext& c, Cleanup& gc, const Scene& s, const Draw& d, VkRenderPass rp,
                         VkPipelineLayout layout, double& pipeline_ms) {
    VkShaderModule vs =
        make_module(c, gc, !d.vertex_spirv.empty() ? d.vertex_spirv : compile_glsl(Stage::kVertex, vertex_source(d)));
    VkShaderModule fs =
        make_module(c, gc,
                    !d.fragment_spirv.empty()
                        ? d.fragment_spirv
                        : compile_glsl(Stage::kFragment, fragment_source(d, s.target.color != VK_FORMAT_UNDEFINED)));
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;
    stages[1].pName = "main";

    VertexInputLayout layout_in = vertex_input_of(d);
    VkVertexInputBindingDescription* bindings = layout_in.bindings;
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = layout_in.binding_count;
    vi.pVertexBindingDescriptions = bindings;
    vi.vertexAttributeDescriptionCount = 4;
    vi.pVertexAttributeDescriptions = layout_in.attributes;
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = d.dynamic ? other_of_class(d.topology) : d.topology;
    ia.primitiveRestartEnable = d.dynamic ? !d.primitive_restart : d.primitive_restart;
    if (d.dynamic) bindings[0].stride = bindings[1].stride = 0;  // VERTEX_INPUT_BINDING_STRIDE

    const Target& t = s.target;
    VkViewport vp = d.viewport.value_or(VkViewport{0, 0, float(t.width), float(t.height), 0, 1});
    VkRect2D sc = d.scissor.value_or(VkRect2D{{0, 0}, {t.width, t.height}});
    const std::vector<VkViewport> vps_all(d.viewport_count, vp);
    const std::vector<VkRect2D> scs_all(d.viewport_count, sc);
    VkPipelineViewportDepthClipControlCreateInfoEXT clip_control{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_DEPTH_CLIP_CONTROL_CREATE_INFO_EXT};
    clip_control.negativeOneToOne = VK_TRUE;
    VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vps.pNext = d.negative_one_to_one ? &clip_control : nullptr;
    vps.viewportCount = d.dynamic ? 0 : d.viewport_count;  // VIEWPORT/SCISSOR_WITH_COUNT
    vps.pViewports = d.dynamic ? nullptr : vps_all.data();
    vps.scissorCount = d.dynamic ? 0 : d.viewport_count;
    vps.pScissors = d.dynamic ? nullptr : scs_all.data();

    RasterizationChain raster;
    fill_rasterization(d, raster);
    const VkPipelineRasterizationStateCreateInfo& rs = raster.rs;

    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = t.samples;
    VkSampleMask mask = d.dynamic3 ? ~d.sample_mask : d.sample_mask;
    ms.pSampleMask = &mask;
    ms.alphaToCoverageEnable = d.alpha_to_coverage;
    ms.alphaToOneEnable = d.alpha_to_one;
    ms.sampleShadingEnable = d.min_sample_shading >= 0.0f;
    ms.minSampleShading = ms.sampleShadingEnable ? d.min_sample_shading : 0.0f;

    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = d.depth_test;
    ds.depthWriteEnable = d.depth_write;
    ds.depthCompareOp = d.depth_op;
    ds.stencilTestEnable = d.stencil_test;
    ds.front = d.stencil_front;
    ds.back = d.stencil_back;
    ds.maxDepthBounds = 1.0f;
    if (d.dynamic) {
        ds.depthTestEnable = !d.depth_test;
        ds.depthWriteEnable = !d.depth_write;
        ds.depthCompareOp = VkCompareOp((d.depth_op + 3) % 8);
        ds.stencilTestEnable = !d.stencil_test;
        ds.front = other_ops(d.stencil_front);
        ds.back = other_ops(d.stencil_back);
    }

    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = t.color != VK_FORMAT_UNDEFINED ? 1 : 0;
    VkPipelineColorBlendAttachmentState blend = d.blend;
    cb.pAttachments = &blend;
    cb.logicOpEnable = d.logic_op.has_value();
    cb.logicOp = d.logic_op.value_or(VK_LOGIC_OP_COPY);
    if (d.dynamic && d.logic_op) cb.logicOp = VkLogicOp((*d.logic_op + 7) % 16);
    VkPipelineColorWriteCreateInfoEXT color_write{VK_STRUCTURE_TYPE_PIPELINE_COLOR_WRITE_CREATE_INFO_EXT};
    VkBool32 write_enable = VK_TRUE;
    std::vector<VkDynamicState> dynamic_states;
    if (d.dynamic)
        dynamic_states.assign(kDynamicStates, kDynamicStates + std::size(kDynamicStates) - (c.cmd.logic_op ? 0 : 1));
    if (d.dynamic3) bake_dynamic3(d, Dynamic3Parts{ia, raster, ms, blend, cb, vps, clip_control, dynamic_states});
    if (d.color_write_enable) {
        write_enable = d.color_write_dynamic ? !*d.color_write_enable : *d.color_write_enable;
        color_write.attachmentCount = cb.attachmentCount;
        color_write.pColorWriteEnables = &write_enable;
        cb.pNext = &color_write;
        if (d.color_write_dynamic) dynamic_states.push_back(VK_DYNAMIC_STATE_COLOR_WRITE_ENABLE_EXT);
    }
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = uint32_t(dynamic_states.size());
    dyn.pDynamicStates = dynamic_states.data();
    std::memcpy(cb.blendConstants, d.blend_constants, sizeof cb.blendConstants);

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = d.dynamic3 ? nullptr : &vi;  // VK_DYNAMIC_STATE_VERTEX_INPUT_EXT ignores it
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vps;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = t.depth != VK_FORMAT_UNDEFINED ? &ds : nullptr;
    ci.pColorBlendState = &cb;
    ci.layout = layout;
    ci.renderPass = rp;
    if (!dynamic_states.empty()) ci.pDynamicState = &dyn;
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

}  // namespace tilevk::cts::frame
