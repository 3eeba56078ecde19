#!/usr/bin/python3
"""Generate vk_names.{h,cpp} from vk.xml: the Vulkan names of enum values, flag bits and feature members, so that
every message the driver prints names things as the Vulkan spec does ("VK_FORMAT_R8G8B8A8_UINT", not "format 41").

  const char* vk_enum_name(VkFormat v);                 // "VK_FORMAT_R8G8B8A8_UINT", or "VkFormat(12345)"
  std::string vk_flags_name<VkShaderStageFlagBits>(m);  // "VK_SHADER_STAGE_VERTEX_BIT|VK_SHADER_STAGE_FRAGMENT_BIT"
  const FeatureStruct* find_feature_struct(sType);      // a VkPhysicalDevice*Features struct: name, members, offsets
  const FeatureStruct& features10();                    // VkPhysicalDeviceFeatures itself (no sType)

Only what the shipped headers define without platform or beta macros is generated.

Usage: gen_vk_names.py --xml vk.xml --out-h vk_names.h --out-cpp vk_names.cpp
"""
import argparse
import sys
import xml.etree.ElementTree as ET


def api_ok(elem):
    api = elem.get('api')
    return api is None or 'vulkan' in api.split(',')


class Registry:
    def __init__(self, path):
        root = ET.parse(path).getroot()
        self.root = root
        # Types and enum values that need a platform or beta macro to be declared.
        self.hidden_types, self.hidden_enums = set(), set()
        self.visible_types = set()  # required by a core version or by an extension the headers declare
        # extension number of each enabled extension (for enum offsets)
        self.enum_values = {}  # enum type -> {name: value}, in registry order
        self.bitmask = {}  # enum type -> bool
        self.bitwidth = {}
        for enums in root.findall('enums'):
            kind = enums.get('type')
            if kind not in ('enum', 'bitmask'):
                continue
            name = enums.get('name')
            self.bitmask[name] = kind == 'bitmask'
            self.bitwidth[name] = int(enums.get('bitwidth', '32'))
            vals = self.enum_values.setdefault(name, {})
            for e in enums.findall('enum'):
                if not api_ok(e) or e.get('alias'):
                    continue
                vals[e.get('name')] = self.value_of(e, None)
        for feat in root.findall('feature'):
            if not api_ok(feat):
                continue
            for req in feat.findall('require'):
                self.add_required(req, None, hidden=False)
        for ext in root.find('extensions'):
            if 'vulkan' not in ext.get('supported', '').split(','):
                continue
            hidden = ext.get('platform') is not None or ext.get('provisional') == 'true'
            for req in ext.findall('require'):
                if not api_ok(req):
                    continue
                self.add_required(req, int(ext.get('number')), hidden)

    @staticmethod
    def value_of(e, ext_number):
        if e.get('value') is not None:
            v = e.get('value')
            return int(v, 0) if not v.startswith('"') and not v.startswith('(') else None
        if e.get('bitpos') is not None:
            return 1 << int(e.get('bitpos'))
        if e.get('offset') is not None:
            number = int(e.get('extnumber', ext_number))
            v = 1000000000 + (number - 1) * 1000 + int(e.get('offset'))
            return -v if e.get('dir') == '-' else v
        return None

    def add_required(self, req, ext_number, hidden):
        for t in req.findall('type'):
            (self.hidden_types if hidden else self.visible_types).add(t.get('name'))
        for e in req.findall('enum'):
            if e.get('extends') is None or e.get('alias') or not api_ok(e):
                continue
            v = self.value_of(e, ext_number)
            if v is None:
                continue
            if hidden:
                self.hidden_enums.add(e.get('name'))
                continue
            self.enum_values.setdefault(e.get('extends'), {})[e.get('name')] = v

    def feature_structs(self):
        out = []
        for t in self.root.find('types').findall('type'):
            if t.get('category') != 'struct' or t.get('alias') or not api_ok(t):
                continue
            name = t.get('name')
            extends = (t.get('structextends') or '').split(',')
            if name not in self.visible_types or 'VkPhysicalDeviceFeatures2' not in extends:
                continue
            members = [m for m in t.findall('member') if api_ok(m)]
            stype = members[0].get('values')
            bools = [m.find('name').text for m in members[2:]]
            if not all(m.find('type').text == 'VkBool32' for m in members[2:]) or stype in self.hidden_enums:
                continue
            out.append((name, stype, bools))
        return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--xml', required=True)
    ap.add_argument('--out-h', required=True)
    ap.add_argument('--out-cpp', required=True)
    args = ap.parse_args()
    reg = Registry(args.xml)
    types = [t for t in sorted(reg.enum_values) if t in reg.visible_types and t not in reg.hidden_types
             and reg.enum_values[t] and t in reg.bitmask]
    enums = [t for t in types if not reg.bitmask[t]]
    # 64-bit flag bits are all typedefs of VkFlags64: they get named functions instead of template specialisations.
    flags = [t for t in types if reg.bitmask[t] and reg.bitwidth[t] == 32]
    flags64 = [t for t in types if reg.bitmask[t] and reg.bitwidth[t] == 64]

    h = ['// Generated by icd/gen/gen_vk_names.py from vk.xml. Do not edit.', '#pragma once',
         '#include <vulkan/vulkan.h>', '', '#include <cstddef>', '#include <cstdint>', '#include <string>', '',
         'namespace tilevk::icd {', '',
         '// The Vulkan name of an enum value ("VK_FORMAT_R8G8B8A8_UINT"); an unknown value gives "VkFormat(12345)"',
         '// (in a thread-local buffer valid until the next unknown value on the same thread).']
    h += [f'const char* vk_enum_name({t} value);' for t in enums]
    h += ['', '// The Vulkan names of the bits set in a mask, joined by "|" ("0" for none; unknown bits as hex).',
          'template <class FlagBits>', 'std::string vk_flags_name(uint64_t mask);', '']
    h += [f'template <>\nstd::string vk_flags_name<{t}>(uint64_t mask);' for t in flags]
    h += ['// 64-bit masks (VkFlags64 types cannot be told apart by a template): vk_<FlagBits2 type>_name(mask).']
    h += [f'std::string vk_{t}_name(uint64_t mask);' for t in flags64]
    h += ['', '// A struct of VkBool32 features: VkPhysicalDeviceFeatures, or one that extends VkPhysicalDeviceFeatures2.',
          'struct FeatureStruct {', '    const char* name;              // "VkPhysicalDeviceVulkan11Features"',
          '    VkStructureType s_type;        // 0 for VkPhysicalDeviceFeatures (it has none)',
          '    size_t size;                   // sizeof the struct',
          '    uint32_t count;                // number of VkBool32 members',
          '    const char* const* members;    // their names, in order',
          '    const size_t* offsets;         // their byte offsets', '};', '',
          'const FeatureStruct& features10();', '// The feature struct with this sType, or nullptr.',
          'const FeatureStruct* find_feature_struct(VkStructureType s_type);',
          'const FeatureStruct* feature_structs(size_t* count);', '', '}  // namespace tilevk::icd', '']

    c = ['// Generated by icd/gen/gen_vk_names.py from vk.xml. Do not edit.', '#include "vk_names.h"', '',
         '#include <cstddef>', '#include <cstdio>', '', 'namespace tilevk::icd {', 'namespace {', '',
         'const char* unknown_enum(const char* type, long long value) {', '    thread_local char buf[96];',
         '    std::snprintf(buf, sizeof buf, "%s(%lld)", type, value);', '    return buf;', '}', '',
         'struct Bit {', '    uint64_t bit;', '    const char* name;', '};', '',
         'std::string join_bits(uint64_t mask, const Bit* bits, size_t count) {',
         '    if (mask == 0) return "0";', '    std::string out;',
         '    for (size_t i = 0; i < count; ++i) {',
         '        if ((mask & bits[i].bit) == 0 || bits[i].bit == 0) continue;',
         '        if (!out.empty()) out += "|";', '        out += bits[i].name;', '        mask &= ~bits[i].bit;', '    }',
         '    if (mask != 0) {', '        char buf[32];', '        std::snprintf(buf, sizeof buf, "0x%llx", (unsigned long long)mask);',
         '        if (!out.empty()) out += "|";', '        out += buf;', '    }', '    return out;', '}', '',
         '}  // namespace', '']
    for t in enums:
        c.append(f'const char* vk_enum_name({t} value) {{')
        c.append('    switch (static_cast<long long>(value)) {')
        seen = set()
        for n, v in reg.enum_values[t].items():
            if v is None or v in seen or n.endswith('_MAX_ENUM') or n in reg.hidden_enums:
                continue
            seen.add(v)
            c.append(f'        case {v}LL: return "{n}";')
        c += ['        default: break;', '    }', f'    return unknown_enum("{t}", static_cast<long long>(value));', '}',
              '']
    for t in flags + flags64:
        bits = [(v, n) for n, v in reg.enum_values[t].items()
                if v is not None and v > 0 and (v & (v - 1)) == 0 and n not in reg.hidden_enums]
        seen, uniq = set(), []
        for v, n in bits:
            if v not in seen:
                seen.add(v)
                uniq.append((v, n))
        if t in flags64:
            c.append(f'std::string vk_{t}_name(uint64_t mask) {{')
        else:
            c.append('template <>')
            c.append(f'std::string vk_flags_name<{t}>(uint64_t mask) {{')
        c.append(f'    static const Bit kBits[] = {{' + ', '.join(f'{{{v}ULL, "{n}"}}' for v, n in uniq) + '};')
        c.append('    return join_bits(mask, kBits, sizeof kBits / sizeof kBits[0]);')
        c += ['}', '']

    fs = reg.feature_structs()
    root_types = reg.root.find('types')
    f10 = next(t for t in root_types.findall('type') if t.get('name') == 'VkPhysicalDeviceFeatures')
    f10_members = [m.find('name').text for m in f10.findall('member') if api_ok(m)]
    c.append('namespace {')
    c.append('const char* const kFeatures10Names[] = {' + ', '.join(f'"{m}"' for m in f10_members) + '};')
    c.append('const size_t kFeatures10Offsets[] = {' +
             ', '.join(f'offsetof(VkPhysicalDeviceFeatures, {m})' for m in f10_members) + '};')
    for name, stype, members in fs:
        c.append(f'const char* const k{name}Names[] = {{' + ', '.join(f'"{m}"' for m in members) + '};')
        c.append(f'const size_t k{name}Offsets[] = {{' + ', '.join(f'offsetof({name}, {m})' for m in members) + '};')
    c.append(f'const FeatureStruct kFeatureStructs[{len(fs)}] = {{')
    for name, stype, members in fs:
        c.append(f'    {{"{name}", {stype}, sizeof({name}), {len(members)}, k{name}Names, k{name}Offsets}},')
    c += ['};', '}  // namespace', '',
          'const FeatureStruct& features10() {',
          '    static const FeatureStruct k{"VkPhysicalDeviceFeatures", VkStructureType(0), '
          'sizeof(VkPhysicalDeviceFeatures),',
          f'                                 {len(f10_members)}, kFeatures10Names, kFeatures10Offsets}};',
          '    return k;', '}', '',
          'const FeatureStruct* find_feature_struct(VkStructureType s_type) {',
          '    for (const FeatureStruct& f : kFeatureStructs) {', '        if (f.s_type == s_type) return &f;', '    }',
          '    return nullptr;', '}', '',
          'const FeatureStruct* feature_structs(size_t* count) {',
          '    *count = sizeof kFeatureStructs / sizeof kFeatureStructs[0];', '    return kFeatureStructs;', '}', '',
          '}  // namespace tilevk::icd', '']
    with open(args.out_h, 'w', encoding='utf-8') as f:
        f.write('\n'.join(h))
    with open(args.out_cpp, 'w', encoding='utf-8') as f:
        f.write('\n'.join(c))
    return 0


if __name__ == '__main__':
    sys.exit(main())
