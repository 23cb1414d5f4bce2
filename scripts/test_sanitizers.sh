#!/usr/bin/env bash
# The sanitizer step of CI (scripts/test.sh calls it last): a clang 14 build with ASan + UBSan
# (build-sanitize/, or $SANITIZE_BUILD_DIR) of the libraries, the SIMD cpu backend included, then
# under it:
#   1. the `unit` tier and the hostile cases (ctest labels unit and hostile; tests/README.md);
#   2. each fuzz target for $FUZZ_SECONDS (10 by default; a release runs the 1 M-execution
#      campaign of docs/RELIABILITY.md instead), from its seeds, $(nproc) targets at a time;
#   3. each fuzz target once over its files of the regression corpus (tests/data/hostile/).
# Any sanitizer report fails the step. LIDAR_SGM_SKIP_SANITIZERS=1 skips it (local runs).
# LIDAR_SGM_SANITIZE_TIER=all builds everything and runs every test that can run sanitized (the
# e2e tier too: about 20 minutes more here), for a release.
# Appends its phases' times to $LIDAR_SGM_PHASE_LOG when set.
set -euo pipefail

if [ "${LIDAR_SGM_SKIP_SANITIZERS:-0}" = "1" ]; then
  echo "test_sanitizers: skipped (LIDAR_SGM_SKIP_SANITIZERS=1)"
  exit 0
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SANITIZE_BUILD_DIR:-$root/build-sanitize}"
fuzz_seconds="${FUZZ_SECONDS:-10}"
tier="${LIDAR_SGM_SANITIZE_TIER:-unit}"
jobs="$(nproc)"
source "$root/scripts/ccache_env.sh"
phase() { if [ -n "${LIDAR_SGM_PHASE_LOG:-}" ]; then echo "$1 $2" >> "$LIDAR_SGM_PHASE_LOG"; fi; }
elapsed() { printf '%dm%02ds' $(($1 / 60)) $(($1 % 60)); }

# Why the e2e tier is not run here: its tests drive the same library code through the tools on
# whole frames (or through packaging, Python, Open3D and Slurm), and what can break memory in that
# code is reached by the unit tier, stage by stage on small frames with odd sizes and padded strides,
# by the hostile cases (every reader and the tool's checks, on bad input, through
# lidar_sgm_densify) and by the fuzz targets (every reader and the option parser, on arbitrary
# bytes). Label by label:
# - e2e tool runs (densify, disparity, batch, eval, synth CLIs): the Densifier, readers and writers
#   the unit tier runs, on larger inputs; the tools' own parsing is fuzzed (fuzz_arguments) and
#   their bad-input paths are the hostile cases.
# - e2e KITTI runs (the P1 protocol on real frames, the KITTI frames through the PCL class): the
#   matcher, protocols and metrics of the unit tier on whole real frames; sanitized they took 2-4
#   minutes each, for no code the unit tier does not reach.
# - install: builds downstream projects without -fsanitize against the installed libraries; it
#   checks packaging, not memory (and cannot link against sanitized static libraries).
# - slurm: starts Debian's unsanitized munged, slurmctld and slurmd as root to run the batch tool.
# - python: Debian's unsanitized python3 cannot load the ASan runtime after start-up.
# - open3d (test_open3d_frames): the data/sample frame and the README's example through the Open3D
#   front end, whose conversions and densification test_open3d (unit) runs sanitized.
case "$tier" in
  unit)
    targets=(--target lidar_sgm_tests_unit lidar_sgm_densify lidar_sgm_fuzzers)
    labels=(-L '^(unit|hostile)$')
    # Not reached by the sanitized tier: no need to build it.
    skip=(-DLIDAR_SGM_BUILD_PYTHON=OFF)
    ;;
  all)
    targets=()
    labels=(-LE '^(install|slurm|python)$')
    skip=()
    ;;
  *) echo "test_sanitizers: LIDAR_SGM_SANITIZE_TIER is unit or all, not '$tier'" >&2; exit 1 ;;
esac

# Reports stop the program (halt_on_error) with a stack (print_stacktrace) and exit code 86, not
# ASan's default 1: the tools' tests expect exit code 1 for bad input, and a tool that crashed in
# ASan must not pass for one that refused the input. Leaks are findings too (detect_leaks: LSan
# works here, also for the tools the tests start).
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1:exitcode=86"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:exitcode=86"
# Leaks inside third-party libraries only (each explained in the file).
export LSAN_OPTIONS="suppressions=$root/scripts/lsan_suppressions.txt"

# RelWithDebInfo at -O1, with line tables only and with assertions (no -DNDEBUG): -O0 (Debug)
# makes the matcher's tests several times slower under ASan, -O2 costs build time for nothing the
# sanitizers need, and the reports' stacks need files and lines, not variables. The test suites'
# own code at -O0 (LIDAR_SGM_TEST_COMPILE_OPTIONS): it compiles in about 40 % of the time at -O1
# (a PCL-heavy test file: 8 s instead of 19 s), and the work under test is the libraries', still -O1.
start=$SECONDS
mkdir -p "$build"
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DLIDAR_SGM_BUILD_TESTS=ON -DLIDAR_SGM_BUILD_FUZZERS=ON \
  -DLIDAR_SGM_TEST_COMPILE_OPTIONS=-O0 \
  -DLIDAR_SGM_WITH_CUDA=OFF -DLIDAR_SGM_WITH_CPU_BACKEND=ON "${skip[@]}" "${lidar_sgm_launcher[@]}" \
  > "$build/sanitize-configure.log" || { cat "$build/sanitize-configure.log"; exit 1; }
cmake --build "$build" -j"$jobs" "${targets[@]}" > "$build/sanitize-build.log" 2>&1 ||
  { tail -40 "$build/sanitize-build.log"; exit 1; }
build_time=$((SECONDS - start))
phase "sanitizer build" $build_time
echo "test_sanitizers: build $(elapsed $build_time)"

# The tests. ctest starts a process per test; under ASan a suite linked with PCL and OpenCV takes
# 0.6-0.9 s here only to start (some 190 shared libraries through the sanitizer's interceptors),
# more than most tests take.
# So each GoogleTest suite of the selection runs as $jobs processes (GoogleTest's shards), each
# with its share of the suite's tests, and the other tests of the selection (scripts) through
# ctest, all from one pool of $jobs workers (tests/scripts/sanitize_suites.py makes the jobs).
# LIDAR_SGM_SANITIZE_PER_TEST=1 runs every test through ctest instead (a process per test).
# A failure here is reported at the end: the fuzzing still runs.
failed=()
start=$SECONDS
if [ "${LIDAR_SGM_SANITIZE_PER_TEST:-0}" = "1" ]; then
  (cd "$build" && ctest --output-on-failure -j"$jobs" --timeout 1200 "${labels[@]}") || failed+=(ctest)
else
  (cd "$build" && ctest -N "${labels[@]}" --show-only=json-v1) > "$build/sanitize-tests.json"
  python3 "$root/tests/scripts/sanitize_suites.py" "$build/sanitize-tests.json" "$jobs" "$build/sanitize-jobs.txt"
  rm -rf "$build/suite-logs"
  mkdir -p "$build/suite-logs"
  run_job() {  # ctest REGEX | suite EXECUTABLE FOLDER INDEX TOTAL: its log's end on failure
    local kind=$1 log start=$SECONDS
    if [ "$kind" = ctest ]; then
      log="$build/suite-logs/ctest.log"
      if (cd "$build" && ctest --output-on-failure --no-tests=error --timeout 1200 -R "$2" > "$log" 2>&1); then
        echo "test_sanitizers: ctest: $(grep -o '[0-9]*% tests passed.*' "$log"), $((SECONDS - start)) s"
        return 0
      fi
    else
      log="$build/suite-logs/$(basename "$2").$4.log"
      if (cd "$3" && GTEST_SHARD_INDEX=$4 GTEST_TOTAL_SHARDS=$5 timeout 1800 "$2" --gtest_brief=1 > "$log" 2>&1); then
        echo "test_sanitizers: $(basename "$2") (shard $(($4 + 1))/$5):" \
          "$(grep -o 'PASSED  \] [0-9]*' "$log" | grep -o '[0-9]*$') passed," \
          "$( (grep -o 'SKIPPED \] [0-9]*' "$log" || echo 0) | grep -o '[0-9]*$' | head -1) skipped, $((SECONDS - start)) s"
        return 0
      fi
    fi
    echo "test_sanitizers: $* FAILED (log $log):"
    tail -60 "$log"
    return 1
  }
  export -f run_job
  export build
  xargs -a "$build/sanitize-jobs.txt" -P "$jobs" -L 1 bash -c 'run_job "$@"' job || failed+=(tests)
fi
ctest_time=$((SECONDS - start))
phase "sanitizer tests" $ctest_time
echo "test_sanitizers: ctest $(elapsed $ctest_time)"

# Each fuzz target briefly, from the seeds of data/sample, $jobs at a time: -timeout 10 (a hang is
# over 10 s) and 2 GB for one allocation or the whole process. Findings land in
# $build/findings/<target>/; each becomes a regression file in tests/data/hostile/.
fuzz_targets=(fuzz_kitti_bin fuzz_pcd fuzz_ply fuzz_kitti_calib fuzz_kitti_raw_calib fuzz_yaml_calib fuzz_png fuzz_arguments)
limits=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048)
fuzz_one() {
  local target=$1 corpus="$build/corpus/$1" findings="$build/findings/$1" log="$build/findings/$1.log"
  mkdir -p "$corpus" "$findings"
  if "$build/tests/fuzz/$target" "$corpus" "$build/seeds/$target" -max_total_time="$fuzz_seconds" "${limits[@]}" \
       -print_final_stats=1 -artifact_prefix="$findings/" > "$log" 2>&1; then
    local execs
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    echo "test_sanitizers: $target: $execs executions in ${fuzz_seconds} s, no finding"
  else
    echo "test_sanitizers: $target FAILED (log $log, findings in $findings):"
    tail -40 "$log"
    return 1
  fi
}
start=$SECONDS
rm -rf "$build/seeds" "$build/corpus" "$build/findings"
python3 "$root/tests/fuzz/make_seeds.py" "$build/seeds"
declare -A running=()
for target in "${fuzz_targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do sleep 0.2; done
  fuzz_one "$target" &
  running[$!]=$target
done
for pid in "${!running[@]}"; do
  wait "$pid" || failed+=("${running[$pid]}")
done

# The regression corpus under ASan: tests/data/hostile/<format>_*.<ext> goes to fuzz_<format>
# (pcd_*.pcd to fuzz_pcd, ply_*.ply to fuzz_ply, ...). Given files, libFuzzer runs each once.
for target in "${fuzz_targets[@]}"; do
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
fuzz_time=$((SECONDS - start))
phase "fuzzing + corpus" $fuzz_time

echo "test_sanitizers: build $(elapsed $build_time), ctest $(elapsed $ctest_time)," \
  "fuzzing and regression corpus $(elapsed $fuzz_time)"
if [ ${#failed[@]} -ne 0 ]; then
  echo "test_sanitizers: FAILED: ${failed[*]}"
  exit 1
fi
