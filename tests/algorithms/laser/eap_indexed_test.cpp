// The indexed EAP matcher returns exactly the plain matcher's matches, at a fraction of the work.
#include <gtest/gtest.h>

#include <iostream>
#include <memory>

#include "algorithms/laser/eap_matcher.h"
#include "core/errors.h"
#include "core/units.h"
#include "eap_test_helpers.h"

namespace locbench::laser {
namespace {

void expect_identical(const MatchResult& a, const MatchResult& b, const std::string& what) {
  test::expect_same_segments(a, b, what, [&](const SegmentMatch& x, const SegmentMatch& y) {
    for (std::size_t i = 0; i < x.points.size(); ++i) {
      EXPECT_EQ(x.points[i].beam, y.points[i].beam) << what;
    }
    EXPECT_EQ(x.fit.line.rho, y.fit.line.rho) << what;  // same points, same order: bit-equal
    EXPECT_EQ(x.fit.line.beta, y.fit.line.beta) << what;
  });
}

std::vector<EapOptions> option_variants() { return test::claim_and_region_variants(); }

// Random pose in [margin, size − margin]² and an estimate off by up to 0.1 m and 3°.
struct Poses {
  Pose2 truth, estimate;
};
Poses random_poses(double size, Rng& rng) {
  const Pose2 t(rng.uniform(1.0, size - 1.0), rng.uniform(1.0, size - 1.0), rng.uniform(-kPi, kPi));
  return {
      t, Pose2(t.x + rng.uniform(-0.1, 0.1), t.y + rng.uniform(-0.1, 0.1), t.theta + rng.uniform(deg(-3.0), deg(3.0)))};
}

TEST(EapIndexed, RoomAtThesisPoseGivesThePlainMatchesWithFewerTests) {
  const auto idx = std::make_shared<const SegmentGridIndex>(sim::room_world());
  const Pose2 pose = test::thesis_pose();
  const Scan scan = test::simulated_scan(idx->map(), pose, mm(5.0), 11);
  for (const EapOptions& o : option_variants()) {
    const MatchResult plain = EapMatcher(o).match(scan, idx->map(), pose);
    const MatchResult fast = EapMatcher(idx, o).match(scan, idx->map(), pose);
    expect_identical(plain, fast, "room");
    EXPECT_LT(fast.work * 4, plain.work);
    std::cout << "[ room ] " << to_string(o.claim_order) << (o.remove_claimed ? "" : " (no claim)")
              << ": membership tests plain " << plain.work << ", indexed " << fast.work << "\n";
  }
}

TEST(EapIndexed, RandomMapsAndPosesGiveThePlainMatches) {
  Rng rng(424242);
  int matched = 0;
  for (int map_k = 0; map_k < 8; ++map_k) {
    const double size = rng.uniform(6.0, 25.0);
    LineMap map = test::random_map(static_cast<std::size_t>(rng.uniform(5.0, 120.0)), size, rng);
    const auto idx = std::make_shared<const SegmentGridIndex>(
        map, GridIndexOptions{.d_limit = 0.2, .cell_size = rng.uniform() < 0.5 ? 0.0 : 0.3});
    for (int pose_k = 0; pose_k < 3; ++pose_k) {
      const Poses p = random_poses(size, rng);
      const auto seed = static_cast<std::uint64_t>(rng.uniform() * 1e6);
      const Scan scan = test::simulated_scan(map, p.truth, mm(5.0), seed, 0.05);
      for (const EapOptions& o : option_variants()) {
        const MatchResult plain = EapMatcher(o).match(scan, map, p.estimate);
        // `map` is a different object with the same segments: accepted (compared in O(m)).
        const MatchResult fast = EapMatcher(idx, o).match(scan, map, p.estimate);
        expect_identical(plain, fast, "map " + std::to_string(map_k));
        matched += static_cast<int>(plain.matches.size());
      }
    }
  }
  EXPECT_GT(matched, 100);  // the comparison is not between empty results
}

TEST(EapIndexed, TenThousandSegmentMapGivesThePlainMatchesWithFlatWork) {
  Rng rng(10000);
  const auto idx = std::make_shared<const SegmentGridIndex>(test::random_map(10000, 300.0, rng));
  const Poses p = random_poses(300.0, rng);
  // Simulated against the segments within reach of the 8 m beams only (same ranges, and
  // 100× cheaper to ray-cast than the whole map).
  LineMap near;
  for (const Segment& s : idx->map().segments) {
    if (distance_to_segment(s, p.truth.translation()) < 8.5) near.segments.push_back(s);
  }
  const Scan scan = test::simulated_scan(near, p.truth, mm(5.0), 100, 0.05);
  std::size_t points = 0;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) points += scan.valid(i);
  for (const EapOptions& o : {option_variants()[0], option_variants()[1]}) {
    const MatchResult plain = EapMatcher(o).match(scan, idx->map(), p.estimate);
    const MatchResult fast = EapMatcher(idx, o).match(scan, idx->map(), p.estimate);
    expect_identical(plain, fast, std::string("10k ") + to_string(o.claim_order));
    EXPECT_GE(plain.matches.size(), 2u);  // a random clutter of short segments: few long runs
    // Each point is tested against the few segments near it, not against 10 000.
    EXPECT_LT(fast.work, 5 * points);
    std::cout << "[ 10 000 segments, " << near.segments.size() << " within 8.5 m ] " << to_string(o.claim_order) << ": "
              << plain.matches.size() << " matches; membership tests per point: plain "
              << double(plain.work) / double(points) << ", indexed " << double(fast.work) / double(points) << "\n";
  }
  std::cout << "[ 10 000 segments ] grid " << idx->columns() << " × " << idx->rows() << " cells of " << idx->cell_size()
            << " m, " << idx->entries() << " entries\n";
}

TEST(EapIndexed, RejectsAnotherMapANullIndexAndADifferentDLimit) {
  const auto idx = std::make_shared<const SegmentGridIndex>(sim::room_world());
  const Pose2 pose = test::thesis_pose();
  const Scan scan = test::simulated_scan(idx->map(), pose);
  LineMap moved = idx->map();
  moved.segments[3].p1.x() += 0.01;
  EXPECT_THROW(EapMatcher(idx).match(scan, moved, pose), UsageError);
  EXPECT_THROW(EapMatcher(idx).match(scan, sim::corridor_world(10.0), pose), UsageError);
  EXPECT_THROW(EapMatcher(nullptr), UsageError);
  EapOptions o;
  o.d_limit = 0.3;
  EXPECT_THROW(EapMatcher(idx, o), UsageError);
  EXPECT_EQ(EapMatcher(idx).name(), "eap_indexed");
  EXPECT_EQ(EapMatcher().name(), "eap");
}

}  // namespace
}  // namespace locbench::laser
