#pragma once
// The fast CPU backend's matcher: the stages of cpu_ref, streamed in two sweeps over the image.
//
//   sweep up    bottom to top, columns split among the threads (no synchronisation with 4
//               paths): the cost C(p, .) of each pixel - the pair's census of the row (each
//               thread the columns it needs: no census image is kept), census cost, LiDAR cost from the points
//               around p, fusion, all on the fly - is stored (8 bits, the only full volume;
//               in a LiDAR-gated frame each pixel's window alone, packed), and the upward paths (1 of 4, 3 of 8) recurse in row buffers; their state is
//               kept only at the first row of every chunk of kChunkRows rows (a checkpoint).
//   sweep down  top to bottom, chunk by chunk: first (columns split) the upward paths of the
//               chunk's rows again from the checkpoint below it, then the downward paths; then
//               (rows split) the left-to-right and right-to-left paths, S = the sum of all
//               paths, winner-takes-all + sub-pixel and, in the same visit of each pixel's S
//               (never a whole row of it), the right view's winners (left-right check, the
//               confidence's left-right difference) and the peak-ratio margin. One barrier per chunk (per row only for the diagonals of 8
//               paths): lock step per row would stall whenever another process takes a core.
//   two threads (the default on a 2-core machine) in bands instead: the top chunks' thread runs
//               the downward paths while the bottom chunks' runs the upward ones (each costing its
//               rows and keeping checkpoints; the band done first costs the other's last rows for it,
//               since a frame's LiDAR points weigh on one band), then, after the frame's one barrier, each walks its
//               band away from the other, continuing the other direction from the other band's
//               last row and recomputing its own from the checkpoints, with the horizontal paths
//               and the selection chunk by chunk. Split by columns, then by rows, half of every
//               chunk's path rows crossed between the cores twice: the vertical paths took as long
//               on two threads as on one (sweeps.cpp; BENCHMARK.md).
//   LR check, median   rows in parallel.
//   confidence  the core's part too (LiDAR distance, texture, disparity range, the model), rows
//               or columns in parallel, so that no stage of the frame runs on one thread.
//
// Why this shape: this machine class moves about 8 GB/s, so every full volume costs ~15 ms to
// write and read back. C is the one volume kept (it costs the most to recompute: 62-bit
// Hamming distances); the upward paths are recomputed per chunk instead of stored (one path
// step, cheaper than a second volume). Every sum is of the same non-negative integers in any
// order, so the result is cpu_ref's bit for bit whatever the thread count. Packing a gated
// frame's volume (KITTI 000007_10 with its scan: 64 % of the bytes at 80 disparities, 54 % at
// 128) saves no measurable time on the 2-core VM but 10-24 MiB of peak memory, and the volume
// grows with the windows instead of the range (BENCHMARK.md).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include "backends/common/cost_volume.hpp"
#include "backends/common/lidar_cost_table.hpp"
#include "backends/common/search_windows.hpp"
#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/huge_buffer.hpp"
#include "core/backend.hpp"

namespace lidar_sgm {
namespace cpu {

class CpuMatcher final : public MatcherBackend {
 public:
  Backend backend() const override { return Backend::Cpu; }
  bool searchesGatedWindows() const override { return true; }
  void run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
           FrameResults& out) override;
  /// The confidence's core part runs here too, with the backend's threads (confidence.cpp).
  bool computesConfidence() const override { return true; }

 private:
  /// One compute() call: the core's plan and how this backend lays it out.
  struct Frame {
    Frame(const FramePlan& framePlan, FrameResults& results) : plan(framePlan), out(results) {}
    const FramePlan& plan;
    FrameResults& out;
    GrayImageView left;  // empty in LiDAR-only mode (the confidence reads no image there)
    GrayImageView right;  // the cost rows' right image (empty in LiDAR-only mode)
    const LidarPoints* lidar = nullptr;
    /// The gated search's windows (Parameters::gatedSearch); null: every pixel the whole range.
    /// With them, the cost volume holds each pixel's window alone (packCostLayout).
    const SearchWindows* windows = nullptr;
    int threads = 1;
    int verticalPaths = 1;       // per sweep: 1 with 4 paths, 3 with 8
    bool paths8 = true;          // path costs in 8 bits (aggregation.cpp)
    std::size_t rowSlots = 0;    // path elements per image row: width * pathSlot(D)
    int planePad = 0;            // the right census planes' layout (census_cost.cpp)
    std::size_t planeStride = 0;
  };
  /// One thread's scratch rows and stage clocks.
  struct Worker {
    std::vector<std::uint8_t> stereo;    // C_S (fused mode)
    std::vector<std::uint8_t> lidar;     // C_L (fused mode)
    std::vector<std::uint8_t> vertical;  // C_V (Triple-SGM)
    std::vector<std::uint8_t> costRow;   // C of the row being costed, whole range (packed cost volume)
    std::vector<std::uint16_t> total;      // S of one pixel (the selection needs no more)
    std::vector<std::uint64_t> leftCensus;   // the left census of the row being costed
    std::vector<std::uint64_t> rightCensus;  // ... the right one
    std::vector<std::uint8_t> rightPlanes;   // ... as reversed byte planes (census_cost.cpp)
    std::vector<std::uint8_t> rightward;  // L of the left-to-right path along one row (slots, bytes)
    std::vector<std::uint8_t> leftward;   // ... and of the right-to-left path
    std::vector<std::uint16_t> rightScratch;  // the right view's winners of a row
    double censusCostMs = 0;
    double verticalCostMs = 0;
    double lidarCostMs = 0;
    double fuseMs = 0;
    double selectMs = 0;
  };
  /// Adds the time since the previous lap to one of a worker's stage clocks.
  class Lap {
   public:
    void operator()(double& ms) {
      const auto now = std::chrono::steady_clock::now();
      ms += std::chrono::duration<double, std::milli>(now - last_).count();
      last_ = now;
    }

   private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  };

  // Before the sweeps (cpu_matcher.cpp).
  void censusImages(Frame& frame, const FrameInputs& in);
  void lidarPixels(const Frame& frame);
  /// The gated search's windows (lidarSearchWindows, rows split among the threads).
  void searchWindows(const Frame& frame);
  /// Where each pixel's window lies in the packed cost volume (costRowStart_, costOffsets_).
  void packCostLayout(const Frame& frame);
  void runStages(const Frame& frame, ImageView<std::int16_t> disparity);
  /// Grows the buffers of the sweeps and the selection to the frame (kept between frames).
  void prepareBuffers(const Frame& frame);
  void preparePathRows(const Frame& frame, bool& newLayout);
  void prepareWorkers(const Frame& frame, bool newLayout);
  // The sweeps (sweeps.cpp): the costs, Eq. 1 along every path, and the selection.
  void aggregateAndSelect(const Frame& frame);
  template <typename PathT>
  void sweepUp(const Frame& frame);
  template <typename PathT>
  void sweepDown(const Frame& frame);
  /// Two threads: each its own band of rows, start to end (sweeps.cpp says why).
  static bool inBands(const Frame& frame);
  template <typename PathT>
  void sweepBands(const Frame& frame);
  /// Band 0 holds the chunks [0, splitChunk), band 1 the rest: its rows in the order of its own
  /// first-phase walk (band 0 downward, band 1 upward), and the i-th of them.
  static int bandRowCount(const Frame& frame, int band, int splitChunk);
  static int bandRow(const Frame& frame, int band, int i);
  template <typename PathT>
  void bandCosts(const Frame& frame, int band, int splitChunk, Worker& worker);
  template <typename PathT>
  void bandSelect(const Frame& frame, int band, int splitChunk, Worker& worker);
  /// The other thread's share of band `band`'s costs in phase 1 (sweeps.cpp).
  void bandHelp(const Frame& frame, int band, int splitChunk, Worker& worker);
  void costWholeRow(const Frame& frame, int y, Worker& worker);
  template <typename PathT>
  void stepRow(const Frame& frame, int i, int x0, int x1, int rowSet, int group, const std::uint8_t* row, int rowX0,
               RowWindows windows);
  template <typename PathT>
  void costAndStepRow(const Frame& frame, int y, int i, int x0, int x1, int rowSet, int group, Worker& worker);
  template <typename PathT, typename Entry>
  void verticalPathsOfChunk(const Frame& frame, int chunk, int parity, bool upward, int x0, int x1, bool lockStep,
                            const Entry& entry);
  /// Rows r0 .. r1-1 of a chunk whose vertical paths are in the chunk buffers `parity`.
  template <typename PathT>
  void selectChunkRows(const Frame& frame, int chunk, int parity, int r0, int r1, Worker& worker);
  /// A chunk's path row r of path k (k < verticalPaths: downward, else upward) and its minima.
  template <typename PathT>
  PathT* chunkPath(const Frame& frame, int parity, int k, int r);
  std::uint16_t* chunkMin(const Frame& frame, int parity, int k, int r);
  /// Path k's row in a checkpoint group (the sweep up's, or a band's) and its minima.
  template <typename PathT>
  std::pair<PathT*, std::uint16_t*> checkpointRow(const Frame& frame, int group, int k);
  /// Path buffers (bytes) viewed as path elements of type T.
  template <typename T, typename Bytes>
  static T* as(Bytes& bytes, std::size_t elementOffset = 0) {
    return reinterpret_cast<T*>(bytes.data()) + elementOffset;
  }
  /// The pair's census of row y that pixels x0 .. x1-1 need, in the worker's row buffers
  /// (row_costs.cpp): the left census, the right one as planes.
  static void censusRows(const Frame& frame, int y, int x0, int x1, Worker& worker);
  /// C of pixels x0 .. x1-1 of row y (row_costs.cpp): into `cost` from pixel x0 on in the whole
  /// range's layout, or (the census costs with windows.costOffset) packed from the row's start.
  void costRange(const Frame& frame, int y, int x0, int x1, std::uint8_t* cost, RowWindows windows, Worker& worker);
  /// Whether costRange writes a packed row itself (else the row is packed after it).
  static bool costsPackedInPlace(const Frame& frame);
  void lidarCostRange(const Frame& frame, int y, int x0, int x1, std::uint8_t* lidar);
  void tripleCostRange(const Frame& frame, int y, int x0, int x1, const std::uint8_t* lidar, std::uint8_t* cost,
                       Worker& worker, Lap& lap);
  /// Pixels x0 .. x1-1 of a costed row into the packed cost volume (sweeps.cpp).
  void packCostRow(const Frame& frame, int y, int x0, int x1, const std::uint8_t* row);
  /// Row y's search windows for the row kernels (none without the gated search).
  static RowWindows rowWindows(const Frame& frame, int y);
  /// Row y of the cost volume, and its windows with where their costs lie in it.
  std::uint8_t* costRow(const Frame& frame, int y);
  RowWindows costWindows(const Frame& frame, int y) const;
  // After the sweeps (cpu_matcher.cpp).
  void leftRightCheck(const Frame& frame);
  /// The confidence and the inputs the core would compute (the facade's computeConfidence), from
  /// the frame's left image, the support and the final disparity.
  void confidenceStage(const Frame& frame, ImageView<const std::int16_t> disparity);

  // Buffers kept between frames (resized only when the frame size changes).
  Image<std::uint64_t> upCensus_;
  HugeBuffer<std::uint8_t> cost_;        // C of every pixel, from the sweep up to the sweep down
  // A gated frame's cost volume holds each pixel's window alone (a KITTI frame: 64 % of the whole
  // range's bytes, written once and read twice): row y from costRowStart_[y], pixel x's window
  // from costOffsets_[y * width + x] in its row.
  std::vector<std::size_t> costRowStart_;
  HugePageVector<std::uint32_t> costOffsets_;  // 4 bytes a pixel: on huge pages, as the volume
  // Path rows hold uint8 or uint16 elements (aggregation.cpp): kept as bytes, their slots' ends
  // marked with all ones (both types' sentinel) once per layout (type, width, D). A frame's stereo
  // witness runs on this matcher before the frame itself, so the rows of the last two layouts are
  // kept: re-marking one set for the other layout touched every cache line of ~9 MB twice a frame.
  struct PathRows {
    HugePageVector<std::uint8_t> rows;         // sweep up: every path's double-buffered row (slots)
    HugePageVector<std::uint8_t> chunks;       // sweep down: a chunk's path rows (slots), two parities
    HugePageVector<std::uint8_t> checkpoints;  // sweep up: the upward paths at every chunk's first row
    std::size_t layout = 0;
    std::uint64_t lastUse = 0;
  };
  PathRows pathSets_[2];
  PathRows* paths_ = &pathSets_[0];  // the frame's set (preparePathRows)
  std::uint64_t pathSetUses_ = 0;  // preparePathRows calls, the sets' clock for lastUse
  std::size_t workerLayout_ = 0;  // the layout the workers' horizontal path rows are marked for
  std::vector<std::uint16_t> pathMins_;
  static constexpr int kChunkRows = 8;
  std::vector<std::uint16_t> chunkMins_;    // the chunk path rows' minima
  std::vector<std::uint16_t> checkpointMins_;
  std::vector<Worker> workers_;
  // Who costs each row in the bands' phase 1: the first band to claim it; kHelped once the other
  // band (bandHelp) has put its costs in the volume.
  enum RowClaim : std::uint8_t { kUnclaimed, kClaimed, kHelped };
  std::vector<std::atomic<std::uint8_t>> rowClaims_;
  SearchWindows windows_;  // the gated search's windows (Parameters::gatedSearch)
  Image<std::int16_t> rawDisparity_;
  Image<std::int16_t> bestIndex_;
  Image<std::int16_t> rightIndex_;
  Image<std::uint8_t> coverage_;
  Image<std::uint8_t> touched_;  // 1 where a LiDAR point lies in the pixel's 3x3 neighbourhood
  Image<std::uint16_t> lidarWeights_;  // w(p) of Eq. 5 with an adaptive alpha (a fixed one needs none)
  ConfidenceBuffers confidenceBuffers_;
  LidarCostRows lidarRows_;  // Eq. 4's table for the sigma and cap below, laid out per point's sub-pixel phase
  float tableSigma_ = 0;
  int tableCap_ = -1;
};

}  // namespace cpu
}  // namespace lidar_sgm
