#include "densify/frame_loader.hpp"

#include <future>
#include <stdexcept>

#include "common/timer.hpp"
#include "densify/densify_options.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

/// "Loading WHAT" ... " [done, N ms : DETAIL]" on `log`, when there is one.
class LoadLine {
 public:
  LoadLine(std::FILE* log, const std::string& what) : log_(log) {
    if (log_ == nullptr) return;
    std::fprintf(log_, "Loading %s", what.c_str());
    std::fflush(log_);
  }
  void more(const std::string& what) const {
    if (log_ != nullptr) std::fprintf(log_, ", %s", what.c_str());
  }
  void done(const std::string& detail) const {
    if (log_ != nullptr) std::fprintf(log_, " [done, %.0f ms : %s]\n", timer_.elapsedMs(), detail.c_str());
  }

 private:
  std::FILE* log_;
  Timer timer_;
};

}  // namespace

LoadedFrame loadFrame(const FrameFiles& files, std::FILE* log) {
  // The images decode on threads of their own while the scan and the calibration load (a KITTI
  // PNG takes ~13 ms to decode): the frame is ready in about the time of its slowest file, not of
  // their sum. A failure is still reported in the order below (the futures are only read there;
  // an unread one is waited for and its error dropped when the scan or calibration failed).
  std::future<cv::Mat> left;
  std::future<cv::Mat> right;
  if (!files.left.empty()) {
    left = std::async(std::launch::async, [path = files.left] { return io::readImage(path); });
    if (!files.right.empty()) right = std::async(std::launch::async, [path = files.right] { return io::readImage(path); });
  }
  LoadedFrame frame;
  {
    const LoadLine line(log, files.scan);
    frame.scan.reset(new pcl::PointCloud<pcl::PointXYZI>(io::readCloud(files.scan, files.maxPoints)));
    line.done(std::to_string(frame.scan->size()) + " points");
  }
  if (frame.scan->empty()) throw std::invalid_argument("the input cloud '" + files.scan + "' has no points");

  {
    const LoadLine line(log, files.calib);
    frame.calibration = files.readCalibration ? files.readCalibration(files.calib, files.width, files.height)
                                              : io::readCalibration(files.calib, files.width, files.height);
    line.done(geometry::describe(frame.calibration));
  }
  if (files.width > 0 && (frame.calibration.width != files.width || frame.calibration.height != files.height)) {
    throw std::invalid_argument("-image_size " + sizeText(files.width, files.height) +
                                " disagrees with the calibration '" + files.calib + "', which is for " +
                                sizeText(frame.calibration.width, frame.calibration.height));
  }

  if (!files.left.empty()) {
    const LoadLine line(log, files.left);
    frame.left = left.get();
    if (!files.right.empty()) {
      line.more(files.right);
      frame.right = right.get();
      if (frame.right.size() != frame.left.size()) {
        throw std::invalid_argument("the left image is " + sizeText(frame.left.cols, frame.left.rows) +
                                    " but the right image is " + sizeText(frame.right.cols, frame.right.rows));
      }
    }
    line.done(sizeText(frame.left.cols, frame.left.rows));
    requireOrganizedImage(files.left, frame.left);
  } else if (!files.right.empty()) {
    throw std::invalid_argument("a right image '" + files.right + "' needs a left one");
  }
  return frame;
}

}  // namespace apps
}  // namespace lidar_sgm
