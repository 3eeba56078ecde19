#!/usr/bin/env bash
# CI step: every test suite again in an ASan+UBSan build (build-asan/), and the thread pool under TSan
# (build-tsan/). Leaks inside lavapipe, LLVM, the Vulkan loader and the validation layer are not ours and are
# suppressed (tools/lsan.supp); everything else fails the run. UBSan findings are fatal.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
asan="${TILEVK_ASAN_BUILD_DIR:-$here/build-asan}"
tsan="${TILEVK_TSAN_BUILD_DIR:-$here/build-tsan}"

# The ASan build is also the portable build (-Dsimd=none): every suite passes without the AVX2/FMA kernels too.
"$here/tools/bootstrap.sh" "$asan" -Db_sanitize=address,undefined -Db_lundef=false -Dbenchmarks=disabled -Dsimd=none
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$here/tools/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# vulkaninfo is not instrumented, so an instrumented ICD cannot be loaded into it: that one test runs in the
# normal build only.
tests=$(meson test -C "$asan" --list 2>/dev/null | sed -n 's/^tilevk:[a-z_]* \/ //p' | grep -v '^icd_vulkaninfo$')
"$here/tools/run_tests.sh" "$asan" --timeout-multiplier 6 $tests

# TSan: only what runs threads of ours (the tile thread pool and the renderer on it) is built and run.
[[ -f "$tsan/build.ninja" ]] || meson setup "$tsan" "$here" -Db_sanitize=thread -Db_lundef=false -Dbenchmarks=disabled
ninja -C "$tsan" tests/rast/core/rast_core_threads_test tests/rast/render/rast_render_test
TSAN_OPTIONS="halt_on_error=1" meson test -C "$tsan" --no-rebuild --print-errorlogs --timeout-multiplier 6 \
    rast_core_threads rast_render
