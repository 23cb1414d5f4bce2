#include "lidar_sgm/io/kitti_bin.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>

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

/// The one KITTI .bin record decoder, for files and buffers: `count` records at `bytes`.
void decodeKittiRecords(const unsigned char* bytes, std::size_t count, KittiPoint* out) {
  for (std::size_t i = 0; i < count; ++i) {
    const unsigned char* record = bytes + i * kKittiPointBytes;
    KittiPoint& p = out[i];
    p.x = littleEndianFloat(record);
    p.y = littleEndianFloat(record + 4);
    p.z = littleEndianFloat(record + 8);
    p.intensity = littleEndianFloat(record + 12);
  }
}

std::vector<KittiPoint> decodeKittiBin(const std::string& source, const unsigned char* bytes, std::uint64_t size,
                                       std::uint64_t maxPoints) {
  checkKittiBinSize(source, size, maxPoints);
  std::vector<KittiPoint> points;
  reserveOnHugePages(points, static_cast<std::size_t>(size / kKittiPointBytes));
  points.resize(static_cast<std::size_t>(size / kKittiPointBytes));
  decodeKittiRecords(bytes, points.size(), points.data());
  return points;
}

}  // namespace

std::size_t readKittiScanBlocks(const std::string& path, std::uint64_t maxPoints,
                                const std::function<void(std::size_t points)>& begin,
                                const std::function<void(const KittiPoint* points, std::size_t count)>& block) {
  detail::requireReadableCloudFile(path);
  const std::uint64_t size = detail::cloudFileSize(path);
  checkKittiBinSize(path, size, maxPoints);  // before reading: a huge file is not loaded to be refused
  const auto total = static_cast<std::size_t>(size / kKittiPointBytes);
  begin(total);
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::failCloudRead(path, "cannot open the file");
  // A block of records at a time: the file is never held whole beside the points it becomes.
  constexpr std::size_t kBlockPoints = 4096;
  std::vector<unsigned char> bytes(kBlockPoints * kKittiPointBytes);
  std::vector<KittiPoint> points(kBlockPoints);
  std::uint64_t done = 0;
  while (done < size) {
    const auto want = static_cast<std::streamsize>(std::min<std::uint64_t>(bytes.size(), size - done));
    in.read(reinterpret_cast<char*>(bytes.data()), want);
    if (in.gcount() != want) {
      detail::failCloudRead(path, "read error after " + std::to_string(done + static_cast<std::uint64_t>(in.gcount())) +
                                      " of " + std::to_string(size) + " bytes");
    }
    const auto count = static_cast<std::size_t>(want) / kKittiPointBytes;
    decodeKittiRecords(bytes.data(), count, points.data());
    block(points.data(), count);
    done += static_cast<std::uint64_t>(want);
  }
  return total;
}

std::vector<KittiPoint> readKittiScan(const std::string& path, std::uint64_t maxPoints) {
  std::vector<KittiPoint> points;
  readKittiScanBlocks(
      path, maxPoints, [&points](std::size_t total) { reserveOnHugePages(points, total); },
      [&points](const KittiPoint* block, std::size_t count) { points.insert(points.end(), block, block + count); });
  return points;
}

std::vector<KittiPoint> readKittiScanFromBuffer(const void* data, std::size_t size, const std::string& source) {
  if (data == nullptr && size != 0) {
    detail::failCloudRead(source, "null data pointer for " + std::to_string(size) + " bytes");
  }
  return decodeKittiBin(source, static_cast<const unsigned char*>(data), size, kMaxCloudPoints);
}

}  // namespace io
}  // namespace lidar_sgm
