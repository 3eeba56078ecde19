#include "clear_pack.h"

#include <cmath>
#include <cstring>

namespace tilevk::icd {
namespace {

uint32_t bits_of(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

float float_of(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// Reference curve used to fit the table: the sRGB encode with the exponent 0.41666666 (as Mesa's generator).
double linear_to_srgb_curve(double x) {
    return x >= 0.0031308 ? 1.055 * std::pow(x, 0.41666666) - 0.055 : 12.92 * x;
}

// rygorous' linear->sRGB scheme (public domain gist 2203834), which Mesa uses: 13 exponents x 8 mantissa buckets
// between 2^-13 and 1; per bucket a least-squares line val(t) = a + b*t over the next 8 mantissa bits t, fitted to
// curve*255 + 0.5 at every 32nd float of the bucket. Entry = (round(a*128) << 16) | round(b*65536).
struct SrgbTable {
    static constexpr int kExponents = 13, kMantissaMsb = 3, kStepShift = 5, kMantShift = 12;
    static constexpr int kBuckets = kExponents << kMantissaMsb;                   // 104
    static constexpr int kBucketSize = (1 << (23 - kMantissaMsb)) >> kStepShift;  // 32768 samples
    uint32_t entry[kBuckets];

    SrgbTable() {
        double sum_aa = kBucketSize, sum_ab = 0.0, sum_bb = 0.0;
        for (int i = 0; i < kBucketSize; ++i) {
            int j = (i << kStepShift) >> kMantShift;
            sum_ab += j;
            sum_bb += double(j) * j;
        }
        const double inv_det = 1.0 / (sum_aa * sum_bb - sum_ab * sum_ab);
        for (int bucket = 0; bucket < kBuckets; ++bucket) {
            uint32_t start = (uint32_t(127 - kExponents) << 23) + uint32_t(bucket) * (kBucketSize << kStepShift);
            double sum_a = 0.0, sum_b = 0.0;
            for (int i = 0; i < kBucketSize; ++i) {
                int j = (i << kStepShift) >> kMantShift;
                double val = linear_to_srgb_curve(double(float_of(start + (uint32_t(i) << kStepShift)))) * 255.0 + 0.5;
                sum_a += val;
                sum_b += j * val;
            }
            double a = inv_det * (sum_bb * sum_a - sum_ab * sum_b);
            double b = inv_det * (sum_aa * sum_b - sum_ab * sum_a);
            uint32_t int_a = uint32_t(int64_t(a * 65536.0 / 512.0 + 0.5));
            uint32_t int_b = uint32_t(int64_t(b * 65536.0 + 0.5));
            entry[bucket] = (int_a << 16) + int_b;
        }
    }
};

}  // namespace

uint8_t float_to_ubyte(float f) {
    if (!(f > 0.0f)) return 0;  // NaN too
    if (f >= 1.0f) return 255;
    // 32768 + f*255/256 puts round(f*255) in the low mantissa byte (ulp of 32768.0f is 1/256).
    float t = f * (255.0f / 256.0f) + 32768.0f;
    return uint8_t(bits_of(t));
}

uint8_t linear_float_to_srgb8(float x) {
    static const SrgbTable table;
    const float min_val = float_of(uint32_t(127 - 13) << 23);  // 2^-13 and below map to 0
    const float almost_one = float_of(0x3f7fffff);             // 1 - 2^-24 and above map to 255
    if (!(x > min_val)) x = min_val;
    if (x > almost_one) x = almost_one;
    uint32_t u = bits_of(x);
    uint32_t tab = table.entry[(u - bits_of(min_val)) >> 20];
    uint32_t bias = (tab >> 16) << 9, scale = tab & 0xffff;
    uint32_t t = (u >> 12) & 0xff;  // the next 8 mantissa bits interpolate inside the bucket
    return uint8_t((bias + scale * t) >> 16);
}

// Round toward zero, like vcvtps2ph with imm 3 (what Mesa's _mesa_float_to_float16_rtz runs on F16C CPUs):
// finite values too large for half become the largest finite half, never infinity.
uint16_t float_to_half_rtz(float f) {
    uint32_t u = bits_of(f);
    uint16_t sign = uint16_t((u >> 16) & 0x8000);
    uint32_t exp = (u >> 23) & 0xff, mant = u & 0x7fffff;
    if (exp == 0xff) return uint16_t(sign | 0x7c00 | (mant ? 0x200 | (mant >> 13) : 0));  // Inf; NaN made quiet
    int e = int(exp) - 127 + 15;
    if (e >= 0x1f) return uint16_t(sign | 0x7bff);
    if (e <= 0) {
        if (e < -10) return sign;                                 // below the smallest subnormal: zero
        return uint16_t(sign | ((mant | 0x800000) >> (14 - e)));  // subnormal half, truncated
    }
    return uint16_t(sign | (uint32_t(e) << 10) | (mant >> 13));
}

float half_to_float(uint16_t h) {
    uint32_t sign = uint32_t(h & 0x8000) << 16, exp = (h >> 10) & 0x1f, mant = h & 0x3ff;
    if (exp == 0x1f) return float_of(sign | 0x7f800000 | (mant << 13));
    if (exp == 0) {
        float v = std::ldexp(float(mant), -24);  // subnormal: mant * 2^-24
        return sign ? -v : v;
    }
    return float_of(sign | ((exp + 112) << 23) | (mant << 13));
}

void pack_clear_color(const FormatInfo& f, const VkClearColorValue& value, uint8_t* texel) {
    const float* c = value.float32;
    switch (f.pack) {
        case PackKind::kUnorm8:
        case PackKind::kSrgb8: {
            uint8_t rgba[4];
            for (int i = 0; i < 4; ++i) {
                rgba[i] = f.pack == PackKind::kSrgb8 && i < 3 ? linear_float_to_srgb8(c[i]) : float_to_ubyte(c[i]);
            }
            if (f.bgra) std::swap(rgba[0], rgba[2]);
            std::memcpy(texel, rgba, f.channels);
            break;
        }
        case PackKind::kFloat16:
            for (uint32_t i = 0; i < f.channels; ++i) {
                uint16_t h = float_to_half_rtz(c[i]);
                std::memcpy(texel + 2 * i, &h, 2);
            }
            break;
        case PackKind::kFloat32:
            std::memcpy(texel, c, 4 * f.channels);
            break;
        default:
            break;
    }
}

void pack_clear_depth(const FormatInfo& f, float depth, uint8_t* texel) {
    if (f.pack == PackKind::kD16) {
        double z = depth;
        uint16_t v = z <= 0.0 ? 0 : z >= 1.0 ? 0xffff : uint16_t(std::lrint(z * 65535.0));
        std::memcpy(texel, &v, 2);
    } else if (f.pack == PackKind::kD24S8) {
        // util_pack_z for Z24_UNORM_S8_UINT: lrint in double, 1.0 -> 0xffffff.
        double z = depth;
        uint32_t v = z <= 0.0 ? 0 : z >= 1.0 ? 0xffffff : uint32_t(std::lrint(z * 16777215.0));
        std::memcpy(texel, &v, 3);
    } else if (f.pack == PackKind::kD32F || f.pack == PackKind::kD32FS8) {
        std::memcpy(texel, &depth, 4);
    }
}

}  // namespace tilevk::icd
