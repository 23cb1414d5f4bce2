#!/usr/bin/env bash
# Prepares .gpu_check/ for scripts/gpu_check.sh, on a machine with the full toolchain (OpenCV,
# the shared data), before the one call on a GPU machine, which has no OpenCV, PCL, Eigen,
# GoogleTest or CLI11 and no network:
#   .gpu_check/frame/       KITTI 2015 000000_10 and its simulated 64-beam LiDAR as PGM files
#                           (lidar_sgm_bench -export_frame: the frame the bench times here)
#   .gpu_check/googletest/  GoogleTest's sources (tests/CMakeLists.txt builds them there)
#   .gpu_check/cli11/CLI/   CLI11's headers
#   .gpu_check/libSGM/      libSGM's sources, the GPU SGM we compare with (never committed)
#
#   scripts/gpu_check_prepare.sh [LIBSGM_SOURCE_TREE | --no-libsgm]
#
# The libSGM tree: the argument, else $LIBSGM_SRC, else a clone of github.com/fixstars/libSGM;
# --no-libsgm leaves it out (gpu_check.sh then skips the comparison).
# Then bring .gpu_check/ along with the tree to the GPU machine: it is git-ignored, so a copy of
# what git tracks lacks it.
# Environment: GPU_CHECK_PREP (default .gpu_check: where to write; gpu_check.sh reads the same
# variable), BUILD_DIR (default build; configured if it is not yet), GTEST_SRC (default
# /usr/src/googletest), CLI11_INCLUDE (the folder holding CLI/, default /usr/include),
# LIDAR_SGM_DATA (the shared data, as for the bench).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
dest=${GPU_CHECK_PREP:-.gpu_check}
build=${BUILD_DIR:-build}
gtest_src=${GTEST_SRC:-/usr/src/googletest}
cli11_include=${CLI11_INCLUDE:-/usr/include}
libsgm_src=${1:-${LIBSGM_SRC:-}}
with_libsgm=1
if [[ "$libsgm_src" == --no-libsgm ]]; then
  with_libsgm=0
  libsgm_src=""
fi
max_mb=60

fail() { echo "gpu_check_prepare: $*" >&2; exit 1; }

[[ -f "$gtest_src/CMakeLists.txt" ]] || fail "no GoogleTest sources at $gtest_src (Debian: googletest; or set GTEST_SRC)"
[[ -f "$cli11_include/CLI/CLI.hpp" ]] || fail "no CLI/CLI.hpp under $cli11_include (Debian: libcli11-dev; or set CLI11_INCLUDE)"
if [[ -n "$libsgm_src" ]]; then
  [[ -f "$libsgm_src/include/libsgm.h" && -f "$libsgm_src/src/libsgm.cpp" ]] ||
    fail "$libsgm_src is not a libSGM source tree (no include/libsgm.h or src/libsgm.cpp)"
fi

# The bench, to export the frame (it needs lidar_sgm::io, i.e. OpenCV, here).
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j2 --target lidar_sgm_bench

rm -rf "$dest"
mkdir -p "$dest"
"$build/bench/lidar_sgm_bench" -export_frame "$dest/frame"

cp -r "$gtest_src" "$dest/googletest"
mkdir -p "$dest/cli11"
cp -r "$cli11_include/CLI" "$dest/cli11/CLI"

libsgm_origin="none (--no-libsgm)"
if ((!with_libsgm)); then
  :
elif [[ -n "$libsgm_src" ]]; then
  mkdir -p "$dest/libSGM"
  tar -C "$libsgm_src" --exclude=.git -cf - . | tar -C "$dest/libSGM" -xf -
  libsgm_origin="copied from $libsgm_src"
  if git -C "$libsgm_src" rev-parse HEAD >/dev/null 2>&1; then
    libsgm_origin+=" at $(git -C "$libsgm_src" rev-parse HEAD)"
  fi
else
  echo "no libSGM tree given (argument or LIBSGM_SRC): cloning github.com/fixstars/libSGM"
  git clone --depth 1 https://github.com/fixstars/libSGM "$dest/libSGM" ||
    fail "cannot clone libSGM; give a source tree as the argument or in LIBSGM_SRC"
  libsgm_origin="cloned from https://github.com/fixstars/libSGM at $(git -C "$dest/libSGM" rev-parse HEAD)"
  rm -rf "$dest/libSGM/.git"
fi

{
  echo "prepared by scripts/gpu_check_prepare.sh on $(date -u '+%Y-%m-%d %H:%M UTC') from $(git rev-parse --short HEAD)"
  echo "frame:      $(cat "$dest/frame/source.txt")"
  echo "googletest: $gtest_src"
  echo "cli11:      $cli11_include/CLI"
  echo "libSGM:     $libsgm_origin"
} > "$dest/MANIFEST.txt"

[[ "$dest" != .gpu_check ]] || grep -qxF '/.gpu_check/' .gitignore || echo '/.gpu_check/' >> .gitignore

cat "$dest/MANIFEST.txt"
size_kb=$(du -sk "$dest" | cut -f1)
echo "$dest: $((size_kb / 1024)) MB ($size_kb KiB)"
((size_kb < max_mb * 1024)) || fail "$dest is $((size_kb / 1024)) MB, above the $max_mb MB it must stay under"
echo "next, on a GPU machine, from the repository root with $dest in place: scripts/gpu_check.sh"
