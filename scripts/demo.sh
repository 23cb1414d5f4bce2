#!/usr/bin/env bash
# Installs dependencies, builds, and runs LiDAR-SGM on a sample frame: stereo-only, LiDAR-only
# and fused, writing KITTI disparity PNGs and color pictures to out/demo/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
out="$root/out/demo"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" -DLIDAR_SGM_BUILD_TESTS=OFF
mkdir -p "$out"
tool="$build_dir/apps/lidar_sgm_disparity"

# Until the project's own synthetic sample lands in data/ (issue 3), the demo uses the KITTI
# frame with a projected LiDAR scan from ../shared/data (read in place, never copied).
sample="${LIDAR_SGM_DATA:-$root/../shared/data}/kitti_stereo_sparse_lidar_disparity_sample"
if [ ! -f "$sample/left.png" ]; then
  echo "demo: no sample frame at $sample (set LIDAR_SGM_DATA to the folder holding it)" >&2
  exit 1
fi
"$tool" "$sample/left.png" "$sample/right.png" "$out/stereo.png" -color "$out/stereo_color.png"
"$tool" "$sample/left.png" "$out/lidar.png" -lidar "$sample/sparse_lidar_disparity.png" -color "$out/lidar_color.png"
"$tool" "$sample/left.png" "$sample/right.png" "$out/fused.png" -lidar "$sample/sparse_lidar_disparity.png" \
  -color "$out/fused_color.png"
echo
echo "Results in $out:"
echo "  stereo.png lidar.png fused.png                  KITTI disparity (uint16, disparity*256, 0 = invalid)"
echo "  stereo_color.png lidar_color.png fused_color.png color pictures (invalid = black)"
