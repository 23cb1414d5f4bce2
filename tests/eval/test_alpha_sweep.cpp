// The alpha sweep and one group run: the alphas, the best one, and results that do not depend
// on the thread count.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "lidar_sgm/eval/group_run.hpp"
#include "lidar_sgm/eval/protocols.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

TEST(SweepAlphas, GridPlusThePapersAlpha) {
  const std::vector<double> tenth = sweepAlphas(0.1);
  ASSERT_EQ(tenth.size(), 11u);
  EXPECT_EQ(tenth[7], 0.7);  // exactly: rounded, so it matches kPaperAlpha
  EXPECT_EQ(tenth.back(), 1.0);
  EXPECT_EQ(sweepAlphas(0.25), (std::vector<double>{0.0, 0.25, 0.5, 0.7, 0.75, 1.0}));
  EXPECT_EQ(sweepAlphas(1.0), (std::vector<double>{0.0, 0.7, 1.0}));
  EXPECT_THROW(sweepAlphas(0.0), std::invalid_argument);
  EXPECT_THROW(sweepAlphas(1.5), std::invalid_argument);
}

DisparityMetrics correctAndRmse(double correct, double rmse) {
  DisparityMetrics m;
  m.correct = correct;
  m.rmse = rmse;
  return m;
}

TEST(BestAlphaIndex, HighestCorrectThenLowestRmse) {
  EXPECT_EQ(bestAlphaIndex({{0.0, correctAndRmse(0.8, 1.0)}, {0.5, correctAndRmse(0.9, 1.0)},
                            {1.0, correctAndRmse(0.85, 0.1)}}),
            1u);
  EXPECT_EQ(bestAlphaIndex({{0.0, correctAndRmse(0.9, 1.0)}, {0.5, correctAndRmse(0.9, 0.5)}}), 1u);  // tie
  EXPECT_EQ(bestAlphaIndex({{0.0, correctAndRmse(0.9, 0.5)}, {0.5, correctAndRmse(0.9, 0.5)}}), 0u);  // first
  EXPECT_THROW(bestAlphaIndex({}), std::invalid_argument);
}

TEST(RunGroup, EveryMethodThePapersAlphaAndTheBestPerFrameWhateverTheThreads) {
  P3Options o;
  o.frames = 2;
  o.width = 310;
  o.height = 94;
  FrameGroup group;
  group.name = "P3 tiny";
  group.frames = loadP3(o);
  group.methods = {{MethodKind::StereoSgm, 0.0}, {MethodKind::LidarSgm, 1.0}};
  GroupRunOptions options;
  options.alphas = sweepAlphas(0.5);  // 0, 0.5, 0.7, 1
  options.threads = 1;
  const ProtocolResult one = runGroup(group, options);
  options.threads = 3;
  const ProtocolResult three = runGroup(group, options);

  ASSERT_EQ(one.frames.size(), 2u);
  ASSERT_EQ(one.sweeps.size(), 1u);
  EXPECT_EQ(one.sweeps[0].kind, MethodKind::FusedSgm);
  ASSERT_EQ(one.sweeps[0].medians.size(), 4u);
  const std::size_t best = bestAlphaIndex(one.sweeps[0].medians);
  for (std::size_t i = 0; i < one.frames.size(); ++i) {
    const std::vector<MethodResult>& methods = one.frames[i].methods;
    ASSERT_EQ(methods.size(), 4u);  // the group's two, the paper's alpha, the sweep's best
    EXPECT_EQ(methods[0].method.kind, MethodKind::StereoSgm);
    EXPECT_EQ(methods[1].method.kind, MethodKind::LidarSgm);
    EXPECT_TRUE(sameMethod(methods[2].method, {MethodKind::FusedSgm, kPaperAlpha}));
    EXPECT_FALSE(methods[2].bestAlpha);
    EXPECT_TRUE(methods[3].bestAlpha);
    EXPECT_EQ(methods[3].method.alpha, options.alphas[best]);
    for (std::size_t m = 0; m < methods.size(); ++m) {
      EXPECT_EQ(methods[m].metrics.correct, three.frames[i].methods[m].metrics.correct) << i << " " << m;
      EXPECT_EQ(methods[m].metrics.rmse, three.frames[i].methods[m].metrics.rmse) << i << " " << m;
    }
  }
  EXPECT_THROW(runGroup(group, GroupRunOptions{}), std::invalid_argument);  // no alphas
}

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
