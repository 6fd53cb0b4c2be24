#pragma once
// The measured data of one UMBmark experiment (§2.1, Borenstein & Feng), shared by the classic
// method (baselines/calibration) and the thesis's improved one (algorithms/calibration): the
// nominal robot, the square's side, the tape-measured scale E_s, the encoder counts logged on a
// straight leg, and the return error of every run. SI units: metres.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "core/robot_params.h"

namespace locbench {

enum class UmbmarkDirection { kClockwise, kCounterClockwise };

// "cw" / "ccw".
std::string to_string(UmbmarkDirection d);

// One run's return error, Borenstein's ε = absolute − calculated position [m]: the true end
// minus the robot's odometry end, in the start pose's frame (x along the first leg, y to its
// left). In this frame eq. 2.3a and 2.6a hold with their printed signs.
struct UmbmarkReturn {
  UmbmarkDirection direction = UmbmarkDirection::kClockwise;
  double x_error = 0.0;
  double y_error = 0.0;
};

struct UmbmarkInput {
  double side_length = 0.0;          // L [m]
  WheelGeometry nominal;             // what the robot's software believed while driving
  EncoderSpec encoder;               // n, C_e
  double tape_measure_scale = 1.0;   // E_s = D_a/D_n measured with a tape (2.15); 1 = not measured
  std::int64_t leg_ticks_left = 0;   // N_L: encoder counts logged on one straight leg
  std::int64_t leg_ticks_right = 0;  // N_R
  std::vector<UmbmarkReturn> runs;
};

// Which centroid coordinates give the Type B angle β and the Type A angle α:
//   kX: β = (x_cw − x_ccw)/(−4L) (2.3a), α = (x_cw + x_ccw)/(−4L) (2.6a);
//   kY: β = (y_cw + y_ccw)/(−4L) (2.3b), α = (y_cw − y_ccw)/(−4L) (2.6b as corrected: the text
//       prints x_ccw for y_ccw);
//   kMean: the mean of the two. All are first-order (small-angle) relations; see
//   algorithms/calibration/README.md for their accuracy.
enum class UmbmarkAngleFormula { kX, kY, kMean };

// Centroids of the return errors per direction, (x_cg, y_cg), and
// E_max,syst = max(|c_cw|, |c_ccw|) (§2.1). A direction without runs has a zero centroid.
struct UmbmarkCentroids {
  Eigen::Vector2d cw = Eigen::Vector2d::Zero();
  Eigen::Vector2d ccw = Eigen::Vector2d::Zero();
  int runs_cw = 0;
  int runs_ccw = 0;
  double e_max_syst = 0.0;  // [m]
  // Pooled standard deviation of one run's return error about its direction's centroid, per
  // coordinate [m]: sqrt(Σ|ε − c|² / (2·(runs − directions))). 0 when no direction has 2 runs.
  double run_sigma = 0.0;
};

UmbmarkCentroids umbmark_centroids(const std::vector<UmbmarkReturn>& runs);

// Throws std::invalid_argument naming the first offending field ("side_length", "runs",
// "leg_ticks_left", ...) when the input cannot be calibrated from: non-finite or non-positive
// lengths, no run in one of the directions, non-finite return errors. Leg counts are checked
// only when `need_leg_ticks`.
void check_umbmark_input(const UmbmarkInput& in, bool need_leg_ticks);

}  // namespace locbench
