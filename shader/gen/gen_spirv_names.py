#!/usr/bin/env python3
"""Generates spirv_names.h (names of SPIR-V opcodes and enumerants, for error messages) from the SPIR-V grammar
that SPIRV-Headers installs (spirv.core.grammar.json). Usage: gen_spirv_names.py GRAMMAR OUTPUT"""
import json
import sys

# (function name, operand kind in the grammar)
KINDS = [("capability", "Capability"), ("builtin", "BuiltIn"), ("storage_class", "StorageClass"),
         ("execution_mode", "ExecutionMode"), ("decoration", "Decoration")]


def value(v):
    return int(v, 0) if isinstance(v, str) else int(v)


def function(name, pairs):
    lines = [f"inline const char* {name}(uint32_t v) {{", "    switch (v) {"]
    seen = set()
    for val, text in pairs:
        if val in seen:  # aliases share a value: the first name wins
            continue
        seen.add(val)
        lines.append(f'        case {val}: return "{text}";')
    lines += ['        default: return "unknown";', '    }', '}']
    return "\n".join(lines)


def main():
    grammar = json.load(open(sys.argv[1]))
    parts = [function("opcode", [(value(i["opcode"]), i["opname"]) for i in grammar["instructions"]])]
    kinds = {k["kind"]: k for k in grammar["operand_kinds"]}
    for fname, kind in KINDS:
        parts.append(function(fname, [(value(e["value"]), e["enumerant"]) for e in kinds[kind]["enumerants"]]))
    out = ["// Generated at build time by shader/gen/gen_spirv_names.py from spirv.core.grammar.json. Do not edit.",
           "#pragma once", "#include <cstdint>", "namespace tilevk::shader::names {", ""]
    out += ["\n\n".join(parts), "", "}  // namespace tilevk::shader::names", ""]
    open(sys.argv[2], "w").write("\n".join(out))


if __name__ == "__main__":
    main()
