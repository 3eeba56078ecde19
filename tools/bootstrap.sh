#!/usr/bin/env bash
# Make a fresh Debian 12 machine ready: install the missing Debian packages, configure and build.
# Usage: tools/bootstrap.sh [build-dir] [extra meson setup options...]
# TILEVK_JOBS=N limits ninja's parallel jobs (default: ninja's own, cores + 2).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
shift || true

missing=()
while read -r pkg; do
    [[ -z "$pkg" || "$pkg" == \#* ]] && continue
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done <"$here/tools/debian-packages.txt"

if ((${#missing[@]})); then
    echo "tilevk: installing missing Debian packages: ${missing[*]}"
    sudo_cmd=()
    [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
    "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [[ ! -f "$build/build.ninja" ]]; then
    meson setup "$build" "$here" "$@"
fi
ninja -C "$build" ${TILEVK_JOBS:+-j "$TILEVK_JOBS"}
