// The measured data of a UMBmark experiment: centroids per direction, E_max,syst, run scatter
// and the input checks shared by the classic and the improved method.
#include "core/umbmark_measurements.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tests/core/umbmark_inputs.h"

namespace locbench {
namespace {

constexpr auto kCw = UmbmarkDirection::kClockwise;
constexpr auto kCcw = UmbmarkDirection::kCounterClockwise;

// Two CW and three CCW return errors [m].
std::vector<UmbmarkReturn> five_runs() {
  return {{kCw, 0.30, -0.10}, {kCcw, -0.10, 0.20}, {kCw, 0.50, -0.30}, {kCcw, -0.30, 0.40}, {kCcw, -0.20, 0.30}};
}

TEST(UmbmarkCentroids, AreTheMeanReturnErrorPerDirectionAndEMaxSystIsTheLongerOne) {
  // CW: (0.30, −0.10), (0.50, −0.30) → (0.40, −0.20), |c_cw| = √(0.16 + 0.04) = 0.4472.
  // CCW: (−0.10, 0.20), (−0.30, 0.40), (−0.20, 0.30) → (−0.20, 0.30), |c_ccw| = √0.13 = 0.3606.
  // E_max,syst = max(0.4472, 0.3606) = 0.4472.
  const std::vector<UmbmarkReturn> runs = five_runs();
  const UmbmarkCentroids c = umbmark_centroids(runs);
  EXPECT_EQ(c.runs_cw, 2);
  EXPECT_EQ(c.runs_ccw, 3);
  EXPECT_NEAR(c.cw.x(), 0.40, 1e-15);
  EXPECT_NEAR(c.cw.y(), -0.20, 1e-15);
  EXPECT_NEAR(c.ccw.x(), -0.20, 1e-15);
  EXPECT_NEAR(c.ccw.y(), 0.30, 1e-15);
  EXPECT_NEAR(c.e_max_syst, std::sqrt(0.20), 1e-15);
}

TEST(UmbmarkCentroids, RunSigmaIsThePooledPerCoordinateScatterAboutTheCentroids) {
  // CW deviations (±0.1, ∓0.1) → Σ = 4·0.01 = 0.04; CCW (0.1, −0.1), (−0.1, 0.1), (0, 0) → 0.04.
  // Degrees of freedom 2·(5 runs − 2 centroids) = 6: σ = √(0.08/6) = 0.11547.
  const std::vector<UmbmarkReturn> runs = five_runs();
  EXPECT_NEAR(umbmark_centroids(runs).run_sigma, std::sqrt(0.08 / 6.0), 1e-12);
  // One run per direction: no scatter to pool.
  EXPECT_EQ(umbmark_centroids({{kCw, 0.1, 0.0}, {kCcw, 0.0, 0.1}}).run_sigma, 0.0);
}

TEST(UmbmarkCentroids, ADirectionWithoutRunsHasAZeroCentroid) {
  const UmbmarkCentroids c = umbmark_centroids({{kCw, 0.3, 0.4}});
  EXPECT_EQ(c.runs_ccw, 0);
  EXPECT_EQ(c.ccw, Eigen::Vector2d::Zero());
  EXPECT_NEAR(c.e_max_syst, 0.5, 1e-15);
}

// A Trilobot-like robot on a 1.6 m square, one run per direction.
UmbmarkInput valid_input() {
  return testing::umbmark_square(1.6, {0.0885, 0.0885, 0.198}, {1.0, 22.0}, 127, {{kCw, 0.1, 0.2}, {kCcw, -0.1, 0.2}});
}

void expect_rejected(const UmbmarkInput& in, bool need_ticks, const std::string& field) {
  try {
    check_umbmark_input(in, need_ticks);
    ADD_FAILURE() << "accepted input with a bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(UmbmarkInputCheck, AcceptsOneRunPerDirectionAndRejectsEachBadFieldByName) {
  EXPECT_NO_THROW(check_umbmark_input(valid_input(), true));
  UmbmarkInput in = valid_input();
  in.side_length = 0.0;
  expect_rejected(in, false, "side_length");
  in = valid_input();
  in.nominal.wheelbase = std::nan("");
  expect_rejected(in, false, "nominal.wheelbase");
  in = valid_input();
  in.runs.pop_back();
  expect_rejected(in, false, "counter-clockwise");
  in = valid_input();
  in.runs.erase(in.runs.begin());
  expect_rejected(in, false, "no clockwise run");
  in = valid_input();
  in.runs[1].y_error = INFINITY;
  expect_rejected(in, false, "runs[1]");
  in = valid_input();
  in.leg_ticks_right = 0;
  EXPECT_NO_THROW(check_umbmark_input(in, false));  // the classic method needs no counts
  expect_rejected(in, true, "leg_ticks_right");
}

TEST(UmbmarkDirection, PrintsAsInTheInputFile) {
  EXPECT_EQ(to_string(kCw), "cw");
  EXPECT_EQ(to_string(kCcw), "ccw");
}

}  // namespace
}  // namespace locbench
