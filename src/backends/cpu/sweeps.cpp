// The cpu backend's two sweeps over the image (cpu_matcher.hpp says why this shape): the sweep up
// stores C and checkpoints the upward paths; the sweep down, chunk by chunk, recomputes the
// upward paths from the checkpoints, runs the downward and horizontal paths, sums S and selects
// the winners in the same visit of each pixel's S. With two threads, the same stages in two bands
// of rows (sweepBands).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_matcher.hpp"
#include "backends/cpu/parallel.hpp"

namespace lidar_sgm {
namespace cpu {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The vertical paths' columns steps: the previous pixel on path k is (x - dx, y -+ 1), the same
// dx whichever way a walk goes: (0, +-1), then with 8 paths (1, +-1), (-1, +-1).
constexpr int kVerticalDx[3] = {0, 1, -1};

}  // namespace

RowWindows CpuMatcher::rowWindows(const Frame& f, int y) {
  if (f.windows == nullptr) return {};
  return {f.windows->firstRow(y), f.windows->countRow(y)};
}

// Pixels x0 .. x1-1 of row y, costed in the whole range's layout (`row` from pixel x0), into the
// packed volume: each pixel's window alone (a whole number of 16-byte vectors).
void CpuMatcher::packCostRow(const Frame& f, int y, int x0, int x1, const std::uint8_t* row) {
  const std::size_t D = static_cast<std::size_t>(f.plan.D);
  const std::int16_t* first = f.windows->firstRow(y);
  const std::int16_t* count = f.windows->countRow(y);
  const std::uint32_t* offset = costOffsets_.data() + static_cast<std::size_t>(y) * f.plan.width;
  std::uint8_t* packed = cost_.data() + costRowStart_[static_cast<std::size_t>(y)];
  for (int x = x0; x < x1; ++x) {
    std::memcpy(packed + offset[x], row + static_cast<std::size_t>(x - x0) * D + first[x],
                static_cast<std::size_t>(count[x]));
  }
}

bool CpuMatcher::costsPackedInPlace(const Frame& f) {
  return f.plan.useCameras() && !f.plan.upCamera();
}

void CpuMatcher::aggregateAndSelect(const Frame& f) {
  const auto t0 = Clock::now();
  if (inBands(f)) {
    if (f.paths8) {
      sweepBands<std::uint8_t>(f);
    } else {
      sweepBands<std::uint16_t>(f);
    }
  } else if (f.paths8) {
    sweepUp<std::uint8_t>(f);
    sweepDown<std::uint8_t>(f);
  } else {
    sweepUp<std::uint16_t>(f);
    sweepDown<std::uint16_t>(f);
  }
  const double sweeps = msBetween(t0, Clock::now());
  // Worker 0's clocks split the sweeps' wall time into the stages it streamed.
  const Worker& w0 = workers_[0];
  StageTimings& timings = f.out.timings;
  timings.censusCost = w0.censusCostMs;
  timings.verticalCensusCost = w0.verticalCostMs;
  timings.lidarCost = w0.lidarCostMs;
  timings.fuseCosts = w0.fuseMs;
  timings.selectDisparity = w0.selectMs;
  timings.aggregatePaths =
      std::max(0.0, sweeps - w0.censusCostMs - w0.verticalCostMs - w0.lidarCostMs - w0.fuseMs - w0.selectMs);
}

template <typename PathT>
void CpuMatcher::sweepUp(const Frame& f) {
  const int W = f.plan.width;
  const int H = f.plan.height;
#pragma omp parallel num_threads(f.threads)
  {
    const int team = teamSize();
    const int t = threadIndex();
    const int x0 = partBegin(W, team, t);
    const int x1 = partBegin(W, team, t + 1);
    Worker& w = workers_[static_cast<std::size_t>(t)];
    for (int i = 0; i < H; ++i) {
      const int y = H - 1 - i;
      // The first row of every chunk but the top one: the sweep down restarts the upward paths of
      // the chunk above from here.
      const int group = y > 0 && y % kChunkRows == 0 ? y / kChunkRows - 1 : -1;
      costAndStepRow<PathT>(f, y, i, x0, x1, 0, group, w);
      // Diagonal paths read the neighbouring columns of the previous row: wait for them.
      if (f.verticalPaths > 1) {
#pragma omp barrier
      }
    }
  }
}

// Row y, the i-th of a walk that costs as it goes (the sweep up, a band's first phase): the
// row's costs for pixels x0 .. x1-1, into the volume (the census costs of a gated frame packed in
// place) or in the whole range's layout into the worker's row, packed into the volume after the
// paths (the LiDAR-only and Triple-SGM costs of a gated frame); then the walk's vertical paths one
// step on from its previous row, in the double-buffered path rows of set `rowSet`, copied to
// checkpoint group `group` unless it is negative.
template <typename PathT>
void CpuMatcher::costAndStepRow(const Frame& f, int y, int i, int x0, int x1, int rowSet, int group, Worker& w) {
  const int D = f.plan.D;
  const bool inPlace = f.windows == nullptr || costsPackedInPlace(f);
  std::uint8_t* row = inPlace ? costRow(f, y) : w.costRow.data();
  const int rowX0 = inPlace ? 0 : x0;  // the pixel of `row`'s first costs in the whole range's layout
  const RowWindows windows = inPlace ? costWindows(f, y) : rowWindows(f, y);
  // costRange writes a packed row from its start (windows.costOffset), any other from pixel x0.
  std::uint8_t* costOut = windows.costOffset != nullptr ? row : row + static_cast<std::size_t>(x0 - rowX0) * D;
  costRange(f, y, x0, x1, costOut, windows, w);
  stepRow<PathT>(f, i, x0, x1, rowSet, group, row, rowX0, windows);
  if (!inPlace) packCostRow(f, y, x0, x1, row);
}

// The whole of row y's costs into the cost volume (a band's row that the other band costs for it).
void CpuMatcher::costWholeRow(const Frame& f, int y, Worker& w) {
  const int W = f.plan.width;
  if (f.windows == nullptr || costsPackedInPlace(f)) {
    costRange(f, y, 0, W, costRow(f, y), costWindows(f, y), w);
  } else {
    costRange(f, y, 0, W, w.costRow.data(), rowWindows(f, y), w);
    packCostRow(f, y, 0, W, w.costRow.data());
  }
}

// The walk's vertical paths one step on, onto costed row `row` (pixel rowX0's costs first; its
// windows, with costOffset when the row is the packed volume's).
template <typename PathT>
void CpuMatcher::stepRow(const Frame& f, int i, int x0, int x1, int rowSet, int group, const std::uint8_t* row,
                         int rowX0, RowWindows windows) {
  const int W = f.plan.width;
  const int D = f.plan.D;
  const std::size_t rowSlots = f.rowSlots;
  const std::size_t slot = static_cast<std::size_t>(pathSlot(D));
  const Parameters& p = f.plan.params;
  for (int k = 0; k < f.verticalPaths; ++k) {
    const std::size_t current = static_cast<std::size_t>((rowSet * 3 + k) * 2 + i % 2);
    const std::size_t previous = static_cast<std::size_t>((rowSet * 3 + k) * 2 + (i + 1) % 2);
    PathT* out = as<PathT>(paths_->rows, current * rowSlots);
    std::uint16_t* outMin = pathMins_.data() + current * W;
    pathRowFromPrevious(row, rowX0, i == 0 ? nullptr : as<PathT>(paths_->rows, previous * rowSlots),
                        pathMins_.data() + previous * W, kVerticalDx[k], W, x0, x1, D, p.P1, p.P2, out, outMin,
                        windows);
    if (group >= 0) {
      const auto [saved, savedMin] = checkpointRow<PathT>(f, group, k);
      std::copy(out + x0 * slot, out + x1 * slot, saved + x0 * slot);
      std::copy(outMin + x0, outMin + x1, savedMin + x0);
    }
  }
}

// Two threads in bands. In the sweeps above the threads split the columns for the vertical paths
// and the rows for the rest, so that half of every chunk's path rows, written by one core, are
// read by the other, and the next chunk writes rows the other core has read: with two threads the
// sweep down's vertical paths took as long as on one (BENCHMARK.md). Here each thread keeps a band
// of whole rows from start to end, and only two rows cross between the cores. Band 0 (the top
// chunks [0, m)) runs the downward paths top to bottom while band 1 runs the upward paths bottom to
// top, both costing their rows and keeping checkpoints; then, after the one barrier, band 0 walks
// up chunk by chunk, continuing the upward paths from band 1's last row and recomputing the
// downward ones from its checkpoints, and band 1 walks down, continuing the downward paths from
// band 0's last row and recomputing the upward ones; each chunk's horizontal paths and selection
// follow on the same thread. The same arithmetic on the same values as the sweeps above. Before
// the barrier, the band that finishes first costs the other band's last rows for it (bandHelp).
// Checkpoint groups (kChunkRows rows of the image each): the downward paths at row 8c - 1 for
// band 0's chunk c in group c - 1, the upward paths at row 8c + 8 for band 1's chunk c in group
// c + 1 (chunks m and m - 1 read the other band's groups m - 1 and m).
bool CpuMatcher::inBands(const Frame& f) { return f.threads == 2 && f.plan.height > kChunkRows; }

namespace {

int chunkCount(int height, int chunkRows) { return (height + chunkRows - 1) / chunkRows; }

}  // namespace

template <typename PathT>
void CpuMatcher::sweepBands(const Frame& f) {
  const int H = f.plan.height;
  const int chunks = chunkCount(H, kChunkRows);
  const int m = chunks / 2;  // band 0: chunks [0, m), band 1: [m, chunks); both non-empty
  if (rowClaims_.size() < static_cast<std::size_t>(H)) {
    rowClaims_ = std::vector<std::atomic<std::uint8_t>>(static_cast<std::size_t>(H));  // atomics do not move
  }
  for (int y = 0; y < H; ++y) rowClaims_[static_cast<std::size_t>(y)].store(kUnclaimed, std::memory_order_relaxed);
#pragma omp parallel num_threads(2)
  {
    const int team = teamSize();
    const int t = threadIndex();
    Worker& w = workers_[static_cast<std::size_t>(t)];
    for (int band = t; band < 2; band += team) {
      bandCosts<PathT>(f, band, m, w);
      // Then the other band's costs, from the rows it reaches last, until the two meet.
      bandHelp(f, 1 - band, m, w);
    }
#pragma omp barrier
    for (int band = t; band < 2; band += team) bandSelect<PathT>(f, band, m, w);
  }
}

// Phase 1 of a band: its rows' costs and its own direction's vertical paths, keeping checkpoints.
// A row the other band has claimed (bandHelp) is only stepped, once its costs are in the volume.
int CpuMatcher::bandRowCount(const Frame& f, int band, int splitChunk) {
  const int yMid = splitChunk * kChunkRows;
  return band == 0 ? yMid : f.plan.height - yMid;
}

int CpuMatcher::bandRow(const Frame& f, int band, int i) { return band == 0 ? i : f.plan.height - 1 - i; }

template <typename PathT>
void CpuMatcher::bandCosts(const Frame& f, int band, int splitChunk, Worker& w) {
  const int count = bandRowCount(f, band, splitChunk);
  for (int i = 0; i < count; ++i) {
    const int y = bandRow(f, band, i);
    // The other walk restarts here: band 0 at a chunk's last row, band 1 at a chunk's first.
    const bool checkpoint = band == 0 ? y % kChunkRows == kChunkRows - 1 : y % kChunkRows == 0;
    const int group = checkpoint ? y / kChunkRows : -1;
    std::atomic<std::uint8_t>& claim = rowClaims_[static_cast<std::size_t>(y)];
    std::uint8_t expected = kUnclaimed;
    if (claim.compare_exchange_strong(expected, kClaimed, std::memory_order_relaxed)) {
      costAndStepRow<PathT>(f, y, i, 0, f.plan.width, band, group, w);
      continue;
    }
    while (claim.load(std::memory_order_acquire) != kHelped) std::this_thread::yield();
    stepRow<PathT>(f, i, 0, f.plan.width, band, group, costRow(f, y), 0, costWindows(f, y));
  }
}

// Band `band`'s costs computed by the other thread, from the band's far end (the rows its own walk
// reaches last) towards its start, until a row is already claimed: the bands' phase 1 differ in
// work (a KITTI frame's LiDAR points lie in the bottom band: its costs took twice the top band's
// time, BENCHMARK.md), and whichever band finishes first takes over the other's costs.
void CpuMatcher::bandHelp(const Frame& f, int band, int splitChunk, Worker& w) {
  for (int i = bandRowCount(f, band, splitChunk) - 1; i >= 0; --i) {
    const int y = bandRow(f, band, i);
    std::atomic<std::uint8_t>& claim = rowClaims_[static_cast<std::size_t>(y)];
    std::uint8_t expected = kUnclaimed;
    if (!claim.compare_exchange_strong(expected, kClaimed, std::memory_order_relaxed)) return;
    costWholeRow(f, y, w);
    claim.store(kHelped, std::memory_order_release);  // the costs before the mark
  }
}

// Phase 2 of a band: chunk by chunk away from the other band, the vertical paths of the chunk's
// rows (one continuing, one recomputed from its checkpoint), then its horizontal paths and
// selection. The chunk buffers of parity `band` are this band's alone.
template <typename PathT>
void CpuMatcher::bandSelect(const Frame& f, int band, int splitChunk, Worker& w) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  const int vp = f.verticalPaths;
  const int chunks = chunkCount(H, kChunkRows);
  const int m = splitChunk;
  using Entry = std::pair<const PathT*, const std::uint16_t*>;
  const int first = band == 0 ? m - 1 : m;
  const int last = band == 0 ? -1 : chunks;
  const int step = band == 0 ? -1 : 1;
  for (int chunk = first; chunk != last; chunk += step) {
    const int yBegin = chunk * kChunkRows;
    const int rows = std::min(kChunkRows, H - yBegin);
    // Band 0 restarts the downward paths from its checkpoints and continues the upward ones from
    // the chunk below (its last chunk from band 1's first row); band 1 the other way round.
    verticalPathsOfChunk<PathT>(f, chunk, band, false, 0, W, false, [&](int k) {
      if (band == 0 || chunk == m) return Entry(checkpointRow<PathT>(f, chunk - 1, k));
      return Entry(chunkPath<PathT>(f, band, k, kChunkRows - 1), chunkMin(f, band, k, kChunkRows - 1));
    });
    verticalPathsOfChunk<PathT>(f, chunk, band, true, 0, W, false, [&](int k) {
      if (band == 1 || chunk == m - 1) return Entry(checkpointRow<PathT>(f, chunk + 1, k));
      return Entry(chunkPath<PathT>(f, band, vp + k, 0), chunkMin(f, band, vp + k, 0));
    });
    selectChunkRows<PathT>(f, chunk, band, 0, rows, w);
  }
}

// Chunk buffers of each parity: paths [0, vp) downward, [vp, 2 vp) upward (recomputed),
// kChunkRows rows each (vp = verticalPaths).
template <typename PathT>
PathT* CpuMatcher::chunkPath(const Frame& f, int parity, int k, int r) {
  const std::size_t row = (static_cast<std::size_t>(parity) * 2 * f.verticalPaths + k) * kChunkRows + r;
  return as<PathT>(paths_->chunks, row * f.rowSlots);
}

// Path k's row in checkpoint group `group` (one group of verticalPaths rows a chunk) and its minima.
template <typename PathT>
std::pair<PathT*, std::uint16_t*> CpuMatcher::checkpointRow(const Frame& f, int group, int k) {
  const std::size_t g = static_cast<std::size_t>(group) * f.verticalPaths + k;
  return {as<PathT>(paths_->checkpoints, g * f.rowSlots), checkpointMins_.data() + g * f.plan.width};
}

std::uint16_t* CpuMatcher::chunkMin(const Frame& f, int parity, int k, int r) {
  const std::size_t row = (static_cast<std::size_t>(parity) * 2 * f.verticalPaths + k) * kChunkRows + r;
  return chunkMins_.data() + row * f.plan.width;
}

// The sweep down, one chunk of kChunkRows rows at a time. One barrier per chunk (per row only for
// the diagonals of 8 paths): lock step per row would stall whenever another process takes a core.
template <typename PathT>
void CpuMatcher::sweepDown(const Frame& f) {
  const int W = f.plan.width;
  const int H = f.plan.height;
#pragma omp parallel num_threads(f.threads)
  {
    const int team = teamSize();
    const int t = threadIndex();
    const int x0 = partBegin(W, team, t);
    const int x1 = partBegin(W, team, t + 1);
    Worker& w = workers_[static_cast<std::size_t>(t)];
    for (int chunk = 0; chunk * kChunkRows < H; ++chunk) {
      // Stage 1, this thread's columns: the vertical (and diagonal) paths of the chunk's rows.
      // The upward paths again from the checkpoint the sweep up left below the chunk (the costs
      // were stored, the paths not: a volume of them would cost as much memory as the costs),
      // then the downward paths continuing the previous chunk's (the other parity).
      const int parity = chunk % 2;
      const bool lockStep = f.verticalPaths > 1;
      using Entry = std::pair<const PathT*, const std::uint16_t*>;
      verticalPathsOfChunk<PathT>(f, chunk, parity, true, x0, x1, lockStep,
                                  [&](int k) { return Entry(checkpointRow<PathT>(f, chunk, k)); });
      verticalPathsOfChunk<PathT>(f, chunk, parity, false, x0, x1, lockStep, [&](int k) {
        return Entry(chunkPath<PathT>(f, 1 - parity, k, kChunkRows - 1), chunkMin(f, 1 - parity, k, kChunkRows - 1));
      });
#pragma omp barrier
      // Stage 2, whole rows split among the threads: the horizontal paths need the row's every
      // cost, then S (all paths) and the winners, and the right view's winners, which read S
      // diagonally.
      const int rows = std::min(kChunkRows, H - chunk * kChunkRows);
      selectChunkRows<PathT>(f, chunk, parity, partBegin(rows, team, t), partBegin(rows, team, t + 1), w);
      // No barrier here: the next chunk fills the other parity's buffers, and the barrier after
      // its stage 1 keeps this chunk's buffers alive until every thread has finished stage 2.
    }
  }
}

// One vertical direction of the chunk's rows for pixels x0 .. x1-1, into the chunk buffers of
// `parity`: downward (paths [0, vp)) from the chunk's first row, or upward ([vp, 2 vp)) from its
// last. `entry(k)` gives path k's row before the chunk and its minima (a checkpoint or the chunk
// next to it); at the image's edge the path starts. `lockStep`: a barrier after each row, which
// every thread of the team must then reach (the diagonals read the neighbouring columns).
template <typename PathT, typename Entry>
void CpuMatcher::verticalPathsOfChunk(const Frame& f, int chunk, int parity, bool upward, int x0, int x1,
                                      bool lockStep, const Entry& entry) {
  const int W = f.plan.width;
  const int H = f.plan.height;
  const int D = f.plan.D;
  const Parameters& p = f.plan.params;
  const int vp = f.verticalPaths;
  const int yBegin = chunk * kChunkRows;
  const int rows = std::min(kChunkRows, H - yBegin);
  const int path0 = upward ? vp : 0;
  for (int step = 0; step < rows; ++step) {
    const int r = upward ? rows - 1 - step : step;
    const int y = yBegin + r;
    const bool edge = upward ? y == H - 1 : y == 0;
    for (int k = 0; k < vp; ++k) {
      const PathT* previous = nullptr;
      const std::uint16_t* previousMin = nullptr;
      if (step > 0) {
        const int before = upward ? r + 1 : r - 1;
        previous = chunkPath<PathT>(f, parity, path0 + k, before);
        previousMin = chunkMin(f, parity, path0 + k, before);
      } else if (!edge) {
        std::tie(previous, previousMin) = entry(k);
      }
      pathRowFromPrevious(costRow(f, y), 0, previous, previousMin, kVerticalDx[k], W, x0, x1, D, p.P1, p.P2,
                          chunkPath<PathT>(f, parity, path0 + k, r), chunkMin(f, parity, path0 + k, r),
                          costWindows(f, y));
    }
    if (lockStep) {
#pragma omp barrier
    }
  }
}

// Rows r0 .. r1-1 of the chunk: the horizontal paths, then S and the winners, the right view's
// winners and the confidence inputs that need S (from the winners before the left-right check),
// all in the same pass over each pixel's S.
template <typename PathT>
void CpuMatcher::selectChunkRows(const Frame& f, int chunk, int parity, int r0, int r1, Worker& w) {
  const FramePlan& plan = f.plan;
  const Parameters& p = plan.params;
  const int W = plan.width;
  const int D = plan.D;
  ConfidenceInputs& confidence = f.out.confidenceInputs;
  PathT* rightward = as<PathT>(w.rightward);
  PathT* leftward = as<PathT>(w.leftward);
  const PathT* paths[8];
  for (int r = r0; r < r1; ++r) {
    const int y = chunk * kChunkRows + r;
    const RowWindows windows = rowWindows(f, y);
    pathRowsHorizontal(costRow(f, y), W, D, p.P1, p.P2, rightward, leftward, costWindows(f, y));
    int count = 0;
    for (int k = 0; k < f.verticalPaths; ++k) {
      paths[count++] = chunkPath<PathT>(f, parity, k, r);
      paths[count++] = chunkPath<PathT>(f, parity, f.verticalPaths + k, r);
    }
    paths[count++] = rightward;
    paths[count++] = leftward;
    const auto s0 = Clock::now();
    WinnerExtras extras;
    extras.width = W;
    extras.pixelTotal = true;  // nothing reads the row's S after the selection
    if (plan.lrCheck || plan.confidenceLr) {
      extras.rightScratch = w.rightScratch.data();
      extras.rightIndex = rightIndex_.view().row(y);
    }
    if (plan.confidence) {
      extras.margin = confidence.margin.view().row(y);
      extras.bestCost = confidence.bestCost.view().row(y);
    }
    sumSelectRow(paths, count, nullptr, nullptr, 0, W, D, plan.minDisparity, p.uniquenessRatio, p.subpixel,
                 w.total.data(), rawDisparity_.view().row(y), bestIndex_.view().row(y), &extras, windows);
    if (plan.confidenceLr) {
      leftRightDifferenceRow(bestIndex_.view().row(y), rightIndex_.view().row(y), W, plan.minDisparity,
                             confidence.leftRightDifference.view().row(y));
    }
    w.selectMs += msBetween(s0, Clock::now());
  }
}

}  // namespace cpu
}  // namespace lidar_sgm
