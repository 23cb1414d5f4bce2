#pragma once
// A bench frame as plain binary PGM files (core types only, no OpenCV), so that the bench reads
// the same real frame on a machine without lidar_sgm::io (e.g. the GPU machine):
//   DIR/left.pgm     8-bit P5, the left rectified image
//   DIR/right.pgm    8-bit P5, the right rectified image
//   DIR/lidar16.pgm  16-bit P5 (big-endian, as the PGM format says), the projected LiDAR as a
//                    sparse x16 disparity image: 0 = no point
//   DIR/source.txt   optional, one line: where the frame came from (the settings block shows it)

#include <cstdint>
#include <string>

#include "bench_frame.hpp"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace bench {

/// A binary PGM (P5) with maxval < 256. Throws std::runtime_error naming the file and the
/// problem (unreadable, not P5, bad header, 16-bit samples, truncated raster, sample > maxval).
Image<std::uint8_t> readPgm8(const std::string& path);
/// A binary PGM (P5) with 256 <= maxval <= 65535 (2 bytes per sample, most significant first).
Image<std::uint16_t> readPgm16(const std::string& path);

/// Writes `image` as P5 with maxval 255 / 65535. Throws std::runtime_error when the file cannot
/// be written.
void writePgm(const std::string& path, ImageView<const std::uint8_t> image);
void writePgm(const std::string& path, ImageView<const std::uint16_t> image);

/// The frame in `folder` (the layout above). Throws std::runtime_error naming the file for a
/// missing or malformed file, sizes that differ, or a LiDAR disparity above the x16 range
/// (32767 = 2047.9 px).
Frame readPgmFrame(const std::string& folder);

/// Writes `frame` into `folder` (created if missing) in the layout above. Throws
/// std::runtime_error for a pixel with more than one LiDAR point (a PGM holds one value per
/// pixel, and dropping one would change the frame) or when a file cannot be written.
void writePgmFrame(const Frame& frame, const std::string& folder);

}  // namespace bench
}  // namespace lidar_sgm
