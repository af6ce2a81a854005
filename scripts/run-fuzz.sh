#!/usr/bin/env bash
# Builds the libFuzzer targets with clang in build-fuzz/ and runs each for SECONDS
# (default 180) on a copy of its seed corpus (tests/fuzz_corpus/<target>/); findings land
# in build-fuzz/findings/ (docs/reliability.md). New interesting inputs stay in
# build-fuzz/corpus/<target>/: copy the few worth keeping into tests/fuzz_corpus/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-180}"
targets=(deck_macro deck_sequence road_profile curve_data property_file road_file checkpoint capi)
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTIREFE_FUZZ=ON \
  -DBUILD_TESTING=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" >/dev/null
cmake --build build-fuzz -j "${JOBS:-2}" --target "${targets[@]/#/fuzz_}"
mkdir -p build-fuzz/findings
status=0
for target in "${targets[@]}"; do
  corpus="build-fuzz/corpus/$target"
  mkdir -p "$corpus"
  cp -n tests/fuzz_corpus/"$target"/* "$corpus"/ 2>/dev/null || true
  echo "== fuzz_$target for $seconds s"
  if ! ASAN_OPTIONS="detect_leaks=1" UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" \
      "build-fuzz/fuzz/fuzz_$target" "$corpus" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
      -rss_limit_mb=2048 -artifact_prefix="build-fuzz/findings/${target}-" -print_final_stats=1 2>&1 |
      tail -n 25; then
    status=1
  fi
done
exit $status
