#!/usr/bin/python3
"""vulkaninfo on tilevk alone, in all three modes, must not crash and must report what the driver does.

  --summary  exactly one device: a CPU named tilevk
  text       every feature struct section, the device extensions and the key limits it prints
  -j         the Vulkan-profiles JSON it writes: Vulkan 1.3, features, extensions, formats, queue families, key
             properties
are compared with icd_report_probe's JSON, which reads the same through the API and checks each claim against the
driver's behaviour (every feature member reported true creates a device, every false one is refused; every device
extension can be enabled); the probe exits 1 on a disagreement.

Usage: vulkaninfo_test.py <vulkaninfo> <tilevk_icd.json> <icd_report_probe> <vk.xml>
Exit 77 (meson: skipped) only if vulkaninfo is absent."""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

vulkaninfo, manifest, probe, registry = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
if shutil.which(vulkaninfo) is None:
    print(f'SKIP: {vulkaninfo} not found (Debian package vulkan-tools)')
    sys.exit(77)
env = dict(os.environ, VK_ICD_FILENAMES=manifest, VK_DRIVER_FILES=manifest)
env.pop('VK_INSTANCE_LAYERS', None)
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
    return cond


def run(args, cwd=None):
    out = subprocess.run(args, env=env, capture_output=True, text=True, timeout=120, cwd=cwd)
    check(out.returncode == 0, f'{" ".join(args)} exited with {out.returncode}: {out.stderr[-2000:]}')
    return out


# The driver's own answers, checked against its behaviour. vulkaninfo names structs by the spelling of the
# extension it found them through (VkPhysicalDeviceHostQueryResetFeaturesEXT); the probe by vk.xml's canonical
# name: the aliases of vk.xml map the one to the other.
p = run([probe])
ours = json.loads(p.stdout) if p.returncode == 0 else None
if ours is None:
    print('\n'.join(failures))
    sys.exit(1)
for t in ET.parse(registry).getroot().find('types').findall('type'):
    if t.get('category') == 'struct' and t.get('alias') in ours['features']:
        ours['features'][t.get('name')] = ours['features'][t.get('alias')]

# --summary
s = run([vulkaninfo, '--summary']).stdout
devices = s.split('Devices:', 1)[-1]
names = re.findall(r'deviceName\s*=\s*(.*)', devices)
types = re.findall(r'deviceType\s*=\s*(\S+)', devices)
check(len(names) == 1 and names[0].startswith('tilevk') and types == ['PHYSICAL_DEVICE_TYPE_CPU'],
      f'--summary: devices {names} types {types}')

# -j: the profile JSON is written into the working directory.
with tempfile.TemporaryDirectory() as d:
    run([vulkaninfo, '-j'], cwd=d)
    files = glob.glob(os.path.join(d, '*.json'))
    check(len(files) == 1, f'-j wrote {files}')
    profile = json.load(open(files[0])) if files else {'capabilities': {'device': {}}}
dev = profile['capabilities']['device']

for struct, members in dev.get('features', {}).items():
    if check(struct in ours['features'], f'-j: feature struct {struct} unknown to the probe'):
        for m, v in members.items():
            check(ours['features'][struct].get(m) == v, f'-j: {struct}::{m} = {v}, API says {ours["features"][struct].get(m)}')
check('VkPhysicalDeviceFeatures' in dev.get('features', {}), '-j: no VkPhysicalDeviceFeatures')
check(dev.get('extensions', {}) == ours['extensions'],
      f'-j: extensions {dev.get("extensions")} != API {ours["extensions"]}')


def flag_set(v):
    if isinstance(v, list):
        return set(v)
    return set(x for x in v.split('|') if x)


j_formats = {f: v['VkFormatProperties'] for f, v in dev.get('formats', {}).items()}
# vulkaninfo 1.3.239's -j does not walk the VK_EXT_4444_formats formats (on lavapipe either): the API's answer for them
# is checked by tests/icd ApiBreadth.Formats4444WorkLikeLavapipe instead.
not_walked = {'VK_FORMAT_A4R4G4B4_UNORM_PACK16', 'VK_FORMAT_A4B4G4R4_UNORM_PACK16'}
api_formats = set(ours['formats']) - not_walked
check(set(j_formats) == api_formats,
      f'-j: formats differ: only vulkaninfo {sorted(set(j_formats) - api_formats)}, '
      f'only API {sorted(api_formats - set(j_formats))}')
for f, props in j_formats.items():
    for k in ('linearTilingFeatures', 'optimalTilingFeatures', 'bufferFeatures'):
        if f in ours['formats']:
            check(flag_set(props.get(k, [])) == flag_set(ours['formats'][f][k]), f'-j: {f} {k}')

jp = dev.get('properties', {}).get('VkPhysicalDeviceProperties', {})
# Vulkan 1.3 (icd/meson.build icd_api_minor): in the properties (an encoded number) and in the profile's name for it.
api = jp.get('apiVersion', 0)
check((api >> 22, (api >> 12) & 0x3ff) == (1, 3), f'-j: apiVersion {api >> 22}.{(api >> 12) & 0x3ff}, not 1.3')
for name, prof in profile.get('profiles', {}).items():
    check(prof.get('api-version', '').startswith('1.3.'), f'-j: profile {name} api-version {prof.get("api-version")}')
for k, v in ours['properties'].items():
    got = jp.get(k, jp.get('limits', {}).get(k))
    if isinstance(v, bool):
        got = bool(got)
    check(got == v, f'-j: {k} = {got}, API says {v}')
jq = [q['VkQueueFamilyProperties'] for q in dev.get('queueFamiliesProperties', [])]
check(len(jq) == len(ours['queueFamilies']), f'-j: {len(jq)} queue families')
for a, b in zip(jq, ours['queueFamilies']):
    check(set(a['queueFlags']) == flag_set(b['queueFlags']) and a['queueCount'] == b['queueCount'] and
          a['timestampValidBits'] == b['timestampValidBits'], f'-j: queue family {a} != {b}')

# Text mode: sections "Name:" underlined with = or -, members "\tname = value".
t = run([vulkaninfo, '--text']).stdout
lines = t.splitlines()
sections = {}
for i, line in enumerate(lines[:-1]):
    m = re.fullmatch(r'\s*(Vk\w+):', line)
    if m and re.fullmatch(r'\s*[=-]+', lines[i + 1]):
        body = {}
        for row in lines[i + 2:]:
            if not row.strip():
                break
            mm = re.fullmatch(r'\s+(\w+)\s*=\s*(.*)', row)
            if mm:  # array members ("name: count = 3" and their items) are skipped
                body[mm.group(1)] = mm.group(2).strip()
        sections.setdefault(m.group(1), body)
text_structs = [k for k in sections if k in ours['features']]
check('VkPhysicalDeviceFeatures' in text_structs, 'text: no VkPhysicalDeviceFeatures section')
for struct in text_structs:
    for m, v in sections[struct].items():
        if m in ours['features'][struct]:
            check((v == 'true') == ours['features'][struct][m], f'text: {struct}::{m} = {v}')
    check(set(sections[struct]) == set(ours['features'][struct]), f'text: {struct} members differ')
check(set(text_structs) == set(dev.get('features', {})),
      f'text and -j list different feature structs: {sorted(text_structs)} vs {sorted(dev.get("features", {}))}')
m = re.search(r'^Device Extensions:.*?(?:\n\n|\Z)', t, re.M | re.S)
ext_block = m.group(0) if m else ''
text_ext = {m.group(1): int(m.group(2)) for m in re.finditer(r'(VK_\w+)\s*:\s*extension revision\s*(\d+)', ext_block)}
check(text_ext == ours['extensions'], f'text: device extensions {text_ext} != API {ours["extensions"]}')
limits = sections.get('VkPhysicalDeviceLimits', {})
for k in ('maxBoundDescriptorSets', 'maxColorAttachments', 'maxViewports', 'maxImageDimension2D'):
    check(limits.get(k) == str(ours['properties'][k]), f'text: {k} = {limits.get(k)}, API says {ours["properties"][k]}')

print(f'vulkaninfo: {len(dev.get("features", {}))} feature structs, {len(ours["extensions"])} device extensions, '
      f'{len(j_formats)} formats compared in -j; {len(text_structs)} feature sections in text')
if failures:
    print('FAILED:\n  ' + '\n  '.join(failures[:50]))
    sys.exit(1)
print('vulkaninfo reports what the driver does')
