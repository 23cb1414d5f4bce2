// The option table (config_options.hpp): its defaults are DensifierConfig's, each option reads
// its own setting and nothing else, the rules that join options, and the messages for bad values.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "lidar_sgm/pipeline/config_options.hpp"

namespace lidar_sgm {
namespace {

/// Every option's value in `config`, by name.
std::map<std::string, std::string> values(const DensifierConfig& config) {
  std::map<std::string, std::string> out;
  for (const DensifierOption& o : densifierOptions()) out[o.name] = o.value(config);
  return out;
}

/// A value other than the default, in range, for each kind of option.
std::string otherValue(const DensifierOption& o) {
  static const std::map<std::string, std::string> choices{
      {"alpha_mode", "adaptive"}, {"disparity_range", "fixed"}, {"census", "cs9x7"}, {"backend", "cpu_ref"},
      {"frame", "camera"},        {"paths", "8"},               {"median", "3"},     {"scale", "0.5"},
      {"max_depth", "40"},        {"min_confidence", "0.25"},   {"alpha", "0.25"},   {"num_disparities", "64"},
      {"min_disparity", "-16"},   {"p2", "150"},                {"sky_texture", "2.5"},
      {"lidar_consistency_ratio", "3"}, {"hidden_lidar_scale", "1"}};
  if (o.kind == OptionKind::Flag) return "true";
  const auto it = choices.find(o.name);
  if (it != choices.end()) return it->second;
  return std::to_string(std::stoi(defaultValue(o)) + 2);  // the remaining integers: +2 stays in range
}

TEST(ConfigOptions, TheDefaultsAreDensifierConfigsAndReadBackUnchanged) {
  const DensifierConfig defaults;
  EXPECT_EQ(values(configFromOptions({}, {})), values(defaults));
  for (const DensifierOption& o : densifierOptions()) {
    SCOPED_TRACE(o.name);
    DensifierConfig c;
    o.apply(c, o.value(c));
    EXPECT_EQ(values(c), values(defaults));
  }
}

TEST(ConfigOptions, EachOptionSetsItsOwnSettingAndNothingElse) {
  const std::map<std::string, std::string> defaults = values(DensifierConfig());
  std::set<std::string> names;
  for (const DensifierOption& o : densifierOptions()) {
    SCOPED_TRACE(o.name);
    EXPECT_TRUE(names.insert(o.name).second) << "listed twice";
    EXPECT_EQ(findDensifierOption(o.name), &o);
    EXPECT_FALSE(o.help.empty());
    EXPECT_EQ(o.kind == OptionKind::Flag, std::string(o.valueName).empty());
    DensifierConfig c;
    const std::string value = otherValue(o);
    o.apply(c, value);
    std::map<std::string, std::string> expected = defaults;
    expected[o.name] = value;
    EXPECT_EQ(o.value(c), value);
    EXPECT_NE(value, defaults.at(o.name)) << "the option changed nothing";
    EXPECT_EQ(values(c), expected);
  }
  EXPECT_EQ(names.size(), 44u);  // the table as documented in docs/LIBRARY.md
  EXPECT_EQ(findDensifierOption("nonsense"), nullptr);
}

TEST(ConfigOptions, ScopesListTheDisparitysOptionsEverywhereAndTheCloudsOnlyWithACloud) {
  const auto named = [](OptionScope scope) {
    std::set<std::string> out;
    for (const DensifierOption* o : densifierOptions(scope)) out.insert(o->name);
    return out;
  };
  const std::set<std::string> disparity = named(OptionScope::Disparity);
  const std::set<std::string> cloud = named(OptionScope::Cloud);
  EXPECT_EQ(cloud.size(), densifierOptions().size());
  for (const char* name : {"alpha", "backend", "min_confidence", "no_sky_filter", "no_crop_to_scan"}) {
    EXPECT_EQ(disparity.count(name), 1u) << name;
  }
  for (const char* name : {"frame", "max_depth", "stride", "keep_organized", "no_occlusion_filter"}) {
    EXPECT_EQ(disparity.count(name), 0u) << name;
    EXPECT_EQ(cloud.count(name), 1u) << name;
  }
}

TEST(ConfigOptions, TheRulesThatJoinOptions) {
  EXPECT_EQ(configFromOptions({}, {}).rangeMode, DisparityRangeMode::FromLidar);
  EXPECT_EQ(configFromOptions({{"num_disparities", "64"}}, {}).rangeMode, DisparityRangeMode::Fixed);
  EXPECT_EQ(configFromOptions({{"min_disparity", "-16"}}, {}).rangeMode, DisparityRangeMode::Fixed);
  EXPECT_EQ(configFromOptions({{"num_disparities", "64"}, {"disparity_range", "lidar"}}, {}).rangeMode,
            DisparityRangeMode::FromLidar);
  const DensifierConfig noConfidence = configFromOptions({}, {"no_confidence"});
  EXPECT_FALSE(noConfidence.matcher.confidence);
  EXPECT_EQ(noConfidence.minConfidence, 0.0);
  EXPECT_EQ(configFromOptions({{"min_confidence", "0"}}, {"no_confidence"}).minConfidence, 0.0);
  const DensifierConfig noLimit = configFromOptions({{"max_depth", "0"}}, {});
  EXPECT_TRUE(std::isinf(noLimit.reprojection.maxDepth));
  EXPECT_NE(optionsHelp(OptionGroup::Output, OptionScope::Cloud).find("-max_depth M"), std::string::npos);
}

TEST(ConfigOptions, ABadValueOrNameIsRefusedNamingIt) {
  const std::map<std::map<std::string, std::string>, std::string> cases{
      {{{"alpha", "high"}}, "option -alpha: 'high' is not a finite number"},
      {{{"paths", "four"}}, "option -paths: 'four' is not an integer"},
      {{{"census", "5x5"}}, "option -census: '5x5' must be 9x7 or cs9x7"},
      {{{"frame", "world"}}, "option -frame: 'world' must be lidar or camera"},
      {{{"disparity_range", "near"}}, "option -disparity_range: 'near' must be lidar or fixed"},
      {{{"alpha_mode", "sometimes"}}, "option -alpha_mode: 'sometimes' must be fixed or adaptive"},
      {{{"backend", "tpu"}}, "option -backend: unknown backend 'tpu'"},
      {{{"stride", "0"}}, "option -stride: must be >= 1"},
      {{{"max_depth", "-1"}}, "option -max_depth: must be >= 0 [m] (0 = keep all)"},
      {{{"alpha", "1.5"}}, "invalid parameter alpha = 1.5: must be in [0, 1]"},
      {{{"gated_search_margin", "-1"}}, "invalid parameter gatedSearchMargin = -1: must be in [0, 512] px"},
      {{{"gated_search_rows", "65"}}, "invalid parameter gatedSearchRows = 65: must be in [0, 64]"},
      {{{"gated_search_rows", "six"}}, "option -gated_search_rows: 'six' is not an integer"},
      {{{"min_confidence", "2"}}, "option -min_confidence: 2 must be in [0, 1]"},
      {{{"outlier_min_neighbours", "99"}}, "minNeighbours"},
      {{{"bogus", "1"}}, "unknown option -bogus"},
  };
  for (const auto& [given, message] : cases) {
    SCOPED_TRACE(given.begin()->first);
    try {
      configFromOptions(given, {});
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(configFromOptions({}, {"alpha"}), std::invalid_argument);  // not a flag
  try {
    configFromOptions({{"min_confidence", "0.5"}}, {"no_confidence"});
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "option -min_confidence: needs the confidence, which -no_confidence turns off");
  }
}

TEST(ConfigOptions, TheHelpListsEveryOptionOnceWithItsDefaultWhole) {
  std::string all;
  for (OptionGroup g : {OptionGroup::Method, OptionGroup::Speed, OptionGroup::Filters, OptionGroup::Output}) {
    all += optionsHelp(g, OptionScope::Cloud);
  }
  for (const DensifierOption& o : densifierOptions()) {
    SCOPED_TRACE(o.name);
    const std::string line = std::string("\n  -") + o.name;
    const std::size_t at = ("\n" + all).find(line + (o.kind == OptionKind::Flag ? "" : " "));
    ASSERT_NE(at, std::string::npos);
    if (o.kind != OptionKind::Flag) {
      const std::size_t next = ("\n" + all).find("\n  -", at + 1);
      EXPECT_NE(("\n" + all).substr(at, next - at).find("(default: " + defaultValue(o) + ")"), std::string::npos);
    }
  }
  for (std::size_t start = 0; start < all.size();) {
    const std::size_t end = all.find('\n', start);
    EXPECT_LE(end - start, 112u) << all.substr(start, end - start);
    start = end + 1;
  }
}

}  // namespace
}  // namespace lidar_sgm
