#pragma once
// Everything a simulation run is made of: the world, the true and the nominal robot, how it is
// driven, the noise and slip models, and each sensor. SI units throughout (m, rad, s, Hz);
// defaults describe a noise-free robot whose true geometry equals its nominal one.
// The JSON form (scenario_json.h) uses the same field names; datasets/sim/README.md lists them.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/robot_params.h"
#include "core/units.h"
#include "datasets/sim/drive_response.h"
#include "datasets/sim/motion_noise.h"

namespace locbench::sim {

enum class WorldKind {
  kNone,      // empty plane
  kRoom,      // the thesis's 8 m × 8 m room with three obstacles (§5.4), worlds.h
  kCorridor,  // closed corridor along +x: x ∈ [0, length], y ∈ [−width/2, width/2]
  kFile,      // JSON world file {"name", "segments": [[x1, y1, x2, y2], ...]}
  kInline,    // segments given in the scenario itself
};

struct WorldConfig {
  WorldKind kind = WorldKind::kNone;
  double corridor_length = 12.0;          // [m]
  double corridor_width = 1.8;            // [m]
  std::string file;                       // kFile: path of the world JSON file
  std::vector<Eigen::Vector4d> segments;  // kInline: [x1, y1, x2, y2] [m]
};

// The true robot and the model its software believes (eq. 2.1, 2.2, 2.15: E_d, E_b, E_o).
// Defaults: one tick is exactly 0.1 mm (D = 0.2/π m, 2000 counts per wheel revolution) and a
// 90° on-the-spot turn is exactly 3000 ticks per wheel (B = 1.2/π m), so paths made of whole
// millimetres and right angles are commanded in whole ticks.
struct RobotConfig {
  WheelGeometry nominal{0.2 / kPi, 0.2 / kPi, 1.2 / kPi};
  WheelGeometry actual{0.2 / kPi, 0.2 / kPi, 1.2 / kPi};
  EncoderSpec encoder{1.0, 2000.0};

  RobotParams params() const { return {nominal, actual, encoder}; }
};

// How legs are executed. Every leg is commanded in encoder counts computed from the nominal
// model; each wheel's servo turns the wheel until its encoder has counted exactly that many
// ticks, so the true travel is counts × true metres per tick.
struct DriveConfig {
  double speed = 0.25;           // forward speed on straight legs [m/s] (nominal model)
  double turn_rate = deg(30.0);  // on-the-spot turn rate [rad/s] (nominal model)
  double pause = 0.5;            // standstill after every leg [s]
  // Trilobot limitation (§2.4): both wheels always get the same count (the rounded mean of
  // the per-wheel counts), so unequal nominal diameters cannot be compensated.
  bool equal_wheel_ticks = false;
  // Replayed motion only: how the drive turns the replayed command into true motion.
  DriveResponse response;
};

enum class MotionKind {
  kStraight,   // one straight leg of `distance` (a corridor run when the world is a corridor)
  kUmbmark,    // bidirectional square: `runs` clockwise then `runs` counter-clockwise
  kWaypoints,  // for each waypoint: turn on the spot towards it, then drive straight to it
  kReplay,     // a logged command or odometry velocity sequence (a log's synthetic twin)
};

// One replayed command: from logged time t on (until the next command) the robot is told to move
// at (v, ω). The robot executes it from true time t − latency of its odometry sensor (ODOM when
// enabled, else ENCODER), the convention of SensorTiming::latency.
struct ReplayCommand {
  double t = 0.0;      // [s], ≥ 0, increasing
  double v = 0.0;      // [m/s]
  double omega = 0.0;  // [rad/s]
};

struct MotionConfig {
  MotionKind kind = MotionKind::kStraight;
  double distance = 10.0;                  // kStraight [m]; negative drives backwards
  double side = 4.0;                       // kUmbmark square side L [m]
  int runs = 5;                            // kUmbmark runs per direction
  std::vector<Eigen::Vector2d> waypoints;  // kWaypoints, world frame [m]
  std::vector<ReplayCommand> commands;     // kReplay
};

struct PhysicsConfig {
  double step = 1e-3;              // integration step [s]; sensor instants are rounded to it
  double trajectory_rate = 100.0;  // rate of SimulationResult::trajectory [Hz]; 0 = every step
};

// Floor noise per wheel, δ ~ N(0, k²|U|) for a travel U (eq. 4.16, Chong & Kleeman) [√m].
struct FloorNoiseConfig {
  double k_left = 0.0;
  double k_right = 0.0;
};

enum class SlipRateUnit {
  kPerSample,  // probability of a slip event per encoder sample interval
  kPerMetre,   // expected events per metre of wheel travel: p = 1 − exp(−rate · d) per interval
};

// A slip event: one wheel (left or right, equally likely) loses the fraction f ~ U[min, max]
// of its travel for one encoder sample interval. At most one wheel slips per interval.
struct SlipProfile {
  double rate = 0.0;
  double magnitude_min = 0.1;  // fraction of the wheel's travel lost
  double magnitude_max = 0.3;
};

struct SlipConfig {
  SlipRateUnit unit = SlipRateUnit::kPerSample;
  SlipProfile straight;  // applies when the interval starts on a straight leg
  SlipProfile turn;      // applies when the interval starts on an on-the-spot turn
};

// When a sensor samples. Measurement instants are k/rate (+ jitter); the logged timestamp is
// the true measurement time + latency (a positive latency logs the record late).
struct SensorTiming {
  bool enabled = false;
  double rate = 10.0;    // [Hz]
  double latency = 0.0;  // logged time − true measurement time [s]
  double jitter = 0.0;   // std-dev of each measurement instant around k/rate, clipped to ±0.45/rate [s]
};

struct EncoderConfig {
  SensorTiming timing{true, 10.0, 0.0, 0.0};
};

// Velocity odometry (ODOM records): the robot's own dead-reckoned pose (eq. 1.1–1.3 with the
// nominal model, integrated at every encoder count change) and tv, rv averaged since the last
// record.
struct OdometryConfig {
  SensorTiming timing{false, 10.0, 0.0, 0.0};
};

// A compass disturbance zone: readings taken while the robot centre is inside get `bias` added.
struct DisturbanceZone {
  enum class Shape { kRectangle, kCircle };
  Shape shape = Shape::kRectangle;
  Eigen::Vector2d min = Eigen::Vector2d::Zero();     // kRectangle, lower-left corner [m]
  Eigen::Vector2d max = Eigen::Vector2d::Zero();     // kRectangle, upper-right corner [m]
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // kCircle [m]
  double radius = 0.0;                               // kCircle [m]
  double bias = 0.0;                                 // [rad]

  bool contains(const Eigen::Vector2d& p) const;
};

// Absolute heading, counter-clockwise from world +x: reading = quantize(θ + bias + zone biases
// + N(0, noise²)) to a multiple of `resolution` (0 = continuous), wrapped to [−π, π).
struct CompassConfig {
  SensorTiming timing{false, 10.0, 0.0, 0.0};
  double resolution = 0.0;  // [rad]; should divide 2π
  double noise = 0.0;       // white noise std-dev [rad]
  double bias = 0.0;        // constant bias [rad]
  std::vector<DisturbanceZone> zones;
};

// A 2D scanner like the SICK LMS 200. For each beam: with probability `dropout` the reading is
// max_range; with probability `spurious` it is uniform on [0, true range); otherwise it is
// scale · true range + offset + N(0, noise²), clipped to [0, max_range]. No hit = max_range.
struct LaserConfig {
  SensorTiming timing{false, 5.0, 0.0, 0.0};
  int beams = 181;
  double first_bearing = deg(-90.0);  // [rad], sensor frame
  double last_bearing = deg(90.0);    // [rad]
  double max_range = 8.0;             // [m] (LMS 200 in millimetre mode)
  double noise = 0.0;                 // [m]
  double range_offset = 0.0;          // systematic offset [m]
  double range_scale = 1.0;           // systematic scale
  double dropout = 0.0;               // probability per beam
  double spurious = 0.0;              // probability per beam
  Pose2 mount;                        // sensor pose in the robot frame
};

// Ground-truth records (TRUEPOS) in the log.
struct TruthConfig {
  double rate = 10.0;  // [Hz]; 0 = none
  // White noise of the reference itself (a motion-capture system's jitter), per record.
  double noise_xy = 0.0;     // [m], each of x and y
  double noise_theta = 0.0;  // [rad]
};

struct Scenario {
  std::string name = "custom";
  std::string description;
  WorldConfig world;
  Pose2 start;  // true start pose; the robot's odometry starts there too
  RobotConfig robot;
  DriveConfig drive;
  MotionConfig motion;
  PhysicsConfig physics;
  FloorNoiseConfig floor;
  MotionNoiseConfig motion_noise;
  SlipConfig slip;
  EncoderConfig encoders;
  OdometryConfig odometry;
  CompassConfig compass;
  LaserConfig laser;
  TruthConfig truth;
  // Free text a reader should know (e.g. what a diagnosis twin could not simulate).
  std::vector<std::string> notes;
};

// Throws UsageError naming the first invalid field, e.g. "drive.speed must be > 0".
void validate(const Scenario& s);

}  // namespace locbench::sim
