#!/usr/bin/python3
"""Generate tilevk's format table from vk.xml and format/support.txt.

One row per format of vk.xml's <formats> section (plus UNDEFINED): the registry's facts (block size and extent,
components with their bits and numeric formats, packed word size, compression, planes, chroma subsampling) and
tilevk's own (what it supports per tiling and usage, sample counts: support.txt). Derived per row: where each
channel sits in the texel, tilevk's storage bytes, the colour and depth codecs that apply.

  --mode format   format_ids.h (enum class Format, the Feature bits) and format_table.cpp (the rows), Vulkan-free
  --mode icd      format_map.h / format_map.cpp: VkFormat <-> format::Format, with static checks that the Feature
                  and Aspect bits are numbered as Vulkan numbers them

The component order and widths come from the format's name (vk.xml lists some of them out of order, e.g. the
components of B5G5R5A1_UNORM_PACK16 and R64G64_SFLOAT); array formats place the named components from the lowest
address up, packed formats from the top bit of each packed word down (the spec's "Identification of Formats").

Usage: gen_format_table.py --xml vk.xml --support support.txt --mode format --out-h H --out-cpp CPP
"""
import argparse
import re
import sys
import xml.etree.ElementTree as ET

NUMERIC = {'UNORM': 'kUnorm', 'SNORM': 'kSnorm', 'USCALED': 'kUscaled', 'SSCALED': 'kSscaled', 'UINT': 'kUint',
           'SINT': 'kSint', 'UFLOAT': 'kUfloat', 'SFLOAT': 'kSfloat', 'SRGB': 'kSrgb'}
COMPONENT = {'R': 'kR', 'G': 'kG', 'B': 'kB', 'A': 'kA', 'D': 'kD', 'S': 'kS', 'E': 'kE', 'X': 'kX'}


def fail(msg):
    sys.exit('gen_format_table.py: ' + msg)


def camel(flag_name):
    """VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT -> kSampledImageFilterLinear"""
    core = flag_name[len('VK_FORMAT_FEATURE_'):]
    if core.endswith('_BIT'):
        core = core[:-4]
    return 'k' + ''.join(w.capitalize() for w in core.split('_'))


def feature_bits(root):
    """The core VkFormatFeatureFlagBits (1.0 and later core versions): short name -> (enumerant, value)."""
    bits = {}

    def add(e):
        if e.get('alias'):
            return
        if e.get('bitpos') is not None:
            value = 1 << int(e.get('bitpos'))
        elif e.get('value') is not None:
            value = int(e.get('value'), 0)
        else:
            return
        name = e.get('name')
        bits[name[len('VK_FORMAT_FEATURE_'):-len('_BIT')]] = (name, value)

    for enums in root.findall('enums'):
        if enums.get('name') == 'VkFormatFeatureFlagBits':
            for e in enums.findall('enum'):
                add(e)
    for feat in root.findall('feature'):
        if 'vulkan' not in feat.get('api', 'vulkan').split(','):
            continue
        for req in feat.findall('require'):
            for e in req.findall('enum'):
                if e.get('extends') == 'VkFormatFeatureFlagBits':
                    add(e)
    return bits


def name_components(short):
    """Component tokens of a format name in name order, e.g. 'D24_UNORM_S8_UINT' -> [('D', 24), ('S', 8)],
    'X8_D24_UNORM_PACK32' -> [('X', 8), ('D', 24)]. A fixed-point descriptor such as the S10_5 of R16G16_S10_5_NV
    is a numeric word, not a component."""
    parts = short.split('_')
    tokens = []
    for i, p in enumerate(parts):
        fixed_point = i + 1 < len(parts) and parts[i + 1].isdigit()
        if re.fullmatch(r'(?:[RGBADSXE]\d+)+', p) and not fixed_point:
            tokens.extend((c, int(b)) for c, b in re.findall(r'([RGBADSXE])(\d+)', p))
    return tokens


def colour_kind(r):
    """The colour codec of a row (format.h ChannelKind): which of lavapipe's conversion families its texels take."""
    color = [(c, n, b, sh) for c, n, b, sh in r.channels if c in 'RGBA']
    if r.short == 'B10G11R11_UFLOAT_PACK32':
        return 'Ufloat11'
    if r.layout == 'kSharedExponent':
        return 'SharedExp'
    if r.layout not in ('kArray', 'kPacked') or not color or len(color) != len(r.channels):
        return 'None'
    numerics = {n for _, n, _, _ in color}
    widths = {b for _, _, b, _ in color}
    # whole-byte channels: array formats, and packed words whose channels are bytes (A8B8G8R8_*_PACK32)
    bytewise = len(widths) == 1 and all(b % 8 == 0 and sh % 8 == 0 for _, _, b, sh in color)
    width = max(widths)
    if bytewise and width == 8 and 'SRGB' in numerics and numerics <= {'SRGB', 'UNORM'}:
        return 'Srgb8'
    if len(numerics) != 1:
        return 'None'
    numeric = numerics.pop()
    if bytewise:
        kind = {('UNORM', 8): 'Unorm8', ('SNORM', 8): 'Snorm8', ('UNORM', 16): 'Unorm16', ('SNORM', 16): 'Snorm16',
                ('SFLOAT', 16): 'Half', ('SFLOAT', 32): 'Float32'}.get((numeric, width))
        if kind:
            return kind
    if numeric in ('UINT', 'SINT') and width <= 32:
        return 'Uint' if numeric == 'UINT' else 'Sint'
    if r.layout == 'kPacked' and not bytewise and numeric in ('UNORM', 'SNORM'):
        return 'PackedUnorm' if numeric == 'UNORM' else 'PackedSnorm'
    return 'None'


class Row:
    pass


def build_rows(root, support):
    rows = []
    undefined = Row()
    undefined.__dict__.update(vk='VK_FORMAT_UNDEFINED', short='UNDEFINED', layout='kUndefined', block_bytes=0,
                              block_w=1, block_h=1, bytes=0, channels=[], kind='None', depth='None', aspects=0)
    rows.append(undefined)
    for f in root.find('formats'):
        r = Row()
        r.vk = f.get('name')
        r.short = r.vk[len('VK_FORMAT_'):]
        r.block_bytes = int(f.get('blockSize'))
        extent = [int(x) for x in f.get('blockExtent', '1,1,1').split(',')]
        r.block_w, r.block_h = extent[0], extent[1]
        comps = f.findall('component')
        numeric_of = {}
        for c in comps:
            numeric_of.setdefault(c.get('name'), c.get('numericFormat'))
        r.channels = []
        r.xml_alpha = 'A' in numeric_of  # compressed rows list no channels: their alpha comes from the components
        if f.get('compressed'):
            r.layout = 'kCompressed'
        elif f.find('plane') is not None:
            r.layout = 'kMultiPlanar'
        elif f.get('chroma'):
            r.layout = 'kSubsampled'
        elif r.short.startswith('E5B9G9R9'):
            r.layout = 'kSharedExponent'
        else:
            r.layout = 'kPacked' if f.get('packed') else 'kArray'
        if r.layout in ('kArray', 'kPacked', 'kSharedExponent'):
            tokens = name_components(r.short)
            word = int(f.get('packed')) if f.get('packed') else None
            shift, placed = 0, []
            if word is None:
                for c, bits in tokens:
                    placed.append((c, bits, shift))
                    shift += bits
            else:
                # packed: each word filled from its top bit down, words from the lowest address up
                base, top = 0, word
                for c, bits in tokens:
                    if top - bits < 0:
                        base, top = base + word, word
                    top -= bits
                    placed.append((c, bits, base + top))
            for c, bits, sh in placed:
                if c == 'X':
                    continue
                numeric = numeric_of.get(c, 'UFLOAT' if c == 'E' else None)
                if numeric is None and c in 'RGBA' and comps:
                    numeric = comps[0].get('numericFormat')  # vk.xml's R64G64 lists R and B: same numeric format
                if numeric is None:
                    fail(f'{r.short}: no numeric format for component {c}')
                if c in 'RGB' and numeric == 'SRGB':
                    pass
                elif c == 'A' and numeric == 'SRGB':
                    numeric = 'UNORM'  # the alpha of an sRGB format is linear (the spec's "sRGB" numeric format)
                r.channels.append((c, numeric, bits, sh))
            total = max((sh + bits for c, bits, sh in placed), default=0)
            if total > r.block_bytes * 8:
                fail(f'{r.short}: components need {total} bits, block has {r.block_bytes * 8}')
        names = [c for c, _, _, _ in r.channels]
        r.aspects = (1 if any(c in 'RGBA' for c in names) or r.layout in ('kCompressed', 'kMultiPlanar',
                                                                         'kSubsampled') else 0)
        r.aspects |= (2 if 'D' in names else 0) | (4 if 'S' in names else 0)
        r.kind = colour_kind(r)
        r.depth = 'None'
        for c, n, b, _ in r.channels:
            if c == 'D':
                r.depth = {('UNORM', 16): 'D16', ('UNORM', 24): 'X8D24', ('SFLOAT', 32): 'D32F'}.get((n, b), 'None')
        r.bytes = r.block_bytes
        rows.append(r)
    by_name = {r.short: r for r in rows}
    for name, s in support.items():
        if name not in by_name:
            fail(f'support.txt names {name}, which vk.xml does not define')
        by_name[name].support = s
        if 'bytes' in s:
            by_name[name].bytes = s['bytes']
    for r in rows:
        if not hasattr(r, 'support'):
            r.support = {'optimal': [], 'linear': [], 'buffer': [], 'samples': [1] if r.short != 'UNDEFINED' else []}
    return rows


def parse_support(path, bits):
    groups, rows = {}, {}

    def expand(words, where):
        out = []
        for w in words:
            if w == '-':
                continue
            if w.startswith('@'):
                if w not in groups:
                    fail(f'{where}: unknown group {w}')
                out.extend(groups[w])
            elif w in bits:
                out.append(w)
            else:
                fail(f'{where}: {w} is not a VkFormatFeatureFlagBits name (without VK_FORMAT_FEATURE_ and _BIT)')
        return sorted(set(out), key=lambda n: bits[n][1])

    for lineno, line in enumerate(open(path), 1):
        line = line.split('#', 1)[0].strip()
        if not line:
            continue
        where = f'{path}:{lineno}'
        fields = line.split()
        if fields[0].startswith('@'):
            groups[fields[0]] = expand(fields[1:], where)
            continue
        if len(fields) < 5:
            fail(f'{where}: expected "FORMAT optimal linear buffer samples [bytes=N]"')
        name, optimal, linear, buffer, samples = fields[:5]
        entry = {'optimal': expand(optimal.split(','), where), 'linear': expand(linear.split(','), where),
                 'buffer': expand(buffer.split(','), where),
                 'samples': [int(x) for x in samples.split(',')]}
        for extra in fields[5:]:
            key, _, value = extra.partition('=')
            if key != 'bytes':
                fail(f'{where}: unknown field {key}')
            entry['bytes'] = int(value)
        if name in rows:
            fail(f'{where}: {name} listed twice')
        rows[name] = entry
    return rows


def features_expr(names, bits):
    return ' | '.join(camel(bits[n][0]) for n in names) if names else '0'


def write_format(rows, bits, out_h, out_cpp):
    with open(out_h, 'w') as h:
        h.write('// Generated by format/gen/gen_format_table.py from vk.xml: do not edit.\n')
        h.write('#pragma once\n#include <cstdint>\n\nnamespace tilevk::format {\n\n')
        h.write('// Every format of the Vulkan registry, named as Vulkan names it (without VK_FORMAT_).\n')
        h.write('enum class Format : uint16_t {\n')
        for r in rows:
            h.write(f'    {r.short},\n')
        h.write('    kCount\n};\n\n')
        h.write('// What a format supports, numbered as VkFormatFeatureFlagBits (icd/ checks that at compile time).\n')
        h.write('enum Feature : uint32_t {\n')
        for short, (name, value) in sorted(bits.items(), key=lambda kv: kv[1][1]):
            h.write(f'    {camel(name)} = 0x{value:x}u,\n')
        h.write('};\n\n}  // namespace tilevk::format\n')
    with open(out_cpp, 'w') as c:
        c.write('// Generated by format/gen/gen_format_table.py from vk.xml and format/support.txt: do not edit.\n')
        c.write('#include "format/format.h"\n\nnamespace tilevk::format {\n\n')
        c.write('const FormatInfo kFormatTable[] = {\n')
        for r in rows:
            s = r.support
            samples = sum(1 << (n.bit_length() - 1) for n in s['samples'])
            chans = ', '.join(f'{{Component::{COMPONENT[ch]}, Numeric::{NUMERIC[n]}, {b}, {sh}}}'
                              for ch, n, b, sh in r.channels)
            color = [ch for ch, _, _, _ in r.channels if ch in 'RGBA']
            has_alpha = 'true' if 'A' in color or (r.layout == 'kCompressed' and r.xml_alpha) else 'false'
            bgra = 'true' if r.kind in ('Unorm8', 'Srgb8') and color[:1] == ['B'] else 'false'
            c.write(f'    {{.id = Format::{r.short},\n')
            c.write(f'     .name = "{r.short}",\n')
            c.write(f'     .layout = Layout::{r.layout},\n')
            c.write(f'     .block_bytes = {r.block_bytes},\n')
            c.write(f'     .block_width = {r.block_w},\n')
            c.write(f'     .block_height = {r.block_h},\n')
            c.write(f'     .bytes = {r.bytes},\n')
            c.write(f'     .channels = {len(r.channels)},\n')
            c.write(f'     .has_alpha = {has_alpha},\n')
            c.write(f'     .bgra = {bgra},\n')
            c.write(f'     .kind = ChannelKind::{r.kind},\n')
            c.write(f'     .depth = DepthFormat::{r.depth},\n')
            c.write(f'     .aspects = {r.aspects},\n')
            c.write(f'     .channel = {{{chans}}},\n')
            c.write(f'     .optimal = {features_expr(s["optimal"], bits)},\n')
            c.write(f'     .linear = {features_expr(s["linear"], bits)},\n')
            c.write(f'     .buffer = {features_expr(s["buffer"], bits)},\n')
            c.write(f'     .sample_counts = 0x{samples:x}}},\n')
        c.write('};\n')
        c.write('static_assert(sizeof(kFormatTable) / sizeof(kFormatTable[0]) == size_t(Format::kCount));\n\n')
        c.write('}  // namespace tilevk::format\n')


def write_icd(rows, bits, out_h, out_cpp):
    with open(out_h, 'w') as h:
        h.write('// Generated by format/gen/gen_format_table.py from vk.xml: do not edit.\n')
        h.write('// The one mapping between VkFormat and tilevk\'s format table.\n')
        h.write('#pragma once\n#include <vulkan/vulkan.h>\n\n#include "format/format.h"\n\n')
        h.write('namespace tilevk::icd {\n\n')
        h.write('// Format::UNDEFINED for values that are not a registry format.\n')
        h.write('format::Format to_format(VkFormat f);\n')
        h.write('VkFormat to_vk_format(format::Format f);\n\n}  // namespace tilevk::icd\n')
    with open(out_cpp, 'w') as c:
        c.write('// Generated by format/gen/gen_format_table.py from vk.xml: do not edit.\n')
        c.write('#include "format_map.h"\n\nnamespace tilevk::icd {\n\n')
        for short, (name, value) in sorted(bits.items(), key=lambda kv: kv[1][1]):
            c.write(f'static_assert(uint32_t(format::{camel(name)}) == uint32_t({name}));\n')
        for aspect in ('Color', 'Depth', 'Stencil'):
            c.write(f'static_assert(uint32_t(format::k{aspect}) == uint32_t(VK_IMAGE_ASPECT_{aspect.upper()}_BIT));\n')
        c.write('\n')
        c.write('format::Format to_format(VkFormat f) {\n    switch (f) {\n')
        for r in rows:
            c.write(f'        case {r.vk}:\n            return format::Format::{r.short};\n')
        c.write('        default:\n            return format::Format::UNDEFINED;\n    }\n}\n\n')
        c.write('VkFormat to_vk_format(format::Format f) {\n    static constexpr VkFormat kVk[] = {\n')
        for r in rows:
            c.write(f'        {r.vk},\n')
        c.write('    };\n    return size_t(f) < sizeof(kVk) / sizeof(kVk[0]) ? kVk[size_t(f)] : VK_FORMAT_UNDEFINED;\n}\n\n')
        c.write('}  // namespace tilevk::icd\n')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--xml', required=True)
    ap.add_argument('--support', required=True)
    ap.add_argument('--mode', choices=['format', 'icd'], required=True)
    ap.add_argument('--out-h', required=True)
    ap.add_argument('--out-cpp', required=True)
    a = ap.parse_args()
    root = ET.parse(a.xml).getroot()
    bits = feature_bits(root)
    rows = build_rows(root, parse_support(a.support, bits))
    (write_format if a.mode == 'format' else write_icd)(rows, bits, a.out_h, a.out_cpp)


if __name__ == '__main__':
    main()
