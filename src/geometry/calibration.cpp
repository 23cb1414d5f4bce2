#include "lidar_sgm/geometry/calibration.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace lidar_sgm {
namespace geometry {

namespace {
[[noreturn]] void reject(const std::string& what) {
  throw std::invalid_argument("StereoCalibration: " + what);
}
}  // namespace

void StereoCalibration::validate() const {
  if (width <= 0 || height <= 0) {
    reject("image size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
  }
  if (width > kMaxImageSide || height > kMaxImageSide) {
    reject("image size " + std::to_string(width) + "x" + std::to_string(height) + " is larger than the limit of " +
           std::to_string(kMaxImageSide) + "x" + std::to_string(kMaxImageSide) + " pixels");
  }
  if (!K.allFinite()) reject("K has a non-finite entry");
  if (!(fx() > 0.0) || !(fy() > 0.0)) {
    std::ostringstream s;
    s << "focal lengths must be positive, got fx=" << fx() << " fy=" << fy();
    reject(s.str());
  }
  if (fx() < kMinFocalLength || fx() > kMaxFocalLength || fy() < kMinFocalLength || fy() > kMaxFocalLength) {
    std::ostringstream s;
    s << "focal lengths must lie in [" << kMinFocalLength << ", " << kMaxFocalLength << "] px, got fx=" << fx()
      << " fy=" << fy();
    reject(s.str());
  }
  if (K(0, 1) != 0.0 || K(1, 0) != 0.0 || K(2, 0) != 0.0 || K(2, 1) != 0.0 || K(2, 2) != 1.0) {
    reject("K must be [fx 0 cx; 0 fy cy; 0 0 1] (rectified, no skew)");
  }
  if (!std::isfinite(baseline) || !(baseline > 0.0)) {
    std::ostringstream s;
    s << "baseline must be positive and finite [m], got " << baseline;
    reject(s.str());
  }
  if (baseline < kMinBaseline || baseline > kMaxBaseline) {
    std::ostringstream s;
    s << "baseline must lie in [" << kMinBaseline << ", " << kMaxBaseline << "] m, got " << baseline;
    reject(s.str());
  }
  const Eigen::Matrix4d& T = T_cam_lidar.matrix();
  if (!T.allFinite()) reject("T_cam_lidar has a non-finite entry");
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) reject("T_cam_lidar's last row must be (0 0 0 1)");
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double orthoError = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = R.determinant();
  if (orthoError > kRotationTolerance || std::abs(det - 1.0) > kRotationTolerance) {
    std::ostringstream s;
    s << "T_cam_lidar's rotation is not a rotation (max |R^T R - I| = " << orthoError
      << ", det = " << det << ")";
    reject(s.str());
  }
}

std::string describe(const StereoCalibration& c) {
  std::ostringstream s;
  s.precision(6);
  const Eigen::Vector3d t = c.T_cam_lidar.translation();
  if (c.width == 0 && c.height == 0) {
    s << "size from the images";
  } else {
    s << c.width << "x" << c.height;
  }
  s << ", fx " << c.fx() << ", fy " << c.fy() << ", cx " << c.cx()
    << ", cy " << c.cy() << ", baseline " << c.baseline << " m, t_cam_lidar (" << t.x() << ", "
    << t.y() << ", " << t.z() << ") m";
  return s.str();
}

}  // namespace geometry
}  // namespace lidar_sgm
