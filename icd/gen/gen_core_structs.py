#!/usr/bin/python3
"""Generate core_structs.{h,cpp} from vk.xml: the copies between the feature and property structs that Vulkan 1.1,
1.2 and 1.3 promoted from extensions (VkPhysicalDeviceMultiviewFeatures, VkPhysicalDeviceDriverProperties, ...) and
the VkPhysicalDeviceVulkan1{1,2,3}{Features,Properties} structs that hold the same members.

tilevk keeps each fact once, in the six Vulkan1x structs (icd/features.cpp, icd/properties.cpp); every promoted struct
an application chains is filled from them, member by member, so the two spellings can never disagree:

  bool read_core_features(const CoreFeatures&, VkBaseOutStructure* s);    // fill s from the Vulkan1xFeatures
  bool merge_core_features(const VkBaseOutStructure* s, CoreFeatures*);   // OR s's VkBool32s into them
  bool read_core_properties(const CoreProperties&, VkBaseOutStructure* s);

Each returns false when s is not a promoted struct. A member is found in the Vulkan1x struct by its name, or with a
"subgroup" prefix (VkPhysicalDeviceSubgroupProperties::supportedStages is Vulkan11Properties::subgroupSupportedStages);
the build fails if a member has no counterpart.

Usage: gen_core_structs.py --xml vk.xml --out-h core_structs.h --out-cpp core_structs.cpp
"""
import argparse
import re
import sys
import xml.etree.ElementTree as ET

CORE = {(1, 1): '11', (1, 2): '12', (1, 3): '13'}


def api_ok(elem):
    api = elem.get('api')
    return api is None or 'vulkan' in api.split(',')


def members_of(t):
    """(name, is_array) of every member after sType and pNext."""
    out = []
    for m in t.findall('member'):
        if not api_ok(m):
            continue
        name = m.find('name').text
        if name in ('sType', 'pNext'):
            continue
        text = ''.join(m.itertext())
        out.append((name, re.search(r'\[', text.split(name, 1)[1]) is not None))
    return out


def promoted_structs(root):
    """[(kind, struct name, sType, version)] for the structs promoted into core 1.1-1.3."""
    types = {t.get('name'): t for t in root.find('types').findall('type')}
    out = []
    for feat in root.findall('feature'):
        m = re.fullmatch(r'VK_VERSION_(\d+)_(\d+)', feat.get('name') or '')
        if not m or not api_ok(feat):
            continue
        ver = (int(m.group(1)), int(m.group(2)))
        if ver not in CORE:
            continue
        for req in feat.findall('require'):
            for r in req.findall('type'):
                t = types.get(r.get('name'))
                if t is None or t.get('alias') or re.fullmatch(r'VkPhysicalDeviceVulkan1\d(Features|Properties)',
                                                               t.get('name')):
                    continue
                extends = (t.get('structextends') or '').split(',')
                kind = 'Features' if 'VkPhysicalDeviceFeatures2' in extends else \
                    'Properties' if 'VkPhysicalDeviceProperties2' in extends else None
                if kind is None:
                    continue
                stype = next(mm.get('values') for mm in t.findall('member') if mm.find('name').text == 'sType')
                out.append((kind, t.get('name'), stype, ver))
    return out, types


def counterpart(name, core_members):
    if name in core_members:
        return name
    prefixed = 'subgroup' + name[0].upper() + name[1:]
    return prefixed if prefixed in core_members else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--xml', required=True)
    ap.add_argument('--out-h', required=True)
    ap.add_argument('--out-cpp', required=True)
    args = ap.parse_args()
    root = ET.parse(args.xml).getroot()
    structs, types = promoted_structs(root)

    errors = []
    bodies = {'Features': ([], []), 'Properties': ([], [])}  # kind -> (read cases, merge cases)
    for kind, name, stype, ver in structs:
        core_name = f'VkPhysicalDeviceVulkan{CORE[ver]}{kind}'
        core_members = {n for n, _ in members_of(types[core_name])}
        field = f'v{CORE[ver]}'
        read = [f'        case {stype}: {{', f'            auto* d = reinterpret_cast<{name}*>(s);']
        merge = [f'        case {stype}: {{', f'            const auto* d = reinterpret_cast<const {name}*>(s);']
        for member, is_array in members_of(types[name]):
            c = counterpart(member, core_members)
            if c is None:
                errors.append(f'{name}::{member} has no counterpart in {core_name}')
                continue
            if is_array:
                read.append(f'            std::memcpy(d->{member}, core.{field}.{c}, sizeof d->{member});')
            else:
                read.append(f'            d->{member} = core.{field}.{c};')
            merge.append(f'            core->{field}.{c} |= d->{member};')
        read += ['            return true;', '        }']
        merge += ['            return true;', '        }']
        bodies[kind][0].extend(read)
        bodies[kind][1].extend(merge)
    if errors:
        for e in errors:
            print('gen_core_structs.py: error: ' + e, file=sys.stderr)
        return 1

    h = ['// Generated by icd/gen/gen_core_structs.py from vk.xml. Do not edit.', '#pragma once',
         '#include <vulkan/vulkan.h>', '', 'namespace tilevk::icd {', '',
         '// The Vulkan 1.1-1.3 feature and property structs that hold every promoted member.',
         '// (All members start as zero / VK_FALSE; pNext stays nullptr.)',
         'struct CoreFeatures {',
         '    VkPhysicalDeviceVulkan11Features v11{};', '    VkPhysicalDeviceVulkan12Features v12{};',
         '    VkPhysicalDeviceVulkan13Features v13{};',
         '    CoreFeatures() {', '        v11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES;',
         '        v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;',
         '        v13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;', '    }', '};',
         'struct CoreProperties {',
         '    VkPhysicalDeviceVulkan11Properties v11{};', '    VkPhysicalDeviceVulkan12Properties v12{};',
         '    VkPhysicalDeviceVulkan13Properties v13{};',
         '    CoreProperties() {', '        v11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES;',
         '        v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES;',
         '        v13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES;', '    }', '};',
         '',
         '// `s` is a struct promoted into core 1.1-1.3 (VkPhysicalDeviceMultiviewFeatures, ...): its members are',
         '// written from / OR-ed into the Vulkan1x struct that holds them. false (nothing touched) for any other sType.',
         'bool read_core_features(const CoreFeatures& core, VkBaseOutStructure* s);',
         'bool merge_core_features(const VkBaseOutStructure* s, CoreFeatures* core);',
         'bool read_core_properties(const CoreProperties& core, VkBaseOutStructure* s);', '',
         '}  // namespace tilevk::icd', '']
    c = ['// Generated by icd/gen/gen_core_structs.py from vk.xml. Do not edit.', '#include "core_structs.h"', '',
         '#include <cstring>', '', 'namespace tilevk::icd {', '',
         'bool read_core_features(const CoreFeatures& core, VkBaseOutStructure* s) {', '    switch (s->sType) {']
    c += bodies['Features'][0]
    c += ['        default:', '            return false;', '    }', '}', '',
          'bool merge_core_features(const VkBaseOutStructure* s, CoreFeatures* core) {', '    switch (s->sType) {']
    c += bodies['Features'][1]
    c += ['        default:', '            return false;', '    }', '}', '',
          'bool read_core_properties(const CoreProperties& core, VkBaseOutStructure* s) {', '    switch (s->sType) {']
    c += bodies['Properties'][0]
    c += ['        default:', '            return false;', '    }', '}', '', '}  // namespace tilevk::icd', '']
    with open(args.out_h, 'w', encoding='utf-8') as f:
        f.write('\n'.join(h))
    with open(args.out_cpp, 'w', encoding='utf-8') as f:
        f.write('\n'.join(c))
    return 0


if __name__ == '__main__':
    sys.exit(main())
