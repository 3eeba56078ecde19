#!/usr/bin/env python3
"""The AVX2/FMA build of the kernels must not leak code into the portable path.

An inline function or template that a translation unit compiled with -mavx2 emits out of line is a weak symbol;
the linker keeps one copy of each, possibly that one, and a portable caller on a CPU without AVX2 would then run
AVX2 instructions. So the AVX2 archive may define, besides local symbols, only its own entry points (namespace
isa_avx2) and unique read-only data (constant tables, the same bytes in every build).

usage: isa_symbols.py NM ARCHIVE
"""
import subprocess
import sys

nm, archive = sys.argv[1], sys.argv[2]
out = subprocess.run([nm, "-C", "--defined-only", archive], check=True, capture_output=True, text=True).stdout
bad, entry_points = [], 0
for line in out.splitlines():
    parts = line.split(" ", 2)
    if len(parts) != 3:
        continue  # archive member headers and blank lines
    kind, name = parts[1], parts[2]
    if kind.islower() and kind not in "uvw":
        continue  # local
    if kind == "u" and not name.endswith(")"):
        continue  # unique data object
    if kind == "T" and "::isa_avx2::" in name:
        entry_points += 1
        continue
    bad.append(f"{kind} {name}")
if bad:
    print(f"{archive}: {len(bad)} symbols the portable path could bind to:")
    for b in bad[:50]:
        print("  " + b)
    sys.exit(1)
if entry_points == 0:
    print(f"{archive}: no isa_avx2 entry points (wrong archive?)")
    sys.exit(1)
print(f"{archive}: {entry_points} isa_avx2 entry points, nothing else global")
