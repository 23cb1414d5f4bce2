#pragma once
/// @file gated_stages.hpp  The stages of the LiDAR-gated search (Parameters::gatedSearch), on
/// per-pixel search windows (search_windows.hpp, lidarSearchWindows). The functions in namespace
/// `cpu_ref` are the specification, as in stages.hpp.
///
/// Disparity indices d count from the frame's minDisparity, as everywhere: W(p) = [first(p),
/// first(p) + count(p)) is pixel p's window inside [0, D). Only d in W(p) is stored and only d in
/// W(p) is a candidate for p; every rule below is the ungated one restricted to the windows, so
/// that with W(p) = [0, D) at every pixel each stage is bit for bit the ungated stage.
///
/// Path costs (Eq. 1), for d in W(p), with q = p - r the previous pixel on path r:
///   L_r(p, d) = C(p, d)                                                       where q is outside the image,
///   L_r(p, d) = C(p, d) + min(A, B-, B+, M + P2) - M                          otherwise, with
///     M  = min over k in W(q) of L_r(q, k),
///     A  = L_r(q, d)          if d     in W(q), else absent (+infinity),
///     B- = L_r(q, d - 1) + P1 if d - 1 in W(q), else absent,
///     B+ = L_r(q, d + 1) + P1 if d + 1 in W(q), else absent.
/// W(q) is never empty, so M + P2 is always present: L_r(p, d) <= C(p, d) + P2, and the sum over
/// 8 paths still fits 16 bits. S(p, d) = sum over r of L_r(p, d) (Eq. 2), for d in W(p).
///
/// Selection (Eq. 2): the winner b is the first minimum of S(p, .) over W(p); the uniqueness rule
/// compares it with every d in W(p) with |d - b| > 1; the parabola needs b - 1 and b + 1 in W(p)
/// (a winner on its window's edge keeps its integer disparity, as one on the range's edge does).
/// The right view (left-right check, confidence): right pixel xr takes the first minimum of
/// S(xr + minDisparity + d, d) over the d with that left pixel inside the image AND d in its
/// window; none (every such entry outside a window): -1, which the check treats as it treats a
/// right pixel without a winner. The peak-ratio margin's rival S2 runs over W(p) as well.

#include <cstdint>

#include "backends/common/search_windows.hpp"
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

/// The matching cost restricted to the windows: windowed(p, d) = cost(p, d) for d in W(p).
/// (The matching cost of one (p, d) does not depend on any other, so restricting it is exact.)
void restrictToWindows(const MatchingCostVolume& cost, WindowedMatchingCost& windowed);

/// Eq. 1 on the windows (above) along 4 or 8 paths; `sum` (laid out on cost's windows) receives S.
void aggregatePaths(const WindowedMatchingCost& cost, int P1, int P2, int paths, WindowedAggregatedCost& sum);

/// One step of Eq. 1 on the windows for d in p's window, given the previous pixel's path costs
/// `previous` (entry k is disparity index previousFirst + k, previousCount entries) and their
/// minimum M.
int pathCostStep(int matchingCost, const std::uint16_t* previous, int previousFirst, int previousCount, int d,
                 int previousMin, int P1, int P2);

/// Winner-takes-all on the windows, with uniqueness and parabola (above). bestIndex holds the
/// index d in [0, D) (not the offset in the window).
void selectDisparity(const WindowedAggregatedCost& sum, int minDisparity, int uniquenessRatio, bool subpixel,
                     SelectedDisparity out);

/// The right view's winner index on the windows (above).
void rightDisparityIndex(const WindowedAggregatedCost& sum, int minDisparity, ImageView<std::int16_t> rightIndex);

/// The peak-ratio margin (stages.hpp) with S2 over the winner's window.
void peakRatioMargin(const WindowedAggregatedCost& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost);

}  // namespace cpu_ref
}  // namespace lidar_sgm
