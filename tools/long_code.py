#!/usr/bin/env python3
"""Functions over 150 lines and files over 800 lines in tilevk's non-test code (everything git tracks outside
tests/), each marked 'justified' when a comment says why it stays long.

  tools/long_code.py            the list; exit 0
  tools/long_code.py --check    the same, exit 1 when an entry is not justified (for CI or a reviewer)

A function is justified by a comment in the block right above it that contains "over 150 lines"; a file by a
comment in its first 30 lines that contains "over 800 lines". Lengths count every line from the one that opens
the signature to the closing brace, comments and blank lines included (what a reader scrolls through).

Functions are found by their braces, without a compiler: after comments, strings and preprocessor lines are
blanked, a '{' opens a function when it is at namespace or class level and follows ')' (optionally with
const/noexcept/override/final, a trailing return type or a constructor's initializer list). Lambdas and local
classes count inside the function that holds them. Deterministic and offline; about a second for the tree.
"""
import os
import re
import subprocess
import sys

FUNCTION_LIMIT = 150
FILE_LIMIT = 800
SOURCE_SUFFIXES = (".cpp", ".h", ".hpp", ".cc", ".inc")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def tracked_sources():
    out = subprocess.run(["git", "-C", ROOT, "ls-files"], capture_output=True, text=True, check=True).stdout
    return [f for f in out.split("\n") if f.endswith(SOURCE_SUFFIXES) and not f.startswith("tests/")]


def blank_non_code(text):
    """Comments, string/char literals and preprocessor lines replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            # A preprocessor directive, with its continuation lines.
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        if c == "/" and text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if c == "/" and text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        if c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(]*)\(', text[i:])
            if m:
                end = text.find(")" + m.group(1) + '"', i)
                end = n if end < 0 else end + len(m.group(1)) + 2
                out.append(re.sub(r"[^\n]", " ", text[i:end]))
                i = end
                continue
        if c in "\"'":
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
            continue
        out.append(c)
        at_line_start = c == "\n" or (at_line_start and c in " \t")
        i += 1
    return "".join(out)


SCOPE_KEYWORDS = re.compile(r"\b(namespace|class|struct|union|enum)\b[^;{}()]*$")
# What may stand between a function's ')' and its '{'.
AFTER_PARAMS = re.compile(
    r"\)\s*(const|noexcept(\s*\([^()]*\))?|override|final|mutable|volatile|&|&&|\s)*"
    r"(->\s*[\w:<>,\s*&]+)?\s*(:\s*[\s\S]*)?$")


def functions(code):
    """(first line, last line, name) of each function body at namespace or class level; 1-based lines."""
    found = []
    stack = []  # one entry per open '{': 'scope' (namespace/class/...), 'function' or 'block'
    line = 1
    last_stop = 0  # index after the last ';', '{' or '}' at this level: where a declaration starts
    start_of = {}
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
        elif c == "{":
            head = code[last_stop:i]
            in_function = any(kind == "function" for kind, _ in stack)
            if in_function:
                stack.append(("block", None))
            elif SCOPE_KEYWORDS.search(head) and "(" not in head.split("{")[-1].split("=")[0][-200:]:
                stack.append(("scope", None))
            elif AFTER_PARAMS.search(head.rstrip()) or re.search(r"\)\s*(:|$)", head.rstrip()):
                m = re.search(r"([~\w:]+(?:<[^<>]*>)?|operator\s*[^\s(]+)\s*\(", head)
                name = m.group(1) if m else "?"
                sig_line = line - head.rstrip().count("\n") + (len(head) - len(head.lstrip())) * 0
                # The signature starts at the first non-blank line of the declaration.
                lead = head[: len(head) - len(head.lstrip())]
                sig_line = line - head.count("\n") + lead.count("\n")
                stack.append(("function", (sig_line, name)))
            else:
                stack.append(("block", None))  # an initializer, an enum body, an array
            last_stop = i + 1
        elif c == "}":
            if stack:
                kind, info = stack.pop()
                if kind == "function":
                    found.append((info[0], line, info[1]))
            last_stop = i + 1
        elif c == ";":
            last_stop = i + 1
    return found


def justified_function(lines, first):
    """True when the comment block right above line `first` (1-based) says 'over 150 lines'."""
    k = first - 2
    while k >= 0 and lines[k].strip().startswith(("template", "[[", "inline", "static")):
        k -= 1
    block = []
    while k >= 0 and lines[k].strip().startswith("//"):
        block.append(lines[k])
        k -= 1
    return "over %d lines" % FUNCTION_LIMIT in " ".join(l.strip("/ ") for l in block)


def main():
    check = "--check" in sys.argv[1:]
    rows, unjustified = [], 0
    for path in sorted(tracked_sources()):
        with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as f:
            text = f.read()
        lines = text.split("\n")
        nlines = len(lines) - (1 if text.endswith("\n") else 0)
        if nlines > FILE_LIMIT:
            ok = any("over %d lines" % FILE_LIMIT in l for l in lines[:30])
            rows.append((nlines, "file", path, "", ok))
        for first, last, name in functions(blank_non_code(text)):
            length = last - first + 1
            if length > FUNCTION_LIMIT:
                rows.append((length, "function", "%s:%d" % (path, first), name, justified_function(lines, first)))
    for length, kind, where, name, ok in sorted(rows, key=lambda r: (r[1], -r[0], r[2])):
        unjustified += not ok
        print("%-8s %5d  %-9s %s %s" % (kind, length, "justified" if ok else "-", where, name))
    print("long_code: %d functions over %d lines, %d files over %d lines, %d not justified" %
          (sum(r[1] == "function" for r in rows), FUNCTION_LIMIT, sum(r[1] == "file" for r in rows), FILE_LIMIT,
           unjustified))
    return 1 if check and unjustified else 0


if __name__ == "__main__":
    sys.exit(main())
