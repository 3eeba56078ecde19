// BPTC (BC6H, BC7) block decoding as lavapipe 22.3.6 samples it (texel_bc.h has the rules and their Mesa sources);
// the spec's tables are in texel_bptc_tables.h.
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "format/texel_bc.h"
#include "format/texel_bptc_tables.h"
#include "format/texel_codec.h"

namespace tilevk::format {
namespace {

// `n` (at most 16) bits of the 128-bit little-endian block from bit `at`; bits past the block read 0.
uint32_t field(const uint8_t* block, int at, int n) {
    uint64_t w[2];
    std::memcpy(w, block, 16);
    if (n <= 0 || at >= 128) return 0;
    uint64_t v = at >= 64 ? w[1] >> (at - 64) : at == 0 ? w[0] : (w[0] >> at) | (w[1] << (64 - at));
    return uint32_t(v & ((1ull << n) - 1));
}

// The spec's interpolation weights (in 64ths) for 2-, 3- and 4-bit indices, and the rounding mix of two endpoints.
int32_t mix(int32_t a, int32_t b, uint32_t index, int bits) {
    static constexpr uint8_t kW2[4] = {0, 21, 43, 64};
    static constexpr uint8_t kW3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
    static constexpr uint8_t kW4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};
    const int32_t w = bits == 2 ? kW2[index & 3] : bits == 3 ? kW3[index & 7] : kW4[index & 15];
    return ((64 - w) * a + w * b + 32) >> 6;  // arithmetic shift for BC6H's signed endpoints
}

// Which subset texel t (0..15) belongs to, and whether its index is stored one bit short (an anchor).
struct Partition {
    int subsets = 1;
    int number = 0;
    int subset(int t) const {
        if (subsets == 1) return 0;
        const char* row = subsets == 2 ? bptc::kPartition2[number] : bptc::kPartition3[number];
        return row[t] - '0';
    }
    bool anchor(int t) const {
        if (t == 0) return true;
        if (subsets == 2) return bptc::kAnchor2[number] == t;
        if (subsets == 3) return bptc::kAnchor3Second[number] == t || bptc::kAnchor3Third[number] == t;
        return false;
    }
    // Bit offset of texel t's index in an index field of `bits` bits per texel starting at `start`.
    int index_at(int start, int bits, int t) const {
        int at = start;
        for (int k = 0; k < t; ++k) at += anchor(k) ? bits - 1 : bits;
        return at;
    }
};

// ---- BC7 ----

enum class PBits : uint8_t { None, PerEndpoint, PerSubset };
struct Bc7Mode {
    uint8_t subsets, partition_bits, rotation_bits, selector_bits, colour_bits, alpha_bits;
    PBits pbits;
    uint8_t index_bits, index2_bits;
};
// The spec's BC7 mode table (modes 0..7).
constexpr Bc7Mode kBc7Modes[8] = {
    {3, 4, 0, 0, 4, 0, PBits::PerEndpoint, 3, 0}, {2, 6, 0, 0, 6, 0, PBits::PerSubset, 3, 0},
    {3, 6, 0, 0, 5, 0, PBits::None, 2, 0},        {2, 6, 0, 0, 7, 0, PBits::PerEndpoint, 2, 0},
    {1, 0, 2, 1, 5, 6, PBits::None, 2, 3},        {1, 0, 2, 0, 7, 8, PBits::None, 2, 2},
    {1, 0, 0, 0, 7, 7, PBits::PerEndpoint, 4, 0}, {2, 6, 0, 0, 5, 5, PBits::PerEndpoint, 2, 0},
};

// An n-bit endpoint channel (5..8 bits) widened to 8 bits by repeating its top bits below it.
uint8_t widen(uint32_t v, int n) {
    return uint8_t((v << (8 - n)) | (v >> (2 * n - 8)));
}

// The endpoints of a BC7 block: 2 per subset, RGBA bytes; returns the bit offset after them.
int bc7_endpoints(const Bc7Mode& m, const uint8_t* block, int at, uint8_t ep[6][4]) {
    const int n_ep = 2 * m.subsets;
    uint32_t raw[6][4] = {};
    for (int c = 0; c < 4; ++c) {
        const int bits = c < 3 ? m.colour_bits : m.alpha_bits;
        for (int e = 0; e < n_ep; ++e, at += bits) raw[e][c] = field(block, at, bits);
    }
    const int channels = m.alpha_bits ? 4 : 3;  // without alpha bits the p-bits only reach colour
    int extra = 0;
    if (m.pbits != PBits::None) {
        extra = 1;
        const int n_p = m.pbits == PBits::PerEndpoint ? n_ep : m.subsets;
        for (int e = 0; e < n_ep; ++e) {
            const uint32_t p = field(block, at + (m.pbits == PBits::PerEndpoint ? e : e / 2), 1);
            for (int c = 0; c < channels; ++c) raw[e][c] = raw[e][c] << 1 | p;
        }
        at += n_p;
    }
    for (int e = 0; e < n_ep; ++e) {
        for (int c = 0; c < 3; ++c) ep[e][c] = widen(raw[e][c], m.colour_bits + extra);
        ep[e][3] = m.alpha_bits ? widen(raw[e][3], m.alpha_bits + extra) : 255;
    }
    return at;
}

void decode_bc7(const uint8_t* block, int t, uint8_t out[4]) {
    // the mode is the number of zero bits below the first 1; a block without one (mode 8) is reserved: Mesa
    // (texcompress_bptc_tmp.h fetch_rgba_unorm_from_block) returns (0, 0, 0, 0) for it
    if (block[0] == 0) {
        out[0] = out[1] = out[2] = out[3] = 0;
        return;
    }
    const int mode = std::countr_zero(unsigned(block[0]));
    const Bc7Mode& m = kBc7Modes[mode];
    int at = mode + 1;
    Partition part;
    part.subsets = m.subsets;
    part.number = int(field(block, at, m.partition_bits));
    at += m.partition_bits;
    const uint32_t rotation = field(block, at, m.rotation_bits);
    at += m.rotation_bits;
    const uint32_t selector = field(block, at, m.selector_bits);
    at += m.selector_bits;
    uint8_t ep[6][4];
    at = bc7_endpoints(m, block, at, ep);
    const bool anchor = part.anchor(t);
    const uint32_t i1 = field(block, part.index_at(at, m.index_bits, t), m.index_bits - (anchor ? 1 : 0));
    const int start2 = at + 16 * m.index_bits - m.subsets;
    const uint32_t i2 =
        m.index2_bits ? field(block, part.index_at(start2, m.index2_bits, t), m.index2_bits - anchor) : 0;
    // colour takes the second index set where the selector asks for it, alpha the other one
    const bool swap = selector != 0;
    const uint32_t ci = swap ? i2 : i1, ai = (m.index2_bits && !swap) ? i2 : i1;
    const int cbits = swap ? m.index2_bits : m.index_bits,
              abits = (m.index2_bits && !swap) ? m.index2_bits : m.index_bits;
    const int s = part.subset(t);
    for (int c = 0; c < 3; ++c) out[c] = uint8_t(mix(ep[2 * s][c], ep[2 * s + 1][c], ci, cbits));
    out[3] = uint8_t(mix(ep[2 * s][3], ep[2 * s + 1][3], ai, abits));
    if (rotation) std::swap(out[rotation - 1], out[3]);
}

// ---- BC6H ----

// One parsed field of a BC6H layout: `bits` bits going to endpoint `ep`, channel `ch`, the first at bit `first`,
// the next ones stepping by `step` (+1, or -1 for the spec's bit-reversed fields).
struct Bc6Field {
    uint8_t ep, ch, bits, first;
    int8_t step;
};
struct Bc6Layout {
    const bptc::Bc6Mode* mode = nullptr;
    std::array<Bc6Field, 24> fields{};
    int count = 0;
};

// Parses the spec's notation of texel_bptc_tables.h ("rw9:0", "gz4", "rw10:15").
Bc6Layout parse_layout(const bptc::Bc6Mode& m) {
    Bc6Layout l;
    l.mode = &m;
    const char* p = m.layout;
    while (*p && l.count < int(l.fields.size())) {
        while (*p == ' ') ++p;
        if (!*p) break;
        Bc6Field f{};
        f.ch = uint8_t(*p == 'r' ? 0 : *p == 'g' ? 1 : 2);
        f.ep = uint8_t(p[1] - 'w');  // w, x, y, z
        char* end = nullptr;
        const long a = std::strtol(p + 2, &end, 10);
        long b = a;
        if (*end == ':') b = std::strtol(end + 1, &end, 10);
        p = end;
        f.bits = uint8_t(std::labs(a - b) + 1);
        f.first = uint8_t(b);  // the field's first bit goes to the position written last
        f.step = int8_t(a >= b ? 1 : -1);
        l.fields[size_t(l.count++)] = f;
    }
    return l;
}

// The parsed layout of the mode whose bits start byte 0 (2 bits where bit 1 is 0, else 5), or null: reserved.
const Bc6Layout* bc6_layout(uint8_t byte0) {
    static const std::array<Bc6Layout, 32> kLayouts = [] {
        std::array<Bc6Layout, 32> t{};
        for (const bptc::Bc6Mode& m : bptc::kBc6Modes) t[m.mode] = parse_layout(m);
        return t;
    }();
    const int key = (byte0 & 2) ? byte0 & 31 : byte0 & 3;
    return kLayouts[size_t(key)].mode ? &kLayouts[size_t(key)] : nullptr;
}

int32_t sign_extend(uint32_t v, int bits) {
    const uint32_t sign = 1u << (bits - 1);
    return int32_t((v & ((sign << 1) - 1)) ^ sign) - int32_t(sign);
}

// The spec's endpoint unquantization to 16 bits (signed: 15 bits and a sign).
int32_t unquantize(int32_t v, int bits, bool is_signed) {
    if (!is_signed) {
        if (bits >= 15 || v == 0) return v;
        if (v == (1 << bits) - 1) return 0xffff;
        return ((v << 15) + 0x4000) >> (bits - 1);
    }
    if (bits >= 16 || v == 0) return v;
    const int32_t mag = v < 0 ? -v : v;
    const int32_t q = mag >= (1 << (bits - 1)) - 1 ? 0x7fff : ((mag << 15) + 0x4000) >> (bits - 1);
    return v < 0 ? -q : q;
}

void decode_bc6(const uint8_t* block, int t, bool is_signed, float out[4]) {
    out[3] = 1.0f;
    const Bc6Layout* l = bc6_layout(block[0]);
    if (!l) {  // reserved modes: (0, 0, 0, 1) as Mesa's fetch_rgb_float_from_block
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    const bptc::Bc6Mode& m = *l->mode;
    int at = (block[0] & 2) ? 5 : 2;
    uint32_t raw[4][3] = {};
    for (int k = 0; k < l->count; ++k) {
        const Bc6Field& f = l->fields[size_t(k)];
        const uint32_t v = field(block, at, f.bits);
        at += f.bits;
        for (int b = 0; b < f.bits; ++b)
            if (v >> b & 1) raw[f.ep][f.ch] |= 1u << (f.first + f.step * b);
    }
    Partition part;
    if (m.partition_bits) {
        part.subsets = 2;
        part.number = int(field(block, at, m.partition_bits));
        at += m.partition_bits;
    }
    const int n_ep = 2 * part.subsets, eb = m.endpoint_bits;
    int32_t ep[4][3];
    for (int e = 0; e < n_ep; ++e)
        for (int c = 0; c < 3; ++c) {
            uint32_t v = raw[e][c];
            // deltas from endpoint 0, wrapped to the endpoint precision
            if (m.deltas && e > 0)
                v = uint32_t(int32_t(raw[0][c]) + sign_extend(v, m.delta_bits[c])) & ((1u << eb) - 1);
            ep[e][c] = unquantize(is_signed ? sign_extend(v, eb) : int32_t(v), eb, is_signed);
        }
    const bool anchor = part.anchor(t);
    const uint32_t index = field(block, part.index_at(at, m.index_bits, t), m.index_bits - (anchor ? 1 : 0));
    const int s = part.subset(t);
    for (int c = 0; c < 3; ++c) {
        const int32_t v = mix(ep[2 * s][c], ep[2 * s + 1][c], index, m.index_bits);
        // scale to the half-float range: 31/64 unsigned, 31/32 of the magnitude with the sign bit for signed
        const int32_t h = !is_signed ? v * 31 / 64 : v < 0 ? ((-v * 31 / 32) | 0x8000) : v * 31 / 32;
        out[c] = half_to_float(uint16_t(h));
    }
}

// util_format_srgb_8unorm_to_linear_float_table as Mesa generates it (util/format_srgb.py): the exact curve in
// double, printed with 8 significant digits ("%.7e") and read back as a float.
float srgb8_table(uint8_t u) {
    static const std::array<float, 256> kTable = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double x = i / 255.0;
            const double lin = x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
            char text[32];
            std::snprintf(text, sizeof text, "%.7e", lin);
            t[size_t(i)] = std::strtof(text, nullptr);
        }
        return t;
    }();
    return kTable[u];
}

}  // namespace

bool is_bptc(const FormatInfo& f) {
    return f.id >= Format::BC6H_UFLOAT_BLOCK && f.id <= Format::BC7_SRGB_BLOCK;
}

void decode_bc7_rgba8(const uint8_t* block, int i, int j, uint8_t rgba[4]) {
    decode_bc7(block, (j & 3) * 4 + (i & 3), rgba);
}

void decode_bptc_color(const FormatInfo& f, const uint8_t* block, int i, int j, float rgba[4]) {
    const int t = (j & 3) * 4 + (i & 3);
    if (f.id == Format::BC6H_UFLOAT_BLOCK || f.id == Format::BC6H_SFLOAT_BLOCK) {
        decode_bc6(block, t, f.id == Format::BC6H_SFLOAT_BLOCK, rgba);
        return;
    }
    uint8_t c[4];
    decode_bc7(block, t, c);
    const bool srgb = f.id == Format::BC7_SRGB_BLOCK;
    for (int k = 0; k < 3; ++k) rgba[k] = srgb ? srgb8_table(c[k]) : unorm8_to_float(c[k]);
    rgba[3] = unorm8_to_float(c[3]);
}

}  // namespace tilevk::format
