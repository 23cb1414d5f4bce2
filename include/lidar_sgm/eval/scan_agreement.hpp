#pragma once
/// @file scan_agreement.hpp  Does a frame's GT agree with its own LiDAR scan, object by object?
///
/// KITTI 2015's GT on objects (cars) comes from CAD models fitted to accumulated scans; where a
/// model sits off the scan of the frame's own instant, every method that follows the scan is
/// scored wrong on that object, however right it is. The evaluation therefore measures, per object
/// of the object map, the median of (scan disparity - GT disparity) over the object's scan pixels,
/// and gives Table II a second time without the objects whose scan lies NEARER than their GT by
/// more than kScanAgreementTolerancePx: a LiDAR return cannot come from in front of the surface it
/// hit, so there the GT's surface is behind the measured one. A scan FARTHER than its object's GT is
/// not a GT fault: those are the points the LiDAR sees past the object's edge (hidden_lidar.hpp), a
/// failure of the input that a method is rightly scored on. The full table stays the headline.

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace eval {

/// An object whose GT lies more than this behind its own scan (median over its scan pixels) is
/// "off the scan": the background's median |scan - GT| is about 0.01 px on KITTI142's frames.
constexpr double kScanAgreementTolerancePx = 1.0;
/// Fewer scan pixels than this on an object: no verdict (its median would be noise).
constexpr long kScanAgreementMinPoints = 20;

struct ObjectScanAgreement {
  int object = 0;                ///< the object map's id (> 0)
  long points = 0;               ///< scan pixels on the object with a GT disparity
  double medianDifference = 0;   ///< median of scan - GT disparity [px] over them
  /// medianDifference > kScanAgreementTolerancePx (the scan nearer than the GT) with at least
  /// kScanAgreementMinPoints points.
  bool offTheScan() const;
};

/// Every object of `objectMap` with a scan pixel on its GT, ordered by id. `scan` holds the
/// projected scan as x16 disparities (kInvalidDisparity where no point), `groundTruth` disparities
/// in px (0 = none); all three have one size (std::invalid_argument otherwise).
std::vector<ObjectScanAgreement> scanAgreement(ImageView<const std::int16_t> scan, ImageView<const float> groundTruth,
                                               ImageView<const std::uint8_t> objectMap);

/// 1 on the pixels of the objects off their scan, 0 elsewhere (empty when none is).
Image<std::uint8_t> offTheScanPixels(ImageView<const std::uint8_t> objectMap,
                                     const std::vector<ObjectScanAgreement>& agreement);

}  // namespace eval
}  // namespace lidar_sgm
