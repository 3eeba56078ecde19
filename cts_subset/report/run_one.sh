#!/usr/bin/env bash
# One complete run of tilevk-cts into a JSON file, surviving driver crashes: if the runner dies inside a case,
# that case is recorded as a Fail and the run resumes after it; if it dies before any case (e.g. the driver breaks
# instance creation), every case is recorded as failing with the runner's last error line.
# usage: run_one.sh RUNNER OUT.json [runner args...]
set -uo pipefail
runner="$1"; out="$2"; shift 2
parts=()
start=()
err="$out.stderr"
: >"$err"
for attempt in $(seq 1 50); do
    part="$out.part$attempt"
    "$runner" --json "$part" "${start[@]}" "$@" 2> >(tee -a "$err" >&2)
    rc=$?
    parts+=("$part")
    if [[ $rc -le 1 ]]; then break; fi
    running=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("running",""))' "$part" 2>/dev/null)
    if [[ -z "$running" ]]; then echo "run_one: runner failed (exit $rc) before any case" >&2; break; fi
    echo "run_one: runner died (exit $rc) in $running; resuming after it" >&2
    start=(--start-after "$running")
done
# The case list for the fallback: --list never touches Vulkan. Keep only the --filter argument.
filter=("--filter" "*")
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do [[ "${args[i]}" == --filter ]] && filter=(--filter "${args[i + 1]}"); done
"$runner" --list "${filter[@]}" >"$out.list" 2>/dev/null
why="tilevk-cts exited with status $rc before running any case: $(tail -n 1 "$err")"
/usr/bin/python3 "$(dirname "$0")/merge_runs.py" --fallback "$out.list" "$why" "$out" "${parts[@]}"
rc=$?
rm -f "${parts[@]}" "$out.list"
exit $rc
