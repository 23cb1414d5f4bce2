#!/usr/bin/env bash
# The CUDA backend's check on a GPU machine, in one call from the repository root, after
# scripts/gpu_check_prepare.sh filled .gpu_check/ on a machine with the full toolchain:
#   1. the machine (nvidia-smi, nvcc, cmake, g++)
#   2. configure and build test_backends, test_core, test_bench and lidar_sgm_bench with
#      -DLIDAR_SGM_WITH_CUDA=ON (GoogleTest and CLI11 from .gpu_check/), as the GPU machine has
#      them: every package it lacks (Eigen, OpenCV, PCL, Highway, GoogleTest, CLI11, ...) is hidden
#      from CMake here too, so that the tree built is the same on every machine
#   3. the CUDA tests against cpu_ref, the core's tests, the PGM frame tests
#   4. lidar_sgm_bench on .gpu_check/frame: fused, stereo-only, LiDAR-only at 4 and 8 paths, fused
#      at half scale, 128 disparities, the whole range at every pixel (-no_gated_search: libSGM has
#      no gate)
#   5. libSGM built from .gpu_check/libSGM with nvcc, and timed on the same pair (4 and 8 paths)
#   6. the fused frame as the tools run it, with the LiDAR-gated search (the default)
#   7. compute-sanitizer's memcheck over the CUDA test cases, racecheck over those at one host
#      thread (last: the slowest)
#   8. a table: ours (kernel, with transfers) beside libSGM
# A step that fails is recorded and the later steps still run; the exit code is 1 if any step
# failed. Everything goes to $OUT when it is set, else to out/gpu_check/.
#
#   scripts/gpu_check.sh             on the GPU machine
#   scripts/gpu_check.sh --dry-run   here, without a GPU: prepares .gpu_check/ if it is missing
#                                    (without libSGM), then configures and builds the GPU machine's
#                                    tree with nvcc, and libSGM when .gpu_check/ has it; the steps
#                                    that need a GPU are listed as skipped. CI runs it.
#
# Environment (defaults for the GPU machine):
#   GPU_CHECK_BACKEND=cuda   the bench's backend (cpu: try the script on a machine without a GPU)
#   GPU_CHECK_RUNS=100       timed frames per configuration (after GPU_CHECK_WARMUPS=10)
#   GPU_CHECK_JOBS=16        build jobs (--dry-run: the cores here)
#   GPU_CHECK_BUILD=build-gpu-check          the build folder
#   GPU_CHECK_PREP=.gpu_check                what scripts/gpu_check_prepare.sh filled
#   GPU_CHECK_CUDA_ARCHITECTURES=90          the GPU's architecture (H100/H200: 90)
#   GPU_CHECK_TEST_FILTER='*cuda*:*Cuda*:*Reuse*:*Registry*:*DeviceFrames*'   test_backends' filter
#   GPU_CHECK_RACECHECK_FILTER='*cuda_1threads*:*Reuse*:*DeviceFrames*'    racecheck's (memcheck: the above)
#   GPU_CHECK_CMAKE_ARGS     more configure arguments
#   GPU_CHECK_TOTAL_S=450    the whole script's budget (--dry-run: 3600): a step gets what is left of it
set -uo pipefail

dry_run=0
for argument in "$@"; do
  case "$argument" in
    --dry-run) dry_run=1 ;;
    -h | --help) sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "gpu_check: unknown argument '$argument' (try --help)" >&2; exit 2 ;;
  esac
done

root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1
out=${OUT:-$root/out/gpu_check}
backend=${GPU_CHECK_BACKEND:-cuda}
runs=${GPU_CHECK_RUNS:-100}
warmups=${GPU_CHECK_WARMUPS:-10}
jobs=${GPU_CHECK_JOBS:-$( ((dry_run)) && nproc || echo 16)}
build=${GPU_CHECK_BUILD:-build-gpu-check}
test_filter=${GPU_CHECK_TEST_FILTER:-'*cuda*:*Cuda*:*Reuse*:*Registry*:*DeviceFrames*'}
racecheck_filter=${GPU_CHECK_RACECHECK_FILTER:-'*cuda_1threads*:*Reuse*:*DeviceFrames*'}
prep=${GPU_CHECK_PREP:-$root/.gpu_check}
cuda_architectures=${GPU_CHECK_CUDA_ARCHITECTURES:-90}
frame=$prep/frame
# A dry run compiles on a small machine: more time, nothing of the GPU's.
deadline=$((SECONDS + ${GPU_CHECK_TOTAL_S:-$( ((dry_run)) && echo 3600 || echo 450)}))
mkdir -p "$out"
log=$out/gpu_check.log
: > "$log"
failed=()
summary=()

if ! command -v nvcc >/dev/null && [[ -x /usr/local/cuda/bin/nvcc ]]; then
  export PATH=/usr/local/cuda/bin:$PATH
fi

# step NAME CAP_S COMMAND...: runs COMMAND (a program or a function below) under a timeout (CAP_S
# or what is left of the budget), its output into $out/NAME.log and the main log, its last lines
# on the terminal; records the outcome, never stops the script.
step() {
  local name=$1 cap=$2
  shift 2
  local left=$((deadline - SECONDS))
  local limit=$((cap < left ? cap : left))
  echo "=== $name (limit ${limit}s): $*" | tee -a "$log"
  if ((limit < 5)); then
    echo "--- $name: FAILED (no time left in GPU_CHECK_TOTAL_S)" | tee -a "$log"
    failed+=("$name")
    summary+=("$name: no time left")
    return 1
  fi
  local start=$SECONDS rc
  timeout --kill-after=10 "$limit" bash -c '"$@"' "$name" "$@" > "$out/$name.log" 2>&1
  rc=$?
  cat "$out/$name.log" >> "$log"
  tail -n $((rc == 0 ? 6 : 30)) "$out/$name.log"
  local took=$((SECONDS - start))
  if ((rc == 0)); then
    echo "--- $name: ok (${took}s)" | tee -a "$log"
    summary+=("$name: ok (${took}s)")
  else
    local why="exit $rc"
    ((rc == 124 || rc == 137)) && why="timed out after ${limit}s"
    echo "--- $name: FAILED ($why, ${took}s; see $name.log)" | tee -a "$log"
    failed+=("$name")
    summary+=("$name: FAILED ($why)")
  fi
  return "$rc"
}

machine() {
  if command -v nvidia-smi >/dev/null; then
    nvidia-smi
  else
    echo "no nvidia-smi on this machine"
    [[ "$backend" != cuda ]] || ((dry_run)) || return 1
  fi
  echo
  uname -a
  echo "cores: $(nproc)"
  command -v nvcc >/dev/null && nvcc --version | tail -n 2
  command -v nvcc >/dev/null || ! ((dry_run)) || { echo "no nvcc: a dry run builds with it"; return 1; }
  cmake --version | head -n 1
  "${CXX:-g++}" --version | head -n 1
  command -v ninja >/dev/null && echo "ninja $(ninja --version)"
  git -C "$root" log -1 --format='lidar_sgm %h %s' 2>/dev/null || true
  [[ -d "$prep" ]] && cat "$prep/MANIFEST.txt"
  [[ -d "$prep" ]] || {
    echo "no $prep: run scripts/gpu_check_prepare.sh on a machine with the full toolchain first, and"
    echo "bring $(basename "$prep")/ along with the tree (it is git-ignored: a copy of what git tracks lacks it)"
    return 1
  }
}

# --dry-run: what gpu_check_prepare.sh makes, where it is missing; libSGM only from a source tree
# given in LIBSGM_SRC (this machine may have no network).
prepare() {
  local args=(--no-libsgm)
  [[ -n "${LIBSGM_SRC:-}" ]] && args=("$LIBSGM_SRC")
  GPU_CHECK_PREP="$prep" "$root/scripts/gpu_check_prepare.sh" "${args[@]}"
}

configure() {
  local generator=()
  # Ninja where it is and the build folder is new (a folder keeps the generator it was made with).
  [[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null && generator=(-G Ninja)
  # shellcheck disable=SC2086  # GPU_CHECK_CMAKE_ARGS is a list of arguments
  # The packages the GPU machine lacks, hidden here too: the same tree is built on every machine
  # (GoogleTest and CLI11 then come from $prep).
  local hidden=() package lidar_sgm_launcher=()
  # ccache where it is installed (here, for CI's dry run; the GPU machine has none).
  source "$root/scripts/ccache_env.sh"
  for package in Eigen3 OpenCV PCL yaml-cpp Open3D CLI11 GTest hwy pybind11 nlohmann_json benchmark; do
    hidden+=("-DCMAKE_DISABLE_FIND_PACKAGE_$package=ON")
  done
  # --no-warn-unused-cli: a hidden package the tree never looks for (without Eigen: PCL, OpenCV) is no news.
  cmake --no-warn-unused-cli -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DLIDAR_SGM_BUILD_TESTS=ON \
    -DLIDAR_SGM_WITH_CUDA="${GPU_CHECK_WITH_CUDA:-ON}" -DCMAKE_CUDA_ARCHITECTURES="$cuda_architectures" "${hidden[@]}" "${lidar_sgm_launcher[@]}" \
    -DLIDAR_SGM_GTEST_SOURCE_DIR="$prep/googletest" -DLIDAR_SGM_CLI11_INCLUDE_DIR="$prep/cli11" \
    -DCMAKE_POLICY_VERSION_MINIMUM=3.5 ${GPU_CHECK_CMAKE_ARGS:-}
}

build_targets() {
  # Keep going past a target that fails: the others' steps can still run.
  local keep_going=(-k)
  [[ -f "$build/build.ninja" ]] && keep_going=(-k 0)
  cmake --build "$build" -j "$jobs" --target test_backends test_core test_bench lidar_sgm_bench -- "${keep_going[@]}"
}

cuda_tests() {
  "$build/tests/test_backends" --gtest_filter="$test_filter" | tee "$out/test_backends.raw"
  local rc=${PIPESTATUS[0]}
  ((rc == 0)) || return "$rc"
  # A filter that matched no CUDA test would pass without checking anything.
  if [[ "$backend" == cuda ]] && ! grep -Eq '^\[       OK \] .*[Cc]uda' "$out/test_backends.raw"; then
    echo "no CUDA test ran (is the cuda backend built?)"
    return 1
  fi
}

# compute-sanitizer (the CUDA toolkit's) over the CUDA test cases: memcheck (out-of-bounds and
# misaligned device accesses, leaks) or racecheck (shared-memory hazards between a block's threads).
cuda_sanitizer() {
  local sanitizer
  sanitizer=$(command -v compute-sanitizer || echo /usr/local/cuda/bin/compute-sanitizer)
  [[ -x "$sanitizer" ]] || { echo "no compute-sanitizer in PATH or /usr/local/cuda/bin"; return 1; }
  local extra=() filter=$test_filter
  [[ "$1" == memcheck ]] && extra=(--leak-check full)
  # racecheck is ~3x slower than memcheck (the whole filter: 209 s on an H200): the cases at one
  # host thread (the GPU's work does not depend on it) and the device-frame cases.
  [[ "$1" == racecheck ]] && filter=$racecheck_filter
  "$sanitizer" --tool "$1" "${extra[@]}" --error-exitcode 1 "$build/tests/test_backends" --gtest_filter="$filter" |
    tee "$out/$1.raw"
  local rc=${PIPESTATUS[0]}
  ((rc == 0)) || return "$rc"
  grep -Eq '^\[       OK \] .*[Cc]uda' "$out/$1.raw" || { echo "no CUDA test ran under $1"; return 1; }
}

bench() {
  local paths=$1 configs=$2
  shift 2
  "$build/bench/lidar_sgm_bench" -frame_dir "$frame" -backend "$backend" -num_disparities 128 -paths "$paths" \
    -configs "$configs" -runs "$runs" -warmups "$warmups" "$@"
}

# libSGM's own sources, compiled with nvcc here (its CMake may not work with CMake 4 / CUDA 13).
# libsgm_config.h is generated from its .in as libSGM's CMake would (static, no OpenCV wrapper).
libsgm_build() {
  local src=$build/libsgm/src obj=$build/libsgm/obj
  [[ -f "$prep/libSGM/include/libsgm_config.h.in" ]] || { echo "no libSGM sources in $prep/libSGM"; return 1; }
  command -v nvcc >/dev/null || { echo "no nvcc"; return 1; }
  rm -rf "$build/libsgm"
  mkdir -p "$src" "$obj" && cp -r "$prep/libSGM/." "$src/" || return 1
  local version
  version=$(sed -n 's/.*project(libSGM VERSION \([0-9.]*\)).*/\1/p' "$src/CMakeLists.txt" | head -n 1)
  [[ -n "$version" ]] || version=0.0.0
  IFS=. read -r major minor patch <<< "$version"
  sed -e 's|^#cmakedefine \(.*\)$|/* #undef \1 */|' -e "s/@libSGM_VERSION@/$version/" \
    -e "s/@libSGM_VERSION_MAJOR@/$major/" -e "s/@libSGM_VERSION_MINOR@/${minor:-0}/" \
    -e "s/@libSGM_VERSION_PATCH@/${patch:-0}/" "$src/include/libsgm_config.h.in" > "$src/include/libsgm_config.h" ||
    return 1
  local flags=(-std=c++17 -O3 -arch=sm_90 -I"$src/include")
  # shellcheck disable=SC2016  # the single-quoted script expands in the child shell
  printf '%s\n' "$src"/src/*.cu "$src"/src/*.cpp "$root/scripts/gpu_check/libsgm_bench.cpp" |
    xargs -P "$jobs" -I{} sh -c 'f=$0 o=$1; shift; nvcc "$@" -c "$f" -o "$o/$(basename "$f").o"' {} "$obj" "${flags[@]}" ||
    return 1
  nvcc -arch=sm_90 "$obj"/*.o -o "$build/libsgm_bench"
}

libsgm_run() {
  "$build/libsgm_bench" "$frame" -paths "$1" -runs "$runs" -warmups "$warmups"
}

# The table: one row per bench "result" line, libSGM's time at the same paths beside it.
table() {
  local logs=() name
  for name in bench_paths4 bench_paths8 libsgm_paths4 libsgm_paths8; do
    [[ -f "$out/$name.log" ]] && logs+=("$out/$name.log")
  done
  # awk would read stdin without a file.
  ((${#logs[@]} > 0)) || logs=(/dev/null)
  awk -v backend="$backend" '
    function field(line, key,   n, parts, i, kv) {
      n = split(line, parts, " ")
      for (i = 1; i <= n; ++i) { split(parts[i], kv, "="); if (kv[1] == key) return kv[2] }
      return ""
    }
    /^libsgm paths=/ { lk[field($0, "paths")] = field($0, "median_ms"); lt[field($0, "paths")] = field($0, "with_transfers_ms") }
    /^result config=/ { rows[++n] = $0 }
    END {
      print "| mode | paths | scale | ours kernel ms | ours with transfers ms | libSGM ms | libSGM with transfers ms | ours/libSGM kernel | ours/libSGM with transfers |"
      print "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
      for (i = 1; i <= n; ++i) {
        c = field(rows[i], "config"); p = field(rows[i], "paths"); s = field(rows[i], "scale")
        k = field(rows[i], "kernel_ms"); f = field(rows[i], "frame_ms")
        mode = c == "stereo" ? "stereo-only" : c == "lidar" ? "LiDAR-only" : c == "half" ? "fused" : c
        # libSGM matches stereo at full resolution: beside the fused and stereo-only frames only.
        L = ""; T = ""
        if ((c == "fused" || c == "stereo") && (p in lk)) { L = lk[p]; T = lt[p] }
        comparable = L != "" && L + 0 > 0
        withTransfers = comparable && T + 0 > 0
        # No comparison among the printf arguments: awk reads ">" there as a redirection.
        printf "| %s | %s | %s | %.2f | %.2f | %s | %s | %s | %s |\n", mode, p, s, k, f,
               L == "" ? "-" : sprintf("%.2f", L), T == "" ? "-" : sprintf("%.2f", T),
               comparable ? sprintf("%.2f", k / L) : "-", withTransfers ? sprintf("%.2f", f / T) : "-"
      }
      printf "\nours: lidar_sgm_bench -backend %s, medians; kernel = StageTimings::total() - transfers, with transfers = wall clock around the frame.\n", backend
      print "libSGM: CUDA events around execute (images on the device), and around upload + execute + download; stereo-only, full resolution."
      print "ours/libSGM: < 1 means ours is faster; fused and stereo-only rows against libSGM at the same paths."
    }' "${logs[@]}"
}

# The steps run in child shells (under timeout): they see these.
export root out backend runs warmups jobs build test_filter racecheck_filter prep frame cuda_architectures dry_run
export -f machine prepare configure build_targets cuda_tests cuda_sanitizer bench libsgm_build libsgm_run

# skip NAME: a step that needs the GPU, in a dry run.
skip() {
  echo "--- $1: skipped (dry run: needs a GPU)" | tee -a "$log"
  summary+=("$1: skipped (dry run)")
}
# gpu_step NAME CAP_S COMMAND...: step on the GPU machine, skip in a dry run.
gpu_step() {
  if ((dry_run)); then skip "$1"; else step "$@"; fi
}

if ((dry_run)) && [[ ! -d "$prep" ]]; then
  step prepare 600 prepare
fi
step machine 60 machine
step configure 120 configure
step build "$( ((dry_run)) && echo 1500 || echo 300)" build_targets
gpu_step test_backends 180 cuda_tests
gpu_step test_core 120 "$build/tests/test_core"
gpu_step test_bench 30 "$build/tests/test_bench"
gpu_step bench_paths4 120 bench 4 fused,stereo,lidar,half -no_gated_search
gpu_step bench_paths8 90 bench 8 fused,stereo,lidar -no_gated_search
if [[ -d "$prep/libSGM" ]] || ((!dry_run)); then
  step libsgm_build "$( ((dry_run)) && echo 600 || echo 180)" libsgm_build
else
  echo "--- libsgm_build: skipped (no libSGM in $prep)" | tee -a "$log"
  summary+=("libsgm_build: skipped (no libSGM in $prep)")
fi
gpu_step libsgm_paths4 60 libsgm_run 4
gpu_step libsgm_paths8 60 libsgm_run 8
# The LiDAR-gated search on the fused frame (its own log, outside the table: libSGM has no gate).
gpu_step bench_gated 60 bench 4 fused
# The sanitizers last: they are the slowest steps, and get what is left of the budget after the
# figures.
gpu_step memcheck 90 cuda_sanitizer memcheck
gpu_step racecheck 120 cuda_sanitizer racecheck

{
  echo
  echo "=== results ($backend, frame $(cat "$frame/source.txt" 2>/dev/null || echo '?'))"
  table
  echo
  echo "=== steps"
  printf '%s\n' "${summary[@]}"
} | tee "$out/summary.md" | tee -a "$log"

if ((${#failed[@]} > 0)); then
  echo "gpu_check: ${#failed[@]} step(s) failed: ${failed[*]}" | tee -a "$log"
  exit 1
fi
if ((dry_run)); then
  echo "gpu_check --dry-run: every step that runs without a GPU passed" | tee -a "$log"
else
  echo "gpu_check: every step passed" | tee -a "$log"
fi
