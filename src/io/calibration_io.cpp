#include "lidar_sgm/io/calibration_io.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <istream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <opencv2/core.hpp>

#include "lidar_sgm/io/atomic_file.hpp"
#include "calibration_yaml.hpp"
#include "lidar_sgm/io/file_access.hpp"
#include "text_excerpt.hpp"

namespace lidar_sgm {
namespace io {
namespace fs = std::filesystem;
namespace {

using geometry::StereoCalibration;
using Matrix34 = Eigen::Matrix<double, 3, 4>;

/// One "KEY: v1 v2 ..." line parsed into numbers; it remembers where it came from so that every
/// later complaint about its content can name the file, the line and the key.
struct Field {
  std::string file;
  std::string key;
  int line = 0;
  std::vector<double> values;

  std::string where() const { return file + ":" + std::to_string(line) + ": key '" + key + "'"; }
  [[noreturn]] void fail(const std::string& problem) const { throw std::runtime_error(where() + ": " + problem); }
};

std::string trim(const std::string& text) {
  const auto notSpace = [](unsigned char c) { return std::isspace(c) == 0; };
  const auto first = std::find_if(text.begin(), text.end(), notSpace);
  const auto last = std::find_if(text.rbegin(), text.rend(), notSpace).base();
  return first < last ? std::string(first, last) : std::string();
}

std::string numberText(double value) {
  std::ostringstream s;
  s.precision(10);
  s << value;
  return s.str();
}

/// The whole token must be a finite number: strtod alone would accept "7.2abc" as 7.2, and
/// "nan"/"inf" would poison every later computation silently.
double parseNumber(const Field& field, const std::string& token) {
  const char* begin = token.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0') field.fail("malformed number '" + token + "'");
  if (!std::isfinite(value)) field.fail("non-finite number '" + token + "'");
  return value;
}

[[noreturn]] void cannotRead(const std::string& source, const std::string& reason) {
  throw std::runtime_error("cannot read calibration '" + source + "': " + reason);
}

/// The text is not what the reader expected (another file than a KITTI calibration was given):
/// readCalibration() adds the formats it accepts, which the format-specific readers do not know.
class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What readCalibration() accepts, for messages about a file that is none of it.
const char* const kAcceptedCalibrations =
    "calibrations read: a KITTI object calib file (keys P2, P3, R0_rect, Tr_velo_to_cam); a KITTI raw date "
    "folder (with calib_cam_to_cam.txt and calib_velo_to_cam.txt), or its calib_cam_to_cam.txt with "
    "calib_velo_to_cam.txt beside it; a lidar_sgm YAML file (.yaml/.yml: width, height, K, baseline, T_cam_lidar)";

std::ifstream openFile(const std::string& path) {
  const std::string reason = unreadableFileReason(path);
  if (!reason.empty()) cannotRead(path, reason);
  std::ifstream in(path, std::ios::binary);  // binary: the text parsers see exactly the file's bytes
  if (!in) cannotRead(path, "cannot open the file");
  return in;
}

std::string readAll(std::istream& in, const std::string& source) {
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) cannotRead(source, "read error");
  return text.str();
}

/// A KITTI calibration text: "KEY: values" lines. Values are kept as text and only the keys
/// asked for are parsed, so unknown keys with non-numeric values (calib_time) do no harm.
/// `source` names the text in every message: a path, or the caller's label for memory input.
class KittiText {
 public:
  KittiText(std::istream& in, const std::string& source) : source_(source) {
    const std::string all = readAll(in, source);
    // A scan or an image given as the calibration: say so, and never echo its bytes.
    if (detail::looksBinary(std::string_view(all).substr(0, 4096))) {
      throw FormatError("cannot read calibration '" + source + "': the file looks binary (" +
                        std::to_string(all.size()) + " bytes, starting '" + detail::printableExcerpt(all, 16) +
                        "'), not a KITTI calibration text");
    }
    std::istringstream lines(all);
    std::string text;
    for (int number = 1; std::getline(lines, text); ++number) addLine(number, text);
  }

  /// The numbers of `key`, exactly `count` of them.
  Field numbers(const std::string& key, std::size_t count) const {
    const auto found = lines_.find(key);
    if (found == lines_.end()) throw FormatError(source_ + ": missing key '" + key + "'" + describeKeys());
    const std::vector<Line>& occurrences = found->second;
    Field field{source_, key, occurrences.front().number, {}};
    // Two values for one key: which one the author meant is a guess we do not make.
    if (occurrences.size() > 1) field.fail("appears again on line " + std::to_string(occurrences[1].number));
    std::istringstream tokens(occurrences.front().text);
    for (std::string token; tokens >> token;) field.values.push_back(parseNumber(field, token));
    if (field.values.size() != count) {
      field.fail("expected " + std::to_string(count) + " numbers, got " + std::to_string(field.values.size()));
    }
    return field;
  }

 private:
  struct Line {
    int number;
    std::string text;
  };

  /// " (the text has keys A, B, C)" and, where they are another KITTI file's, which one it is.
  std::string describeKeys() const {
    if (lines_.empty()) return " (the text has no 'KEY: values' line)";
    std::string keys;
    std::size_t listed = 0;
    for (const auto& entry : lines_) {
      if (++listed > 12) {
        keys += ", ...";
        break;
      }
      keys += (keys.empty() ? "" : ", ") + detail::printableExcerpt(entry.first, 24);
    }
    const auto has = [&](const char* key) { return lines_.count(key) > 0; };
    std::string hint;
    if (has("R") && has("T") && !has("P2") && !has("P_rect_02")) {
      hint = "; this looks like KITTI raw's calib_velo_to_cam.txt: give its date folder, or the "
             "calib_cam_to_cam.txt beside it";
    } else if (has("P_rect_02")) {
      hint = "; this looks like KITTI raw's calib_cam_to_cam.txt: give its date folder, or the file under that "
             "name with calib_velo_to_cam.txt beside it";
    } else if (has("Tr") && has("P2") && !has("Tr_velo_to_cam")) {
      hint = "; this looks like a KITTI odometry calib.txt (Tr instead of Tr_velo_to_cam and R0_rect): "
             "lidar_sgm_batch reads odometry sequences";
    }
    return " (the text has keys " + keys + ")" + hint;
  }

  void addLine(int number, std::string text) {
    if (!text.empty() && text.back() == '\r') text.pop_back();  // files saved with CRLF
    if (trim(text).empty()) return;
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) {
      throw FormatError(source_ + ":" + std::to_string(number) + ": expected 'KEY: values', got '" +
                        detail::printableExcerpt(text, 60) + "'");
    }
    lines_[trim(text.substr(0, colon))].push_back({number, text.substr(colon + 1)});
  }

  std::string source_;
  std::map<std::string, std::vector<Line>> lines_;
};

Matrix34 rowMajor3x4(const Field& field) {
  Matrix34 m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = field.values[static_cast<std::size_t>(4 * r + c)];
  }
  return m;
}

Eigen::Matrix3d rowMajor3x3(const Field& field) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = field.values[static_cast<std::size_t>(3 * r + c)];
  }
  return m;
}

/// Checked per key (not only on the composed T_cam_lidar) so the message names the culprit line.
void requireRotation(const Field& field, const Eigen::Matrix3d& R) {
  const double orthoError = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = R.determinant();
  if (orthoError > StereoCalibration::kRotationTolerance ||
      std::abs(det - 1.0) > StereoCalibration::kRotationTolerance) {
    field.fail("not a rotation (max |R^T R - I| = " + numberText(orthoError) + ", det = " + numberText(det) + ")");
  }
}

/// A rectified projection's left 3x3 must be [fx 0 cx; 0 fy cy; 0 0 1]: K is built from fx, fy,
/// cx, cy alone, so anything else in it would be dropped without a word.
void requireRectifiedIntrinsics(const Field& field, const Matrix34& P) {
  if (P(0, 1) != 0.0 || P(1, 0) != 0.0 || P(2, 0) != 0.0 || P(2, 1) != 0.0 || P(2, 2) != 1.0) {
    field.fail("left 3x3 must be [fx 0 cx; 0 fy cy; 0 0 1] (rectified, no skew)");
  }
}

/// Rigid transform from a rotation and a translation; last row exactly (0 0 0 1).
Eigen::Matrix4d rigid(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = t;
  return T;
}

/// The KITTI composition shared by the object and raw formats (see the header):
/// K = left 3x3 of P2, baseline = (P2[0,3] - P3[0,3]) / fx,
/// T_cam_lidar = [I | K^-1 P2[:,3]] * R0_rect * Tr_velo_to_cam. The [I | t2] term moves from the
/// rectified reference camera 0 to camera 2, so P2 * R0 * Tr * X == K * (T_cam_lidar * X).
StereoCalibration composeKitti(const Field& p2Field, const Field& p3Field, const Field& r0Field,
                               const Eigen::Matrix4d& veloToCam) {
  const Matrix34 P2 = rowMajor3x4(p2Field);
  const Matrix34 P3 = rowMajor3x4(p3Field);
  requireRectifiedIntrinsics(p2Field, P2);
  requireRectifiedIntrinsics(p3Field, P3);
  // A rectified pair shares its intrinsics; KITTI prints them identically.
  if ((P3.leftCols<3>() - P2.leftCols<3>()).cwiseAbs().maxCoeff() > 1e-6 * std::abs(P2(0, 0))) {
    p3Field.fail("left 3x3 differs from " + p2Field.key + "'s: the pair is not rectified");
  }
  const Eigen::Matrix3d R0 = rowMajor3x3(r0Field);
  requireRotation(r0Field, R0);

  StereoCalibration calibration;
  calibration.K << P2(0, 0), 0.0, P2(0, 2), 0.0, P2(1, 1), P2(1, 2), 0.0, 0.0, 1.0;
  if (!(P2(0, 0) > 0.0)) p2Field.fail("focal length fx must be positive, got " + numberText(P2(0, 0)));
  if (P2(0, 0) < StereoCalibration::kMinFocalLength || P2(0, 0) > StereoCalibration::kMaxFocalLength) {
    p2Field.fail("focal length fx must lie in [" + numberText(StereoCalibration::kMinFocalLength) + ", " +
                 numberText(StereoCalibration::kMaxFocalLength) + "] px, got " + numberText(P2(0, 0)));
  }
  calibration.baseline = (P2(0, 3) - P3(0, 3)) / P2(0, 0);
  if (!(calibration.baseline > 0.0)) {
    p3Field.fail("baseline (" + p2Field.key + "[0,3] - " + p3Field.key + "[0,3]) / fx must be positive [m], got " +
                 numberText(calibration.baseline));
  }
  if (calibration.baseline < StereoCalibration::kMinBaseline || calibration.baseline > StereoCalibration::kMaxBaseline) {
    p3Field.fail("baseline (" + p2Field.key + "[0,3] - " + p3Field.key + "[0,3]) / fx must lie in [" +
                 numberText(StereoCalibration::kMinBaseline) + ", " + numberText(StereoCalibration::kMaxBaseline) +
                 "] m, got " + numberText(calibration.baseline));
  }
  const Eigen::Vector3d cameraOffset = calibration.K.triangularView<Eigen::Upper>().solve(P2.col(3));
  calibration.T_cam_lidar.matrix() =
      rigid(Eigen::Matrix3d::Identity(), cameraOffset) * rigid(R0, Eigen::Vector3d::Zero()) * veloToCam;
  return calibration;
}

/// validate() with the source named; with the size unknown (0x0) everything but the size is
/// still checked, on a copy given a placeholder size.
void validateFromSource(const StereoCalibration& calibration, const std::string& source) {
  StereoCalibration checked = calibration;
  if (checked.width == 0 && checked.height == 0) checked.width = checked.height = 1;
  try {
    checked.validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("invalid calibration " + source + ": " + e.what());
  }
}

/// S_rect_02 is printed as floats (1.242000e+03); a size must still be a positive whole number.
int imageSide(const Field& field, double value) {
  if (!(value >= 1.0) || value > static_cast<double>(INT_MAX) || value != std::floor(value)) {
    field.fail("image size must be positive whole pixels, got " + numberText(value));
  }
  return static_cast<int>(value);
}

/// The R (row-major 3x3) and T of a KITTI raw sensor-to-sensor file, as one rigid transform.
Eigen::Matrix4d rigidOfRAndT(const KittiText& text) {
  const Field rotation = text.numbers("R", 9);
  const Field translation = text.numbers("T", 3);
  const Eigen::Matrix3d R = rowMajor3x3(rotation);
  requireRotation(rotation, R);
  return rigid(R, Eigen::Vector3d(translation.values[0], translation.values[1], translation.values[2]));
}

// --- YAML: written by cv::FileStorage, read by calibration_yaml.cpp -----------------------

template <typename Derived>
cv::Mat toCvMat(const Eigen::MatrixBase<Derived>& m) {
  cv::Mat out(static_cast<int>(m.rows()), static_cast<int>(m.cols()), CV_64F);
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) out.at<double>(r, c) = m(r, c);
  }
  return out;
}

void writeYamlContent(cv::FileStorage& storage, const StereoCalibration& c) {
  storage.writeComment("lidar_sgm stereo calibration: metres and pixels; rectified left camera K,");
  storage.writeComment("baseline between the rectified cameras, p_cam = T_cam_lidar * p_lidar.");
  storage << "width" << c.width << "height" << c.height;
  storage << "K" << toCvMat(c.K);
  storage << "baseline" << c.baseline;
  storage << "T_cam_lidar" << toCvMat(c.T_cam_lidar.matrix());
}

bool hasYamlExtension(const fs::path& path) {
  const std::string extension = lowerExtension(path.string());
  return extension == ".yaml" || extension == ".yml";
}

}  // namespace

StereoCalibration readKittiCalibration(std::istream& in, const std::string& source, int width, int height) {
  const KittiText text(in, source);
  const Field p2 = text.numbers("P2", 12);
  const Field p3 = text.numbers("P3", 12);
  const Field r0 = text.numbers("R0_rect", 9);
  const Field tr = text.numbers("Tr_velo_to_cam", 12);
  const Matrix34 veloToCam = rowMajor3x4(tr);
  requireRotation(tr, veloToCam.leftCols<3>());

  StereoCalibration calibration = composeKitti(p2, p3, r0, rigid(veloToCam.leftCols<3>(), veloToCam.col(3)));
  calibration.width = width;
  calibration.height = height;
  validateFromSource(calibration, "'" + source + "'");
  return calibration;
}

StereoCalibration readKittiCalibrationFromString(const std::string& text, const std::string& source, int width,
                                                 int height) {
  std::istringstream in(text);
  return readKittiCalibration(in, source, width, height);
}

StereoCalibration readKittiCalibration(const std::string& path, int width, int height) {
  std::ifstream in = openFile(path);
  return readKittiCalibration(in, path, width, height);
}

StereoCalibration readKittiRawCalibration(std::istream& camToCam, const std::string& camToCamSource,
                                          std::istream& veloToCam, const std::string& veloToCamSource) {
  const KittiText camToCamText(camToCam, camToCamSource);
  const KittiText veloToCamText(veloToCam, veloToCamSource);
  const Field p2 = camToCamText.numbers("P_rect_02", 12);
  const Field p3 = camToCamText.numbers("P_rect_03", 12);
  const Field r0 = camToCamText.numbers("R_rect_00", 9);  // rectifies camera 0, the reference of P_rect_0x
  const Field size = camToCamText.numbers("S_rect_02", 2);

  StereoCalibration calibration = composeKitti(p2, p3, r0, rigidOfRAndT(veloToCamText));
  calibration.width = imageSide(size, size.values[0]);
  calibration.height = imageSide(size, size.values[1]);
  validateFromSource(calibration, "from '" + camToCamSource + "' and '" + veloToCamSource + "'");
  return calibration;
}

StereoCalibration readKittiRawCalibrationFromString(const std::string& camToCamText,
                                                    const std::string& veloToCamText,
                                                    const std::string& camToCamSource,
                                                    const std::string& veloToCamSource) {
  std::istringstream camToCam(camToCamText);
  std::istringstream veloToCam(veloToCamText);
  return readKittiRawCalibration(camToCam, camToCamSource, veloToCam, veloToCamSource);
}

StereoCalibration readKittiRawCalibration(const std::string& camToCamPath, const std::string& veloToCamPath) {
  std::ifstream camToCam = openFile(camToCamPath);
  std::ifstream veloToCam = openFile(veloToCamPath);
  return readKittiRawCalibration(camToCam, camToCamPath, veloToCam, veloToCamPath);
}

Eigen::Isometry3d readKittiRawRigidTransform(std::istream& in, const std::string& source) {
  Eigen::Isometry3d transform;
  transform.matrix() = rigidOfRAndT(KittiText(in, source));
  return transform;
}

Eigen::Isometry3d readKittiRawRigidTransform(const std::string& path) {
  std::ifstream in = openFile(path);
  return readKittiRawRigidTransform(in, path);
}

StereoCalibration readCalibrationYamlFromString(const std::string& text, const std::string& source) {
  // A NUL would cut the text short for a C-string parser: refused rather than half read.
  if (text.find('\0') != std::string::npos) cannotRead(source, "the YAML text contains a NUL byte");
  if (trim(text).empty()) cannotRead(source, "the YAML text is empty");
  const StereoCalibration calibration = detail::parseCalibrationYaml(text, source);
  validateFromSource(calibration, "'" + source + "'");
  return calibration;
}

StereoCalibration readCalibrationYaml(std::istream& in, const std::string& source) {
  return readCalibrationYamlFromString(readAll(in, source), source);
}

StereoCalibration readCalibrationYaml(const std::string& path) {
  std::ifstream in = openFile(path);
  return readCalibrationYamlFromString(readAll(in, path), path);
}

void writeCalibrationYaml(const std::string& path, const StereoCalibration& calibration) {
  // Refuse to write what readCalibrationYaml would refuse to read back.
  try {
    calibration.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("cannot write calibration '" + path + "': " + e.what());
  }
  // Checked here so a missing directory gets a plain message instead of OpenCV's error log.
  const fs::path directory = fs::path(path).parent_path();
  std::error_code ec;
  if (!directory.empty() && !fs::is_directory(directory, ec)) {
    throw std::runtime_error("cannot write '" + path + "': no such directory '" + directory.string() + "'");
  }
  // Written in memory, then through AtomicFile: every write checked, nothing half written.
  std::string text;
  try {
    cv::FileStorage storage(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    writeYamlContent(storage, calibration);
    text = storage.releaseAndGetString();
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot write '" + path + "': " + trim(e.what()));
  }
  writeFileAtomically(path, text);
}

StereoCalibration readCalibration(const std::string& path, int width, int height) {
  const fs::path p(path);
  try {
    if (hasYamlExtension(p)) return readCalibrationYaml(path);
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      const fs::path camToCam = p / "calib_cam_to_cam.txt";
      if (!fs::exists(camToCam, ec)) {
        throw FormatError("cannot read calibration '" + path +
                          "': it is a directory without calib_cam_to_cam.txt, not a KITTI raw date folder");
      }
      return readKittiRawCalibration(camToCam.string(), (p / "calib_velo_to_cam.txt").string());
    }
    if (p.filename() == "calib_cam_to_cam.txt") {
      return readKittiRawCalibration(path, (p.parent_path() / "calib_velo_to_cam.txt").string());
    }
    return readKittiCalibration(path, width, height);
  } catch (const FormatError& e) {
    // The file is none of the formats: say which ones there are.
    throw std::runtime_error(std::string(e.what()) + ". " + kAcceptedCalibrations);
  }
}

}  // namespace io
}  // namespace lidar_sgm
