#!/usr/bin/env bash
# Installs dependencies, builds, and runs LiDAR-SGM on the bundled sample frame (data/sample): stereo-only, LiDAR-only
# and fused, writing KITTI disparity PNGs and color pictures to out/demo/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
out="$root/out/demo"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" -DLIDAR_SGM_BUILD_TESTS=OFF
mkdir -p "$out"
tool="$build_dir/apps/lidar_sgm_disparity"

# The bundled sample: one synthetic street frame the project renders itself (data/sample/README.md).
sample="$root/data/sample"
left="$sample/image_2/000000.png"
right="$sample/image_3/000000.png"
lidar="$sample/lidar_disp/000000.png"
"$tool" "$left" "$right" "$out/stereo.png" -color "$out/stereo_color.png"
"$tool" "$left" "$out/lidar.png" -lidar "$lidar" -color "$out/lidar_color.png"
"$tool" "$left" "$right" "$out/fused.png" -lidar "$lidar" -color "$out/fused_color.png"
echo
echo "Results in $out:"
echo "  stereo.png lidar.png fused.png                  KITTI disparity (uint16, disparity*256, 0 = invalid)"
echo "  stereo_color.png lidar_color.png fused_color.png color pictures (invalid = black)"
echo "Ground truth for comparison: $sample/disp_gt/000000.png (same format)"
