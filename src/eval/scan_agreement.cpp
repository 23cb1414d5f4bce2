// The GT against the frame's own scan, per object (scan_agreement.hpp).
#include "lidar_sgm/eval/scan_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>


namespace lidar_sgm {
namespace eval {

bool ObjectScanAgreement::offTheScan() const {
  return points >= kScanAgreementMinPoints && medianDifference > kScanAgreementTolerancePx;
}

std::vector<ObjectScanAgreement> scanAgreement(ImageView<const std::int16_t> scan, ImageView<const float> groundTruth,
                                               ImageView<const std::uint8_t> objectMap) {
  if (scan.width != groundTruth.width || scan.height != groundTruth.height || objectMap.width != scan.width ||
      objectMap.height != scan.height) {
    throw std::invalid_argument("scanAgreement: scan, ground truth and object map differ in size");
  }
  std::map<int, std::vector<double>> differences;
  for (int y = 0; y < scan.height; ++y) {
    for (int x = 0; x < scan.width; ++x) {
      const int object = objectMap(x, y);
      const float gt = groundTruth(x, y);
      const std::int16_t d = scan(x, y);
      if (object == 0 || !(gt > 0.0f) || d == kInvalidDisparity) continue;
      differences[object].push_back(static_cast<double>(d) / kDisparityScale - gt);
    }
  }
  std::vector<ObjectScanAgreement> result;
  for (auto& [object, values] : differences) {
    const std::size_t middle = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle), values.end());
    double median = values[middle];
    if (values.size() % 2 == 0) {
      median = 0.5 * (median + *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle)));
    }
    result.push_back({object, static_cast<long>(values.size()), median});
  }
  return result;
}

Image<std::uint8_t> offTheScanPixels(ImageView<const std::uint8_t> objectMap,
                                     const std::vector<ObjectScanAgreement>& agreement) {
  bool off[256] = {};
  bool any = false;
  for (const ObjectScanAgreement& a : agreement) {
    if (a.offTheScan() && a.object > 0 && a.object < 256) off[a.object] = any = true;
  }
  if (!any) return {};
  Image<std::uint8_t> mask(objectMap.width, objectMap.height);
  for (int y = 0; y < objectMap.height; ++y) {
    for (int x = 0; x < objectMap.width; ++x) mask(x, y) = off[objectMap(x, y)] ? 1 : 0;
  }
  return mask;
}

}  // namespace eval
}  // namespace lidar_sgm
