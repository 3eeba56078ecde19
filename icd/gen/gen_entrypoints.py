#!/usr/bin/python3
"""Generate tilevk's entry-point and extension tables from vk.xml.

Adding a Vulkan command to the driver means writing ONE function in icd/*.cpp:

    VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateBuffer(VkDevice device, ...)

Exposing an extension means adding its name to icd/extensions.txt and writing its commands. A vkCmdSet* whose
whole job is one recorded dynamic value or one refusal is a line of icd/dynamic_commands.txt instead
(--simple-commands): this script writes its definition into entrypoints.cpp.

This script scans the sources for definitions of that shape (`VKAPI_CALL tvk_<Name>(`), looks each command up in
vk.xml, and writes
  entrypoints.h    prototypes (from vk.xml, so a wrong signature is a compile error), the extension ids and the
                   lookup API,
  entrypoints.cpp  one sorted table {name, function, level, core version, providing extensions} (a command's
                   extension aliases, e.g. vkGetPhysicalDeviceProperties2KHR, point at the same function) and the
                   extension table {name, spec version, instance/device} for vkEnumerate*ExtensionProperties.
The level comes from the first parameter's type: VkPhysicalDevice -> physical device, VkInstance -> instance,
VkDevice/VkQueue/VkCommandBuffer -> device, anything else -> global (vkGetInstanceProcAddr counts as global).

The build fails when a written command is neither core Vulkan up to --max-version nor part of a listed extension,
and when a listed extension has a command that is not written: an extension is exposed whole or not at all.

Usage: gen_entrypoints.py --xml vk.xml --max-version 1.0 --extensions extensions.txt
                          [--simple-commands dynamic_commands.txt]
                          --out-h entrypoints.h --out-cpp entrypoints.cpp src.cpp...
"""
import argparse
import re
import sys
import xml.etree.ElementTree as ET

DEFINITION = re.compile(r'VKAPI_CALL\s+tvk_([A-Z]\w*)\s*\(')
DEVICE_HANDLES = {'VkDevice', 'VkQueue', 'VkCommandBuffer'}


def api_ok(elem):
    """vk.xml marks Vulkan SC-only variants with api="vulkansc"; keep elements meant for plain Vulkan."""
    api = elem.get('api')
    return api is None or 'vulkan' in api.split(',')


def clean(text):
    return ' '.join(text.split())


def parse_version(name):
    m = re.fullmatch(r'VK_VERSION_(\d+)_(\d+)', name or '')
    return (int(m.group(1)), int(m.group(2))) if m else None


class Registry:
    def __init__(self, path):
        root = ET.parse(path).getroot()
        self.commands = {}  # canonical name -> (return type, [(param type, param text)])
        self.aliases = {}  # alias name -> canonical name
        for cmd in root.find('commands'):
            if not api_ok(cmd):
                continue
            if cmd.get('alias'):
                self.aliases[cmd.get('name')] = cmd.get('alias')
                continue
            proto = cmd.find('proto')
            name = proto.find('name').text
            ret = clean(''.join(proto.itertext()))[: -len(name)].strip()
            params = [(p.find('type').text, clean(''.join(p.itertext()))) for p in cmd.findall('param') if api_ok(p)]
            self.commands[name] = (ret, params)
        self.core = {}  # command name -> (major, minor) of the first core version that has it
        for feat in root.findall('feature'):
            ver = parse_version(feat.get('name')) if api_ok(feat) else None
            if ver is None:
                continue
            for req in feat.findall('require'):
                for c in req.findall('command'):
                    self.core.setdefault(c.get('name'), ver)
        # platform name -> the macro that guards its declarations in the Vulkan headers (VK_USE_PLATFORM_XCB_KHR)
        self.protect = {p.get('name'): p.get('protect') for p in root.find('platforms')}
        # extension name -> {type, spec_version, protect, requires: [(condition feature/extension or None, [commands])]}
        self.extensions = {}
        for ext in root.find('extensions'):
            supported = ext.get('supported', '').split(',')
            if 'vulkan' not in supported:
                continue
            info = {'type': ext.get('type'), 'number': int(ext.get('number')), 'spec_version': None, 'requires': [],
                    'depends': [d for d in (ext.get('requires') or '').split(',') if d],
                    'promoted': parse_version(ext.get('promotedto')),
                    'protect': self.protect.get(ext.get('platform'))}
            for req in ext.findall('require'):
                if not api_ok(req):
                    continue
                for e in req.findall('enum'):
                    if e.get('name', '').endswith('_SPEC_VERSION') and info['spec_version'] is None:
                        info['spec_version'] = int(e.get('value'))
                cond = req.get('feature') or req.get('extension')
                info['requires'].append((cond, [c.get('name') for c in req.findall('command')]))
            self.extensions[ext.get('name')] = info

    def canonical(self, name):
        while name in self.aliases:
            name = self.aliases[name]
        return name


def level_of(name, params):
    if name == 'vkGetInstanceProcAddr' or not params:
        return 'kGlobal'
    first = params[0][0]
    if first == 'VkPhysicalDevice':
        return 'kPhysicalDevice'
    if first == 'VkInstance':
        return 'kInstance'
    if first in DEVICE_HANDLES:
        return 'kDevice'
    return 'kGlobal'


def read_extension_list(path):
    names = []
    with open(path, encoding='utf-8') as f:
        for line in f:
            line = line.split('#', 1)[0].strip()
            if line:
                names.append(line)
    return names


SIMPLE_KINDS = ('record', 'refuse')


def read_simple_commands(path, reg):
    """icd/dynamic_commands.txt: {command: (kind, argument)} and the errors of the lines this script cannot write:
    a command must return void and take the command buffer first; `record` takes exactly one scalar value."""
    simple, errors = {}, []
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            words = line.split('#', 1)[0].split()
            if not words:
                continue
            where = f'{path}:{number}'
            if len(words) != 3 or words[1] not in SIMPLE_KINDS:
                errors.append(f'{where}: expected "COMMAND record STATE" or "COMMAND refuse FEATURE"')
                continue
            name, kind, arg = words
            if name not in reg.commands:
                errors.append(f'{where}: {name} is not a command in vk.xml (aliases are not written)')
                continue
            ret, params = reg.commands[name]
            if ret != 'void' or not params or params[0][0] != 'VkCommandBuffer':
                errors.append(f'{where}: {name} is not a void command on a VkCommandBuffer')
            elif kind == 'record' and (len(params) != 2 or '*' in params[1][1] or '[' in params[1][1]):
                errors.append(f'{where}: {name} does not set one scalar value; write it by hand')
            elif name in simple:
                errors.append(f'{where}: {name} is listed twice')
            else:
                simple[name] = (kind, arg)
    return simple, errors


def split_param(text):
    """'const float blendConstants[4]' -> ('const float', 'blendConstants', '[4]')."""
    m = re.fullmatch(r'(.*?)(\w+)\s*(\[[^\]]*\])?', text)
    return m.group(1).strip(), m.group(2), m.group(3) or ''


def simple_definitions(reg, simple):
    """The C++ definitions of the commands of --simple-commands (record_dynamic_value and refuse_dynamic_command
    are in icd/dynamic_commands.h)."""
    c = ['// The commands of icd/dynamic_commands.txt: one recorded value or one refusal each.']
    for name, (kind, arg) in sorted(simple.items()):
        _, params = reg.commands[name]
        if kind == 'record':
            plist = ', '.join(p[1] for p in params)
            body = (f'record_dynamic_value({split_param(params[0][1])[1]}, DynamicState::{arg}, '
                    f'uint32_t({split_param(params[1][1])[1]}));')
        else:
            plist = ', '.join(split_param(p[1])[0] + split_param(p[1])[2] for p in params)
            body = f'refuse_dynamic_command("{name}", "{arg}");'
        c += [f'VKAPI_ATTR void VKAPI_CALL tvk_{name[2:]}({plist}) {{', f'    {body}', '}']
    return c + ['']


def extension_commands(reg, ext, listed, max_ver):
    """The commands an exposed extension brings, given what else tilevk exposes (a require block that depends on
    a core version or another extension counts only when that is exposed too)."""
    out = []
    for cond, cmds in reg.extensions[ext]['requires']:
        if cond is not None:
            ver = parse_version(cond)
            if (ver is not None and ver > max_ver) or (ver is None and cond not in listed):
                continue
        out += cmds
    return out


def build_tables(reg, implemented, listed, max_ver, max_version_text):
    errors = []
    for ext in listed:
        if ext not in reg.extensions:
            errors.append(f'{ext} (extensions.txt): not a Vulkan extension in vk.xml')
    if errors:
        return None, errors
    listed_set = set(listed)
    for ext in listed:
        # An extension needs the extensions it requires (vk.xml `requires`), listed or promoted into the core
        # version tilevk reports.
        for dep in reg.extensions[ext]['depends']:
            promoted = reg.extensions.get(dep, {}).get('promoted')
            if dep not in listed_set and not (promoted is not None and promoted <= max_ver):
                errors.append(f'{ext} (extensions.txt) requires {dep}, which is not listed')
    if errors:
        return None, errors
    exposed = {}  # exposed name -> {'canonical', 'core', 'exts'}
    for name, ver in reg.core.items():
        if ver <= max_ver:
            exposed.setdefault(name, {'canonical': reg.canonical(name), 'core': ver, 'exts': []})
    for ext in listed:
        for cmd in extension_commands(reg, ext, listed_set, max_ver):
            e = exposed.setdefault(cmd, {'canonical': reg.canonical(cmd), 'core': None, 'exts': []})
            e['exts'].append(ext)
    for name, e in sorted(exposed.items()):
        if e['canonical'] not in implemented:
            where = 'core Vulkan ' + max_version_text if e['core'] else ', '.join(e['exts'])
            if e['exts'] or e['core']:
                errors.append(f'{name}: required by {where} but tvk_{e["canonical"][2:]} is not written')
    reachable = {e['canonical'] for e in exposed.values()}
    for name in sorted(implemented):
        if name not in reg.commands:
            errors.append(f'{name}: not a command in vk.xml')
        elif name not in reachable:
            errors.append(f'{name}: neither core Vulkan <= {max_version_text} nor a command of an extension '
                          'listed in icd/extensions.txt')
    return exposed, errors


def write_header(path, reg, names, exposed, listed):
    h = ['// Generated by icd/gen/gen_entrypoints.py from vk.xml and icd/extensions.txt. Do not edit.', '#pragma once',
         '#include <vulkan/vulkan.h>', '', '#include <bitset>', '#include <cstddef>', '#include <cstdint>', '',
         'namespace tilevk::icd {', '',
         '// Which dispatchable handle a command is called through (from the type of its first parameter).',
         'enum class EntryLevel : uint8_t { kGlobal, kInstance, kPhysicalDevice, kDevice };', '',
         '// The extensions tilevk exposes (icd/extensions.txt), in that order.',
         'enum class Ext : uint16_t {']
    h += [f'    {n[3:]},' for n in listed]
    h += ['};', f'constexpr size_t kExtensionCount = {len(listed)};',
          'using ExtensionSet = std::bitset<kExtensionCount == 0 ? 1 : kExtensionCount>;', '',
          'struct ExtensionInfo {', '    const char* name;', '    uint32_t spec_version;',
          '    bool device;  // a device extension (else an instance extension)', '};', '',
          '// Every exposed extension, indexed by Ext.', 'const ExtensionInfo* extensions(size_t* count);',
          '// The id of the exposed extension called `name`, or -1.', 'int find_extension(const char* name);', '',
          'struct EntryPoint {', '    const char* name;', '    PFN_vkVoidFunction function;', '    EntryLevel level;',
          '    // VK_MAKE_API_VERSION(0, major, minor, 0) of the core version that has this name; 0 if only extensions do',
          '    uint32_t core_version;',
          '    const Ext* extensions;  // the exposed extensions that bring this name',
          '    uint8_t extension_count;', '};', '',
          '// The exposed command called `name` (core or extension, aliases included), or nullptr.',
          'const EntryPoint* find_entry_point(const char* name);', '',
          '// Every exposed command, sorted by name.', 'const EntryPoint* entry_points(size_t* count);', '']
    # A window-system command's prototype names that system's types (xcb_connection_t, wl_display, Display): it is
    # declared only where its platform macro is defined (icd/wsi/ and entrypoints.cpp), as the Vulkan headers do.
    for name in names:
        ret, params = reg.commands[name]
        plist = ', '.join(p[1] for p in params) or 'void'
        guard = command_protect(reg, name)
        if guard:
            h.append(f'#ifdef {guard}')
        h.append(f'VKAPI_ATTR {ret} VKAPI_CALL tvk_{name[2:]}({plist});')
        if guard:
            h.append('#endif')
    h += ['', '}  // namespace tilevk::icd', '']
    with open(path, 'w', encoding='utf-8') as f:
        f.write('\n'.join(h))


def command_protect(reg, name):
    """The platform macro of the extension that brings a command (vkCreateXcbSurfaceKHR: VK_USE_PLATFORM_XCB_KHR),
    or None for a command of core Vulkan or of a platform-independent extension."""
    for ext in reg.extensions.values():
        if ext['protect'] and any(name in cmds for _, cmds in ext['requires']):
            return ext['protect']
    return None


def write_source(path, reg, exposed, listed, simple):
    ext_index = {n: i for i, n in enumerate(listed)}
    # The table takes the address of every exposed command, window-system ones included: define their platforms.
    guards = sorted({g for g in (command_protect(reg, e['canonical']) for e in exposed.values()) if g})
    c = ['// Generated by icd/gen/gen_entrypoints.py from vk.xml and icd/extensions.txt. Do not edit.']
    c += [f'#define {g}' for g in guards]
    c += ['#include "entrypoints.h"', '', '#include <cstring>', '']
    if simple:
        c += ['#include "dynamic_commands.h"', '']
    c += ['namespace tilevk::icd {', 'namespace {', '']
    if listed:
        c.append(f'const ExtensionInfo kExtensions[{len(listed)}] = {{')
        for n in listed:
            info = reg.extensions[n]
            c.append(f'    {{"{n}", {info["spec_version"] or 1}, {str(info["type"] == "device").lower()}}},')
        c.append('};')
        c.append('')
    # One flat array of extension ids; each entry point points at its run.
    flat, runs = [], {}
    for name in sorted(exposed):
        exts = [ext_index[x] for x in exposed[name]['exts']]
        runs[name] = (len(flat), len(exts))
        flat += exts
    if flat:
        c.append(f'const Ext kProviders[{len(flat)}] = {{')
        c += [f'    Ext::{listed[i][3:]},' for i in flat]
        c.append('};')
        c.append('')
    c.append(f'const EntryPoint kEntryPoints[{len(exposed)}] = {{')
    for name in sorted(exposed):  # strcmp order == Python's order for ASCII names
        e = exposed[name]
        ret, params = reg.commands[e['canonical']]
        core = f'VK_MAKE_API_VERSION(0, {e["core"][0]}, {e["core"][1]}, 0)' if e['core'] else '0'
        first, count = runs[name]
        providers = f'kProviders + {first}' if count else 'nullptr'
        c.append(f'    {{"{name}", reinterpret_cast<PFN_vkVoidFunction>(&tvk_{e["canonical"][2:]}), '
                 f'EntryLevel::{level_of(e["canonical"], params)}, {core}, {providers}, {count}}},')
    c += ['};', '', '}  // namespace', '',
          'const EntryPoint* find_entry_point(const char* name) {',
          '    if (name == nullptr) return nullptr;',
          '    size_t lo = 0, hi = sizeof(kEntryPoints) / sizeof(kEntryPoints[0]);',
          '    while (lo < hi) {  // binary search over the sorted table',
          '        size_t mid = lo + (hi - lo) / 2;',
          '        int cmp = std::strcmp(name, kEntryPoints[mid].name);',
          '        if (cmp == 0) return &kEntryPoints[mid];',
          '        if (cmp < 0) hi = mid; else lo = mid + 1;',
          '    }',
          '    return nullptr;', '}', '',
          'const EntryPoint* entry_points(size_t* count) {',
          '    *count = sizeof(kEntryPoints) / sizeof(kEntryPoints[0]);',
          '    return kEntryPoints;', '}', '',
          'const ExtensionInfo* extensions(size_t* count) {',
          f'    *count = {len(listed)};',
          f'    return {"kExtensions" if listed else "nullptr"};', '}', '',
          'int find_extension(const char* name) {',
          '    if (name == nullptr) return -1;']
    if listed:
        c += ['    for (size_t i = 0; i < kExtensionCount; ++i) {',
              '        if (std::strcmp(name, kExtensions[i].name) == 0) return int(i);', '    }']
    c += ['    return -1;', '}', '']
    if simple:
        c += simple_definitions(reg, simple)
    c += ['}  // namespace tilevk::icd', '']
    with open(path, 'w', encoding='utf-8') as f:
        f.write('\n'.join(c))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--xml', required=True)
    ap.add_argument('--max-version', default='1.0')
    ap.add_argument('--extensions', required=True)
    ap.add_argument('--simple-commands', help='icd/dynamic_commands.txt: commands this script writes')
    ap.add_argument('--out-h', required=True)
    ap.add_argument('--out-cpp', required=True)
    ap.add_argument('sources', nargs='+')
    args = ap.parse_args()
    max_ver = tuple(int(x) for x in args.max_version.split('.'))

    reg = Registry(args.xml)
    listed = read_extension_list(args.extensions)
    implemented = set()
    for src in args.sources:
        with open(src, encoding='utf-8') as f:
            for m in DEFINITION.finditer(f.read()):
                implemented.add('vk' + m.group(1))
    simple, errors = read_simple_commands(args.simple_commands, reg) if args.simple_commands else ({}, [])
    errors += [f'{name}: written in a source and listed in {args.simple_commands}' for name in simple
               if name in implemented]
    implemented |= set(simple)

    exposed, more = build_tables(reg, implemented, listed, max_ver, args.max_version)
    errors += more
    if errors:
        for e in errors:
            print('gen_entrypoints.py: error: ' + e, file=sys.stderr)
        return 1
    write_header(args.out_h, reg, sorted(implemented), exposed, listed)
    write_source(args.out_cpp, reg, exposed, listed, simple)
    return 0


if __name__ == '__main__':
    sys.exit(main())
