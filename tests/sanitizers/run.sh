#!/bin/sh
# Runs the test suite of a sanitizer build (cmake -DCLEAVE_SANITIZE=address,undefined) with leak
# detection on and every sanitizer report fatal. Extra arguments go to ctest (e.g. -LE long, -R PEM).
#   tests/sanitizers/run.sh build-asan -j2 -LE long
# Leaks in libraries that are not Cleave's (one-time allocations kept for the life of the process)
# are suppressed by tests/sanitizers/lsan.supp; docs/validation.md, "Sanitizers", has the last run.
set -eu
build=${1:?usage: tests/sanitizers/run.sh BUILD_DIR [ctest arguments]}
shift
here=$(cd "$(dirname "$0")" && pwd)
ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
LSAN_OPTIONS="suppressions=$here/lsan.supp:print_suppressions=0" \
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  exec ctest --test-dir "$build" --output-on-failure "$@"
