#!/usr/bin/env bash
# CI step after ./tilevk.sh test (.ci/run calls both): the project under the sanitizers. Any finding fails the run.
#   1. ASan+UBSan build (build-asan/, also the portable -Dsimd=none build): every meson test but the few named below
#      (each printed as EXCLUDED with its reason).
#   2. The full conformance subset under ASan+UBSan, tilevk (the ASan build's ICD) against lavapipe.
#   3. TSan build (build-tsan/, only the test programs it runs): the tile thread pool and the renderer on it, the
#      swapchain tests (their presentation threads, presenting from another thread), the whole driver under a
#      multi-threaded application (icd_concurrency), the device timeout's timer thread against the renderer and a
#      second device (icd_device_loss) and the object lifetime rules (icd_lifetime), with the TSan build's ICD.
# tools/keep_loaded.cpp is preloaded in the ASan runs so that LeakSanitizer sees and names the libraries the Vulkan
# loader unloads; tools/lsan.supp suppresses only leaks of the validation layer's own. Every other leak, ASan or
# UBSan report or TSan race fails its step. Every step runs; the exit status is non-zero if any step failed,
# and the last line counts the tests: "sanitizers: N passed, N failed".
# TILEVK_JOBS=N limits ninja's parallel jobs; TILEVK_ASAN_BUILD_DIR / TILEVK_TSAN_BUILD_DIR move the build folders.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
asan="${TILEVK_ASAN_BUILD_DIR:-$here/build-asan}"
tsan="${TILEVK_TSAN_BUILD_DIR:-$here/build-tsan}"
lvp_icd=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
jobs=(${TILEVK_JOBS:+-j "$TILEVK_JOBS"})
failed_steps=()
subset_ok=0
subset_bad=0

step() { echo; echo "=== run_sanitizers: $* ($(date -u +%H:%M:%S))"; }

# --- 1. ASan+UBSan build and every meson test ---------------------------------------------------------------------
step "ASan+UBSan build in $asan"
"$here/tools/bootstrap.sh" "$asan" -Db_sanitize=address,undefined -Db_lundef=false -Dbenchmarks=disabled -Dsimd=none
# Without sanitizer flags on purpose: see the file's comment.
c++ -O2 -shared -fPIC -o "$asan/keep_loaded.so" "$here/tools/keep_loaded.cpp"

# verify_asan_link_order=0: keep_loaded.so is preloaded ahead of the ASan runtime; it defines only dlclose, so
# malloc and the other interceptors still resolve to ASan's. exitcode=66: a finding never looks like tilevk-cts's
# "1 = a case failed", which the python tests that drive it accept.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:strict_string_checks=1:verify_asan_link_order=0:exitcode=66"
export LSAN_OPTIONS="suppressions=$here/tools/lsan.supp:print_suppressions=0:exitcode=66"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:exitcode=66"
export LD_PRELOAD="$asan/keep_loaded.so${LD_PRELOAD:+:$LD_PRELOAD}"

all_tests=$(meson test -C "$asan" --list 2>/dev/null | sed -n 's/^.* \/ //p')
[[ -n "$all_tests" ]] || { echo "run_sanitizers: meson test --list found no test in $asan" >&2; exit 1; }
# Excluded from this step, each named in the log with its reason (./tilevk.sh test runs them all, uninstrumented):
#   icd_vulkaninfo, icd_wsi_vkcube: they load the ICD into Debian's vulkaninfo / vkcube, not built with ASan; an
#     instrumented ICD cannot be loaded into an uninstrumented program.
#   cts_tilevk_vs_lavapipe_full: step 2 below is the same run (the full subset, --strict, 2 threads each).
#   cts_validation_full/_spirv15/_spirv16: the same cases and the same driver calls as cts_tilevk_vs_lavapipe_full/
#     _spirv15/_spirv16 with the validation layer added; what they check (the harness's API usage) does not depend
#     on the sanitizers, and under ASan each takes 5-7 minutes.
#   cts_lavapipe_vs_lavapipe: runs no tilevk code (lavapipe against itself checks the harness).
declare -A excluded_why=(
    [icd_vulkaninfo]="it loads the ICD into Debian's vulkaninfo, which is not built with ASan"
    [icd_wsi_vkcube]="it loads the ICD into Debian's vkcube, which is not built with ASan"
    [cts_tilevk_vs_lavapipe_full]="step 2 below runs the same full subset under ASan+UBSan"
    [cts_validation_full]="cts_tilevk_vs_lavapipe_full (step 2) makes the same driver calls under ASan"
    [cts_validation_spirv15]="cts_tilevk_vs_lavapipe_spirv15 makes the same driver calls under ASan"
    [cts_validation_spirv16]="cts_tilevk_vs_lavapipe_spirv16 makes the same driver calls under ASan"
    [cts_lavapipe_vs_lavapipe]="it runs no tilevk code"
)
tests=$all_tests
for t in "${!excluded_why[@]}"; do
    if grep -qx "$t" <<<"$all_tests"; then
        tests=$(grep -vx -e "$t" <<<"$tests")
        echo "run_sanitizers: EXCLUDED $t: ${excluded_why[$t]}; ./tilevk.sh test runs it."
    fi
done
step "ASan+UBSan: $(wc -l <<<"$tests") meson tests"
rm -f "$asan/meson-logs/testlog.json" "$asan/meson-logs/testlog-sanitizers.json"  # never count a stale log
# shellcheck disable=SC2086  # one test name per word
"$here/tools/run_tests.sh" "$asan" --no-rebuild --timeout-multiplier 6 $tests || failed_steps+=("ASan+UBSan meson tests")
cp "$asan/meson-logs/testlog.json" "$asan/meson-logs/testlog-sanitizers.json" 2>/dev/null || true

# --- 2. The full conformance subset on the ASan build --------------------------------------------------------------
step "ASan+UBSan: the full conformance subset, tilevk vs lavapipe"
if (cd "$asan" && VK_ICD_FILENAMES="$asan/tilevk_icd.json:$lvp_icd" TILEVK_THREADS=2 LP_NUM_THREADS=2 \
    ./cts_subset/tilevk-cts --strict); then
    subset_ok=1
else
    subset_bad=1
    failed_steps+=("ASan+UBSan conformance subset")
fi
unset LD_PRELOAD ASAN_OPTIONS LSAN_OPTIONS UBSAN_OPTIONS

# --- 3. TSan: the thread pool, the renderer, the swapchains' presentation threads, a multi-threaded application ---
tsan_tests=(rast_core_threads rast_render icd_wsi_swapchain icd_wsi_x11 icd_concurrency icd_device_loss icd_lifetime)
step "TSan build in $tsan (${tsan_tests[*]})"
[[ -f "$tsan/build.ninja" ]] ||
    meson setup "$tsan" "$here" -Db_sanitize=thread -Db_lundef=false -Dbenchmarks=disabled
ninja -C "$tsan" "${jobs[@]}" tests/rast/core/rast_core_threads_test tests/rast/render/rast_render_test \
    icd/libvulkan_tilevk.so tests/icd/icd_wsi_swapchain_test tests/icd/icd_wsi_x11_test tests/icd/icd_concurrency_test \
    tests/icd/icd_device_loss_test tests/icd/icd_lifetime_test
c++ -O2 -shared -fPIC -o "$tsan/keep_loaded.so" "$here/tools/keep_loaded.cpp"
rm -f "$tsan/meson-logs/testlog.json"
# The swapchain tests load Debian's (uninstrumented) validation layer: tools/tsan.supp ignores the locks and frees
# the layer's own threads make, which TSan cannot see paired; keep_loaded.so keeps the layer mapped (TSan aborts when
# a library named in a called_from_lib suppression is unloaded).
LD_PRELOAD="$tsan/keep_loaded.so" TSAN_OPTIONS="halt_on_error=1 suppressions=$here/tools/tsan.supp" \
    "$here/tools/run_tests.sh" "$tsan" --no-rebuild --timeout-multiplier 6 \
    "${tsan_tests[@]}" || failed_steps+=("TSan tests")

# --- Summary -------------------------------------------------------------------------------------------------------
step "summary"
((${#failed_steps[@]} == 0)) || printf 'run_sanitizers: FAILED: %s\n' "${failed_steps[@]}"
/usr/bin/python3 - "$asan/meson-logs/testlog-sanitizers.json" "$tsan/meson-logs/testlog.json" \
    "$subset_ok" "$subset_bad" "${#failed_steps[@]}" <<'PY'
import json, sys
ok, bad = int(sys.argv[3]), int(sys.argv[4])
for path in sys.argv[1:3]:
    try:
        lines = open(path).read().splitlines()
    except OSError:
        bad += 1  # a step that left no log did not run its tests
        continue
    for line in lines:
        r = json.loads(line)["result"]
        if r in ("OK", "EXPECTEDFAIL"): ok += 1
        else: bad += 1  # SKIP included: nothing is skipped silently here
if bad == 0 and int(sys.argv[5]) != 0: bad = 1  # a failed step always shows
print(f"sanitizers: {ok} passed, {bad} failed")
PY
((${#failed_steps[@]} == 0))
