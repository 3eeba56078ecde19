#!/usr/bin/env bash
# clang-tidy (the checks of the root .clang-tidy) on the C++ files a change touches, with the build's
# compile_commands.json. Offline; TILEVK_JOBS jobs (default 2).
#   tools/clang_tidy.sh [BUILD_DIR]            the files "the change" touches (below), and uncommitted ones
#   TILEVK_TIDY_BASE=REV tools/clang_tidy.sh   ... the files changed since REV instead
#   tools/clang_tidy.sh BUILD_DIR --all        every source file (slow: about 20 min on 2 cores)
# "The change", from git history alone (so a fresh clone gives the same answer every time):
#   - on a branch that main (the local branch, else origin/main) does not contain: everything since the merge base
#     with main, i.e. the whole branch as the lead would merge it;
#   - on main itself (or where no main is known): the last commit, against its first parent; for a merge commit
#     that is everything the merge brought in;
#   - a root commit: every file.
# A changed header is checked through each compiled file that includes it (its findings show through the
# .clang-tidy HeaderFilterRegex). Files below tests/ and bench/ are not checked. Findings are printed sorted by
# file; the script ends with "clang-tidy: N files, N findings" and exits 1 on any finding or clang-tidy failure.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build="${1:-build}"
jobs="${TILEVK_JOBS:-2}"
if [[ ! -f "$build/compile_commands.json" ]]; then
    echo "clang-tidy: $build/compile_commands.json missing (configure the build first)" >&2
    exit 2
fi
command -v clang-tidy >/dev/null || { echo "clang-tidy: not installed (tools/debian-packages.txt)" >&2; exit 2; }
# Files the build compiles, below the tree's source folders.
mapfile -t compiled < <(/usr/bin/python3 - "$build/compile_commands.json" <<'PY'
import json, os, sys
root = os.getcwd()
files = set()
for e in json.load(open(sys.argv[1])):
    rel = os.path.relpath(os.path.normpath(os.path.join(e["directory"], e["file"])), root)
    if rel.split(os.sep)[0] in ("format", "rast", "shader", "icd", "cts_subset", "tools") and rel.endswith(".cpp"):
        files.add(rel)
print("\n".join(sorted(files)))
PY
)

# shellcheck source=tools/change_base.sh
source tools/change_base.sh

if [[ "${2:-}" == "--all" ]]; then
    files=("${compiled[@]}")
    echo "clang-tidy: every compiled file"
else
    base=$(change_base clang-tidy) || exit 2
    if [[ "$base" == "root" ]]; then
        files=("${compiled[@]}")
        echo "clang-tidy: root commit, every compiled file"
    else
        echo "clang-tidy: files changed since $(git rev-parse --short "$base")"
        mapfile -t changed < <( { git diff --name-only --diff-filter=ACMR "$base" -- '*.cpp' '*.h' '*.hpp';
                                  git ls-files --others --exclude-standard -- '*.cpp' '*.h' '*.hpp'; } | sort -u)
        files=()
        for f in "${compiled[@]}"; do
            for c in "${changed[@]}"; do
                if [[ "$f" == "$c" ]] ||
                   { [[ "$c" == *.h || "$c" == *.hpp ]] && grep -q "#include \"\(.*/\)\?$(basename "$c")\"" "$f"; }; then
                    files+=("$f")
                    break
                fi
            done
        done
    fi
fi
if [[ ${#files[@]} -eq 0 ]]; then
    echo "clang-tidy: 0 files, 0 findings"
    exit 0
fi
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
# One log per file, named by the file's position, so the report's order does not depend on which job ends first.
export TIDY_BUILD="$build" TIDY_LOGS="$logs"
for i in "${!files[@]}"; do printf '%05d %s\n' "$i" "${files[$i]}"; done |
    xargs -P "$jobs" -L 1 sh -c \
        'clang-tidy -p "$TIDY_BUILD" --quiet "$2" >"$TIDY_LOGS/$1.log" 2>/dev/null || : >"$TIDY_LOGS/$1.failed"' _
findings=0
failed=0
for i in "${!files[@]}"; do
    n=$(printf '%05d' "$i")
    k=$(grep -cE ': (warning|error): ' "$logs/$n.log")
    findings=$((findings + k))
    if [[ "$k" -gt 0 ]]; then
        grep -E ': (warning|error): ' -A3 "$logs/$n.log" >>"$logs/report"
    elif [[ -f "$logs/$n.failed" ]]; then
        echo "clang-tidy: ${files[$i]}: clang-tidy failed without a finding" >>"$logs/report"
        failed=$((failed + 1))
    fi
done
[[ -f "$logs/report" ]] && head -400 "$logs/report"
summary="clang-tidy: ${#files[@]} files, $findings findings"
[[ "$failed" -gt 0 ]] && summary+=", $failed files where clang-tidy failed"
echo "$summary"
[[ "$findings" -eq 0 && "$failed" -eq 0 ]]
