#!/usr/bin/env bash
# The two commands of the README.
#   ./tilevk.sh main   conformance subset on tilevk and lavapipe, pixel diff, timings, report/ (index.html, summary.md)
#   ./tilevk.sh test   every test suite (meson test), ending with "N passed, N failed"
# Both install missing Debian packages, configure and build on first use.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${TILEVK_BUILD_DIR:-$here/build}"
cmd="${1:-}"
shift || true

case "$cmd" in
test)
    "$here/tools/bootstrap.sh" "$build"
    exec "$here/tools/run_tests.sh" "$build" "$@"
    ;;
main)
    "$here/tools/bootstrap.sh" "$build"
    exec "$here/tools/run_main.sh" "$build" "$@"
    ;;
*)
    echo "usage: $0 main|test" >&2
    exit 2
    ;;
esac
