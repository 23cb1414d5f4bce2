#include "lidar_sgm/io/kitti_bin.hpp"

#include <cstring>

#include "cloud_file.hpp"
#include "cloud_read_error.hpp"
#include "lidar_sgm/core/huge_page_allocator.hpp"

namespace lidar_sgm {
namespace io {
namespace {

constexpr std::uint64_t kKittiPointBytes = 4 * sizeof(float);  // x, y, z, reflectance

// KITTI files are little-endian whatever the host; assembling the bytes keeps this portable.
float littleEndianFloat(const unsigned char* bytes) {
  const std::uint32_t bits = static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
                             (static_cast<std::uint32_t>(bytes[2]) << 16) |
                             (static_cast<std::uint32_t>(bytes[3]) << 24);
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// A .bin file's size, checked before its bytes are read: whole records, at most `maxPoints`.
void checkKittiBinSize(const std::string& source, std::uint64_t size, std::uint64_t maxPoints) {
  if (size % kKittiPointBytes != 0) {
    detail::failCloudRead(source, "size " + std::to_string(size) + " bytes is not a multiple of " +
                                      std::to_string(kKittiPointBytes) + " (x, y, z, reflectance float32): truncated?");
  }
  if (size / kKittiPointBytes > maxPoints) {
    detail::failCloudRead(source, std::to_string(size / kKittiPointBytes) + " points is more than the limit of " +
                                      std::to_string(maxPoints) + " points per scan");
  }
}

/// The one KITTI .bin decoder, for files and buffers.
std::vector<KittiPoint> decodeKittiBin(const std::string& source, const unsigned char* bytes, std::uint64_t size,
                                       std::uint64_t maxPoints) {
  checkKittiBinSize(source, size, maxPoints);
  std::vector<KittiPoint> points;
  reserveOnHugePages(points, static_cast<std::size_t>(size / kKittiPointBytes));
  points.resize(static_cast<std::size_t>(size / kKittiPointBytes));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const unsigned char* record = bytes + i * kKittiPointBytes;
    KittiPoint& p = points[i];
    p.x = littleEndianFloat(record);
    p.y = littleEndianFloat(record + 4);
    p.z = littleEndianFloat(record + 8);
    p.intensity = littleEndianFloat(record + 12);
  }
  return points;
}

}  // namespace

std::vector<KittiPoint> readKittiScan(const std::string& path, std::uint64_t maxPoints) {
  detail::requireReadableCloudFile(path);
  const std::uint64_t size = detail::cloudFileSize(path);
  checkKittiBinSize(path, size, maxPoints);  // before reading: a huge file is not loaded to be refused
  const std::vector<unsigned char> bytes = detail::readCloudFileBytes(path, size);
  return decodeKittiBin(path, bytes.data(), size, maxPoints);
}

std::vector<KittiPoint> readKittiScanFromBuffer(const void* data, std::size_t size, const std::string& source) {
  if (data == nullptr && size != 0) {
    detail::failCloudRead(source, "null data pointer for " + std::to_string(size) + " bytes");
  }
  return decodeKittiBin(source, static_cast<const unsigned char*>(data), size, kMaxCloudPoints);
}

}  // namespace io
}  // namespace lidar_sgm
