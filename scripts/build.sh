#!/usr/bin/env bash
# Configures and builds (Release) into build/ (or $BUILD_DIR). Extra arguments go to CMake.
# With ccache installed, the compilers run through it (scripts/ccache_env.sh says how).
#   LIDAR_SGM_BUILD_TARGETS="a b"  builds only these targets (default: all)
#   LIDAR_SGM_PHASE_LOG=FILE       appends "configure SECONDS" and "build SECONDS" to FILE
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
source "$root/scripts/ccache_env.sh"
phase() { if [ -n "${LIDAR_SGM_PHASE_LOG:-}" ]; then echo "$1 $2" >> "$LIDAR_SGM_PHASE_LOG"; fi; }

start=$SECONDS
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${lidar_sgm_launcher[@]}" "$@"
phase configure $((SECONDS - start))
start=$SECONDS
targets=()
if [ -n "${LIDAR_SGM_BUILD_TARGETS:-}" ]; then
  read -r -a names <<< "$LIDAR_SGM_BUILD_TARGETS"
  targets=(--target "${names[@]}")
fi
cmake --build "$build_dir" -j"$(nproc)" "${targets[@]}"
phase build $((SECONDS - start))
