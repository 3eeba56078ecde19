#!/usr/bin/env bash
# The main job: conformance subset on tilevk against lavapipe with timings, then the report
# (report/index.html, report/summary.md). Exits 0 whenever the report was produced, even if cases fail:
# the report is the product. Non-zero only if no report could be made.
#   TILEVK_CTS_THREADS  rasterizer threads for both drivers (LP_NUM_THREADS = TILEVK_THREADS; default: nproc)
#   TILEVK_CTS_TIMING   timed repetitions of each case's frame on each device (default 5)
#   TILEVK_RAST_METHODS rasterization methods compared once tilevk draws (default "reference bbox hier float")
#   TILEVK_CTS_FILTER   case glob (default all)
#   TILEVK_SWEEP_TRIANGLES triangles per point of bench/rast's stability_sweep, when built (default 1000)
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "$1" && pwd)"
shift
runner="$build/cts_subset/tilevk-cts"
report="$here/cts_subset/report"
out="$here/report"
if [[ ! -x "$runner" ]]; then
    echo "tilevk: the conformance runner is not built ($runner); no report" >&2
    exit 1
fi
threads="${TILEVK_CTS_THREADS:-$(nproc)}"
export LP_NUM_THREADS="$threads" TILEVK_THREADS="$threads"
timing="${TILEVK_CTS_TIMING:-5}"
filter="${TILEVK_CTS_FILTER:-*}"
rm -rf "$out"
mkdir -p "$out"

# Main run: the driver's default method.
unset TILEVK_RAST
"$report/run_one.sh" "$runner" "$out/results-default.json" --timing "$timing" --filter "$filter" \
    --log "$out/cts.log" --junit "$out/junit.xml" --png-dir "$out/failures" "$@"
results=("$out/results-default.json")

# One run per rasterization method, once tilevk draws anything at all (otherwise they would repeat the failures).
draws=$(/usr/bin/python3 -c 'import json,sys; r=json.load(open(sys.argv[1]));
print(int(r["device_found"] and any(c["status"]=="Pass" for c in r["cases"])))' "$out/results-default.json" 2>/dev/null)
if [[ "$draws" == 1 ]]; then
    for m in ${TILEVK_RAST_METHODS:-reference bbox hier float}; do
        TILEVK_RAST="$m" "$report/run_one.sh" "$runner" "$out/results-$m.json" --timing "$timing" --filter "$filter" \
            "$@" >"$out/run-$m.txt" && results+=("$out/results-$m.json")
    done
else
    echo "tilevk: tilevk draws nothing yet; the per-method runs (TILEVK_RAST) are skipped" >&2
fi

# The stability sweep, when bench/rast provides it.
sweep_args=()
sweep="$build/bench/rast/stability_sweep"
if [[ -x "$sweep" ]]; then
    if timeout 900 "$sweep" "$out/stability_sweep.csv" "${TILEVK_SWEEP_TRIANGLES:-1000}" && [[ -s "$out/stability_sweep.csv" ]]; then
        sweep_args=(--stability "$out/stability_sweep.csv")
    fi
fi
/usr/bin/python3 "$report/make_report.py" --out "$out" "${sweep_args[@]}" "${results[@]}"
