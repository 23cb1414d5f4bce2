#pragma once
// The frames of a sequence, found in the layouts people have: KITTI odometry, KITTI raw, KITTI
// object, KITTI stereo 2015 training with raw scans, or a plain list file. Only paths are gathered
// here; nothing is read but folder listings and the list file.

#include <string>
#include <vector>

namespace lidar_sgm {
namespace sequence {

/// How a frame's calibration file is read.
enum class CalibrationFormat {
  Auto,           ///< io::readCalibration: KITTI object .txt, KITTI raw (folder or calib_cam_to_cam.txt), YAML
  KittiOdometry,  ///< KITTI odometry calib.txt (P0..P3 and Tr, already rectified)
  KittiRawPair    ///< io::readKittiRawCalibration(calib, veloToCam): KITTI raw's two files in any two folders
                  ///< (KITTI stereo 2015's per-frame calib_cam_to_cam/NNNNNN.txt, calib_velo_to_cam/NNNNNN.txt)
};

/// One frame: its name (unique within the sequence, the output's stem) and its files; `left`
/// and `right` are empty when absent (a frame without a pair runs LiDAR-only, colored from a
/// lone left image).
struct Frame {
  std::string name;
  std::string scan;
  std::string left;
  std::string right;
  std::string calib;
  CalibrationFormat calibFormat = CalibrationFormat::Auto;
  std::string veloToCam;  ///< CalibrationFormat::KittiRawPair: the calib_velo_to_cam file beside `calib`; else ""
  std::string oxts;       ///< a KITTI raw drive's OXTS packet of the frame (oxts/data/<stem>.txt), present or not; else ""
};

/// The layouts framesFromDirectory() reads, and the list file.
enum class Layout {
  KittiOdometrySequence,  ///< NN/{velodyne,image_2,image_3}/, NN/calib.txt
  KittiOdometryRoot,      ///< sequences/NN/...: every sequence
  KittiRawDrive,          ///< {velodyne_points,image_02,image_03}/data/, oxts/data/
  KittiObject,            ///< velodyne/, image_2/, image_3/, calib/NNNNNN.txt
  KittiStereo2015,        ///< velodyne/NNNNNN_10.bin, image_2/, image_3/, calib/calib_{cam,velo}_to_cam.txt
                          ///< or calib_cam_to_cam/NNNNNN.txt, calib_velo_to_cam/NNNNNN.txt
  ListFile                ///< -list FILE
};

/// The layout's name for messages ("KITTI raw drive").
const char* layoutName(Layout layout);

/// The layout framesFromDirectory() reads `dir` as (KittiOdometryRoot when it is none of the
/// others: framesFromDirectory() then refuses a folder without sequences).
Layout directoryLayout(const std::string& dir);

/// The frames under `dir`, in name order, by its layout:
///  - KITTI odometry sequence `NN/{velodyne,image_2,image_3,calib.txt}`; names "000000";
///  - KITTI odometry root `sequences/NN/...` (or the `sequences` folder itself), every sequence;
///    names "NN/000000";
///  - KITTI raw drive `{velodyne_points,image_02,image_03}/data`, calibration in the folder above
///    (the date's calib_cam_to_cam.txt, calib_velo_to_cam.txt); names "0000000000"; each frame's
///    OXTS packet `oxts/data/<stem>.txt` (its pose, for -map);
///  - KITTI stereo 2015 training `{image_2,image_3}/NNNNNN_10.png` with the raw scans
///    `velodyne/NNNNNN_10.bin` beside them; names "000007_10"; only frames with a scan (the `_11`
///    images and the ground-truth folders are not frames); the calibration is KITTI 2015's own per
///    frame, `calib_cam_to_cam/NNNNNN.txt` + `calib_velo_to_cam/NNNNNN.txt` (or NNNNNN_10.txt),
///    when those folders exist, else one KITTI raw pair `calib/calib_cam_to_cam.txt` +
///    `calib/calib_velo_to_cam.txt` for every frame. Told from the object layout by that
///    calibration, or by its scans' names (NNNNNN_10);
///  - KITTI object `{velodyne,image_2,image_3,calib}` with calib/NNNNNN.txt per frame.
/// A scan is any .bin, .pcd or .ply file of the scan folder; its images are the .png of the same
/// stem, when present. Throws std::invalid_argument naming `dir` and the layouts it looked for
/// when it is none of them, or when it has no scan; for a scan folder without a calibration, the
/// calibration files looked for.
std::vector<Frame> framesFromDirectory(const std::string& dir);

/// The frames of a list file: one frame per line, "SCAN LEFT RIGHT CALIB" separated by blanks,
/// "-" for a missing image; blank lines and lines starting with '#' are skipped; relative paths
/// are relative to the list file's folder. Names are the scan's stem. Throws
/// std::invalid_argument naming the file and line for a line without four fields, a right
/// image without a left one, or a name used twice.
std::vector<Frame> framesFromList(const std::string& listPath);

/// A shard "K/N" (0 <= K < N): frame i belongs to it when i % N == K.
struct Shard {
  int index = 0;
  int count = 1;
};
/// Parses "K/N"; std::invalid_argument naming the text otherwise.
Shard parseShard(const std::string& text);
/// The frames of `shard`, in order.
std::vector<Frame> framesOfShard(const std::vector<Frame>& frames, const Shard& shard);

}  // namespace sequence
}  // namespace lidar_sgm
