// Where a fused KITTI frame's time goes after the matcher, and what the fast passes gain.
//  1. Densifier::run on one scan, frame after frame with the same Densifier (as lidar_sgm_batch
//     and Python reuse it): the medians of the whole run and of its steps.
//  2. The passes after the matcher alone, on the matcher's own output of that frame: the
//     specification's loops (what -backend cpu_ref runs) and the fast passes, in turn frame by
//     frame, each with its own buffers kept between frames as the Densifier keeps them; their
//     medians and the median of the per-frame ratios. Exits 1 if the two disagree by one byte.
//  3. The same for the passes before the matcher: the scan's projection into the left image and
//     the pair check at its points, and the pair check of a stereo-only frame (128 disparities).
//
//   build/bench/post_matcher_bench [-threads N] [-runs N] [-data ROOT] [-frame 000007_10]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "pipeline/post_matcher_passes.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using lidar_sgm::Image;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// One frame of the passes after the matcher, as Densifier::match and reprojectResult run them.
struct PassTimes {
  double filters = 0, confidence = 0, reproject = 0;
  double total() const { return filters + confidence + reproject; }
};

struct PassOutput {
  Image<std::int16_t> disparity;
  Image<std::uint8_t> confidence;
  Image<float> depth;
  lidar_sgm::geometry::DenseCloud cloud;
};

PassTimes runPasses(lidar_sgm::PostMatcherPasses& passes, const lidar_sgm::Densifier& raw,
                    const lidar_sgm::Densifier& shipped, PassOutput& out) {
  out.disparity = raw.disparity();  // the matcher's output, before any pass
  PassTimes t;
  auto start = Clock::now();
  passes.applyOutputFilters(out.disparity.view(), raw.projected().samples, raw.leftImage(), shipped.outputFilters());
  t.filters = msSince(start);
  start = Clock::now();
  passes.confidenceOfValidPixels(out.disparity.view(), raw.matcher()->confidence(), shipped.minConfidence(),
                                 out.confidence);
  t.confidence = msSince(start);
  start = Clock::now();
  passes.reproject(std::as_const(out.disparity).view(), shipped.usedCalibration(), shipped.reprojectionOptions(),
                   out.depth, out.cloud);
  t.reproject = msSince(start);
  return t;
}

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

template <typename T>
bool sameImage(const Image<T>& a, const Image<T>& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.data(), b.data(), sizeof(T) * static_cast<std::size_t>(a.width()) * a.height()) == 0;
}

bool sameSamples(const lidar_sgm::geometry::ProjectedLidar& a, const lidar_sgm::geometry::ProjectedLidar& b) {
  if (a.samples.size() != b.samples.size() || !sameBytes(a.sourceIndex, b.sourceIndex) ||
      a.stats.describe() != b.stats.describe()) {
    return false;
  }
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    if (a.samples[i].x != b.samples[i].x || a.samples[i].y != b.samples[i].y ||
        a.samples[i].disparity16 != b.samples[i].disparity16) {
      return false;
    }
  }
  return true;
}

bool sameOutput(const PassOutput& a, const PassOutput& b) {
  if (a.cloud.points.size() != b.cloud.points.size() || a.cloud.width != b.cloud.width ||
      a.cloud.height != b.cloud.height || a.cloud.isDense != b.cloud.isDense) {
    return false;
  }
  for (std::size_t i = 0; i < a.cloud.points.size(); ++i) {
    if (std::memcmp(a.cloud.points[i].data(), b.cloud.points[i].data(), 3 * sizeof(float)) != 0 ||
        a.cloud.pixels[i].x != b.cloud.pixels[i].x || a.cloud.pixels[i].y != b.cloud.pixels[i].y) {
      return false;
    }
  }
  return sameImage(a.disparity, b.disparity) && sameImage(a.confidence, b.confidence) && sameImage(a.depth, b.depth);
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 2;
  int runs = 20;
  std::string data = LIDAR_SGM_SHARED_DATA;
  std::string frame = "000007_10";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 < argc && a == "-threads") {
      threads = std::atoi(argv[++i]);
    } else if (i + 1 < argc && a == "-runs") {
      runs = std::atoi(argv[++i]);
    } else if (i + 1 < argc && a == "-data") {
      data = argv[++i];
    } else if (i + 1 < argc && a == "-frame") {
      frame = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s [-threads N >= 1] [-runs N >= 1] [-data ROOT] [-frame 000007_10]\n", argv[0]);
      return 2;
    }
  }
  if (threads < 1 || runs < 1) {
    std::fprintf(stderr, "%s: -threads and -runs must be >= 1\n", argv[0]);
    return 2;
  }
  const std::string k = data + "/kitti2015_lidar";
  std::vector<Eigen::Vector3f> points;
  for (const auto& p : lidar_sgm::io::readKittiScan(k + "/velodyne/" + frame + ".bin")) points.emplace_back(p.x, p.y, p.z);
  const cv::Mat left = lidar_sgm::io::readGrayImage(k + "/image_2/" + frame + ".png");
  const cv::Mat right = lidar_sgm::io::readGrayImage(k + "/image_3/" + frame + ".png");
  const auto calibration = lidar_sgm::io::readCalibration(k + "/calib/calib_cam_to_cam.txt");

  // 1. The whole run, as the tools ship it (defaults, fused).
  lidar_sgm::Densifier shipped;
  shipped.setCalibration(calibration);
  shipped.setStereoPair(lidar_sgm::io::grayView(left), lidar_sgm::io::grayView(right));
  shipped.parameters().threads = threads;
  std::vector<double> total, match, stages, filters, reproject;
  for (int i = 0; i < runs + 2; ++i) {  // 2 warm-up frames
    const auto start = Clock::now();
    shipped.run(points);
    const double wall = msSince(start);
    if (i < 2) continue;
    total.push_back(wall);
    match.push_back(shipped.timings().match);
    stages.push_back(shipped.matcher()->lastTimings().total());
    filters.push_back(shipped.timings().filters);
    reproject.push_back(shipped.timings().reproject);
  }
  std::printf("lidar_sgm post_matcher_bench: KITTI %s, %dx%d, fused, backend %s, %d threads, median of %d frames "
              "after 2 warm-up frames, ms\n",
              frame.c_str(), left.cols, left.rows, lidar_sgm::toString(shipped.usedBackend()).c_str(), threads, runs);
  std::printf("Densifier::run %.2f: match %.2f (matcher stages %.2f, filters and confidence threshold %.2f), "
              "reproject %.2f\n",
              median(total), median(match), median(stages), median(filters), median(reproject));

  // 2. The passes alone on the matcher's output (filters and threshold off in `raw`).
  lidar_sgm::Densifier raw;
  raw.setCalibration(calibration);
  raw.setStereoPair(lidar_sgm::io::grayView(left), lidar_sgm::io::grayView(right));
  raw.parameters().threads = threads;
  raw.outputFilters().sky.enabled = false;
  raw.outputFilters().outliers.enabled = false;
  raw.setMinConfidence(0.0);
  raw.setComputeCloud(false);
  raw.run(points);
  lidar_sgm::PostMatcherPasses specification;
  lidar_sgm::PostMatcherPasses fast;
  specification.select(lidar_sgm::Backend::CpuRef, threads);
  fast.select(lidar_sgm::Backend::Cpu, threads);
  if (!fast.fast()) {
    std::printf("the fast passes are not built (no fast cpu backend)\n");
    return 0;
  }
  PassOutput a;
  PassOutput b;
  std::vector<double> specFilters, specConfidence, specReproject, specTotal;
  std::vector<double> fastFilters, fastConfidence, fastReproject, fastTotal, ratio;
  for (int i = 0; i < runs + 2; ++i) {
    const PassTimes s = runPasses(specification, raw, shipped, a);
    const PassTimes f = runPasses(fast, raw, shipped, b);
    if (!sameOutput(a, b)) {
      std::printf("the fast passes' output differs from the specification's\n");
      return 1;
    }
    if (i < 2) continue;
    specFilters.push_back(s.filters);
    specConfidence.push_back(s.confidence);
    specReproject.push_back(s.reproject);
    specTotal.push_back(s.total());
    fastFilters.push_back(f.filters);
    fastConfidence.push_back(f.confidence);
    fastReproject.push_back(f.reproject);
    fastTotal.push_back(f.total());
    ratio.push_back(f.total() / s.total());
  }
  std::printf("passes alone, %zu points | sky + outliers | confidence + threshold | depth + cloud | all\n",
              b.cloud.size());
  std::printf("  specification         | %14.2f | %22.2f | %13.2f | %.2f\n", median(specFilters),
              median(specConfidence), median(specReproject), median(specTotal));
  std::printf("  fast                  | %14.2f | %22.2f | %13.2f | %.2f\n", median(fastFilters),
              median(fastConfidence), median(fastReproject), median(fastTotal));
  std::printf("  fast / specification, median of the per-frame ratios: %.3f [%.3f, %.3f]; outputs identical\n",
              median(ratio), *std::min_element(ratio.begin(), ratio.end()), *std::max_element(ratio.begin(), ratio.end()));

  // 3. The passes before the matcher, on the scan and the pair of the frame.
  const lidar_sgm::GrayImageView leftView = lidar_sgm::io::grayView(left);
  const lidar_sgm::GrayImageView rightView = lidar_sgm::io::grayView(right);
  lidar_sgm::geometry::ProjectedLidar specProjected;
  lidar_sgm::geometry::ProjectedLidar fastProjected;
  std::vector<double> specProject, specPair, fastProject, fastPair, beforeRatio, specStereo, fastStereo;
  for (int i = 0; i < runs + 2; ++i) {
    auto start = Clock::now();
    specification.project(points, shipped.usedCalibration(), shipped.projectionOptions(), specProjected);
    const double sp = msSince(start);
    start = Clock::now();
    const lidar_sgm::PairOrientation specVotes =
        specification.pairOrientationFromLidar(leftView, rightView, specProjected.samples);
    const double sv = msSince(start);
    start = Clock::now();
    fast.project(points, shipped.usedCalibration(), shipped.projectionOptions(), fastProjected);
    const double fp = msSince(start);
    start = Clock::now();
    const lidar_sgm::PairOrientation fastVotes =
        fast.pairOrientationFromLidar(leftView, rightView, fastProjected.samples);
    const double fv = msSince(start);
    start = Clock::now();
    const lidar_sgm::PairOrientation specGrid = specification.pairOrientationFromStereo(leftView, rightView, 0, 128);
    const double ss = msSince(start);
    start = Clock::now();
    const lidar_sgm::PairOrientation fastGrid = fast.pairOrientationFromStereo(leftView, rightView, 0, 128);
    const double fs = msSince(start);
    if (!sameSamples(specProjected, fastProjected) || specVotes.tested != fastVotes.tested ||
        specVotes.givenWins != fastVotes.givenWins || specVotes.swappedWins != fastVotes.swappedWins ||
        specGrid.tested != fastGrid.tested || specGrid.givenWins != fastGrid.givenWins ||
        specGrid.swappedWins != fastGrid.swappedWins) {
      std::printf("the fast passes before the matcher differ from the specification's\n");
      return 1;
    }
    if (i < 2) continue;
    specProject.push_back(sp);
    specPair.push_back(sv);
    fastProject.push_back(fp);
    fastPair.push_back(fv);
    beforeRatio.push_back((fp + fv) / (sp + sv));
    specStereo.push_back(ss);
    fastStereo.push_back(fs);
  }
  std::printf("passes before the matcher, %zu of %zu points kept | projection | pair check | both | stereo-only "
              "pair check\n",
              fastProjected.samples.size(), points.size());
  std::printf("  specification         | %10.2f | %10.2f | %4.2f | %.2f\n", median(specProject), median(specPair),
              median(specProject) + median(specPair), median(specStereo));
  std::printf("  fast                  | %10.2f | %10.2f | %4.2f | %.2f\n", median(fastProject), median(fastPair),
              median(fastProject) + median(fastPair), median(fastStereo));
  std::printf("  fast / specification, median of the per-frame ratios: %.3f [%.3f, %.3f]; outputs identical\n",
              median(beforeRatio), *std::min_element(beforeRatio.begin(), beforeRatio.end()),
              *std::max_element(beforeRatio.begin(), beforeRatio.end()));
  return 0;
}
