#!/usr/bin/env bash
# scripts/gpu_check.sh --dry-run, as the GPU check's first half: from a clean prepare folder it
# prepares (without libSGM), configures the GPU machine's tree (every package the GPU machine
# lacks hidden) and builds it with nvcc; the steps that need a GPU must be listed as skipped.
#   gpu_check_dry_run_test.sh BUILD_DIR WORK_DIR
# BUILD_DIR: this build (its lidar_sgm_bench exports the frame). Exit code 77 (skipped) without
# nvcc or without the shared data's KITTI frame.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build_dir=$1
work=$2
nvcc=$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)
[[ -x "$nvcc" ]] || { echo "SKIP: no nvcc"; exit 77; }
data=${LIDAR_SGM_DATA:-$root/../shared/data}
[[ -d "$data/kitti_stereo2015_training_sample" ]] || { echo "SKIP: no $data/kitti_stereo2015_training_sample (the frame the check times)"; exit 77; }

fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work/prep" "$work/out"
mkdir -p "$work"
# Warnings are errors, as in the main build (the CUDA sources are compiled here only).
GPU_CHECK_CMAKE_ARGS="-DLIDAR_SGM_WARNINGS_AS_ERRORS=ON" GPU_CHECK_PREP="$work/prep" GPU_CHECK_BUILD="$work/build" OUT="$work/out" BUILD_DIR="$build_dir" \
  "$root/scripts/gpu_check.sh" --dry-run
rc=$?
summary=$work/out/summary.md
[[ -f "$summary" ]] || fail "no $summary"
cat "$summary"
((rc == 0)) || fail "gpu_check.sh --dry-run exited with $rc"
for step in prepare machine configure build; do
  grep -q "^$step: ok" "$summary" || fail "step $step did not pass"
done
for step in test_backends test_core memcheck racecheck bench_paths4 libsgm_paths4 bench_gated; do
  grep -q "^$step: skipped (dry run)" "$summary" || fail "step $step is not listed as skipped"
done
grep -q "^libsgm_build: skipped (no libSGM" "$summary" || fail "libsgm_build is not skipped without libSGM"
# The GPU machine's tree: CUDA on, and none of the packages it lacks.
configure_log=$work/out/configure.log
grep -q "Eigen not found, building the core only" "$configure_log" || fail "Eigen was not hidden"
grep -q "GoogleTest built from $work/prep/googletest" "$configure_log" || fail "GoogleTest not from the prepare folder"
grep -q "CLI11 from $work/prep/cli11" "$configure_log" || fail "CLI11 not from the prepare folder"
for target in tests/test_backends tests/test_core tests/test_bench bench/lidar_sgm_bench; do
  [[ -x "$work/build/$target" ]] || fail "$target was not built"
done
grep -q "cuda::CudaMatcher" <(nm -C "$work/build/tests/test_backends") || fail "test_backends has no CUDA backend"
[[ -f "$work/prep/MANIFEST.txt" ]] && grep -q "libSGM: *none" "$work/prep/MANIFEST.txt" || fail "MANIFEST does not say libSGM is left out"
echo "PASS: gpu_check.sh --dry-run"
