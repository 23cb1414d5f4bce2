#include "lidar_sgm/io/cloud_preview.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "lidar_sgm/io/color_map.hpp"

namespace lidar_sgm {
namespace io {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Points nearer to the virtual camera than this [m] are not drawn (no division blow-up).
constexpr float kNearPlane = 0.5f;
/// floor(x) = int(x + offset) - offset for x > -offset (the splat loop's u, v are > -64).
constexpr int kFloorOffsetInt = 128;
constexpr float kFloorOffset = 128.0f;
constexpr double kGridStep = 10.0;   ///< [m]
constexpr double kLabelStep = 20.0;  ///< [m]
const cv::Vec3b kBackground(24, 20, 18);
const cv::Scalar kGridColor(62, 58, 54);
const cv::Scalar kLabelColor(170, 170, 170);
const cv::Scalar kRigColor(255, 255, 255);

/// The virtual pinhole camera: rows of R are its axes in the rig frame (x right; z pitched down
/// by theta from the rig's z, so y = z x x), p' = R (p - C).
struct PreviewCamera {
  explicit PreviewCamera(const CloudPreviewOptions& o) {
    const double pitch = o.pitchDeg * kPi / 180.0;
    const double s = std::sin(pitch);
    const double c = std::cos(pitch);
    R << 1.0, 0.0, 0.0,  //
        0.0, c, -s,      //
        0.0, s, c;
    center = Eigen::Vector3d(0.0, -o.cameraHeight, -o.cameraBehind);
    f = 0.5 * o.width / std::tan(0.5 * o.fieldOfViewDeg * kPi / 180.0);
    cx = 0.5 * o.width;
    cy = 0.5 * o.height;
  }
  /// (u, v, z'): the pixel coordinates (floor gives the pixel) and the depth in this camera.
  Eigen::Vector3d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = R * (p - center);
    return {f * q.x() / q.z() + cx, f * q.y() / q.z() + cy, q.z()};
  }
  Eigen::Matrix3d R;
  Eigen::Vector3d center;
  double f = 0.0;
  double cx = 0.0;
  double cy = 0.0;
};

cv::Point toPixel(const Eigen::Vector3d& uvz) {
  return {static_cast<int>(std::floor(uvz.x())), static_cast<int>(std::floor(uvz.y()))};
}

/// A ground segment, drawn only when both ends are in front of the camera (the ground is a
/// plane, so the segment stays a straight line on screen).
void groundLine(cv::Mat& image, const PreviewCamera& camera, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d pa = camera.project(a);
  const Eigen::Vector3d pb = camera.project(b);
  if (pa.z() < kNearPlane || pb.z() < kNearPlane) return;
  cv::line(image, toPixel(pa), toPixel(pb), kGridColor, 1, cv::LINE_8);
}

/// Lines every 10 m across and along the ground from the rig to maxDepth, so a reader sees scale.
void drawGrid(cv::Mat& image, const PreviewCamera& camera, const CloudPreviewOptions& o) {
  const double g = o.groundBelowCamera;
  const double zMax = std::floor(o.maxDepth / kGridStep) * kGridStep;
  const double xMax = zMax;
  for (double z = 0.0; z <= zMax; z += kGridStep) groundLine(image, camera, {-xMax, g, z}, {xMax, g, z});
  for (double x = -xMax; x <= xMax; x += kGridStep) groundLine(image, camera, {x, g, 0.0}, {x, g, zMax});
}

/// "20 m", "40 m", ... at the left edge, on the row of that grid line (no roll: the ground's
/// cross lines are horizontal on screen), over the points so they stay legible.
void drawGridLabels(cv::Mat& image, const PreviewCamera& camera, const CloudPreviewOptions& o) {
  for (double z = kLabelStep; z <= o.maxDepth; z += kLabelStep) {
    const Eigen::Vector3d p = camera.project({0.0, o.groundBelowCamera, z});
    if (p.z() < kNearPlane || p.y() < 0.0 || p.y() >= o.height) continue;
    char text[16];
    std::snprintf(text, sizeof(text), "%.0f m", z);
    cv::putText(image, text, {4, toPixel(p).y - 3}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kLabelColor, 1, cv::LINE_8);
  }
}

/// A triangle on the ground under the rig camera, 2 m wide, pointing forward.
void drawRig(cv::Mat& image, const PreviewCamera& camera, const CloudPreviewOptions& o) {
  const double g = o.groundBelowCamera;
  const std::array<Eigen::Vector3d, 3> corners{
      Eigen::Vector3d(-1.0, g, -2.0), Eigen::Vector3d(1.0, g, -2.0), Eigen::Vector3d(0.0, g, 1.5)};
  std::array<cv::Point, 3> pixels;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector3d p = camera.project(corners[i]);
    if (p.z() < kNearPlane) return;
    pixels[i] = toPixel(p);
  }
  cv::fillConvexPoly(image, pixels.data(), static_cast<int>(pixels.size()), kRigColor, cv::LINE_8);
}

void requireFinite(double value, const char* name) {
  if (!std::isfinite(value)) throw std::invalid_argument(std::string("cloud preview: ") + name + " must be finite");
}

}  // namespace

void validate(const CloudPreviewOptions& o) {
  constexpr int kMaxSide = 8192;
  if (o.width < 16 || o.height < 16 || o.width > kMaxSide || o.height > kMaxSide) {
    throw std::invalid_argument("cloud preview: the picture size " + std::to_string(o.width) + "x" +
                                std::to_string(o.height) + " must be 16..8192 px on each side");
  }
  requireFinite(o.cameraHeight, "the camera height");
  requireFinite(o.cameraBehind, "the distance behind the rig");
  if (!(o.pitchDeg > -90.0 && o.pitchDeg < 90.0)) {
    throw std::invalid_argument("cloud preview: the pitch must be in (-90, 90) degrees");
  }
  if (!(o.fieldOfViewDeg > 0.0 && o.fieldOfViewDeg < 180.0)) {
    throw std::invalid_argument("cloud preview: the field of view must be in (0, 180) degrees");
  }
  if (!(o.maxDepth > 0.0) || !std::isfinite(o.maxDepth)) {
    throw std::invalid_argument("cloud preview: the maximum depth must be a positive number of metres");
  }
  if (!(o.pointSize > 0.0) || !std::isfinite(o.pointSize)) {
    throw std::invalid_argument("cloud preview: the point size must be a positive number of metres");
  }
  if (o.maxSplatPx < 1 || o.maxSplatPx > 64) throw std::invalid_argument("cloud preview: maxSplatPx must be 1..64");
  requireFinite(o.groundBelowCamera, "the ground's distance below the camera");
}

Eigen::Vector3d projectToPreview(const Eigen::Vector3d& pointCamera, const CloudPreviewOptions& options) {
  validate(options);
  return PreviewCamera(options).project(pointCamera);
}

cv::Mat renderCloudPreview(const std::vector<Eigen::Vector3f>& pointsCamera, const std::vector<Rgb8>& colors,
                           const CloudPreviewOptions& o) {
  validate(o);
  if (pointsCamera.empty()) throw std::invalid_argument("cloud preview: the cloud has no points");
  if (!colors.empty() && colors.size() != pointsCamera.size()) {
    throw std::invalid_argument("cloud preview: " + std::to_string(colors.size()) + " colors for " +
                                std::to_string(pointsCamera.size()) + " points");
  }
  const PreviewCamera camera(o);
  cv::Mat image(o.height, o.width, CV_8UC3, cv::Scalar(kBackground[0], kBackground[1], kBackground[2]));
  if (o.grid) drawGrid(image, camera, o);

  // Float in the loop (450k points); the same operations in the same order give the same bytes.
  const Eigen::Matrix3f R = camera.R.cast<float>();
  const Eigen::Vector3f C = camera.center.cast<float>();
  const auto f = static_cast<float>(camera.f);
  const auto cx = static_cast<float>(camera.cx);
  const auto cy = static_cast<float>(camera.cy);
  const auto splatMetres = static_cast<float>(o.pointSize);
  const auto maxDepth = static_cast<float>(o.maxDepth);
  const float colorScale = 255.0f / maxDepth;
  const std::array<cv::Vec3b, 256>& turbo = io::turboColors();
  const auto margin = static_cast<float>(o.maxSplatPx);
  const auto width = static_cast<float>(o.width);
  const auto height = static_cast<float>(o.height);
  cv::Mat1f zBuffer(o.height, o.width, std::numeric_limits<float>::infinity());

  for (std::size_t i = 0; i < pointsCamera.size(); ++i) {
    const Eigen::Vector3f& p = pointsCamera[i];
    if (!p.allFinite() || p.z() > maxDepth) continue;
    const Eigen::Vector3f q = R * (p - C);
    if (q.z() < kNearPlane) continue;
    const float inverse = 1.0f / q.z();
    const float u = f * q.x() * inverse + cx;
    const float v = f * q.y() * inverse + cy;
    if (u < -margin || v < -margin || u > width + margin || v > height + margin) continue;
    // Square splat of pointSize metres at the point: perspective shrinks it with distance.
    // u, v > -margin here: truncation after a positive offset is floor() without a libm call.
    const int size = std::clamp(static_cast<int>(splatMetres * f * inverse + 0.5f), 1, o.maxSplatPx);
    const int x0 = static_cast<int>(u + kFloorOffset) - kFloorOffsetInt - (size - 1) / 2;
    const int y0 = static_cast<int>(v + kFloorOffset) - kFloorOffsetInt - (size - 1) / 2;
    cv::Vec3b bgr;
    if (colors.empty()) {
      const int index = std::min(static_cast<int>(std::max(p.z(), 0.0f) * colorScale + 0.5f), 255);
      bgr = turbo[static_cast<std::size_t>(index)];
    } else {
      bgr = cv::Vec3b(colors[i].b, colors[i].g, colors[i].r);
    }
    for (int y = std::max(y0, 0); y < std::min(y0 + size, o.height); ++y) {
      float* zRow = zBuffer.ptr<float>(y);
      cv::Vec3b* row = image.ptr<cv::Vec3b>(y);
      for (int x = std::max(x0, 0); x < std::min(x0 + size, o.width); ++x) {
        if (q.z() < zRow[x]) {  // strict: on a tie the earlier point stays
          zRow[x] = q.z();
          row[x] = bgr;
        }
      }
    }
  }
  if (o.grid) drawGridLabels(image, camera, o);
  if (o.markRig) drawRig(image, camera, o);
  return image;
}

void previewInputs(const geometry::DenseCloud& cloud, geometry::OutputFrame frame,
                   const geometry::StereoCalibration& calibration, ImageView<const Rgb8> color,
                   std::vector<Eigen::Vector3f>& pointsCamera, std::vector<Rgb8>& colors) {
  pointsCamera.clear();
  colors.clear();
  Eigen::Matrix4f toCamera = Eigen::Matrix4f::Identity();
  if (frame == geometry::OutputFrame::Lidar) toCamera = calibration.T_cam_lidar.matrix().cast<float>();
  pointsCamera.reserve(cloud.size());
  if (!color.empty()) colors.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    if (!p.allFinite()) continue;
    pointsCamera.push_back((toCamera * p.homogeneous()).head<3>());
    if (color.empty()) continue;
    const geometry::PixelIndex& pixel = cloud.pixels[i];
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= color.width || pixel.y >= color.height) {
      throw std::invalid_argument("cloud preview: point " + std::to_string(i) + " comes from pixel (" +
                                  std::to_string(pixel.x) + ", " + std::to_string(pixel.y) +
                                  "), outside the " + std::to_string(color.width) + "x" +
                                  std::to_string(color.height) + " color image");
    }
    colors.push_back(color(pixel.x, pixel.y));
  }
}

}  // namespace io
}  // namespace lidar_sgm
