// The paper's Table I and Table II for the KITTI142 protocol, beside the paper's own figures
// (Sec. IV, Tables I and II: the same 142-frame set, of which ../shared/data holds 29).
#include <cstdio>
#include <sstream>

#include "report_format.hpp"
#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

std::string pixels(double value) { return fixed(value, 3); }

/// The objects whose GT lies off the frame's own scan, and Table II without them (scan_agreement.hpp).
void appendScanAgreement(std::ostringstream& out, const ProtocolResult& result, const std::vector<MethodResult>& medians) {
  std::ostringstream off;
  int objects = 0;
  int offCount = 0;
  for (const FrameResult& frame : result.frames) {
    for (const ObjectScanAgreement& a : frame.scanAgreement) {
      if (a.points < kScanAgreementMinPoints) continue;
      ++objects;
      if (!a.offTheScan()) continue;
      ++offCount;
      off << "| " << frame.frame << " | " << a.object << " | " << a.points << " | " << fixed(a.medianDifference, 2)
          << " |\n";
    }
  }
  if (objects == 0) return;
  out << "\nThe GT against the frame's own scan: of " << objects << " objects with at least "
      << kScanAgreementMinPoints << " scan pixels, " << offCount << " lie more than " << fixed(kScanAgreementTolerancePx, 1)
      << " px (median over the object's scan pixels) behind their scan, where a LiDAR return cannot be";
  if (offCount == 0) {
    out << ".\n";
    return;
  }
  out << ": a method that follows the scan there is scored wrong.\n\n"
      << "| frame | object | scan pixels | median scan - GT px |\n| --- | ---: | ---: | ---: |\n"
      << off.str();
  out << "\nTable II without those objects' pixels (over all the frames' pixels)\n\n"
      << "| method | error bg % | error fg % | error total % | density % |\n"
      << "| --- | ---: | ---: | ---: | ---: |\n";
  for (const MethodResult& m : medians) {
    if (!m.objectSplitOnScan) continue;
    const ObjectSplitMetrics& o = *m.objectSplitOnScan;
    out << "| " << label(m) << " | " << percent(o.background) << " | " << percent(o.foreground) << " | "
        << percent(o.total) << " | " << percent(o.density) << " |\n";
  }
}

}  // namespace

ObjectSplitMetrics meanObjectSplit(const std::vector<ObjectSplitMetrics>& frames) {
  ObjectSplitMetrics mean = pooledObjectSplit(frames);  // the counts summed
  if (frames.empty()) return mean;
  mean.background = mean.foreground = mean.total = mean.density = 0;
  for (const ObjectSplitMetrics& f : frames) {
    mean.background += f.background;
    mean.foreground += f.foreground;
    mean.total += f.total;
    mean.density += f.density;
  }
  const double n = static_cast<double>(frames.size());
  mean.background /= n;
  mean.foreground /= n;
  mean.total /= n;
  mean.density /= n;
  return mean;
}

ObjectSplitMetrics pooledObjectSplit(const std::vector<ObjectSplitMetrics>& frames) {
  ObjectSplitMetrics sum;
  for (const ObjectSplitMetrics& f : frames) {
    sum.gtPixels += f.gtPixels;
    sum.foregroundPixels += f.foregroundPixels;
    sum.estimatedBackground += f.estimatedBackground;
    sum.estimatedForeground += f.estimatedForeground;
    sum.wrongBackground += f.wrongBackground;
    sum.wrongForeground += f.wrongForeground;
  }
  return withShares(sum);
}

std::string paperTablesMarkdown(const ProtocolResult& result) {
  const std::vector<MethodResult> medians = methodMedians(result);
  bool any = false;
  for (const MethodResult& m : medians) any = any || m.objectSplit.has_value();
  if (!any) return {};
  std::ostringstream out;
  out << "\nThe paper's Table I (median over the frames; every GT pixel scored, as the paper; the last "
         "column on the GT pixels no input point covers)\n\n"
      << "| method | correct % | RMSE px | correct % where no input point is |\n"
      << "| --- | ---: | ---: | ---: |\n";
  for (const MethodResult& m : medians) {
    out << "| " << label(m) << " | " << percent(m.metrics.correct) << " | " << pixels(m.metrics.rmse) << " | "
        << (m.uncovered ? percent(m.uncovered->correct) : "-") << " |\n";
  }
  out << "| paper: stereo-only SGM (alpha 0), 142 frames | 90.19 | 0.88 | - |\n"
      << "| paper: LiDAR-only SGM (alpha 1) | 94.16 | 0.57 | - |\n"
      << "| paper: LiDAR-SGM (alpha 0.7) | 95.00 | 0.56 | - |\n";
  out << "\nThe paper's Table II (wrong pixels, error > 3 px and > 5 %, among the estimated ones; over all the "
         "frames' pixels, as KITTI's devkit counts them; last columns: the mean of the frames' shares)\n\n"
      << "| method | error bg % | error fg % | error total % | density % | frame mean: error fg % | error total % |\n"
      << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const MethodResult& m : medians) {
    if (!m.objectSplit) continue;
    const ObjectSplitMetrics& o = *m.objectSplit;
    out << "| " << label(m) << " | " << percent(o.background) << " | " << percent(o.foreground) << " | "
        << percent(o.total) << " | " << percent(o.density) << " | "
        << (m.objectSplitFrameMean ? percent(m.objectSplitFrameMean->foreground) : "-") << " | "
        << (m.objectSplitFrameMean ? percent(m.objectSplitFrameMean->total) : "-") << " |\n";
  }
  out << "| paper: Stereo-SGM | 3.64 | 9.78 | 4.54 | 92.23 |\n"
      << "| paper: LiDAR-SGM (alpha 0.7) | 2.06 | 14.47 | 3.87 | 97.46 |\n"
      << "| paper: Tri.BF | 2.62 | 9.01 | 3.60 | 98.59 |\n"
      << "| paper: Cheng et al. (learned) | - | - | 1.98 | 100.00 |\n";
  appendScanAgreement(out, result, medians);
  return out.str();
}

}  // namespace eval
}  // namespace lidar_sgm
