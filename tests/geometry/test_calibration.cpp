#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/geometry/calibration.hpp"

using lidar_sgm::geometry::StereoCalibration;
using lidar_sgm::test::smallRig;

TEST(StereoCalibration, SmallRigIsValidAndDerivedValuesFollow) {
  const StereoCalibration c = smallRig();
  EXPECT_NO_THROW(c.validate());
  EXPECT_DOUBLE_EQ(c.focalBaseline(), 50.0);  // 100 px * 0.5 m
  EXPECT_TRUE((c.T_lidar_cam() * c.T_cam_lidar).matrix().isIdentity(1e-12));
  const std::string text = lidar_sgm::geometry::describe(c);
  EXPECT_NE(text.find("101x61"), std::string::npos) << text;
  EXPECT_NE(text.find("baseline 0.5 m"), std::string::npos) << text;
}

namespace {
void expectRejected(const std::function<void(StereoCalibration&)>& breakIt, const std::string& mention) {
  StereoCalibration c = smallRig();
  breakIt(c);
  try {
    c.validate();
    ADD_FAILURE() << "accepted; expected a message mentioning '" << mention << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(StereoCalibration, RejectsEachProblemByName) {
  expectRejected([](StereoCalibration& c) { c.width = 0; }, "image size");
  expectRejected([](StereoCalibration& c) { c.height = -5; }, "image size");
  expectRejected([](StereoCalibration& c) { c.K(0, 0) = 0; }, "focal");
  expectRejected([](StereoCalibration& c) { c.K(1, 1) = -100; }, "focal");
  expectRejected([](StereoCalibration& c) { c.K(0, 2) = std::nan(""); }, "non-finite");
  expectRejected([](StereoCalibration& c) { c.K(0, 1) = 0.5; }, "no skew");
  expectRejected([](StereoCalibration& c) { c.K(2, 2) = 2; }, "no skew");
  expectRejected([](StereoCalibration& c) { c.baseline = 0; }, "baseline");
  expectRejected([](StereoCalibration& c) { c.baseline = -0.5; }, "baseline");
  expectRejected([](StereoCalibration& c) { c.baseline = std::numeric_limits<double>::infinity(); }, "baseline");
  expectRejected([](StereoCalibration& c) { c.T_cam_lidar.linear() *= 1.01; }, "not a rotation");
  // A reflection is orthonormal but has det -1.
  expectRejected([](StereoCalibration& c) { c.T_cam_lidar.linear().col(0) *= -1; }, "not a rotation");
  expectRejected([](StereoCalibration& c) { c.T_cam_lidar.translation().x() = std::nan(""); }, "non-finite");
}

TEST(StereoCalibration, ToleratesSevenDigitRotations) {
  // Calibration files print ~7 significant digits: rounding each entry to 1e-7 keeps it valid.
  StereoCalibration c = smallRig();
  Eigen::Matrix3d R = c.T_cam_lidar.linear();
  for (int i = 0; i < 9; ++i) R.data()[i] = std::round(R.data()[i] * 1e7) / 1e7;
  c.T_cam_lidar.linear() = R;
  EXPECT_NO_THROW(c.validate());
}
