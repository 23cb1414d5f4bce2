#include "backends/cpu/cpu_matcher.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <utility>

#include "backends/common/lidar_weights.hpp"
#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

namespace lidar_sgm {

std::unique_ptr<MatcherBackend> createCpuMatcher() { return std::make_unique<cpu::CpuMatcher>(); }

namespace cpu {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The paths of each sweep as (dx, dy): the previous pixel on the path is (x - dx, y - dy).
struct Step {
  int dx;
};
constexpr Step kUpward[3] = {{0}, {1}, {-1}};    // (0,-1), then with 8 paths (1,-1), (-1,-1)
constexpr Step kDownward[3] = {{0}, {1}, {-1}};  // (0,1), then with 8 paths (1,1), (-1,1)

template <typename T>
void resizeKeep(std::vector<T>& v, std::size_t n) {
  if (v.size() < n) v.resize(n);
}

}  // namespace

struct CpuMatcher::Frame {
  Frame(const FramePlan& framePlan, FrameResults& results) : plan(framePlan), out(results) {}
  const FramePlan& plan;
  FrameResults& out;
  GrayImageView left;  // empty in LiDAR-only mode (the confidence reads no image there)
  const LidarPoints* lidar = nullptr;
  int threads = 1;
  int verticalPaths = 1;       // per sweep: 1 with 4 paths, 3 with 8
  bool paths8 = true;          // path costs in 8 bits (aggregation.cpp)
  int planePad = 0;            // the right census planes' layout (census_cost.cpp)
  std::size_t planeStride = 0;
};

struct CpuMatcher::Worker {
  std::vector<std::uint8_t> stereo;    // C_S (fused mode)
  std::vector<std::uint8_t> lidar;     // C_L (fused mode)
  std::vector<std::uint8_t> vertical;  // C_V (Triple-SGM)
  std::vector<std::uint16_t> total;      // S of one pixel (the selection needs no more)
  std::vector<std::uint8_t> rightward;  // L of the left-to-right path along one row (slots, bytes)
  std::vector<std::uint8_t> leftward;   // ... and of the right-to-left path
  std::vector<std::uint16_t> rightScratch;  // the right view's winners of a row
  double censusCostMs = 0;
  double verticalCostMs = 0;
  double lidarCostMs = 0;
  double fuseMs = 0;
  double selectMs = 0;
};

void CpuMatcher::run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                     FrameResults& out) {
  const auto start = Clock::now();
  const Parameters& params = plan.params;
  Frame f(plan, out);
  f.left = in.left;
  f.lidar = in.lidar;
  f.verticalPaths = params.paths == 8 ? 3 : 1;
  f.threads = effectiveThreads(params);
  // The largest matching cost, and so the largest path cost L <= C + P2 (Eq. 1).
  const int maxCost = plan.mode == MatchMode::StereoOnly  ? kMaxCensusCost
                      : plan.mode == MatchMode::LidarOnly ? params.lidarCostCap
                                                          : std::max(kMaxCensusCost, params.lidarCostCap);
  f.paths8 = pathCostsFit8Bits(maxCost, params.P2);

  if (plan.useCameras()) {
    const auto census = [&](const GrayImageView& image, Image<std::uint64_t>& bits) {
      bits.resize(image.width(), image.height());
      if (!image.gray8.empty()) {
        censusTransform(image.gray8, params.censusType, bits.view(), f.threads);
      } else {
        censusTransform(image.gray16, params.censusType, bits.view(), f.threads);
      }
    };
    census(in.left, leftCensus_);
    census(in.right, rightCensus_);
    if (plan.upCamera()) census(in.up, upCensus_);
    f.planePad = censusPlanePad(plan.minDisparity, plan.D);
    f.planeStride = static_cast<std::size_t>(plan.width) + 2 * static_cast<std::size_t>(f.planePad);
    resizeKeep(rightPlanes_, f.planeStride * 8 * plan.height);
    parallelRanges(plan.height, f.threads, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        censusPlanes(rightCensus_.view().row(y), plan.width, f.planePad,
                     rightPlanes_.data() + static_cast<std::size_t>(y) * 8 * f.planeStride, f.planeStride);
      }
    });
  }
  if (plan.useLidar && (tableSigma_ != params.sigma || tableCap_ != params.lidarCostCap)) {
    table_ = LidarCostTable(params.sigma, params.lidarCostCap);
    tableSigma_ = params.sigma;
    tableCap_ = params.lidarCostCap;
  }
  if (plan.useLidar) {
    touched_.resize(plan.width, plan.height);
    parallelRanges(plan.height, f.threads, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) lidarTouchedRow(*f.lidar, y, touched_.view().row(y));
    });
  }
  if (plan.adaptiveAlpha) {
    // Shared with every backend (backends/common): the same integer weights as cpu_ref's.
    lidarWeights_.resize(plan.width, plan.height);
    lidarWeights(*f.lidar, params, lidarWeights_.view());
  }
  out.timings.census = msBetween(start, Clock::now());
  runStages(f, disparity);
}

void CpuMatcher::costRange(const Frame& f, int y, int x0, int x1, std::uint8_t* cost, Worker& w) {
  const FramePlan& plan = f.plan;
  const int W = plan.width;
  const int D = plan.D;
  const auto n = static_cast<std::size_t>(x1 - x0) * D;
  const Parameters& p = plan.params;
  auto t0 = Clock::now();
  const auto lap = [&t0](double& ms) {
    const auto t1 = Clock::now();
    ms += msBetween(t0, t1);
    t0 = t1;
  };
  // The LiDAR cost, streamed from the points around each pixel (no C_L volume). Most pixels
  // have no point around them: C_L = 0 there, without looking for points.
  std::uint8_t* lidar = plan.mode == MatchMode::LidarOnly ? cost : w.lidar.data();
  if (plan.useLidar) {
    std::uint8_t* support = f.out.support.view().row(y);
    const std::uint8_t* touched = touched_.view().row(y);
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* c = lidar + static_cast<std::size_t>(x - x0) * D;
      if (touched[x] != 0) {
        lidarCostPixel(*f.lidar, table_, x, y, p.minDisparity, D, c);
      } else if (plan.mode == MatchMode::LidarOnly || plan.upCamera()) {
        std::memset(c, 0, static_cast<std::size_t>(D));
      }
      support[x] = touched[x];
    }
    lap(w.lidarCostMs);
  }
  if (!plan.useCameras()) return;
  const std::uint16_t* weights = plan.adaptiveAlpha ? lidarWeights_.view().row(y) : nullptr;
  const std::uint64_t* leftRow = leftCensus_.view().row(y);
  const std::uint8_t* planes = rightPlanes_.data() + static_cast<std::size_t>(y) * 8 * f.planeStride;
  if (!plan.upCamera()) {
    // C_S, fused per pixel while it is in the L1 cache.
    if (plan.mode == MatchMode::Fused) {
      censusCostFusedRow(leftRow, planes, f.planeStride, f.planePad, p.censusType, W, x0, x1, p.minDisparity,
                         D, lidar, touched_.view().row(y), weights, plan.alphaWeight, p.stereoCostWithoutLidar, cost);
    } else {
      censusCostRow(leftRow, planes, f.planeStride, f.planePad, p.censusType, W, x0, x1, p.minDisparity, D,
                    cost);
    }
    lap(w.censusCostMs);
    return;
  }
  // Triple-SGM: the camera cost C_S3 = (C_S + C_V + 1) >> 1 takes C_S's place in Eq. 5.
  std::uint8_t* camera = plan.mode == MatchMode::Fused ? w.stereo.data() : cost;
  censusCostRow(leftRow, planes, f.planeStride, f.planePad, p.censusType, W, x0, x1, p.minDisparity, D, camera);
  lap(w.censusCostMs);
  verticalCensusCostRow(leftRow, upCensus_.view(), y, x0, x1, plan.ratio16, p.minDisparity, D, plan.censusScale,
                        w.vertical.data());
  combineCameraCostRow(camera, w.vertical.data(), n, camera);
  lap(w.verticalCostMs);
  if (plan.mode != MatchMode::Fused) return;
  if (weights == nullptr) {
    fuseCostRow(lidar, camera, n, plan.alphaWeight, cost);
  } else {
    for (int x = x0; x < x1; ++x) {
      const auto offset = static_cast<std::size_t>(x - x0) * D;
      fuseCostRow(lidar + offset, camera + offset, static_cast<std::size_t>(D), weights[x], cost + offset);
    }
  }
  if (p.stereoCostWithoutLidar) {
    const std::uint8_t* touched = touched_.view().row(y);
    for (int x = x0; x < x1; ++x) {
      if (touched[x] != 0) continue;
      const auto offset = static_cast<std::size_t>(x - x0) * D;
      std::memcpy(cost + offset, camera + offset, static_cast<std::size_t>(D));
    }
  }
  lap(w.fuseMs);
}

void CpuMatcher::runStages(const Frame& f, ImageView<std::int16_t> disparity) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  const std::size_t slot = static_cast<std::size_t>(pathSlot(f.plan.D));
  f.out.support.resize(W, H);
  if (!f.plan.useLidar) f.out.support.fill(0);

  // Buffers, grown only (no allocation per frame after the first of a size).
  cost_.reserve(static_cast<std::size_t>(W) * H * f.plan.D);
  const std::size_t rowSlots = static_cast<std::size_t>(W) * slot;
  const std::size_t element = f.paths8 ? 1 : 2;
  const std::size_t rowBytes = rowSlots * element;
  const std::size_t chunkRows = 2 * static_cast<std::size_t>(kChunkRows);  // two parities
  // Path rows are filled with sentinels (all ones) once per layout: the kernels never write a
  // slot's two ends.
  const std::size_t layout = (element << 40) ^ (static_cast<std::size_t>(W) << 20) ^ static_cast<std::size_t>(f.plan.D);
  const bool newLayout = layout != pathLayout_;
  pathLayout_ = layout;
  // Per chunk: each vertical path downward and upward (2 * verticalPaths rows of kChunkRows).
  const std::size_t chunkPathRows = chunkRows * 2 * static_cast<std::size_t>(f.verticalPaths);
  const std::size_t checkpoints = static_cast<std::size_t>((H - 1) / kChunkRows) * f.verticalPaths;
  if (newLayout) pathRows_.assign(6 * rowBytes, 0xFF);
  if (newLayout || chunkPaths_.size() < chunkPathRows * rowBytes) chunkPaths_.assign(chunkPathRows * rowBytes, 0xFF);
  if (newLayout || checkpoints_.size() < checkpoints * rowBytes) checkpoints_.assign(checkpoints * rowBytes, 0xFF);
  resizeKeep(pathMins_, 6 * static_cast<std::size_t>(W));
  resizeKeep(chunkMins_, chunkPathRows * W);
  resizeKeep(checkpointMins_, checkpoints * W);
  const int threads = std::max(1, std::min(f.threads, W));
  workers_.resize(static_cast<std::size_t>(threads));
  const std::size_t partMax = (static_cast<std::size_t>(W) / threads + 1) * f.plan.D;
  for (Worker& w : workers_) {
    resizeKeep(w.stereo, partMax);
    resizeKeep(w.lidar, partMax);
    if (f.plan.upCamera()) resizeKeep(w.vertical, partMax);
    resizeKeep(w.total, static_cast<std::size_t>(f.plan.D));
    if (f.plan.lrCheck || f.plan.confidenceLr) {
      resizeKeep(w.rightScratch, rightIndexScratchSize(W, f.plan.D, f.plan.minDisparity));
    }
    if (newLayout || w.rightward.size() != rowBytes) w.rightward.assign(rowBytes, 0xFF);
    if (newLayout || w.leftward.size() != rowBytes) w.leftward.assign(rowBytes, 0xFF);
    w.censusCostMs = w.verticalCostMs = w.lidarCostMs = w.fuseMs = w.selectMs = 0;
  }
  rawDisparity_.resize(W, H);
  bestIndex_.resize(W, H);
  if (f.plan.lrCheck || f.plan.confidenceLr) rightIndex_.resize(W, H);
  if (f.plan.confidence) {
    f.out.confidenceInputs.margin.resize(W, H);
    f.out.confidenceInputs.bestCost.resize(W, H);
  }
  if (f.plan.confidenceLr) f.out.confidenceInputs.leftRightDifference.resize(W, H);

  Frame frame = f;
  frame.threads = threads;
  auto t0 = Clock::now();
  if (f.paths8) {
    sweepUp<std::uint8_t>(frame);
    sweepDown<std::uint8_t>(frame);
  } else {
    sweepUp<std::uint16_t>(frame);
    sweepDown<std::uint16_t>(frame);
  }
  const double sweeps = msBetween(t0, Clock::now());
  // Worker 0's clocks split the sweeps' wall time into the stages it streamed.
  const Worker& w0 = workers_[0];
  f.out.timings.censusCost = w0.censusCostMs;
  f.out.timings.verticalCensusCost = w0.verticalCostMs;
  f.out.timings.lidarCost = w0.lidarCostMs;
  f.out.timings.fuseCosts = w0.fuseMs;
  f.out.timings.selectDisparity = w0.selectMs;
  f.out.timings.aggregatePaths =
      std::max(0.0, sweeps - w0.censusCostMs - w0.verticalCostMs - w0.lidarCostMs - w0.fuseMs - w0.selectMs);

  t0 = Clock::now();
  const SelectedDisparity selected{rawDisparity_.view(), bestIndex_.view()};
  if (f.plan.lrCheck) {
    ImageView<const std::uint8_t> covered;
    if (f.plan.lrCheckTrustsLidar) {
      coverage_.resize(W, H);
      lidarCoverage(*f.lidar, f.plan.params.lidarCoverageRows, coverage_.view(), threads);
      covered = coverage_.view();
    }
    leftRightCheck(selected, rightIndex_.view(), covered, f.plan.params.minDisparity, f.plan.params.disp12MaxDiff,
                   /*keepNoCounterpart=*/f.plan.lrCheckTrustsLidar, threads);
    f.out.timings.leftRightCheck = msBetween(t0, Clock::now());
    t0 = Clock::now();
  }
  medianFilter(rawDisparity_.view(), f.plan.params.medianSize, disparity, threads);
  f.out.timings.medianFilter = msBetween(t0, Clock::now());
  if (f.plan.confidence) {
    t0 = Clock::now();
    confidenceStage(f, disparity);
    f.out.timings.confidence = msBetween(t0, Clock::now());
  }
}

void CpuMatcher::confidenceStage(const Frame& f, ImageView<const std::int16_t> disparity) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  ConfidenceInputs& in = f.out.confidenceInputs;
  if (f.plan.mode == MatchMode::LidarOnly) {
    // No right view: no counterpart anywhere (the core's convention, confidence.hpp).
    in.leftRightDifference.resize(W, H);
    in.leftRightDifference.fill(kNoCounterpartDifference);
  }
  in.lidarDistance.resize(W, H);
  in.texture.resize(W, H);
  in.saturated.resize(W, H);
  in.disparityRange.resize(W, H);
  f.out.confidence.resize(W, H);
  confidenceOfFrame(f.left, std::as_const(f.out.support).view(), disparity, f.plan.mode,
                    f.plan.params.paths, in, f.out.confidence.view(), confidenceBuffers_, f.threads);
}

template <typename PathT>
void CpuMatcher::sweepUp(const Frame& f) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  const int D = f.plan.D;
  const std::size_t rowSlots = static_cast<std::size_t>(W) * pathSlot(D);
  const std::size_t slot = static_cast<std::size_t>(pathSlot(D));
  const Parameters& p = f.plan.params;
#pragma omp parallel num_threads(f.threads)
  {
    const int team = teamSize();
    const int t = threadIndex();
    const int x0 = partBegin(W, team, t);
    const int x1 = partBegin(W, team, t + 1);
    Worker& w = workers_[static_cast<std::size_t>(t)];
    for (int i = 0; i < H; ++i) {
      const int y = H - 1 - i;
      std::uint8_t* cost = cost_.data() + static_cast<std::size_t>(y) * W * D;
      costRange(f, y, x0, x1, cost + static_cast<std::size_t>(x0) * D, w);
      for (int k = 0; k < f.verticalPaths; ++k) {
        PathT* current = as<PathT>(pathRows_, (2 * k + i % 2) * rowSlots);
        const PathT* previous = i == 0 ? nullptr : as<PathT>(pathRows_, (2 * k + (i + 1) % 2) * rowSlots);
        std::uint16_t* currentMin = pathMins_.data() + static_cast<std::size_t>(2 * k + i % 2) * W;
        const std::uint16_t* previousMin = pathMins_.data() + static_cast<std::size_t>(2 * k + (i + 1) % 2) * W;
        pathRowFromPrevious(cost, 0, previous, previousMin, kUpward[k].dx, W, x0, x1, D, p.P1, p.P2, current,
                            currentMin);
        // The first row of every chunk but the top one: the sweep down restarts the upward paths
        // of the chunk above from here.
        if (y > 0 && y % kChunkRows == 0) {
          const std::size_t c = static_cast<std::size_t>(y / kChunkRows - 1) * f.verticalPaths + k;
          std::copy(current + x0 * slot, current + x1 * slot, as<PathT>(checkpoints_, c * rowSlots) + x0 * slot);
          std::copy(currentMin + x0, currentMin + x1, checkpointMins_.data() + c * W + x0);
        }
      }
      // Diagonal paths read the neighbouring columns of the previous row: wait for them.
      if (f.verticalPaths > 1) {
#pragma omp barrier
      }
    }
  }
}

template <typename PathT>
void CpuMatcher::sweepDown(const Frame& f) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  const int D = f.plan.D;
  const std::size_t rowSlots = static_cast<std::size_t>(W) * pathSlot(D);
  const std::size_t costRowSize = static_cast<std::size_t>(W) * D;
  const Parameters& p = f.plan.params;
  const auto costRow = [&](int y) { return cost_.data() + static_cast<std::size_t>(y) * costRowSize; };
  // Chunk buffers of each parity: paths [0, vp) downward, [vp, 2 vp) upward (recomputed),
  // kChunkRows rows each (vp = verticalPaths).
  const int vp = f.verticalPaths;
  const auto chunkPath = [&](int parity, int k, int r) {
    return as<PathT>(chunkPaths_, ((static_cast<std::size_t>(parity) * 2 * vp + k) * kChunkRows + r) * rowSlots);
  };
  const auto chunkMin = [&](int parity, int k, int r) {
    return chunkMins_.data() + ((static_cast<std::size_t>(parity) * 2 * vp + k) * kChunkRows + r) * W;
  };
#pragma omp parallel num_threads(f.threads)
  {
    const int team = teamSize();
    const int t = threadIndex();
    const int x0 = partBegin(W, team, t);
    const int x1 = partBegin(W, team, t + 1);
    Worker& w = workers_[static_cast<std::size_t>(t)];
    const PathT* paths[8];
    PathT* rightward = as<PathT>(w.rightward);
    PathT* leftward = as<PathT>(w.leftward);
    for (int chunk = 0; chunk * kChunkRows < H; ++chunk) {
      const int yBegin = chunk * kChunkRows;
      const int rows = std::min(kChunkRows, H - yBegin);
      const int parity = chunk % 2;
      // Stage 1, this thread's columns. The upward paths of the chunk's rows again, bottom to top
      // from the checkpoint the sweep up left below the chunk (the costs were stored, the paths
      // not: a full volume of them would cost as much memory as the costs).
      for (int r = rows - 1; r >= 0; --r) {
        const int y = yBegin + r;
        for (int k = 0; k < f.verticalPaths; ++k) {
          const std::size_t c = static_cast<std::size_t>(chunk) * f.verticalPaths + k;
          const PathT* previous = y == H - 1 ? nullptr
                                  : r == rows - 1 ? as<PathT>(checkpoints_, c * rowSlots)
                                                  : chunkPath(parity, vp + k, r + 1);
          const std::uint16_t* previousMin =
              r == rows - 1 ? checkpointMins_.data() + c * W : chunkMin(parity, vp + k, r + 1);
          pathRowFromPrevious(costRow(y), 0, previous, previousMin, kUpward[k].dx, W, x0, x1, D, p.P1, p.P2,
                              chunkPath(parity, vp + k, r), chunkMin(parity, vp + k, r));
        }
        if (f.verticalPaths > 1) {
#pragma omp barrier
        }
      }
      // ... then the downward paths, top to bottom, continuing the previous chunk's.
      for (int r = 0; r < rows; ++r) {
        const int y = yBegin + r;
        for (int k = 0; k < f.verticalPaths; ++k) {
          const PathT* previous = y == 0 ? nullptr
                                  : r == 0 ? chunkPath(1 - parity, k, kChunkRows - 1)
                                           : chunkPath(parity, k, r - 1);
          const std::uint16_t* previousMin = r == 0 ? chunkMin(1 - parity, k, kChunkRows - 1) : chunkMin(parity, k, r - 1);
          pathRowFromPrevious(costRow(y), 0, previous, previousMin, kDownward[k].dx, W, x0, x1, D, p.P1, p.P2,
                              chunkPath(parity, k, r), chunkMin(parity, k, r));
        }
        if (f.verticalPaths > 1) {
#pragma omp barrier
        }
      }
#pragma omp barrier
      // Stage 2, whole rows split among the threads: the horizontal paths need the row's every
      // cost, then S (all paths) and the winners, and the right view's winners, which read S
      // diagonally.
      const int r0 = partBegin(rows, team, t);
      const int r1 = partBegin(rows, team, t + 1);
      for (int r = r0; r < r1; ++r) {
        const int y = yBegin + r;
        pathRowsHorizontal(costRow(y), W, D, p.P1, p.P2, rightward, leftward);
        int count = 0;
        for (int k = 0; k < f.verticalPaths; ++k) {
          paths[count++] = chunkPath(parity, k, r);
          paths[count++] = chunkPath(parity, vp + k, r);
        }
        paths[count++] = rightward;
        paths[count++] = leftward;
        const auto s0 = Clock::now();
        // The right view's winners and the confidence inputs that need S (from the winners before
        // the left-right check), in the same pass over each pixel's S as the selection.
        WinnerExtras extras;
        extras.width = W;
        extras.pixelTotal = true;  // nothing reads the row's S after the selection
        if (f.plan.lrCheck || f.plan.confidenceLr) {
          extras.rightScratch = w.rightScratch.data();
          extras.rightIndex = rightIndex_.view().row(y);
        }
        if (f.plan.confidence) {
          extras.margin = f.out.confidenceInputs.margin.view().row(y);
          extras.bestCost = f.out.confidenceInputs.bestCost.view().row(y);
        }
        sumSelectRow(paths, count, nullptr, nullptr, 0, W, D, p.minDisparity, p.uniquenessRatio, p.subpixel,
                     w.total.data(), rawDisparity_.view().row(y), bestIndex_.view().row(y), &extras);
        if (f.plan.confidenceLr) {
          leftRightDifferenceRow(bestIndex_.view().row(y), rightIndex_.view().row(y), W, p.minDisparity,
                                 f.out.confidenceInputs.leftRightDifference.view().row(y));
        }
        w.selectMs += msBetween(s0, Clock::now());
      }
      // No barrier here: the next chunk fills the other parity's buffers, and the barrier after
      // its stage 1 keeps this chunk's buffers alive until every thread has finished stage 2.
    }
  }
}

}  // namespace cpu
}  // namespace lidar_sgm
