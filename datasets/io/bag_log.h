#pragma once
// ROS bags as logs: a ROS 1 bag (*.bag), a ROS 2 sqlite3 bag (a folder with metadata.yaml and
// *.db3 files, or one .db3 file) or a ROS 2 MCAP bag (one *.mcap file, or a folder of them), with
// the topics chosen by name after a '#':
//   run.bag#odom=/wheel_odom,truth=/vicon/robot/pose,scan=/base_scan,base=base_footprint,laser=laser
// Without a choice each role takes the first of its default topics present (kDefault…Topics);
// "none" turns a role off. The header stamps are used, not the record times.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/log.h"
#include "datasets/io/bag_messages.h"

namespace locbench::io {

inline constexpr const char* kDefaultOdometryTopics[] = {"/odom", "/wheel_odom"};
// A simulator's ground truth (Stage, Gazebo's p3d plugin) or a motion-capture pose.
inline constexpr const char* kDefaultTruthTopics[] = {"/ground_truth",       "/base_pose_ground_truth",
                                                      "/ground_truth/state", "/ground_truth/pose",
                                                      "/mocap/pose",         "/vicon/pose"};
inline constexpr const char* kDefaultScanTopics[] = {"/scan", "/base_scan"};
inline constexpr const char* kDefaultHeadingTopics[] = {"/imu", "/imu/data"};
inline constexpr const char* kDefaultJointTopics[] = {"/joint_states"};
// Wheel angles become ENCODER ticks at this resolution unless ticks_per_rev= says otherwise
// (a micro-radian: the angle kept to its measured precision).
inline constexpr double kDefaultTicksPerRev = 6283185.307179586;  // 2π·10⁶
inline constexpr const char* kTfTopics[] = {"/tf_static", "/tf"};

enum class BagFormat { kRos1, kRos2, kMcap };  // kRos2: sqlite3 storage; kMcap: ROS 2 in MCAP

// A bag spec taken apart: the file or folder, and the choices after '#'.
struct BagSpec {
  std::filesystem::path path;
  BagFormat format = BagFormat::kRos1;
  std::optional<std::string> odom, truth, scan, heading, joints;  // chosen topic; "" = none; nullopt = defaults
  // Wheel encoders from sensor_msgs/JointState: the two wheel joints (default: the first names
  // holding "left" and "right"), the angle's resolution, and the nominal model (the wheels' radii
  // and the wheelbase [m]; without them the log has ENCODER records but no nominal model).
  std::string left_joint, right_joint;
  double ticks_per_rev = kDefaultTicksPerRev;
  double left_radius = 0.0, right_radius = 0.0, wheelbase = 0.0;  // radius= sets both radii
  std::string base_frame;   // default: the odometry's child_frame_id, else base_link
  std::string laser_frame;  // default: the scans' frame_id
};

// The path a log spec names: `spec` without a "#robotN" or "#odom=…" suffix.
std::string log_spec_path(const std::string& spec);

// The spec as a bag, or nullopt if the path is not a bag (not *.bag, *.db3, *.mcap, nor a folder
// with metadata.yaml, *.db3 or *.mcap). Throws InputError for a bag whose '#' part is not key=value,… with
// the keys odom, truth, scan, base, laser.
std::optional<BagSpec> parse_bag_spec(const std::string& spec);

// Reads the chosen topics into a Log: ODOM from nav_msgs/Odometry (pose; tv, rv from the twist),
// TRUEPOS from PoseStamped, PoseWithCovarianceStamped, TransformStamped or Odometry, FLASER from
// LaserScan with the laser's mount from /tf_static (or /tf) base → laser, COMPASS from
// sensor_msgs/Imu (the yaw of its orientation, taken as the robot's heading), ENCODER from
// sensor_msgs/JointState wheel angles (ticks = angle·ticks_per_rev/2π) with PARAM records of the
// nominal model when the radius and wheelbase are given. Throws InputError
// naming the file, topic and message for a missing or mistyped topic, an undecodable message
// and header stamps out of order.
Log read_bag_log(const BagSpec& spec);

// What `locbench list LOG` prints for a bag: every topic, the role locbench gives it, and notes.
struct BagTopicUse {
  BagTopic topic;
  std::string role;   // "odometry (ODOM)", "truth (TRUEPOS)", "scan (FLASER)", "laser mount", or ""
  double rate = 0.0;  // messages per second of record time (0 with fewer than 2)
};
struct BagDescription {
  std::string format;  // "ROS 1 bag", "ROS 2 bag (sqlite3)" or "ROS 2 bag (MCAP)"
  std::vector<BagTopicUse> topics;
  std::vector<std::string> notes;  // stamps against record times, the laser mount, missing roles
};
// Does not throw for a missing role (it is a note); throws InputError for an unreadable bag.
BagDescription describe_bag(const BagSpec& spec);

// A Log as bag contents on the default topics (frames odom, base_link, laser, map); the laser
// mount of the first scan becomes the /tf_static transform base_link → laser. A log with ENCODER
// records and a nominal model but no ODOM gets /odom by dead reckoning, as a ROS robot publishes it.
BagContents bag_contents(const Log& log);

// Writes a Log's ODOM, TRUEPOS, FLASER and COMPASS records (COMPASS as sensor_msgs/Imu on /imu) as
// a ROS 1 bag file, a ROS 2 bag folder or an MCAP file (zstd chunks); ENCODER and PARAM records
// have no topic yet and are left out. Written beside the target and renamed into place; a ROS 2 folder that exists
// already is refused (InputError).
void write_bag_log(const Log& log, const std::filesystem::path& path, BagFormat format);

}  // namespace locbench::io
