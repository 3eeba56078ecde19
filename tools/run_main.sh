#!/usr/bin/env bash
# The main job: conformance subset on tilevk against lavapipe, then the report (report/index.html, report/summary.md).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$1"
shift
runner="$build/cts_subset/tilevk-cts"
if [[ ! -x "$runner" ]]; then
    echo "tilevk: the conformance runner is not built yet ($runner); nothing to run" >&2
    exit 1
fi
exec /usr/bin/python3 "$here/cts_subset/report/make_report.py" --build "$build" --out "$here/report" "$@"
