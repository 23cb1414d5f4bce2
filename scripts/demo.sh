#!/usr/bin/env bash
# Installs dependencies, builds, and runs lidar_sgm's main job on the bundled sample frame (data/sample): the sparse
# LiDAR scan in, a dense colored point cloud out, fused with the stereo pair and LiDAR-only; plus stereo-only for
# comparison. Everything goes to out/demo/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
out="$root/out/demo"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" -DLIDAR_SGM_BUILD_TESTS=OFF
mkdir -p "$out"
densify="$build_dir/apps/lidar_sgm_densify"
disparity="$build_dir/apps/lidar_sgm_disparity"

# The bundled sample: one synthetic street frame the project renders itself (data/sample/README.md).
sample="$root/data/sample"
scan="$sample/velodyne/000000.bin"
calib="$sample/calib/000000.txt"
left="$sample/image_2/000000.png"
right="$sample/image_3/000000.png"

echo "== Fused LiDAR-SGM (scan + stereo pair) -> dense colored cloud"
"$densify" "$scan" "$out/dense_fused.pcd" -calib "$calib" -left "$left" -right "$right" \
  -disparity "$out/fused.png" -depth "$out/fused_depth.png" -color "$out/fused_color.png" \
  -confidence "$out/fused_confidence.png" -preview "$out/fused_preview.png"
echo
echo "== LiDAR-only SGM (scan, colored from the left image) -> dense colored cloud"
"$densify" "$scan" "$out/dense_lidar.pcd" -calib "$calib" -left "$left" \
  -disparity "$out/lidar.png" -color "$out/lidar_color.png"
echo
echo "== Stereo-only SGM (no LiDAR), for comparison"
"$disparity" "$left" "$right" "$out/stereo.png" -color "$out/stereo_color.png"

echo
echo "Results in $out:"
echo "  dense_fused.pcd dense_lidar.pcd                  dense XYZRGB clouds with a per-point confidence, LiDAR frame (binary PCD;"
echo "                                                   view with pcl_viewer from Debian's pcl-tools, or CloudCompare)"
echo "  fused.png lidar.png stereo.png                   KITTI disparity (uint16, disparity*256, 0 = invalid)"
echo "  fused_color.png lidar_color.png stereo_color.png color pictures of the disparity (invalid = black)"
echo "  fused_depth.png                                  dense depth, KITTI depth-completion format (uint16, metres*256, 0 = none)"
echo "  fused_confidence.png                             confidence per pixel (8-bit: 255 x the probability that it is right)"
echo "  fused_preview.png                                the fused cloud seen from above and behind the rig"
echo "Ground truth for comparison: $sample/disp_gt/000000.png (same format), $sample/depth_gt/000000.png (depth)"
