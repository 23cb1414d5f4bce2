#!/usr/bin/env bash
# The README's test command, and CI's (.ci/run): installs dependencies, builds (Release, warnings
# as errors) and runs every test, in two tiers (CTest labels, tests/README.md): `unit`, the
# library stage by stage on small frames, then `e2e`, the tools on whole frames, the evaluation
# protocols, install, Python, Open3D and Slurm. Then the sanitizer step (scripts/test_sanitizers.sh:
# the unit tier, the hostile cases and the fuzz targets under ASan + UBSan). It ends with one line
# per phase, so that every log shows where the time went.
#
#   scripts/test.sh           everything (CI)
#   scripts/test.sh --quick   build the unit tier only and run it: for development, no sanitizers
#
# Tests that need ../shared/data skip (with a message) when it is absent.
# LIDAR_SGM_SKIP_SANITIZERS=1 skips the sanitizer step. ccache is used when installed
# (scripts/ccache_env.sh). The CUDA backend, where nvcc is found, is compiled here for one
# architecture and its PTX ($LIDAR_SGM_TEST_CUDA_ARCHITECTURES, 75 by default: nothing runs it on a
# machine without a GPU, and PTX 75 runs on every newer GPU); scripts/build.sh keeps 75 to 90.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
quick=0
for argument in "$@"; do
  case "$argument" in
    --quick) quick=1 ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "test.sh: unknown argument '$argument' (try --help)" >&2; exit 1 ;;
  esac
done

phases="$(mktemp)"
export LIDAR_SGM_PHASE_LOG="$phases"
total_start=$SECONDS
phase() { echo "$1 $2" >> "$phases"; }  # NAME SECONDS; NAME may hold spaces
report() {
  local status=$? line name seconds
  echo "test.sh: time per phase$([ $status -ne 0 ] && echo " (stopped: exit code $status)")"
  phase total $((SECONDS - total_start))
  while read -r line; do
    seconds=${line##* }
    name=${line% *}
    printf 'test.sh:   %-22s %3dm%02ds\n' "$name" $((seconds / 60)) $((seconds % 60))
  done < "$phases"
  rm -f "$phases"
  return $status
}
trap report EXIT

start=$SECONDS
"$root/scripts/install_deps.sh"
phase install $((SECONDS - start))

# The test suites' own code at -O1 (the library under test keeps Release's -O3): the tests build in
# less time and run the same (tests/CMakeLists.txt, LIDAR_SGM_TEST_COMPILE_OPTIONS).
configure=(-DLIDAR_SGM_WARNINGS_AS_ERRORS=ON -DLIDAR_SGM_BUILD_TESTS=ON
           -DLIDAR_SGM_TEST_COMPILE_OPTIONS="${LIDAR_SGM_TEST_COMPILE_OPTIONS:--O1}"
           -DCMAKE_CUDA_ARCHITECTURES="${LIDAR_SGM_TEST_CUDA_ARCHITECTURES:-75}")
failed=()
if [ $quick -eq 1 ]; then
  LIDAR_SGM_BUILD_TARGETS=lidar_sgm_tests_unit "$root/scripts/build.sh" "${configure[@]}"
  start=$SECONDS
  (cd "$build_dir" && ctest --output-on-failure -j"$(nproc)" --timeout 1200 -L '^unit$') || failed+=(unit)
  phase "tests: unit" $((SECONDS - start))
else
  "$root/scripts/build.sh" "${configure[@]}"
  # Every test is in a tier: one without would run here but nowhere else.
  untiered=$(cd "$build_dir" && ctest -N -LE '^(unit|e2e)$' | sed -n 's/^Total Tests: //p')
  if [ "$untiered" != "0" ]; then
    echo "test.sh: $untiered test(s) carry neither the label unit nor e2e:" >&2
    (cd "$build_dir" && ctest -N -LE '^(unit|e2e)$') >&2
    exit 1
  fi
  for tier in unit e2e; do
    start=$SECONDS
    (cd "$build_dir" && ctest --output-on-failure -j"$(nproc)" --timeout 1200 -L "^$tier\$") || failed+=("$tier")
    phase "tests: $tier" $((SECONDS - start))
  done
  if [ ${#failed[@]} -eq 0 ]; then
    "$root/scripts/test_sanitizers.sh" || failed+=(sanitizers)
  else
    echo "test.sh: the sanitizer step is not run: the ${failed[*]} tier(s) failed"
  fi
fi
if [ ${#failed[@]} -ne 0 ]; then
  echo "test.sh: FAILED: ${failed[*]}"
  exit 1
fi
echo "test.sh: every test passed"
