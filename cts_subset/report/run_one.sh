#!/usr/bin/env bash
# One complete run of tilevk-cts into a JSON file, surviving driver crashes: if the runner dies inside a case,
# that case is recorded as a Fail with the signal and the run resumes after it.
# usage: run_one.sh RUNNER OUT.json [runner args...]
set -uo pipefail
runner="$1"; out="$2"; shift 2
parts=()
start=()
for attempt in $(seq 1 50); do
    part="$out.part$attempt"
    "$runner" --json "$part" "${start[@]}" "$@"
    rc=$?
    parts+=("$part")
    if [[ $rc -le 1 ]]; then break; fi
    running=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("running",""))' "$part" 2>/dev/null)
    if [[ -z "$running" ]]; then echo "run_one: runner failed (exit $rc) before any case" >&2; break; fi
    echo "run_one: runner died (exit $rc) in $running; resuming after it" >&2
    start=(--start-after "$running")
done
/usr/bin/python3 "$(dirname "$0")/merge_runs.py" "$out" "${parts[@]}"
rc=$?
rm -f "${parts[@]}"
exit $rc
