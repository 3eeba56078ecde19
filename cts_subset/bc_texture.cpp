// BC-compressed textures for texture.bc.* (cases_texture_bc.cpp): seeded random blocks, with hand-made blocks at the
// start of level 0 for the modes random bytes rarely hit (equal endpoints, the extremes, BC1's three-colour mode with
// its transparent colour, BC3/BC4/BC5's six-value mode with its 0 and 255 / -127 and 127 codes), uploaded through
// block-granular buffer copies: a padded bufferRowLength, level 0 in two regions (the second at a block offset, its
// extent ending in a partial block). BC6H and BC7 blocks keep their random bits but have their mode bits set from the
// block's index in the upload, so that every mode (the reserved ones too) appears at every level.
#include <algorithm>
#include <cstring>

#include "render_objects.hpp"
#include "rng.hpp"

namespace tilevk::cts::frame {

bool is_bc_format(VkFormat f) {
    return f >= VK_FORMAT_BC1_RGB_UNORM_BLOCK && f <= VK_FORMAT_BC7_SRGB_BLOCK;
}

uint32_t bc_block_bytes(VkFormat f) {
    return f <= VK_FORMAT_BC1_RGBA_SRGB_BLOCK || f == VK_FORMAT_BC4_UNORM_BLOCK || f == VK_FORMAT_BC4_SNORM_BLOCK ? 8
                                                                                                                  : 16;
}

namespace {

// Codes 0..7 twice in a 48-bit alpha index field (texel k: bits 3k..3k+2).
constexpr uint64_t kAllAlphaCodes = 0xfac688fac688ull;  // 0,1,...,7,0,1,...,7
// Codes 0..3 in every row of a colour index word.
constexpr uint32_t kAllColourCodes = 0xe4e4e4e4u;

void put_alpha(uint8_t* p, uint8_t a0, uint8_t a1) {
    const uint64_t v = uint64_t(a0) | uint64_t(a1) << 8 | kAllAlphaCodes << 16;
    std::memcpy(p, &v, 8);
}
void put_colour(uint8_t* p, uint16_t c0, uint16_t c1) {
    const uint32_t w = uint32_t(c0) | uint32_t(c1) << 16;
    std::memcpy(p, &w, 4);
    std::memcpy(p + 4, &kAllColourCodes, 4);
}

// Hand-made block `k` (0..3) of format f, written over a random one.
void hand_made_block(VkFormat f, int k, uint8_t* p) {
    static const uint16_t kColours[4][2] = {{0xffff, 0x0000}, {0x0000, 0xffff}, {0x8410, 0x8410}, {0x07e0, 0xf81f}};
    static const uint8_t kAlphas[4][2] = {{255, 0}, {0, 255}, {0x80, 0x7f}, {0x40, 0x40}};
    const uint16_t c0 = kColours[k][0], c1 = kColours[k][1];
    const uint8_t a0 = kAlphas[k][0], a1 = kAlphas[k][1];
    switch (f) {
        case VK_FORMAT_BC1_RGB_UNORM_BLOCK:
        case VK_FORMAT_BC1_RGB_SRGB_BLOCK:
        case VK_FORMAT_BC1_RGBA_UNORM_BLOCK:
        case VK_FORMAT_BC1_RGBA_SRGB_BLOCK:
            put_colour(p, c0, c1);
            break;
        case VK_FORMAT_BC2_UNORM_BLOCK:
        case VK_FORMAT_BC2_SRGB_BLOCK: {
            const uint64_t a = 0xfedcba9876543210ull;  // every 4-bit alpha
            std::memcpy(p, &a, 8);
            put_colour(p + 8, c0, c1);
            break;
        }
        case VK_FORMAT_BC3_UNORM_BLOCK:
        case VK_FORMAT_BC3_SRGB_BLOCK:
            put_alpha(p, a0, a1);
            put_colour(p + 8, c0, c1);
            break;
        case VK_FORMAT_BC4_UNORM_BLOCK:
        case VK_FORMAT_BC4_SNORM_BLOCK:
            put_alpha(p, a0, a1);
            break;
        default:  // BC5: red and green
            put_alpha(p, a0, a1);
            put_alpha(p + 8, a1, a0);
            break;
    }
}

// The mode bits of the n-th BPTC block: BC7 modes 0..7 (mode m: m zero bits, then a one) and the reserved byte-0-zero
// block; BC6H's 14 modes (2 or 5 bits) and its 4 reserved 5-bit codes.
void set_bptc_mode(VkFormat f, uint32_t n, uint8_t* p) {
    if (f == VK_FORMAT_BC7_UNORM_BLOCK || f == VK_FORMAT_BC7_SRGB_BLOCK) {
        const uint32_t m = n % 9;
        p[0] = m == 8 ? 0 : uint8_t((p[0] & ~((2u << m) - 1)) | (1u << m));
        return;
    }
    static const uint8_t kBc6Modes[18] = {0x00, 0x01, 0x02, 0x06, 0x0a, 0x0e, 0x12, 0x16, 0x1a,
                                          0x1e, 0x03, 0x07, 0x0b, 0x0f, 0x13, 0x17, 0x1b, 0x1f};
    const uint8_t mode = kBc6Modes[n % 18];
    p[0] = uint8_t((p[0] & (mode < 2 ? ~3u : ~31u)) | mode);
}

}  // namespace

Texture make_bc_texture(const DeviceContext& c, Cleanup& gc, const TextureSpec& t) {
    Texture tex;
    tex.mips = t.mip_levels;
    tex.image = make_image(c, gc, t.format, t.width, t.height, t.mip_levels, VK_SAMPLE_COUNT_1_BIT,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    tex.view = make_view(c, gc, tex.image, t.format, VK_IMAGE_ASPECT_COLOR_BIT, t.mip_levels);
    const uint32_t bb = bc_block_bytes(t.format);
    const auto half = [](uint32_t n, uint32_t l) { return std::max(1u, n >> l); };
    // every level's blocks with one block of padding per row (bufferRowLength = the padded width in texels)
    VkDeviceSize total = 0;
    for (uint32_t l = 0; l < t.mip_levels; ++l)
        total += VkDeviceSize((half(t.width, l) + 3) / 4 + 1) * ((half(t.height, l) + 3) / 4) * bb;
    tex.staging = make_buffer(c, gc, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    auto* bytes = static_cast<uint8_t*>(tex.staging.mapped);
    Rng rng(uint32_t(t.format) * 7919u + t.width * 31u + t.height);
    for (VkDeviceSize i = 0; i < total; ++i) bytes[i] = uint8_t(rng.next() >> 24);
    if (t.format >= VK_FORMAT_BC6H_UFLOAT_BLOCK && t.format <= VK_FORMAT_BC7_SRGB_BLOCK)
        for (VkDeviceSize i = 0; i < total / bb; ++i) set_bptc_mode(t.format, uint32_t(i), bytes + i * bb);
    VkDeviceSize offset = 0;
    for (uint32_t l = 0; l < t.mip_levels; ++l) {
        const uint32_t w = half(t.width, l), h = half(t.height, l);
        const uint32_t row_blocks = (w + 3) / 4 + 1;
        if (l == 0 && t.format < VK_FORMAT_BC6H_UFLOAT_BLOCK)
            for (int k = 0; k < 4 && uint32_t(k) < row_blocks - 1; ++k) hand_made_block(t.format, k, bytes + k * bb);
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.bufferRowLength = row_blocks * 4;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
        r.imageExtent = {w, h, 1};
        if (l == 0 && w > 8) {
            // two regions: texels [0, 8) and [8, w) (a block offset; the second may end in a partial block)
            VkBufferImageCopy left = r, right = r;
            left.imageExtent.width = 8;
            right.bufferOffset = offset + 2 * bb;
            right.imageOffset.x = 8;
            right.imageExtent.width = w - 8;
            tex.copies.push_back(left);
            tex.copies.push_back(right);
        } else {
            tex.copies.push_back(r);
        }
        offset += VkDeviceSize(row_blocks) * ((h + 3) / 4) * bb;
    }
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = t.mag;
    si.minFilter = t.min;
    si.mipmapMode = t.mip_mode;
    si.addressModeU = si.addressModeV = si.addressModeW = t.wrap;
    si.maxLod = t.max_lod;
    si.mipLodBias = t.lod_bias;
    si.borderColor = t.border;
    vk_check(vkCreateSampler(c.device, &si, nullptr, &tex.sampler), "vkCreateSampler");
    VkDevice dev = c.device;
    gc.add([dev, s = tex.sampler] { vkDestroySampler(dev, s, nullptr); });
    return tex;
}

}  // namespace tilevk::cts::frame
