#!/usr/bin/env bash
# The main job: conformance subset on tilevk against lavapipe with timings, then the report
# (report/index.html, report/summary.md). Exits 0 whenever the report was produced, even if cases fail:
# the report is the product. Non-zero only if no report could be made.
#   TILEVK_CTS_THREADS  rasterizer threads for both drivers (LP_NUM_THREADS = TILEVK_THREADS; default: nproc)
#   TILEVK_CTS_TIMING   timed repetitions of each case's frame on each device (default 5)
#   TILEVK_RAST_METHODS rasterization methods compared once tilevk draws (default "reference bbox hier float")
#   TILEVK_CTS_FILTER   case glob (default all)
#   TILEVK_SWEEP_TRIANGLES triangles per point of bench/rast's stability_sweep, when built (default 1000)
#   TILEVK_FRAME_ROUNDS, TILEVK_FRAME_FRAMES, TILEVK_FRAME_SCENES  the frame benchmark's rounds (default 3), timed
#                       frames per process (default 5) and scene list (default: bench/frame/run_frame_bench.py's)
#   TILEVK_FUZZ_MINUTES time for the day's fuzzing window (tilevk-cts --fuzz; default 10, 0 skips it)
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
# The frame benchmark (whole frames, tilevk and lavapipe alternating): the report opens with its table.
frame_args=()
frame_bench="$build/bench/frame/tilevk-frame-bench"
if [[ -x "$frame_bench" ]]; then
    scenes_arg=()
    [[ -n "${TILEVK_FRAME_SCENES:-}" ]] && scenes_arg=(--scenes "$TILEVK_FRAME_SCENES")
    if /usr/bin/python3 "$here/bench/frame/run_frame_bench.py" --build "$build" --out "$out/frame_bench.json" \
        --threads "$threads" --rounds "${TILEVK_FRAME_ROUNDS:-3}" --frames "${TILEVK_FRAME_FRAMES:-5}" \
        "${scenes_arg[@]}" >"$out/frame_bench.txt" 2>&1 && [[ -s "$out/frame_bench.json" ]]; then
        frame_args=(--frames "$out/frame_bench.json")
    else
        echo "tilevk: the frame benchmark failed (see $out/frame_bench.txt); the report has no frame table" >&2
    fi
fi
/usr/bin/python3 "$report/make_report.py" --out "$out" "${frame_args[@]}" "${sweep_args[@]}" "${results[@]}"

# Fuzzing that keeps running: a fresh window of seeds every run (the start seed comes from the date and is printed),
# failures minimised with the commands that reproduce them (report/fuzz.txt, report/fuzz-failures.txt).
fuzz_minutes="${TILEVK_FUZZ_MINUTES:-10}"
if [[ "$fuzz_minutes" != 0 ]]; then
    spirv_seed=$(( $(date -u +%s) / 86400 * 10000 ))
    {
        echo "## Fuzzing (tilevk-cts --fuzz $fuzz_minutes, TILEVK_FUZZ_SPIRV_SEED=$spirv_seed)"
        "$runner" --fuzz "$fuzz_minutes" --fuzz-log "$out/fuzz-failures.txt" 2>/dev/null | grep -v '^fuzz: spirv seed'
        if [[ -x "$build/tests/shader/shader_fuzz_test" ]]; then
            TILEVK_FUZZ_SPIRV_SEED="$spirv_seed" timeout 900 "$build/tests/shader/shader_fuzz_test" 2>&1 |
                grep -E '^fuzz:|PASSED|FAILED'
        fi
    } >"$out/fuzz.txt" 2>&1
    { echo; cat "$out/fuzz.txt"; } >>"$out/summary.md"
fi
