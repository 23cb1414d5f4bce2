// The PCL-style shim in front of CLI11 and the Arguments built on it: every spelling a user
// types today keeps its meaning, and values that look like options stay values.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/arguments.hpp"
#include "common/pcl_style_options.hpp"
#include "common/config_arguments.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

using Strings = std::vector<std::string>;

class PclStyleOptions : public ::testing::Test {
 protected:
  PclStyleOptions() {
    app_.add_option("--alpha");
    app_.add_option("--min_disparity");
    app_.add_option("--n");
    app_.add_flag("--keep_organized");
    app_.add_option("files");
  }
  CLI::App app_;
};

TEST_F(PclStyleOptions, RegisteredSingleDashNamesBecomeLongOptionsWithTheirValueAttached) {
  EXPECT_EQ(toCli11Arguments(app_, {"-alpha", "0.7", "-keep_organized", "-n", "3"}),
            (Strings{"--alpha=0.7", "--keep_organized", "--n=3"}));
  EXPECT_EQ(toCli11Arguments(app_, {"--alpha", "0.7", "--alpha=0.5", "-alpha=0.2"}),
            (Strings{"--alpha=0.7", "--alpha=0.5", "--alpha=0.2"}));
}

TEST_F(PclStyleOptions, ValuesThatLookLikeOptionsStayValues) {
  EXPECT_EQ(toCli11Arguments(app_, {"-min_disparity", "-16"}), (Strings{"--min_disparity=-16"}));
  EXPECT_EQ(toCli11Arguments(app_, {"-alpha", "-bogus"}), (Strings{"--alpha=-bogus"}));
  EXPECT_EQ(toCli11Arguments(app_, {"-alpha", ""}), (Strings{"--alpha", ""}));
}

TEST_F(PclStyleOptions, PositionalsNegativeNumbersUnknownAndShortOptionsAreCopied) {
  const Strings line{"in.bin", "-16", "-", "-h", "-bogus", "--bogus", "out.pcd"};
  EXPECT_EQ(toCli11Arguments(app_, line), line);
}

TEST_F(PclStyleOptions, EverythingAfterTheEndOfOptionsIsCopied) {
  EXPECT_EQ(toCli11Arguments(app_, {"-keep_organized", "--", "-alpha", "x"}),
            (Strings{"--keep_organized", "--", "-alpha", "x"}));
}

TEST_F(PclStyleOptions, AValueOptionWithoutItsValueIsAnErrorNamingIt) {
  for (const Strings& line : {Strings{"-alpha"}, Strings{"--alpha"}, Strings{"-alpha", "-keep_organized"},
                              Strings{"-alpha", "--n", "3"}}) {
    try {
      toCli11Arguments(app_, line);
      ADD_FAILURE() << line.front() << " was accepted without its value";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "option -alpha needs a value");
    }
  }
}

Arguments parse(const Strings& line) {
  std::vector<const char*> argv{"tool"};
  for (const std::string& s : line) argv.push_back(s.c_str());
  return Arguments(static_cast<int>(argv.size()), argv.data(), {"alpha", "min_disparity", "out"}, {"keep_organized"});
}

TEST(ArgumentsOnCli11, ReadsEverySpellingAsBefore) {
  const Arguments a = parse({"in.bin", "-alpha", "0.25", "-min_disparity", "-16", "--keep_organized", "out.pcd"});
  EXPECT_EQ(a.positionals(), (Strings{"in.bin", "out.pcd"}));
  EXPECT_DOUBLE_EQ(a.number("alpha", 0.7), 0.25);
  EXPECT_EQ(a.integer("min_disparity", 0), -16);
  EXPECT_TRUE(a.has("keep_organized"));
  EXPECT_FALSE(a.has("out"));
  EXPECT_EQ(a.text("out", "fallback"), "fallback");
  EXPECT_FALSE(a.helpRequested());
  EXPECT_FALSE(a.versionRequested());
}

TEST(ArgumentsOnCli11, TheLastOfARepeatedOptionWins) {
  EXPECT_DOUBLE_EQ(parse({"-alpha", "0.1", "--alpha=0.9"}).number("alpha", 0.7), 0.9);
}

TEST(ArgumentsOnCli11, HelpAndVersionInEverySpelling) {
  for (const char* help : {"-h", "-help", "--help"}) EXPECT_TRUE(parse({help}).helpRequested()) << help;
  for (const char* version : {"-version", "--version"}) EXPECT_TRUE(parse({version}).versionRequested()) << version;
  EXPECT_TRUE(parse({"-bogus", "-h"}).helpRequested());  // help answers whatever else the line holds
}

TEST(ArgumentsOnCli11, BadLinesAreRejectedWithTheProblemNamed) {
  const std::pair<Strings, std::string> cases[] = {
      {{"-bogus", "1"}, "unknown option -bogus (see -h)"},
      {{"--bogus=1"}, "unknown option --bogus=1 (see -h)"},
      {{"-alpha"}, "option -alpha needs a value"},
  };
  for (const auto& [line, message] : cases) {
    try {
      parse(line);
      ADD_FAILURE() << line.front() << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(e.what(), message);
    }
  }
  try {
    parse({"-alpha", "abc"}).number("alpha", 0.7);
    ADD_FAILURE() << "'abc' was read as a number";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "option -alpha: 'abc' is not a finite number");
  }
}

TEST(ConfigArguments, TheCommandLineGivesTheTablesConfiguration) {
  const auto parseConfig = [](const Strings& line, OptionScope scope) {
    std::vector<const char*> argv{"tool"};
    for (const std::string& s : line) argv.push_back(s.c_str());
    const Arguments args(static_cast<int>(argv.size()), argv.data(), joined(configValueOptions(scope), {"out"}),
                         configFlagOptions(scope));
    return configFrom(args, scope);
  };
  EXPECT_EQ(parseConfig({}, OptionScope::Cloud).matcher.alphaMode, AlphaMode::Fixed);
  EXPECT_EQ(parseConfig({"-alpha_mode", "adaptive"}, OptionScope::Cloud).matcher.alphaMode, AlphaMode::Adaptive);
  EXPECT_EQ(parseConfig({"--alpha_mode=fixed"}, OptionScope::Disparity).matcher.alphaMode, AlphaMode::Fixed);
  // A tool's own options are the tool's; the table's flags and values are read whole.
  const DensifierConfig c =
      parseConfig({"-out", "x", "-no_lr_check", "-min_disparity", "-16", "-stride", "2"}, OptionScope::Cloud);
  EXPECT_FALSE(c.matcher.lrCheck);
  EXPECT_EQ(c.matcher.minDisparity, -16);
  EXPECT_EQ(c.rangeMode, DisparityRangeMode::Fixed);
  EXPECT_EQ(c.reprojection.stride, 2);
  // The cloud's options are not the disparity tool's.
  EXPECT_THROW(parseConfig({"-stride", "2"}, OptionScope::Disparity), std::invalid_argument);
  try {
    parseConfig({"-alpha_mode", "sometimes"}, OptionScope::Cloud);
    ADD_FAILURE() << "'sometimes' was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "option -alpha_mode: 'sometimes' must be fixed or adaptive");
  }
}

}  // namespace
}  // namespace apps
}  // namespace lidar_sgm
