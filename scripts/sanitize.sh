#!/usr/bin/env bash
# scripts/sanitize.sh [CTEST ARGS...]: builds the CPU test suites (wisp_cpu_tests: loaders, heads,
# the CPU solver and its math, lighting, BSDF, settings and limits) with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-asan/ and runs them (ctest label "cpu"). The first report
# fails the run. The GPU suites are left out: lavapipe is not instrumented and is slow under ASan.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${WISP_ASAN_BUILD_DIR:-$root/build-asan}"
"$root/scripts/build_asan.sh" wisp_cpu_tests
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
cd "$build"
ctest --output-on-failure -L cpu -j "$(nproc 2>/dev/null || echo 2)" "$@"
