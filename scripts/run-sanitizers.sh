#!/usr/bin/env bash
# Builds tirefe with AddressSanitizer + UndefinedBehaviorSanitizer in build-sanitize/ and
# runs the whole test suite under them (docs/reliability.md). Any report fails the run:
# UBSan is made fatal, leaks are reported by ASan at exit.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${JOBS:-2}"
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTIREFE_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j "$jobs"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
start=$(date +%s)
ctest --test-dir build-sanitize --output-on-failure -j "$jobs" -E '^mpi_'
# OpenMPI's own start-up allocations (its plugins, dlopened and gone at exit) are never
# freed: the MPI tests run without leak detection, every other check on.
ASAN_OPTIONS="${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0}" \
  ctest --test-dir build-sanitize --output-on-failure -j "$jobs" -R '^mpi_'
echo "sanitized suite: $(( $(date +%s) - start )) s"
