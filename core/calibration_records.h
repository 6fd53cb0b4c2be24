#pragma once
// Raw records of the calibration data sets, as their files hold them: plain value types shared
// by the readers (datasets/io) and the calibration-data builders (calibration_data.h).
// SI units.
#include <string>
#include <vector>

#include "core/pose2.h"

namespace locbench {

// One Censi et al. (IEEE T-RO 2013) "tuple": over an interval of T seconds the left and right
// wheels turned at the mean angular velocities phi_l, phi_r [rad/s] while the scan matcher saw
// the sensor move by sm = (x, y, θ) in the sensor frame at the interval's start.
struct WheelSpeedTuple {
  double T = 0.0;      // [s]
  double phi_l = 0.0;  // [rad/s]
  double phi_r = 0.0;  // [rad/s]
  Pose2 sm;            // scan-matched sensor displacement [m, m, rad]
};

// A row pair of relative motions (stachniss_ls_calib): the odometry's displacement and the
// reference (scan-matched) displacement over the same interval, each in the frame at its start.
struct RelativeMotionPair {
  Pose2 odometry;
  Pose2 reference;
};

// A row of wheel measurements with a reference displacement (grisetti_diffdrive): the left and
// right encoder increments (in the file's units; the file holds fractional values) and the
// reference displacement over the same interval, in the frame at its start.
struct TickMotion {
  double left = 0.0;
  double right = 0.0;
  Pose2 reference;
};

// The records of one calibration data set as read: one of the three kinds, and the file(s)
// they came from (datasets/catalog/calibration_catalog.h reads them; calibration_data_from_records
// in algorithms/calibration turns them into samples).
struct CalibrationRecords {
  std::string source;                               // the file(s) read, for messages
  std::vector<WheelSpeedTuple> wheel_speed_tuples;  // censi_khepera
  std::vector<TickMotion> tick_motions;             // grisetti_diffdrive
  std::vector<RelativeMotionPair> motion_pairs;     // stachniss_ls_calib
};

}  // namespace locbench
