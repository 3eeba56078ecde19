#!/usr/bin/env bash
# Run every meson test suite and close with the plain "N passed, N failed" line.
set -uo pipefail
build="$1"
shift
meson test -C "$build" --print-errorlogs "$@"
rc=$?
log="$build/meson-logs/testlog.json"
if [[ -f "$log" ]]; then
    /usr/bin/python3 - "$log" <<'PY'
import json, sys
ok = bad = skip = 0
for line in open(sys.argv[1]):
    r = json.loads(line)["result"]
    if r in ("OK", "EXPECTEDFAIL"): ok += 1
    elif r == "SKIP": skip += 1
    else: bad += 1
print(f"tests: {ok} passed, {bad} failed, {skip} skipped")
PY
fi
exit $rc
