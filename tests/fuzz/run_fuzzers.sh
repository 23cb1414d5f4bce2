#!/usr/bin/env bash
# Builds the libFuzzer targets (clang 14, ASan + UBSan, build-fuzz/) and runs each for SECONDS,
# one at a time, from seeds made from data/sample; prints target, execs, execs/s, crashes, hangs.
# Findings (crash-*, oom-*, leak-*, timeout-*) land in build-fuzz/findings/<target>/: each
# becomes a file in tests/data/hostile/ read by the normal test suite (test_hostile_inputs).
# Usage: tests/fuzz/run_fuzzers.sh SECONDS [TARGET...]
# FUZZ_RUNS=N stops a target after N executions if that comes first (e.g. 1000000).
set -euo pipefail

seconds="${1:?usage: run_fuzzers.sh SECONDS [TARGET...]}"
shift
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="$root/build-fuzz"
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_kitti_bin fuzz_pcd fuzz_ply fuzz_kitti_calib fuzz_kitti_raw_calib fuzz_yaml_calib fuzz_png fuzz_arguments)
fi

# The readers need no matcher: the SIMD backend (minutes to compile with ASan) is left out.
source "$root/scripts/ccache_env.sh"
mkdir -p "$build"
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLIDAR_SGM_BUILD_TESTS=OFF \
  -DLIDAR_SGM_WITH_CUDA=OFF -DLIDAR_SGM_WITH_CPU_BACKEND=OFF -DLIDAR_SGM_BUILD_FUZZERS=ON "${lidar_sgm_launcher[@]}" \
  > "$build/fuzz-configure.log" || { cat "$build/fuzz-configure.log"; exit 1; }
cmake --build "$build" -j2 --target "${targets[@]}" > "$build/fuzz-build.log" || { tail -30 "$build/fuzz-build.log"; exit 1; }
python3 "$root/tests/fuzz/make_seeds.py" "$build/seeds"

printf '%-22s %12s %8s %10s %8s %6s\n' target execs seconds execs/s crashes hangs
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  mkdir -p "$corpus" "$findings"
  log="$build/findings/$target.log"
  # -timeout 10: a hang is an input that takes over 10 s; -rss_limit_mb/-malloc_limit_mb 2048:
  # an allocation over 2 GB is a finding (the readers' limits).
  set +e
  runs=()
  if [ -n "${FUZZ_RUNS:-}" ]; then runs=(-runs="$FUZZ_RUNS"); fi
  start=$(date +%s)
  "$build/tests/fuzz/$target" "$corpus" "$build/seeds/$target" -max_total_time="$seconds" "${runs[@]}" -timeout=10 \
    -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/" > "$log" 2>&1
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  elapsed=$(( $(date +%s) - start ))
  rate=$(( execs / (elapsed > 0 ? elapsed : 1) ))
  crashes=$(find "$findings" -name 'crash-*' -o -name 'oom-*' -o -name 'leak-*' | wc -l)
  hangs=$(find "$findings" -name 'timeout-*' | wc -l)
  printf '%-22s %12s %8s %10s %8s %6s\n' "$target" "$execs" "$elapsed" "$rate" "$crashes" "$hangs"
done
