#!/usr/bin/env bash
# Builds the whole project with AddressSanitizer + UndefinedBehaviorSanitizer (the `asan` preset
# of CMakePresets.json, in build-asan/) and runs the test suite under them (issue 7).
#
# Usage: scripts/sanitize.sh [CTEST_ARGS...]
#   scripts/sanitize.sh                       # the whole suite
#   scripts/sanitize.sh -L robustness         # one label; any ctest filter works
# Environment: SANITIZE_BUILD_JOBS (default 1) and SANITIZE_TEST_JOBS (default 1); the machine's
# cores are shared, and an instrumented build is several times slower and larger than a normal one.
# Exit code: that of the build if it fails, else ctest's (0: every selected test passed clean).
set -euo pipefail

source_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_jobs="${SANITIZE_BUILD_JOBS:-1}"
test_jobs="${SANITIZE_TEST_JOBS:-1}"

cd "${source_dir}"
cmake --preset asan
cmake --build --preset asan -j "${build_jobs}"
# The test preset sets ASAN_OPTIONS/UBSAN_OPTIONS so that any report aborts the test that
# triggered it (UBSan: -fno-sanitize-recover in the build as well).
ctest --preset asan -j "${test_jobs}" "$@"
