#!/usr/bin/env bash
# Sets up (packages, build) and runs the whole test suite through ctest.
# usage: scripts/test.sh [--sanitize]   (--sanitize: AddressSanitizer + UBSan build in build-sanitize/)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh "$@"
if [ "${1:-}" = "--sanitize" ]; then
  # The installed-package test links the instrumented static libraries into an uninstrumented program.
  export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 LSAN_OPTIONS=suppressions=$PWD/scripts/lsan_suppressions.txt
  ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -E '^package\.'
else
  ctest --test-dir build --output-on-failure -j "$(nproc)"
fi
