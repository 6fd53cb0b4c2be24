#pragma once
// What a simulation returns: the log a real robot would have written, plus the ground truth
// that no real log has (true trajectory, true wheel travel, slip events, UMBmark return errors)
// for scoring methods.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/line_map.h"
#include "core/log.h"
#include "core/pose2.h"
#include "core/robot_params.h"
#include "core/trajectory.h"
#include "datasets/sim/motion_program.h"
#include "datasets/sim/scenario.h"
#include "datasets/sim/slip_model.h"

namespace locbench::sim {

struct TrajectoryPoint {
  double t = 0.0;  // [s]
  Pose2 pose;      // true pose
};

// The true state at each encoder sample instant (the slip/noise sample grid; see README).
// Cumulative values since the start; per-sample values are differences of consecutive ones.
struct WheelSample {
  double t = 0.0;               // true measurement time [s] (the ENCODER record is logged at t + latency)
  Pose2 pose;                   // true pose
  std::int64_t count_left = 0;  // encoder counts as reported
  std::int64_t count_right = 0;
  double rim_left = 0.0;  // rim travel [m] (what the encoder measures, before quantization)
  double rim_right = 0.0;
  double ground_left = 0.0;  // ground travel [m] = rim − slip + floor noise
  double ground_right = 0.0;
  double slip_left = 0.0;  // travel lost to slip [m]
  double slip_right = 0.0;
};

// One true slip event: `wheel` lost `lost` metres of travel between encoder samples
// `sample` and `sample + 1` (times t_start and t_end).
struct SlipEvent {
  std::size_t sample = 0;
  double t_start = 0.0;
  double t_end = 0.0;
  Side wheel = Side::kLeft;
  MotionPhase phase = MotionPhase::kStraight;
  double fraction = 0.0;  // of the wheel's travel in the interval
  double lost = 0.0;      // [m], same sign as the wheel's travel
};

struct CompassTruth {
  double t = 0.0;            // true measurement time [s]
  double heading = 0.0;      // true heading [rad]
  double disturbance = 0.0;  // zone bias in force [rad]
};

// One UMBmark run. The return error is Borenstein's ε = absolute − calculated position: the
// true end minus the robot's odometry end, both expressed in the start pose's frame
// (x along the first leg, y to its left); error[2] is the heading error [rad].
struct UmbmarkRun {
  Direction direction = Direction::kClockwise;
  int run = 0;
  double t_start = 0.0;
  double t_end = 0.0;
  Pose2 start;
  Pose2 true_end;
  Pose2 odometry_end;
  Eigen::Vector3d error = Eigen::Vector3d::Zero();
};

// Centroids of the return errors per direction and E_max,syst = max(|c_cw|, |c_ccw|) (§2.1).
struct UmbmarkSummary {
  Eigen::Vector2d centroid_cw = Eigen::Vector2d::Zero();
  Eigen::Vector2d centroid_ccw = Eigen::Vector2d::Zero();
  double e_max_syst = 0.0;
};
UmbmarkSummary summarize_umbmark(const std::vector<UmbmarkRun>& runs);

struct SimulationResult;
// The true trajectory as a core Trajectory (interpolable in time).
Trajectory true_trajectory(const SimulationResult& result);
// Where dead reckoning of the run's ENCODER records with the log's nominal model (PARAM) ends up,
// relative to the truth, at the last instant both cover: between(truth, odometry), i.e. the
// odometry end pose in the true end frame. std::logic_error for a run without encoders, nominal
// model or trajectory (a simulator configuration mistake, not user input).
Pose2 dead_reckoning_end_error(const SimulationResult& result);

struct SimulationResult {
  Log log;
  Scenario scenario;
  std::uint64_t seed = 0;
  RobotParams robot;  // true and nominal geometry (E_d, E_b, E_o)
  LineMap world;
  double duration = 0.0;                    // [s]
  std::vector<TrajectoryPoint> trajectory;  // at physics.trajectory_rate
  std::vector<WheelSample> wheel_samples;
  std::vector<SlipEvent> slips;
  std::vector<CompassTruth> compass_truth;  // one per COMPASS record
  std::vector<UmbmarkRun> umbmark_runs;
};

}  // namespace locbench::sim
