// The cpu backend's frame: the census images and the LiDAR's pixels before the sweeps
// (sweeps.cpp), the left-right check, the median filter and the confidence after them.
#include "backends/cpu/cpu_matcher.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <utility>

#include "backends/common/lidar_search_windows.hpp"
#include "backends/common/lidar_weights.hpp"
#include "backends/common/path_costs.hpp"
#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

namespace lidar_sgm {

std::unique_ptr<MatcherBackend> createCpuMatcher() { return std::make_unique<cpu::CpuMatcher>(); }

namespace cpu {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

template <typename Vector>
void resizeKeep(Vector& v, std::size_t n) {
  if (v.size() < n) v.resize(n);
}

}  // namespace

void CpuMatcher::run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                     FrameResults& out) {
  const auto start = Clock::now();
  Frame f(plan, out);
  f.left = in.left;
  f.lidar = in.lidar;
  f.threads = effectiveThreads(plan.params);
  f.verticalPaths = plan.params.paths == 8 ? 3 : 1;
  f.paths8 = pathCostsFit8Bits(largestMatchingCost(plan), plan.params.P2);
  f.rowSlots = static_cast<std::size_t>(plan.width) * pathSlot(plan.D);
  if (plan.useCameras()) censusImages(f, in);
  if (plan.useLidar) lidarPixels(f);
  if (plan.gatedSearch) {
    // The LiDAR gate (shared with cpu_ref): the sweeps step and select over these windows only.
    searchWindows(f);
    f.windows = &windows_;
    packCostLayout(f);
  }
  out.timings.census = msSince(start);
  runStages(f, disparity);
}

// The LiDAR gate (lidar_cost.cpp): its passes split their rows among the threads.
void CpuMatcher::searchWindows(const Frame& f) {
  const Parameters& p = f.plan.params;
  lidarSearchWindows(*f.lidar, f.plan.minDisparity, f.plan.D, p.gatedSearchRows, p.gatedSearchMargin, windows_,
                     f.threads);
}

// The third camera's census image, and the layout of the right census planes. The pair's census
// is computed row by row where the costs need it (row_costs.cpp): the frame holds no census
// image of the pair (2 x 3.7 MB at KITTI size, and the planes 4.6 MB).
void CpuMatcher::censusImages(Frame& f, const FrameInputs& in) {
  const FramePlan& plan = f.plan;
  if (plan.upCamera()) {
    upCensus_.resize(in.up.width(), in.up.height());
    if (!in.up.gray8.empty()) {
      censusTransform(in.up.gray8, plan.params.censusType, upCensus_.view(), f.threads);
    } else {
      censusTransform(in.up.gray16, plan.params.censusType, upCensus_.view(), f.threads);
    }
  }
  f.right = in.right;
  f.planePad = censusPlanePad(plan.minDisparity, plan.D);
  f.planeStride = static_cast<std::size_t>(plan.width) + 2 * static_cast<std::size_t>(f.planePad);
}

// What the cost rows need of the LiDAR besides its points: the cost table, the pixels a point
// touches (most have none, and their C_L is 0 without a search) and the adaptive weights.
void CpuMatcher::lidarPixels(const Frame& f) {
  const FramePlan& plan = f.plan;
  const Parameters& p = plan.params;
  if (tableSigma_ != p.sigma || tableCap_ != p.lidarCostCap) {
    lidarRows_ = LidarCostRows(LidarCostTable(p.sigma, p.lidarCostCap));
    tableSigma_ = p.sigma;
    tableCap_ = p.lidarCostCap;
  }
  touched_.resize(plan.width, plan.height);
  parallelRanges(plan.height, f.threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) lidarTouchedRow(*f.lidar, y, touched_.view().row(y));
  });
  if (plan.adaptiveAlpha) {
    // Shared with every backend (backends/common): the same integer weights as cpu_ref's.
    lidarWeights_.resize(plan.width, plan.height);
    lidarWeights(*f.lidar, p, lidarWeights_.view());
  }
}

void CpuMatcher::runStages(const Frame& f, ImageView<std::int16_t> disparity) {
  const FramePlan& plan = f.plan;
  StageTimings& timings = f.out.timings;
  f.out.support.resize(plan.width, plan.height);
  if (!plan.useLidar) f.out.support.fill(0);
  // The sweeps split the columns: no more threads than columns.
  Frame frame = f;
  frame.threads = std::max(1, std::min(f.threads, plan.width));
  prepareBuffers(frame);
  aggregateAndSelect(frame);

  auto t0 = Clock::now();
  if (plan.lrCheck) {
    leftRightCheck(frame);
    timings.leftRightCheck = msSince(t0);
    t0 = Clock::now();
  }
  medianFilter(rawDisparity_.view(), plan.params.medianSize, disparity, frame.threads);
  timings.medianFilter = msSince(t0);
  if (plan.confidence) {
    t0 = Clock::now();
    confidenceStage(f, disparity);
    timings.confidence = msSince(t0);
  }
}

// Row by row (split among the threads), each pixel's offset in its row; then the rows' starts.
void CpuMatcher::packCostLayout(const Frame& f) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  costOffsets_.resize(static_cast<std::size_t>(W) * H);
  costRowStart_.resize(static_cast<std::size_t>(H) + 1);
  parallelRanges(H, f.threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const std::int16_t* count = windows_.countRow(y);
      std::uint32_t* offset = costOffsets_.data() + static_cast<std::size_t>(y) * W;
      std::uint32_t total = 0;
      for (int x = 0; x < W; ++x) {
        offset[x] = total;
        total += static_cast<std::uint32_t>(count[x]);
      }
      costRowStart_[static_cast<std::size_t>(y) + 1] = total;  // the row's size, summed below
    }
  });
  costRowStart_[0] = 0;
  for (int y = 0; y < H; ++y) costRowStart_[static_cast<std::size_t>(y) + 1] += costRowStart_[static_cast<std::size_t>(y)];
}

std::uint8_t* CpuMatcher::costRow(const Frame& f, int y) {
  return cost_.data() + (f.windows != nullptr ? costRowStart_[static_cast<std::size_t>(y)]
                                      : static_cast<std::size_t>(y) * f.plan.width * f.plan.D);
}

RowWindows CpuMatcher::costWindows(const Frame& f, int y) const {
  RowWindows windows = rowWindows(f, y);
  if (f.windows != nullptr) windows.costOffset = costOffsets_.data() + static_cast<std::size_t>(y) * f.plan.width;
  return windows;
}

void CpuMatcher::prepareBuffers(const Frame& f) {
  const FramePlan& plan = f.plan;
  const int W = plan.width;
  const int H = plan.height;
  cost_.reserve(static_cast<std::size_t>(W) * H * plan.D);
  bool newLayout = false;
  preparePathRows(f, newLayout);
  prepareWorkers(f, newLayout);
  rawDisparity_.resize(W, H);
  bestIndex_.resize(W, H);
  if (plan.lrCheck || plan.confidenceLr) rightIndex_.resize(W, H);
  ConfidenceInputs& confidence = f.out.confidenceInputs;
  if (plan.confidence) {
    confidence.margin.resize(W, H);
    confidence.bestCost.resize(W, H);
  }
  if (plan.confidenceLr) confidence.leftRightDifference.resize(W, H);
}

namespace {

// Sets the two ends ([0] and [D + 1]) of every pixel's slot in `rows` path rows to the sentinel
// (all ones): the kernels write every slot's inside and never its ends (cpu_kernels.hpp).
void markSlotEnds(std::uint8_t* rows, std::size_t count, std::size_t rowBytes, int width, int D,
                  std::size_t element) {
  const std::size_t slotBytes = static_cast<std::size_t>(pathSlot(D)) * element;
  const std::size_t last = static_cast<std::size_t>(D + 1) * element;
  for (std::size_t r = 0; r < count; ++r) {
    std::uint8_t* row = rows + r * rowBytes;
    for (int x = 0; x < width; ++x) {
      std::uint8_t* slot = row + static_cast<std::size_t>(x) * slotBytes;
      std::memset(slot, 0xFF, element);
      std::memset(slot + last, 0xFF, element);
    }
  }
}

// Grows `rows` to `count` path rows (never shrinks it: no allocation per frame after the first
// of a size) and marks their slot ends when the layout changed or the rows grew.
template <typename Bytes>
void preparePathBuffer(Bytes& rows, std::size_t count, std::size_t rowBytes, int width, int D,
                       std::size_t element, bool newLayout) {
  const std::size_t bytes = count * rowBytes;
  if (!newLayout && rows.size() >= bytes) return;
  if (rows.size() < bytes) rows.resize(bytes);
  markSlotEnds(rows.data(), count, rowBytes, width, D, element);
}

}  // namespace

// The path rows of both sweeps, grown only. Only their slots' ends need the sentinel, marked once
// per layout and set of rows: a frame's stereo witness (hidden_lidar.hpp) runs on this matcher at
// half scale before the frame itself, so the layout changes twice a frame; each of the two keeps
// its own set (filling the whole rows each time, 13.6 MB at KITTI size, and then marking one set's
// ends for each layout in turn, cost more).
void CpuMatcher::preparePathRows(const Frame& f, bool& newLayout) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  const int D = f.plan.D;
  const std::size_t element = f.paths8 ? 1 : 2;
  const std::size_t rowBytes = f.rowSlots * element;
  const std::size_t layout =
      (element << 40) ^ (static_cast<std::size_t>(W) << 20) ^ static_cast<std::size_t>(D);
  // The set marked for this layout, else the one used least recently.
  PathRows* set = pathSets_[0].layout == layout ? &pathSets_[0]
                  : pathSets_[1].layout == layout ? &pathSets_[1]
                  : pathSets_[0].lastUse <= pathSets_[1].lastUse ? &pathSets_[0]
                                                                 : &pathSets_[1];
  const bool newSetLayout = set->layout != layout;
  set->layout = layout;
  set->lastUse = ++pathSetUses_;
  paths_ = set;
  newLayout = layout != workerLayout_;  // the workers' rows (prepareWorkers)
  workerLayout_ = layout;
  // Per chunk: each vertical path downward and upward (2 * verticalPaths rows of kChunkRows),
  // in two parities.
  const std::size_t chunkPathRows = 2 * static_cast<std::size_t>(kChunkRows) * 2 * f.verticalPaths;
  // One group of checkpoints a chunk but the last (the sweep up), or one a chunk (the bands).
  const std::size_t checkpoints = static_cast<std::size_t>((H - 1) / kChunkRows + 1) * f.verticalPaths;
  // Each path's double-buffered row, for each of two bands (sweepBands).
  preparePathBuffer(set->rows, 4 * 3, rowBytes, W, D, element, newSetLayout);
  preparePathBuffer(set->chunks, chunkPathRows, rowBytes, W, D, element, newSetLayout);
  preparePathBuffer(set->checkpoints, checkpoints, rowBytes, W, D, element, newSetLayout);
  resizeKeep(pathMins_, 4 * 3 * static_cast<std::size_t>(W));
  resizeKeep(chunkMins_, chunkPathRows * W);
  resizeKeep(checkpointMins_, checkpoints * W);
}

void CpuMatcher::prepareWorkers(const Frame& f, bool newLayout) {
  const FramePlan& plan = f.plan;
  const int W = plan.width;
  const std::size_t rowBytes = f.rowSlots * (f.paths8 ? 1 : 2);
  workers_.resize(static_cast<std::size_t>(f.threads));
  // The costs of a thread's columns of a row, or of the whole row (a band's).
  const std::size_t partMax = (inBands(f) ? static_cast<std::size_t>(W) : static_cast<std::size_t>(W) / f.threads + 1) *
                              static_cast<std::size_t>(plan.D);
  for (Worker& w : workers_) {
    resizeKeep(w.stereo, partMax);
    resizeKeep(w.lidar, partMax);
    if (f.windows != nullptr && !costsPackedInPlace(f)) resizeKeep(w.costRow, partMax);
    if (plan.upCamera()) resizeKeep(w.vertical, partMax);
    resizeKeep(w.total, static_cast<std::size_t>(plan.D));
    if (plan.useCameras()) {
      resizeKeep(w.leftCensus, static_cast<std::size_t>(W));
      resizeKeep(w.rightCensus, static_cast<std::size_t>(W));
      resizeKeep(w.rightPlanes, 8 * f.planeStride);
    }
    if (plan.lrCheck || plan.confidenceLr) {
      resizeKeep(w.rightScratch, rightIndexScratchSize(W, plan.D, plan.minDisparity));
    }
    preparePathBuffer(w.rightward, 1, rowBytes, W, plan.D, f.paths8 ? 1 : 2, newLayout);
    preparePathBuffer(w.leftward, 1, rowBytes, W, plan.D, f.paths8 ? 1 : 2, newLayout);
    w.censusCostMs = w.verticalCostMs = w.lidarCostMs = w.fuseMs = w.selectMs = 0;
  }
}

void CpuMatcher::leftRightCheck(const Frame& f) {
  const FramePlan& plan = f.plan;
  ImageView<const std::uint8_t> covered;
  if (plan.lrCheckTrustsLidar) {
    coverage_.resize(plan.width, plan.height);
    lidarCoverage(*f.lidar, plan.params.lidarCoverageRows, coverage_.view(), f.threads);
    covered = coverage_.view();
  }
  cpu::leftRightCheck(SelectedDisparity{rawDisparity_.view(), bestIndex_.view()}, rightIndex_.view(), covered,
                      plan.minDisparity, plan.params.disp12MaxDiff,
                      /*keepNoCounterpart=*/plan.lrCheckTrustsLidar, f.threads);
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
  confidenceOfFrame(f.left, std::as_const(f.out.support).view(), disparity, f.plan.mode, f.plan.params.paths, in,
                    f.out.confidence.view(), confidenceBuffers_, f.threads);
}

}  // namespace cpu
}  // namespace lidar_sgm
