#pragma once
/// @file encoding.hpp  The frame's data in KITTI's file formats, as bytes and pixels (no file I/O,
/// so the library stays free of OpenCV; lidar_sgm_synth writes them).

#include <cstdint>
#include <string>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/synth/lidar_scan.hpp"
#include "lidar_sgm/synth/render.hpp"

namespace lidar_sgm {
namespace synth {

/// KITTI disparity PNG pixels: round(d * 256), 0 = none; d <= 0 or beyond 255.99 px -> 0.
Image<std::uint16_t> encodeKittiDisparity(ImageView<const float> disparity);

/// KITTI depth PNG pixels: round(z * 256), 0 = none; z <= 0 or beyond 255.99 m -> 0.
Image<std::uint16_t> encodeKittiDepth(ImageView<const float> depth);

/// KITTI velodyne .bin: float32 x, y, z, intensity per point, little-endian.
std::string velodyneBytes(const std::vector<LidarPoint>& points);

/// ITU-R BT.601 luma in integers (as OpenCV's RGB2GRAY): the matcher's input.
Image<std::uint8_t> toGray(const Image<Rgb8>& color);

}  // namespace synth
}  // namespace lidar_sgm
