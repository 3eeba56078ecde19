#!/usr/bin/env bash
# clang-format (the root .clang-format) on the lines a change touches, "the change" as for tools/clang_tidy.sh
# (tools/change_base.sh; TILEVK_TIDY_BASE=REV overrides), uncommitted edits included. Prints the diff clang-format
# would make, ends with "clang-format: clean" or "clang-format: the change needs formatting (git clang-format BASE)"
# and exits 1 in the second case. New files count once they are added to git.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
command -v git-clang-format >/dev/null || { echo "clang-format: not installed (tools/debian-packages.txt)" >&2; exit 2; }
# shellcheck source=tools/change_base.sh
source tools/change_base.sh
base=$(change_base clang-format) || exit 2
# A root commit: every line is the change, compared with the empty tree.
[[ "$base" == "root" ]] && base=$(git hash-object -t tree /dev/null)
echo "clang-format: lines changed since $(git rev-parse --short "$base")"
out=$(git clang-format --diff "$base" 2>&1)
if grep -q '^diff ' <<<"$out"; then
    echo "$out"
    echo "clang-format: the change needs formatting (git clang-format $(git rev-parse --short "$base"))"
    exit 1
fi
echo "clang-format: clean"
