#!/usr/bin/python3
"""`VK_ICD_FILENAMES=<build>/tilevk_icd.json vulkaninfo --summary` must list exactly one device: a CPU named tilevk.
Usage: vulkaninfo_test.py <vulkaninfo> <tilevk_icd.json>. Exit 77 (meson: skipped) only if vulkaninfo is absent."""
import os
import re
import shutil
import subprocess
import sys

vulkaninfo, manifest = sys.argv[1], sys.argv[2]
if shutil.which(vulkaninfo) is None:
    print(f'SKIP: {vulkaninfo} not found (Debian package vulkan-tools)')
    sys.exit(77)
env = dict(os.environ, VK_ICD_FILENAMES=manifest, VK_DRIVER_FILES=manifest)
out = subprocess.run([vulkaninfo, '--summary'], env=env, capture_output=True, text=True, timeout=50)
print(out.stdout)
print(out.stderr, file=sys.stderr)
if out.returncode != 0:
    print(f'FAIL: vulkaninfo exited with {out.returncode}')
    sys.exit(1)
devices = out.stdout.split('Devices:', 1)[-1]
names = re.findall(r'deviceName\s*=\s*(.*)', devices)
types = re.findall(r'deviceType\s*=\s*(\S+)', devices)
ok = len(names) == 1 and names[0].startswith('tilevk') and types == ['PHYSICAL_DEVICE_TYPE_CPU']
print(f'devices: {names} types: {types}')
sys.exit(0 if ok else 1)
