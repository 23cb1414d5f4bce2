#pragma once
/// @file calibration_io.hpp  Reading a StereoCalibration from KITTI object, KITTI raw and our
/// own YAML text, from files or from memory (a string or a std::istream), and writing the YAML one.
///
/// Every reader throws std::runtime_error naming the source, and where it applies the line and
/// the key, for a missing file, a missing key, a malformed or non-finite number, or a
/// calibration that geometry::StereoCalibration::validate() rejects. The source is the path for
/// a file, and the caller's `source` label (default "<string>") for memory input. Each format has
/// one parser: the path readers open the file and hand it to the stream reader.

#include <istream>
#include <string>

#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace io {

/// KITTI object-benchmark format (calib/000000.txt): P2 (left color camera), P3 (right),
/// R0_rect, Tr_velo_to_cam; other keys (P0, P1, Tr_imu_to_velo, ...) are ignored.
///   K = P2's left 3x3, baseline = (P2[0,3] - P3[0,3]) / fx,
///   T_cam_lidar = [I | K^-1 P2[:,3]] * R0_rect * Tr_velo_to_cam.
/// The format has no image size: pass it, or leave it 0 and set it from the images later
/// (StereoCalibration::validate() requires one).
geometry::StereoCalibration readKittiCalibration(const std::string& path, int width = 0, int height = 0);
/// The same from a stream; `source` names it in messages.
geometry::StereoCalibration readKittiCalibration(std::istream& in, const std::string& source, int width = 0,
                                                 int height = 0);
/// The same from the file's text.
geometry::StereoCalibration readKittiCalibrationFromString(const std::string& text,
                                                           const std::string& source = "<string>", int width = 0,
                                                           int height = 0);

/// KITTI raw format: calib_cam_to_cam.txt (P_rect_02, P_rect_03, R_rect_00, S_rect_02) and
/// calib_velo_to_cam.txt (R, T); cameras 02/03 are the color pair. The size is S_rect_02.
geometry::StereoCalibration readKittiRawCalibration(const std::string& camToCamPath,
                                                    const std::string& veloToCamPath);
/// The same from two streams, each named by its `source` in messages.
geometry::StereoCalibration readKittiRawCalibration(std::istream& camToCam, const std::string& camToCamSource,
                                                    std::istream& veloToCam, const std::string& veloToCamSource);
/// The same from the two files' texts.
geometry::StereoCalibration readKittiRawCalibrationFromString(
    const std::string& camToCamText, const std::string& veloToCamText,
    const std::string& camToCamSource = "<calib_cam_to_cam string>",
    const std::string& veloToCamSource = "<calib_velo_to_cam string>");

/// A KITTI raw sensor-to-sensor file (calib_velo_to_cam.txt, calib_imu_to_velo.txt): R (row-major
/// 3x3, a rotation) and T, the transform x_to = R * x_from + T. Other keys (calib_time) are ignored.
Eigen::Isometry3d readKittiRawRigidTransform(const std::string& path);
/// The same from a stream; `source` names it in messages.
Eigen::Isometry3d readKittiRawRigidTransform(std::istream& in, const std::string& source);

/// KITTI odometry calib.txt (P0..P3, Tr: the LiDAR into the rectified camera 0), read as the
/// KITTI object format it is a case of: R0_rect the identity, Tr_velo_to_cam = Tr, so T_cam_lidar
/// ends in camera 2 as for the object benchmark. `width`/`height` as readKittiCalibration (0 = from
/// the images). Throws std::runtime_error naming the file (and the missing Tr line).
geometry::StereoCalibration readKittiOdometryCalibration(const std::string& path, int width = 0, int height = 0);
/// Tr of a KITTI odometry calib.txt: the LiDAR into the rectified camera 0, the camera KITTI's
/// odometry poses refer to. Throws std::runtime_error naming the file when it has no valid Tr line.
Eigen::Isometry3d readKittiOdometryTr(const std::string& path);

/// Our YAML (cv::FileStorage): width, height, K (3x3), baseline, T_cam_lidar (4x4).
geometry::StereoCalibration readCalibrationYaml(const std::string& path);
/// The same from a stream; `source` names it in messages.
geometry::StereoCalibration readCalibrationYaml(std::istream& in, const std::string& source);
/// The same from the file's text (it must start with "%YAML", as written by writeCalibrationYaml;
/// OpenCV picks the format from that first line, for files too).
geometry::StereoCalibration readCalibrationYamlFromString(const std::string& text,
                                                          const std::string& source = "<string>");
/// Writes the YAML form through a temporary file renamed when complete.
void writeCalibrationYaml(const std::string& path, const geometry::StereoCalibration& calibration);

/// Picks the reader from the path: *.yaml / *.yml -> YAML; a directory, or a file named
/// calib_cam_to_cam.txt, -> KITTI raw (calib_velo_to_cam.txt beside it); any other file ->
/// KITTI object format (with the given size, 0 = unknown).
geometry::StereoCalibration readCalibration(const std::string& path, int width = 0, int height = 0);

}  // namespace io
}  // namespace lidar_sgm
