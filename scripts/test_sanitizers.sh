#!/usr/bin/env bash
# The sanitizer step of CI (scripts/test.sh calls it last): one clang 14 build with ASan + UBSan
# (build-sanitize/, or $SANITIZE_BUILD_DIR) of the whole project, the SIMD cpu backend included;
# then the test suite under it, each fuzz target for $FUZZ_SECONDS (30 by default) from its seeds,
# and each fuzz target once over its files of the regression corpus (tests/data/hostile/).
# Any sanitizer report fails the step. LIDAR_SGM_SKIP_SANITIZERS=1 skips it (local runs).
# Prints the wall time of each part.
set -euo pipefail

if [ "${LIDAR_SGM_SKIP_SANITIZERS:-0}" = "1" ]; then
  echo "test_sanitizers: skipped (LIDAR_SGM_SKIP_SANITIZERS=1)"
  exit 0
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SANITIZE_BUILD_DIR:-$root/build-sanitize}"
fuzz_seconds="${FUZZ_SECONDS:-30}"
jobs="$(nproc)"

# Reports stop the program (halt_on_error) with a stack (print_stacktrace) and exit code 86, not
# ASan's default 1: the tools' tests expect exit code 1 for bad input, and a tool that crashed in
# ASan must not pass for one that refused the input. Leaks are findings too (detect_leaks: LSan
# works here, also for the tools the tests start).
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1:exitcode=86"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:exitcode=86"
# Leaks inside third-party libraries only (each explained in the file).
export LSAN_OPTIONS="suppressions=$root/scripts/lsan_suppressions.txt"

elapsed() { printf '%dm%02ds' $(($1 / 60)) $(($1 % 60)); }

# RelWithDebInfo at -O1 and with assertions (no -DNDEBUG): -O0 (Debug) makes the matcher's tests
# several times slower under ASan, -O2 costs build time for nothing the sanitizers need.
start=$SECONDS
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
mkdir -p "$build"
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DLIDAR_SGM_BUILD_TESTS=ON -DLIDAR_SGM_BUILD_FUZZERS=ON \
  -DLIDAR_SGM_WITH_CUDA=OFF -DLIDAR_SGM_WITH_CPU_BACKEND=ON "${launcher[@]}" > "$build/sanitize-configure.log" ||
  { cat "$build/sanitize-configure.log"; exit 1; }
cmake --build "$build" -j"$jobs" > "$build/sanitize-build.log" 2>&1 || { tail -40 "$build/sanitize-build.log"; exit 1; }
build_time=$((SECONDS - start))
echo "test_sanitizers: build $(elapsed $build_time)"

# The whole suite but for the tests that cannot run sanitized:
# - install: tests/install builds downstream projects, without -fsanitize, against the installed
#   (sanitized, static) libraries: they do not link; it checks packaging, not memory.
# - slurm: starts munged, slurmctld and slurmd (unsanitized system daemons, as root) to run
#   scripts/slurm/densify_array.sbatch; the tools it runs are covered by test_batch here.
# - python: the Python extension (where it is built) is loaded into Debian's unsanitized python3,
#   which cannot load an ASan runtime after start-up.
# A failure here is reported at the end: the fuzzing still runs.
failed=()
start=$SECONDS
(cd "$build" && ctest --output-on-failure -j"$jobs" --timeout 1200 -LE '^(install|slurm|python)$') || failed+=(ctest)
ctest_time=$((SECONDS - start))
echo "test_sanitizers: ctest $(elapsed $ctest_time)"

# Each fuzz target briefly, from the seeds of data/sample: -timeout 10 (a hang is over 10 s) and
# 2 GB for one allocation or the whole process (issue 15's targets). Findings land in
# $build/findings/<target>/; each becomes a regression file in tests/data/hostile/.
targets=(fuzz_kitti_bin fuzz_pcd fuzz_ply fuzz_kitti_calib fuzz_kitti_raw_calib fuzz_yaml_calib fuzz_png fuzz_arguments)
limits=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048)
start=$SECONDS
rm -rf "$build/seeds" "$build/corpus"
python3 "$root/tests/fuzz/make_seeds.py" "$build/seeds"
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  mkdir -p "$corpus" "$findings"
  log="$build/findings/$target.log"
  if "$build/tests/fuzz/$target" "$corpus" "$build/seeds/$target" -max_total_time="$fuzz_seconds" "${limits[@]}" \
       -print_final_stats=1 -artifact_prefix="$findings/" > "$log" 2>&1; then
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    echo "test_sanitizers: $target: $execs executions in ${fuzz_seconds} s, no finding"
  else
    echo "test_sanitizers: $target FAILED (log $log, findings in $findings):"
    tail -40 "$log"
    failed+=("$target")
  fi
done
fuzz_time=$((SECONDS - start))
echo "test_sanitizers: fuzzing $(elapsed $fuzz_time)"

# The regression corpus under ASan: tests/data/hostile/<format>_*.<ext> goes to fuzz_<format>
# (pcd_*.pcd to fuzz_pcd, ply_*.ply to fuzz_ply, ...). Given files, libFuzzer runs each once.
start=$SECONDS
for target in "${targets[@]}"; do
  files=()
  for f in "$root/tests/data/hostile/${target#fuzz_}_"*; do
    [ -f "$f" ] && files+=("$f")
  done
  [ ${#files[@]} -eq 0 ] && continue
  log="$build/findings/$target.regression.log"
  if "$build/tests/fuzz/$target" "${limits[@]}" "${files[@]}" > "$log" 2>&1; then
    echo "test_sanitizers: $target: ${#files[@]} regression file(s), no finding"
  else
    echo "test_sanitizers: $target FAILED on the regression corpus (log $log):"
    tail -40 "$log"
    failed+=("$target (regression corpus)")
  fi
done
regression_time=$((SECONDS - start))

echo "test_sanitizers: build $(elapsed $build_time), ctest $(elapsed $ctest_time)," \
  "fuzzing $(elapsed $fuzz_time), regression corpus $(elapsed $regression_time)"
if [ ${#failed[@]} -ne 0 ]; then
  echo "test_sanitizers: FAILED: ${failed[*]}"
  exit 1
fi
