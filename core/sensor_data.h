#pragma once
// Time-stamped sensor records: plain value types shared by the log readers, the simulator and
// the methods. SI units, times in seconds.
#include <cstdint>

#include "core/pose2.h"
#include "core/scan.h"

namespace locbench {

// Cumulative signed encoder counts (ENCODER record).
struct EncoderReading {
  double t = 0.0;
  std::int64_t left = 0;
  std::int64_t right = 0;
};

// Odometry pose and velocities (CARMEN ODOM record; MRCLAM velocities integrated to a pose).
struct OdometryReading {
  double t = 0.0;
  Pose2 pose;       // the robot's own dead-reckoned pose
  double tv = 0.0;  // forward velocity [m/s]
  double rv = 0.0;  // rotational velocity [rad/s]
};

// Absolute heading, counter-clockwise from the world x axis (COMPASS record).
struct CompassReading {
  double t = 0.0;
  double heading = 0.0;
};

// A laser scan with the poses logged beside it (FLASER record).
struct LaserReading {
  Scan scan;        // scan.timestamp is the record time
  Pose2 pose;       // robot (or laser) pose estimate logged with the scan
  Pose2 odom_pose;  // odometry pose at scan time (zero in *.from_bag logs)
};

// Ground-truth pose (TRUEPOS record; MRCLAM Vicon ground truth).
struct TruePose {
  double t = 0.0;
  Pose2 pose;
  Pose2 odom_pose;  // odometry pose logged with it
};

// Reference relative motion between two timestamps (Freiburg .relations).
struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  Pose2 delta;  // motion from the pose at t1 to the pose at t2, in the frame at t1
};

// A landmark observation (MRCLAM measurement): range and bearing to a subject.
struct LandmarkReading {
  double t = 0.0;
  int subject = 0;
  double range = 0.0;
  double bearing = 0.0;
};

// A surveyed landmark of a map (MRCLAM Landmark_Groundtruth.dat, or a user's landmark map): its
// identifier (the subject number an observation names), position and the survey's 1σ [m].
struct MapLandmark {
  int id = 0;
  double x = 0.0, y = 0.0;
  double sigma_x = 0.0, sigma_y = 0.0;
};

}  // namespace locbench
