#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {
namespace {

TEST(Parameters, PaperDefaultsAreValid) {
  const Parameters p;
  EXPECT_EQ(validationError(p), "");
  EXPECT_EQ(p.P1, 10);
  EXPECT_EQ(p.P2, 100);
  EXPECT_EQ(p.paths, 4);
  EXPECT_FLOAT_EQ(p.alpha, 0.7f);
  EXPECT_FLOAT_EQ(p.sigma, 2.0f);
  EXPECT_EQ(p.numDisparities, 128);
  EXPECT_EQ(p.medianSize, 5);
}

struct BadParameter {
  const char* name;
  void (*apply)(Parameters&);
  const char* expectedText;
};

class RejectsParameter : public ::testing::TestWithParam<BadParameter> {};

TEST_P(RejectsParameter, WithAMessageNamingItAndItsRange) {
  Parameters p;
  GetParam().apply(p);
  const std::string error = validationError(p);
  EXPECT_NE(error.find(GetParam().name), std::string::npos) << error;
  EXPECT_NE(error.find(GetParam().expectedText), std::string::npos) << error;
  try {
    validate(p);
    FAIL() << "validate accepted " << GetParam().name;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(error, e.what());
  }
  EXPECT_THROW(Matcher::create(Backend::CpuRef, p), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(
    Parameters, RejectsParameter,
    ::testing::Values(
        BadParameter{"numDisparities", [](Parameters& p) { p.numDisparities = 100; }, "multiple of 16"},
        BadParameter{"numDisparities", [](Parameters& p) { p.numDisparities = 0; }, "[16, 512]"},
        BadParameter{"numDisparities", [](Parameters& p) { p.numDisparities = 528; }, "[16, 512]"},
        BadParameter{"minDisparity", [](Parameters& p) { p.minDisparity = -600; }, "[-512, 512]"},
        BadParameter{"P2", [](Parameters& p) { p.P2 = p.P1; }, "greater than P1"},
        BadParameter{"P2", [](Parameters& p) { p.P1 = 50; p.P2 = 20; }, "greater than P1 (50)"},
        BadParameter{"P2", [](Parameters& p) { p.P2 = 5000; }, "at most 4000"},
        BadParameter{"P1", [](Parameters& p) { p.P1 = -1; }, "[0, 3999]"},
        BadParameter{"paths", [](Parameters& p) { p.paths = 6; }, "4 or 8"},
        BadParameter{"alpha", [](Parameters& p) { p.alpha = 1.5f; }, "[0, 1]"},
        BadParameter{"alpha", [](Parameters& p) { p.alpha = -0.1f; }, "[0, 1]"},
        BadParameter{"alpha", [](Parameters& p) { p.alpha = std::numeric_limits<float>::quiet_NaN(); }, "[0, 1]"},
        BadParameter{"alphaMode", [](Parameters& p) { p.alphaMode = static_cast<AlphaMode>(7); },
                     "Fixed (0) or Adaptive (1)"},
        BadParameter{"sigma", [](Parameters& p) { p.sigma = 0.0f; }, "[0.1, 100]"},
        BadParameter{"sigma", [](Parameters& p) { p.sigma = std::numeric_limits<float>::infinity(); }, "[0.1, 100]"},
        BadParameter{"lidarCostCap", [](Parameters& p) { p.lidarCostCap = 0; }, "[1, 255]"},
        BadParameter{"lidarCostCap", [](Parameters& p) { p.lidarCostCap = 256; }, "[1, 255]"},
        BadParameter{"uniquenessRatio", [](Parameters& p) { p.uniquenessRatio = 100; }, "[0, 99]"},
        BadParameter{"disp12MaxDiff", [](Parameters& p) { p.disp12MaxDiff = -1; }, "[0, numDisparities (128)]"},
        BadParameter{"lidarCoverageRows", [](Parameters& p) { p.lidarCoverageRows = 0; }, "[1, 64]"},
        BadParameter{"gatedSearchMargin", [](Parameters& p) { p.gatedSearchMargin = -1; }, "[0, 512] px"},
        BadParameter{"gatedSearchMargin", [](Parameters& p) { p.gatedSearchMargin = 513; }, "[0, 512] px"},
        BadParameter{"gatedSearchRows", [](Parameters& p) { p.gatedSearchRows = 65; }, "[0, 64]"},
        BadParameter{"medianSize", [](Parameters& p) { p.medianSize = 7; }, "0 (off), 3 or 5"}),
    [](const ::testing::TestParamInfo<BadParameter>& paramInfo) {
      return std::string(paramInfo.param.name) + std::to_string(paramInfo.index);
    });

TEST(Parameters, AlphaModeNamesRoundTripAndUnknownOnesAreRejected) {
  EXPECT_EQ(Parameters().alphaMode, AlphaMode::Fixed);
  for (const AlphaMode mode : {AlphaMode::Fixed, AlphaMode::Adaptive}) {
    EXPECT_EQ(alphaModeFromString(toString(mode)), mode);
  }
  try {
    alphaModeFromString("sometimes");
    ADD_FAILURE() << "'sometimes' was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "alpha mode 'sometimes': must be fixed or adaptive");
  }
}

TEST(Parameters, SetParametersKeepsTheOldOnesWhenRejected) {
  auto matcher = Matcher::create(Backend::CpuRef);
  Parameters bad;
  bad.paths = 3;
  EXPECT_THROW(matcher->setParameters(bad), std::invalid_argument);
  EXPECT_EQ(matcher->parameters().paths, 4);
  Parameters good;
  good.paths = 8;
  matcher->setParameters(good);
  EXPECT_EQ(matcher->parameters().paths, 8);
}

TEST(Backends, NamesRoundTripAndUnknownNamesAreRejected) {
  for (Backend b : {Backend::Auto, Backend::CpuRef, Backend::Cpu, Backend::Cuda}) {
    EXPECT_EQ(backendFromString(toString(b)), b);
  }
  try {
    backendFromString("gpu");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'gpu'"), std::string::npos);
  }
}

TEST(Backends, UnbuiltBackendsFailLoudly) {
  EXPECT_TRUE(isAvailable(Backend::CpuRef));
  for (Backend b : {Backend::Cpu, Backend::Cuda}) {
    if (isAvailable(b)) continue;
    EXPECT_THROW(Matcher::create(b), std::runtime_error);
  }
  // Auto is the fastest backend that runs here: cuda with a device, cpu with Highway, else cpu_ref.
  EXPECT_EQ(Matcher::create(Backend::Auto)->backend(), isAvailable(Backend::Cuda) ? Backend::Cuda
                                                       : isAvailable(Backend::Cpu) ? Backend::Cpu
                                                                                   : Backend::CpuRef);
  try {
    Matcher::create(Backend::Cuda);
    if (!isAvailable(Backend::Cuda)) ADD_FAILURE() << "cuda cannot run here but was created";
  } catch (const std::runtime_error& e) {
    // Not built: the backends that are; built without a device: why it cannot run.
    const std::string why = unavailableReason(Backend::Cuda);
    if (why.find("not built") != std::string::npos) {
      EXPECT_NE(std::string(e.what()).find("available: "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("cpu_ref"), std::string::npos) << e.what();
    } else {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace lidar_sgm
