#include "bench_opencv_sgbm.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <thread>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "bench_timing.hpp"

namespace lidar_sgm {
namespace bench {
namespace {

cv::Mat matView(const Image<std::uint8_t>& image) {
  return cv::Mat(image.height(), image.width(), CV_8UC1, const_cast<std::uint8_t*>(image.data()));
}

cv::Ptr<cv::StereoSGBM> createSgbm(const SgbmSettings& s) {
  return cv::StereoSGBM::create(0, s.numDisparities, s.blockSize, s.P1, s.P2, s.disp12MaxDiff, s.preFilterCap,
                                s.uniquenessRatio, s.speckleWindowSize, s.speckleRange, cv::StereoSGBM::MODE_SGBM_3WAY);
}

}  // namespace

std::string describe(const SgbmSettings& s) {
  std::ostringstream os;
  os << "cv::StereoSGBM (OpenCV " << CV_VERSION << "), MODE_SGBM_3WAY, numDisparities " << s.numDisparities
     << ", blockSize " << s.blockSize << ", P1 " << s.P1 << ", P2 " << s.P2 << ", disp12MaxDiff " << s.disp12MaxDiff
     << ", preFilterCap " << s.preFilterCap
     << ", uniquenessRatio " << s.uniquenessRatio << ", speckleWindowSize " << s.speckleWindowSize
     << ", speckleRange " << s.speckleRange;
  return os.str();
}

double timeOpenCvSgbm(const Frame& frame, const SgbmSettings& s, int threads, int runs, int warmups) {
  // cv::setNumThreads(0) would mean "no threads" to OpenCV, not "all": callers pass the
  // effective count. Restored afterwards so nothing else in the process is affected.
  const int previousThreads = cv::getNumThreads();
  cv::setNumThreads(threads);
  const cv::Ptr<cv::StereoSGBM> sgbm = createSgbm(s);
  const cv::Mat left = matView(frame.left);
  const cv::Mat right = matView(frame.right);
  cv::Mat disparity;  // CV_16S, x16 like ours; allocated once, in the warm-up
  const double ms = medianMs([&] { sgbm->compute(left, right, disparity); }, runs, warmups);
  cv::setNumThreads(previousThreads);
  return ms;
}

PairedTiming pairWithOpenCvSgbm(const Frame& frame, const SgbmSettings& s, int threads,
                                const std::function<void()>& ours, int runs, int warmups, int idleMs) {
  const int previousThreads = cv::getNumThreads();
  cv::setNumThreads(threads);
  const cv::Ptr<cv::StereoSGBM> sgbm = createSgbm(s);
  const cv::Mat left = matView(frame.left);
  const cv::Mat right = matView(frame.right);
  cv::Mat disparity;
  std::vector<double> oursMs, sgbmMs, ratios;
  // After a parallel region each library's workers spin for a while before they sleep (libgomp:
  // ~8-9 ms of a core on this project's 2-core VM), and a spinning worker takes a core from the
  // frame that follows. Back to back, ours would run beside OpenCV's spinning threads and OpenCV
  // beside ours. An idle gap before each frame lets both start from sleeping workers, as they do
  // between a camera's frames.
  const auto idle = [idleMs] { std::this_thread::sleep_for(std::chrono::milliseconds(idleMs)); };
  for (int i = 0; i < warmups + runs; ++i) {
    idle();
    const double a = wallClockMs(ours);
    idle();
    const double b = wallClockMs([&] { sgbm->compute(left, right, disparity); });
    if (i < warmups) continue;
    oursMs.push_back(a);
    sgbmMs.push_back(b);
    ratios.push_back(a / b);
  }
  cv::setNumThreads(previousThreads);
  PairedTiming t;
  t.oursMs = median(oursMs);
  t.sgbmMs = median(sgbmMs);
  t.ratio = median(ratios);
  t.ratioMin = *std::min_element(ratios.begin(), ratios.end());
  t.ratioMax = *std::max_element(ratios.begin(), ratios.end());
  return t;
}

}  // namespace bench
}  // namespace lidar_sgm
