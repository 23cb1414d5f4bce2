// Protocol P3: synthetic frames of the project's own generator, exact dense GT.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/synth/encoding.hpp"
#include "lidar_sgm/synth/frame.hpp"
#include "lidar_sgm/synth/rig.hpp"

namespace lidar_sgm {
namespace eval {

namespace {

cv::Mat toMat(const Image<std::uint8_t>& gray) {
  return cv::Mat(gray.height(), gray.width(), CV_8UC1, const_cast<std::uint8_t*>(gray.data())).clone();
}

cv::Mat toBgr(const Image<Rgb8>& color) {
  cv::Mat bgr(color.height(), color.width(), CV_8UC3);
  for (int y = 0; y < color.height(); ++y) {
    for (int x = 0; x < color.width(); ++x) {
      const Rgb8& c = color(x, y);
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(c.b, c.g, c.r);
    }
  }
  return bgr;
}

/// The rig's calibration as a user gets it: the KITTI text lidar_sgm_synth writes, parsed by the
/// same reader as a calibration file.
geometry::StereoCalibration writtenCalibration(const synth::StereoRig& rig, bool thirdCamera) {
  return io::readKittiCalibrationFromString(synth::kittiCalibrationText(rig, thirdCamera), "<synthetic rig>",
                                            rig.width, rig.height);
}

std::string sixDigits(std::uint32_t seed) {
  char buffer[16];
  std::snprintf(buffer, sizeof(buffer), "%06u", static_cast<unsigned>(seed));
  return buffer;
}

}  // namespace

std::string p3DatasetName(const P3Options& o) {
  return std::string("synth_") + (o.rain ? "rain" : "clear") + "_" + std::to_string(o.beams) +
         (o.thirdCamera ? "_3cam" : "");
}

std::vector<EvalFrame> loadP3(const P3Options& options) {
  if (options.frames < 0) throw std::invalid_argument("P3Options: frames must be >= 0");
  std::vector<EvalFrame> frames;
  frames.reserve(static_cast<std::size_t>(options.frames));
  for (int i = 0; i < options.frames; ++i) {
    synth::FrameOptions fo;
    fo.seed = options.firstSeed + static_cast<std::uint32_t>(i);
    fo.weather = options.rain ? synth::Weather::Rain : synth::Weather::Clear;
    fo.beams = options.beams;
    fo.thirdCamera = options.thirdCamera;
    fo.width = options.width;
    fo.height = options.height;
    const synth::Frame rendered = synth::renderFrame(fo);  // validates the options

    EvalFrame frame;
    frame.protocol = "P3";
    frame.dataset = p3DatasetName(options);
    frame.name = sixDigits(fo.seed);
    frame.left = toMat(synth::toGray(rendered.left));
    frame.right = toMat(synth::toGray(rendered.right));
    frame.leftColor = toBgr(rendered.left);
    if (options.thirdCamera) {
      frame.up = toMat(synth::toGray(rendered.up));
      frame.upBaselineRatio = rendered.rig.thirdCameraOffset / rendered.rig.baseline;
    }
    frame.groundTruth = rendered.disparity;
    frame.denseGroundTruth = true;  // the renderer gives every pixel a depth; 0 is a ray that hit nothing (sky)

    const geometry::StereoCalibration calibration = writtenCalibration(rendered.rig, options.thirdCamera);
    std::vector<Eigen::Vector3f> points;
    points.reserve(rendered.lidar.size());
    for (const synth::LidarPoint& p : rendered.lidar) points.emplace_back(p.x, p.y, p.z);
    setLidarInput(frame, geometry::project(points, calibration).lidarPoints());
    frame.focalBaseline = calibration.focalBaseline();
    frame.numDisparities = numDisparitiesFor(maxGroundTruth(frame.groundTruth));
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace eval
}  // namespace lidar_sgm
