// The faster EapMatcher gives the same matches as the implementation it replaced
// (legacy_eap_matcher.h, kept here only as the reference): the same segments in the same order,
// the same points bit for bit (beam, range, bearing, robot and world coordinates), the same
// `work`, and the same fitted line up to rounding — the fit now comes from one pass of moments
// and the 2×2 eigenvector instead of fit_line's two passes and atan2/cos/sin, so its last bits
// differ; the largest difference seen is printed and must stay below 1e-9 (m, rad).
// On random maps (seeded) for every claim mode, region rule and weighting, plain and indexed,
// and on the first 200 scans of the ACES and Intel logs (skipped when the data are absent).
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>

#include "algorithms/laser/eap_matcher.h"
#include "baselines/laser/extract_then_match.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/units.h"
#include "datasets/catalog/data_root.h"
#include "datasets/catalog/dataset_catalog.h"
#include "eap_test_helpers.h"
#include "legacy_eap_matcher.h"
#include "tests/test_data.h"

namespace locbench::laser {
using locbench::catalog::DatasetEntry, locbench::catalog::find_dataset, locbench::catalog::load_catalog_dataset;
namespace {

constexpr double kFitTolerance = 1e-9;  // [m] and [rad]

// Largest differences between the two implementations' fits over a test.
struct FitDifference {
  double position = 0.0;  // ρ, centroid, first, last, rms [m]
  double angle = 0.0;     // β, direction [rad]
  std::size_t matches = 0, points = 0;
  void print(const std::string& what) const {
    std::cout << "[ " << what << " ] " << matches << " matches, " << points
              << " points identical; largest fit difference " << position << " m, " << angle << " rad\n";
  }
};

void expect_same(const MatchResult& old_r, const MatchResult& new_r, const std::string& what, FitDifference& diff) {
  EXPECT_EQ(old_r.work, new_r.work) << what;
  test::expect_same_segments(old_r, new_r, what, [&](const SegmentMatch& a, const SegmentMatch& b) {
    for (std::size_t i = 0; i < a.points.size(); ++i) {
      const ScanPoint& p = a.points[i];
      const ScanPoint& q = b.points[i];
      ASSERT_EQ(p.beam, q.beam) << what;
      EXPECT_EQ(p.range, q.range) << what;  // bit-equal, not merely close
      EXPECT_EQ(p.bearing, q.bearing) << what;
      EXPECT_EQ(p.robot, q.robot) << what;
      EXPECT_EQ(p.world, q.world) << what;
    }
    EXPECT_EQ(a.fit.count, b.fit.count) << what;
    const double dpos = std::max({std::abs(a.fit.line.rho - b.fit.line.rho), (a.fit.centroid - b.fit.centroid).norm(),
                                  (a.fit.first - b.fit.first).norm(), (a.fit.last - b.fit.last).norm(),
                                  std::abs(a.fit.rms - b.fit.rms)});
    const double dang =
        std::max(std::abs(angle_diff(a.fit.line.beta, b.fit.line.beta)), (a.fit.direction - b.fit.direction).norm());
    EXPECT_LT(dpos, kFitTolerance) << what << ", segment " << a.map_segment;
    EXPECT_LT(dang, kFitTolerance) << what << ", segment " << a.map_segment;
    diff.position = std::max(diff.position, dpos);
    diff.angle = std::max(diff.angle, dang);
    ++diff.matches;
    diff.points += a.points.size();
  });
}

// Every claim mode, both region rules, all three weightings, the thesis's acceptance rules.
std::vector<EapOptions> option_variants() {
  std::vector<EapOptions> v = test::claim_and_region_variants();
  v.resize(7);
  v[4].weighting.kind = HoughWeighting::kRange;
  v[5].max_direction_error = 0.0;  // the thesis's rules
  v[5].trim_distance = 0.0;
  v[6].claim_order = ClaimOrder::kMapOrder;
  v[6].region = RegionRule::kStadium;
  v[6].trim_distance = 0.02;
  return v;
}

// Matches one scan with every option variant, plain and indexed, old and new.
void compare_all(const Scan& scan, const LineMap& map, const Pose2& estimate,
                 const std::shared_ptr<const SegmentGridIndex>& index, const std::string& what, FitDifference& diff) {
  const std::vector<EapOptions> variants = option_variants();
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const EapOptions& o = variants[v];
    const std::string label = what + ", options " + std::to_string(v);
    expect_same(legacy::LegacyEapMatcher(o).match(scan, map, estimate), EapMatcher(o).match(scan, map, estimate),
                label + ", plain", diff);
    if (index) {
      expect_same(legacy::LegacyEapMatcher(index, o).match(scan, index->map(), estimate),
                  EapMatcher(index, o).match(scan, index->map(), estimate), label + ", indexed", diff);
    }
  }
}

// How often the two rules of ours changed the legacy matcher's result on these inputs: the
// equivalence must cover the direction check and the trim, not only plain acceptance.
struct RuleCoverage {
  std::size_t direction = 0, trim = 0;
  void count(const Scan& scan, const LineMap& map, const Pose2& estimate) {
    EapOptions no_direction, no_trim;
    no_direction.max_direction_error = 0.0;
    no_trim.trim_distance = 0.0;
    const MatchResult all = legacy::LegacyEapMatcher().match(scan, map, estimate);
    const MatchResult a = legacy::LegacyEapMatcher(no_direction).match(scan, map, estimate);
    const MatchResult b = legacy::LegacyEapMatcher(no_trim).match(scan, map, estimate);
    direction += a.matches.size() != all.matches.size();
    std::size_t pa = 0, pb = 0;
    for (const auto& m : all.matches) pa += m.points.size();
    for (const auto& m : b.matches) pb += m.points.size();
    trim += pa != pb;
  }
};

TEST(EapEquivalence, RoomFromTheThesisPoseAndFromATable6_2EstimateGivesTheOldMatches) {
  const auto index = std::make_shared<const SegmentGridIndex>(sim::room_world());
  const Pose2 truth = test::thesis_pose();
  FitDifference diff;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Scan scan = test::simulated_scan(index->map(), truth, mm(5.0), seed);
    compare_all(scan, index->map(), truth, index, "room, seed " + std::to_string(seed), diff);
    const Pose2 estimate(truth.x + 0.1, truth.y + 0.1, truth.theta - deg(3.0));
    compare_all(scan, index->map(), estimate, index, "room off, seed " + std::to_string(seed), diff);
  }
  diff.print("room");
  EXPECT_GT(diff.matches, 300u);
}

TEST(EapEquivalence, RandomMapsAndPosesGiveTheOldMatchesForEveryOption) {
  Rng rng(171717);
  FitDifference diff;
  RuleCoverage coverage;
  for (int map_k = 0; map_k < 8; ++map_k) {
    const double size = rng.uniform(6.0, 25.0);
    const LineMap map = test::random_map(static_cast<std::size_t>(rng.uniform(5.0, 150.0)), size, rng);
    const auto index = std::make_shared<const SegmentGridIndex>(map);
    for (int pose_k = 0; pose_k < 3; ++pose_k) {
      const Pose2 truth(rng.uniform(1.0, size - 1.0), rng.uniform(1.0, size - 1.0), rng.uniform(-kPi, kPi));
      const Pose2 estimate(truth.x + rng.uniform(-0.15, 0.15), truth.y + rng.uniform(-0.15, 0.15),
                           truth.theta + rng.uniform(deg(-5.0), deg(5.0)));
      const auto seed = static_cast<std::uint64_t>(rng.uniform() * 1e6);
      const Scan scan = test::simulated_scan(map, truth, mm(5.0), seed, 0.05);
      const std::string what = "map " + std::to_string(map_k) + ", pose " + std::to_string(pose_k);
      compare_all(scan, map, estimate, index, what, diff);
      coverage.count(scan, map, estimate);
    }
  }
  diff.print("random maps");
  std::cout << "[ random maps ] scans where the direction check changed the matches: " << coverage.direction
            << ", where the trim did: " << coverage.trim << "\n";
  EXPECT_GT(diff.matches, 300u);
  EXPECT_GT(coverage.direction + coverage.trim, 0u);
}

TEST(EapEquivalence, TenThousandSegmentMapGivesTheOldMatchesPlainAndIndexed) {
  Rng rng(1717);
  const auto index = std::make_shared<const SegmentGridIndex>(test::random_map(10000, 300.0, rng));
  FitDifference diff;
  for (int k = 0; k < 2; ++k) {
    const Pose2 truth(rng.uniform(10.0, 290.0), rng.uniform(10.0, 290.0), rng.uniform(-kPi, kPi));
    LineMap near;  // ray-cast against the segments within reach only (same scan, 100× cheaper)
    for (const Segment& s : index->map().segments) {
      if (distance_to_segment(s, truth.translation()) < 8.5) near.segments.push_back(s);
    }
    const Scan scan = test::simulated_scan(near, truth, mm(5.0), 50 + k, 0.05);
    const Pose2 estimate(truth.x + 0.05, truth.y - 0.05, truth.theta + deg(1.0));
    std::vector<EapOptions> orders(2);
    orders[1].claim_order = ClaimOrder::kMapOrder;
    for (const EapOptions& o : orders) {
      expect_same(legacy::LegacyEapMatcher(o).match(scan, index->map(), estimate),
                  EapMatcher(o).match(scan, index->map(), estimate), "10k plain", diff);
      expect_same(legacy::LegacyEapMatcher(index, o).match(scan, index->map(), estimate),
                  EapMatcher(index, o).match(scan, index->map(), estimate), "10k indexed", diff);
    }
  }
  diff.print("10 000 segments");
  EXPECT_GT(diff.matches, 4u);
}

// The first 200 scans of a Freiburg log, each matched against its own split-and-merge lines
// (the speed benchmark's case) from the scan's own pose and from estimates off by 5 cm / 2°,
// and against the lines of the scan 10 before it (a real map of the neighbourhood).
void compare_on_log(const std::string& dataset) {
  const DatasetEntry* entry = find_dataset(dataset);
  ASSERT_NE(entry, nullptr) << dataset;
  LOCBENCH_REQUIRE_DATA(entry->path);
  const Log log = load_catalog_dataset(*entry, catalog::data_root());
  const baselines::laser::SplitAndMergeMatcher sm;
  std::vector<LineMap> lines;
  FitDifference diff;
  RuleCoverage coverage;
  const std::size_t count = std::min<std::size_t>(200, log.laser.size());
  for (std::size_t i = 0; i < count; ++i) {
    LineMap m;
    for (const auto& l : sm.extract_lines(log.laser[i].scan).lines) {
      m.segments.push_back(l.fit.segment());
    }
    lines.push_back(std::move(m));
  }
  for (std::size_t i = 0; i < count; ++i) {
    const Scan& scan = log.laser[i].scan;
    const std::string what = dataset + " scan " + std::to_string(i);
    const std::vector<EapOptions> variants = option_variants();
    for (const LineMap* map : {&lines[i], &lines[i >= 10 ? i - 10 : 0]}) {
      if (map->segments.empty()) continue;
      const auto index = std::make_shared<const SegmentGridIndex>(*map);
      for (const Pose2& estimate : {Pose2(), Pose2(0.05, -0.05, deg(2.0))}) {
        for (const std::size_t v : {0, 1, 6}) {  // a subset of the variants: Debug time
          expect_same(legacy::LegacyEapMatcher(variants[v]).match(scan, *map, estimate),
                      EapMatcher(variants[v]).match(scan, *map, estimate), what, diff);
        }
        expect_same(legacy::LegacyEapMatcher(index).match(scan, index->map(), estimate),
                    EapMatcher(index).match(scan, index->map(), estimate), what + " indexed", diff);
        coverage.count(scan, *map, estimate);
        if (map != &lines[i]) break;  // the neighbour's lines: from the scan's own pose only
      }
    }
  }
  diff.print(dataset + ", first " + std::to_string(count) + " scans");
  std::cout << "[ " << dataset
            << " ] cases (scan, map, estimate) where the direction check changed the result: " << coverage.direction
            << ", where the trim did: " << coverage.trim << "\n";
  EXPECT_GT(diff.matches, 1000u);
}

TEST(EapEquivalence, FirstTwoHundredAcesScansGiveTheOldMatches) { compare_on_log("aces"); }
TEST(EapEquivalence, FirstTwoHundredIntelScansGiveTheOldMatches) { compare_on_log("intel"); }

TEST(EapEquivalence, ErrorsAreTheOldOnes) {
  Scan mismatched = test::simulated_scan(sim::room_world(), test::thesis_pose());
  mismatched.bearings.pop_back();
  LineMap degenerate;
  degenerate.segments.push_back({{1.0, 1.0}, {1.0, 1.0}});
  const Scan scan = test::simulated_scan(sim::room_world(), test::thesis_pose());
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const EapMatcher fresh;
  const legacy::LegacyEapMatcher old;
  EXPECT_EQ(message([&] { fresh.match(mismatched, sim::room_world(), {}); }),
            message([&] { old.match(mismatched, sim::room_world(), {}); }));
  EXPECT_EQ(message([&] { fresh.match(scan, degenerate, {}); }), message([&] { old.match(scan, degenerate, {}); }));
  EXPECT_EQ(message([&] { fresh.match(scan, degenerate, {}); }),
            "EapMatcher: map segment 0: EapRegion: segment must have finite, non-zero length");
}

TEST(EapEquivalence, ReusedBuffersDoNotLeakFromOneCallIntoTheNext) {
  // Alternating maps and scan geometries through one thread's cached tables and bearings.
  const LineMap room = sim::room_world();
  Rng rng(99);
  const LineMap other = test::random_map(40, 10.0, rng);
  const Scan a = test::simulated_scan(room, test::thesis_pose(), mm(5.0), 3);
  Scan b = a;
  for (double& bearing : b.bearings) bearing *= 0.5;  // another geometry, same ranges
  const EapMatcher eap;
  FitDifference diff;
  for (int k = 0; k < 3; ++k) {
    for (const Scan* s : {&a, static_cast<const Scan*>(&b)}) {
      for (const LineMap* map : {&room, &other}) {
        expect_same(legacy::LegacyEapMatcher().match(*s, *map, test::thesis_pose()),
                    eap.match(*s, *map, test::thesis_pose()), "alternating", diff);
      }
    }
  }
  EXPECT_GT(diff.matches, 10u);
}

}  // namespace
}  // namespace locbench::laser
