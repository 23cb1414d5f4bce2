#include "calibration_yaml.hpp"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

[[noreturn]] void cannotRead(const std::string& source, const std::string& reason) {
  throw std::runtime_error("cannot read calibration '" + source + "': " + reason);
}

[[noreturn]] void badKey(const std::string& source, const std::string& key, const std::string& problem) {
  throw std::runtime_error(source + ": key '" + key + "': " + problem);
}

/// `map[key]`; `label` names it in messages (a matrix's "K.rows").
YAML::Node requireNode(const YAML::Node& map, const std::string& source, const std::string& key,
                       const std::string& label) {
  const YAML::Node node = map[key];
  if (!node.IsDefined() || node.IsNull()) throw std::runtime_error(source + ": missing key '" + label + "'");
  return node;
}

bool scalarText(const YAML::Node& node, std::string& text) {
  if (!node.IsScalar()) return false;
  text = node.Scalar();
  return !text.empty();
}

int readInt(const YAML::Node& map, const std::string& source, const std::string& key, const std::string& label) {
  const YAML::Node node = requireNode(map, source, key, label);
  std::string text;
  errno = 0;
  char* end = nullptr;
  const long value = scalarText(node, text) ? std::strtol(text.c_str(), &end, 10) : 0;
  if (end == nullptr || end == text.c_str() || *end != '\0' || errno != 0 || value < INT_MIN || value > INT_MAX) {
    badKey(source, label, "expected an integer");
  }
  return static_cast<int>(value);
}

/// A finite number (".inf" and ".nan" would poison every later computation silently).
bool finiteNumber(const YAML::Node& node, double& value) {
  std::string text;
  if (!scalarText(node, text)) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && std::isfinite(value);
}

double readReal(const YAML::Node& root, const std::string& source, const std::string& key) {
  double value = 0.0;
  if (!finiteNumber(requireNode(root, source, key, key), value)) badKey(source, key, "expected a finite number");
  return value;
}

/// OpenCV's matrix: a map of rows, cols, dt and data (row-major).
template <int Rows, int Cols>
Eigen::Matrix<double, Rows, Cols> readMatrix(const YAML::Node& root, const std::string& source, const std::string& key) {
  const YAML::Node node = requireNode(root, source, key, key);
  const std::string shape = "expected a " + std::to_string(Rows) + "x" + std::to_string(Cols) + " matrix";
  if (!node.IsMap()) badKey(source, key, shape);
  if (readInt(node, source, "rows", key + ".rows") != Rows || readInt(node, source, "cols", key + ".cols") != Cols) {
    badKey(source, key, shape);
  }
  const YAML::Node data = node["data"];
  if (!data.IsDefined() || !data.IsSequence() || data.size() != static_cast<std::size_t>(Rows * Cols)) {
    badKey(source, key, shape + " (" + std::to_string(Rows * Cols) + " data values)");
  }
  Eigen::Matrix<double, Rows, Cols> out;
  for (int i = 0; i < Rows * Cols; ++i) {
    if (!finiteNumber(data[static_cast<std::size_t>(i)], out(i / Cols, i % Cols))) {
      badKey(source, key, "data value " + std::to_string(i + 1) + " is not a finite number");
    }
  }
  return out;
}

}  // namespace

geometry::StereoCalibration parseCalibrationYaml(const std::string& text, const std::string& source) {
  if (text.size() > kMaxCalibrationYamlBytes) {
    cannotRead(source, std::to_string(text.size()) + " bytes is more than a calibration's limit of " +
                           std::to_string(kMaxCalibrationYamlBytes));
  }
  // OpenCV's "%YAML:1.0" is not a YAML 1.2 directive: it is checked and blanked (keeping the
  // line numbers of yaml-cpp's messages).
  if (text.rfind("%YAML", 0) != 0) cannotRead(source, "not an OpenCV YAML file (it must start with %YAML)");
  std::string body = text;
  for (std::size_t i = 0; i < body.size() && body[i] != '\n'; ++i) body[i] = ' ';
  YAML::Node root;
  try {
    root = YAML::Load(body);
  } catch (const YAML::Exception& e) {
    cannotRead(source, std::string("YAML syntax error: ") + e.what());  // names line and column
  }
  if (!root.IsMap()) cannotRead(source, "expected a map of keys (width, height, K, baseline, T_cam_lidar)");
  geometry::StereoCalibration calibration;
  try {
    calibration.width = readInt(root, source, "width", "width");
    calibration.height = readInt(root, source, "height", "height");
    calibration.K = readMatrix<3, 3>(root, source, "K");
    calibration.baseline = readReal(root, source, "baseline");
    calibration.T_cam_lidar.matrix() = readMatrix<4, 4>(root, source, "T_cam_lidar");
  } catch (const YAML::Exception& e) {
    cannotRead(source, e.what());
  }
  return calibration;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
