// Invalid options are usage errors; options round-trip through JSON.
#include <gtest/gtest.h>

#include <functional>

#include "baselines/laser/options_json.h"
#include "core/errors.h"
#include "tests/options_error_message.h"

namespace locbench::baselines::laser {
using locbench::laser::ScanPoint;
namespace {

template <class Options>
void expect_each_rejected(const std::vector<std::function<void(Options&)>>& mutations,
                          const std::function<void(const Options&)>& use) {
  for (std::size_t i = 0; i < mutations.size(); ++i) {
    Options o;
    mutations[i](o);
    EXPECT_THROW(use(o), UsageError) << "mutation " << i;
  }
}

TEST(LaserBaselineOptions, DefaultsAreValid) {
  EXPECT_NO_THROW(SplitAndMergeMatcher());
  EXPECT_NO_THROW(AgglomerativeMatcher());
  EXPECT_NO_THROW(RwhtMatcher());
}

TEST(LaserBaselineOptions, SplitAndMergeRejectsNonPositiveAndNegativeThresholds) {
  expect_each_rejected<SplitAndMergeOptions>(
      {[](auto& o) { o.split_distance = 0.0; }, [](auto& o) { o.split_distance = -0.01; },
       [](auto& o) { o.breakpoints.lambda = 0.0; }, [](auto& o) { o.breakpoints.lambda = deg(90.0); },
       [](auto& o) { o.breakpoints.range_sigma = -mm(1.0); }, [](auto& o) { o.acceptance.min_points = 1; },
       [](auto& o) { o.acceptance.min_length = -0.1; }},
      [](const SplitAndMergeOptions& o) { split_and_merge({}, LineFrame::robot, o); });
}

TEST(LaserBaselineOptions, AgglomerativeRejectsBadWindowsConfidencesAndDistances) {
  expect_each_rejected<AgglomerativeOptions>(
      {[](auto& o) { o.window = 2; }, [](auto& o) { o.window_confidence = 1.0; },
       [](auto& o) { o.merge_confidence = 0.0; }, [](auto& o) { o.model_sigma_alpha = -deg(0.1); },
       [](auto& o) { o.model_sigma_r = -mm(1.0); }, [](auto& o) { o.assign_distance = -0.01; },
       [](auto& o) { o.max_gap_points = -1; }, [](auto& o) { o.breakpoints.range_sigma = -mm(5.0); }},
      [](const AgglomerativeOptions& o) { agglomerative_lines({}, LineFrame::robot, o); });
}

TEST(LaserBaselineOptions, RwhtRejectsZeroBinSizesAndNegativeThresholds) {
  expect_each_rejected<RwhtOptions>(
      {[](auto& o) { o.angle_bin = 0.0; }, [](auto& o) { o.range_bin = 0.0; }, [](auto& o) { o.angle_bin = -deg(1.0); },
       [](auto& o) { o.range_bin = -0.05; }, [](auto& o) { o.min_peak_votes = -0.2; },
       [](auto& o) { o.nms_radius = 0; }, [](auto& o) { o.inlier_distance = 0.0; },
       [](auto& o) { o.max_gap_points = -1; }, [](auto& o) { o.acceptance.min_points = 0; }},
      [](const RwhtOptions& o) { rwht_lines({}, LineFrame::robot, o); });
}

TEST(LaserBaselineOptions, RwhtRejectsBinsThatWouldNeedAGiganticAccumulator) {
  std::vector<ScanPoint> points(5);
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].beam = i;
    points[i].range = 8.0;
    points[i].bearing = deg(static_cast<double>(i));
  }
  RwhtOptions o;
  o.range_bin = 1e-6;  // 8 million range bins × 360 angle bins
  EXPECT_THROW(rwht_lines(points, LineFrame::robot, o), UsageError);
}

TEST(LaserBaselineOptions, MatcherConstructorsRejectBadOptions) {
  SplitAndMergeMatcherOptions s;
  s.matching.max_delta_rho = -1.0;
  EXPECT_THROW(SplitAndMergeMatcher{s}, UsageError);
  AgglomerativeMatcherOptions a;
  a.extraction.window = 0;
  EXPECT_THROW(AgglomerativeMatcher{a}, UsageError);
  RwhtMatcherOptions r;
  r.extraction.range_bin = 0.0;
  EXPECT_THROW(RwhtMatcher{r}, UsageError);
}

TEST(LaserBaselineOptions, JsonRoundTripKeepsEveryField) {
  RwhtMatcherOptions o;
  o.extraction.angle_bin = deg(0.5);
  o.extraction.acceptance.min_points = 7;
  o.matching.end_tolerance = 0.1;
  const nlohmann::json j = o;
  EXPECT_DOUBLE_EQ(j["extraction"]["angle_bin"].get<double>(), deg(0.5));
  RwhtMatcherOptions back;
  from_json(j, back);
  EXPECT_EQ(nlohmann::json(back), j);
  AgglomerativeMatcherOptions a;
  a.extraction.window = 9;
  AgglomerativeMatcherOptions a_back;
  from_json(nlohmann::json(a), a_back);
  EXPECT_EQ(a_back.extraction.window, 9);
  SplitAndMergeMatcherOptions s;
  s.extraction.split_distance = 0.04;
  SplitAndMergeMatcherOptions s_back;
  from_json(nlohmann::json(s), s_back);
  EXPECT_DOUBLE_EQ(s_back.extraction.split_distance, 0.04);
}

TEST(LaserBaselineOptions, JsonRejectsUnknownKeysWrongTypesAndBadValuesByName) {
  const auto message = testing::options_error_message<RwhtMatcherOptions>;
  EXPECT_NE(message({{"extraction", {{"angel_bin", 0.1}}}}).find("angel_bin"), std::string::npos);
  EXPECT_NE(message({{"extraction", {{"range_bin", "5 cm"}}}}).find("range_bin"), std::string::npos);
  EXPECT_NE(message({{"extraction", {{"range_bin", 0.0}}}}).find("range_bin"), std::string::npos);
  EXPECT_NE(message({{"matching", {{"min_overlap", 2.0}}}}).find("min_overlap"), std::string::npos);
}

}  // namespace
}  // namespace locbench::baselines::laser
