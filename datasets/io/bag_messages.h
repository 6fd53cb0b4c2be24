#pragma once
// The few ROS message fields locbench reads from a bag, as plain structs: what the ROS 1 reader
// (ros1_bag.cpp, the only unit that includes ROS headers) and the ROS 2 reader (ros2_bag.cpp,
// sqlite3 + CDR) decode into, and what bag_log.cpp turns into a Log.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace locbench::io {

// A pose in the plane: x, y [m], yaw [rad]. Not core's Pose2: ros1_bag.cpp is compiled as C++17
// (the ROS 1 message headers do not compile as C++20) and includes only this header of ours.
struct PlanarPose {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

// Message types, named as ROS 1 names them (ROS 2's "nav_msgs/msg/Odometry" loses its "msg/").
inline constexpr const char* kOdometryType = "nav_msgs/Odometry";
inline constexpr const char* kPoseStampedType = "geometry_msgs/PoseStamped";
inline constexpr const char* kPoseWithCovarianceStampedType = "geometry_msgs/PoseWithCovarianceStamped";
inline constexpr const char* kTransformStampedType = "geometry_msgs/TransformStamped";
inline constexpr const char* kLaserScanType = "sensor_msgs/LaserScan";
inline constexpr const char* kTfMessageType = "tf2_msgs/TFMessage";
inline constexpr const char* kImuType = "sensor_msgs/Imu";
inline constexpr const char* kTwistType = "geometry_msgs/Twist";  // velocity commands: no header
inline constexpr const char* kTwistStampedType = "geometry_msgs/TwistStamped";
inline constexpr const char* kJointStateType = "sensor_msgs/JointState";

// One topic of a bag: its name, message type, message count and first/last record time [s].
struct BagTopic {
  std::string name;
  std::string type;
  std::size_t count = 0;
  double first_record = 0.0;
  double last_record = 0.0;
};

// When a message was stamped (its header) and recorded (the bag's own time), and its number on
// its topic (1-based, in record order).
struct BagStamp {
  double stamp = 0.0;
  double record_time = 0.0;
  std::size_t index = 0;
};

// nav_msgs/Odometry, geometry_msgs/PoseStamped, PoseWithCovarianceStamped or TransformStamped,
// reduced to the plane: yaw from the quaternion; tv, rv from an Odometry's twist (0 otherwise).
// geometry_msgs/Twist or TwistStamped (velocity commands): tv, rv, no pose (`velocity_only`).
struct BagPoseMessage {
  BagStamp time;
  std::string frame_id;
  std::string child_frame_id;  // Odometry and TransformStamped only
  PlanarPose pose;
  double tv = 0.0;
  double rv = 0.0;
  bool velocity_only = false;
};

// sensor_msgs/LaserScan.
struct BagScanMessage {
  BagStamp time;
  std::string frame_id;
  double angle_min = 0.0, angle_increment = 0.0, range_min = 0.0, range_max = 0.0;
  std::vector<float> ranges;
};

// sensor_msgs/Imu's orientation as a heading: the yaw of its quaternion. `has_orientation` is false
// when the IMU says it gives none (orientation_covariance[0] = −1, the ROS convention).
struct BagHeadingMessage {
  BagStamp time;
  std::string frame_id;
  double yaw = 0.0;
  bool has_orientation = true;
};

// sensor_msgs/JointState: joint names and positions [rad] (velocities and efforts are not read).
struct BagJointMessage {
  BagStamp time;
  std::vector<std::string> names;
  std::vector<double> positions;
};

// One transform of a tf2_msgs/TFMessage, in the plane: child frame in its parent frame.
struct BagTransform {
  std::string parent;
  std::string child;
  PlanarPose pose;
};

// Which topic plays which role; empty: none. tf: the TFMessage topics to read (for the laser mount).
struct BagRoles {
  std::string odom;
  std::string truth;
  std::string scan;
  std::string heading;
  std::string joints;
  std::vector<std::string> tf;
};

// What a reader returns: every topic of the bag, and the decoded messages of the chosen topics
// in record order (transforms: the first of each parent–child pair).
struct BagMessages {
  std::vector<BagTopic> topics;
  BagRoles roles;
  std::vector<BagPoseMessage> odom;
  std::vector<BagPoseMessage> truth;
  std::vector<BagScanMessage> scans;
  std::vector<BagHeadingMessage> headings;
  std::vector<BagJointMessage> joints;
  std::vector<BagTransform> transforms;
};

// Called by a reader once it knows the bag's topics, before it decodes any message; it may throw.
using BagRoleChooser = std::function<BagRoles(const std::vector<BagTopic>&)>;

// Seconds of a ROS time (sec, nanosec), the double nearest to sec + nsec/10⁹ (what a CARMEN log's
// "12.3" parses to), not sec + 1e-9 * nsec, which can miss it by one bit and move a record
// across a window boundary.
inline double stamp_seconds(std::int64_t sec, std::int64_t nsec) {
  const std::int64_t ns = sec * 1000000000 + nsec;
  constexpr std::int64_t kExact = std::int64_t{1} << 53;  // integers a double holds exactly
  if (ns > -kExact && ns < kExact) return static_cast<double>(ns) / 1e9;
  return static_cast<double>(sec) + static_cast<double>(nsec) / 1e9;
}
inline double nanoseconds_to_seconds(std::int64_t ns) { return stamp_seconds(ns / 1000000000, ns % 1000000000); }

// Text from a bag (topic and type names, a library's message) as printed in an error: bytes
// outside printable ASCII become '?', at most 200 characters (ROS names are ASCII).
inline std::string printable(const std::string& text) {
  std::string out = text.substr(0, 200);
  for (char& c : out) {
    if (c < 0x20 || c > 0x7e) c = '?';
  }
  return out;
}

// A planar pose from a 3D position and a unit quaternion (x, y, z, w): yaw about z.
PlanarPose planar_pose(double x, double y, double qx, double qy, double qz, double qw);

// The ROS 1 reader and writer (ros1_bag.cpp; the records are walked by ros1_bag_records.cpp).
// Read errors are InputErrors naming the file.
BagMessages read_ros1_bag(const std::filesystem::path& path, const BagRoleChooser& choose);
// The ROS 2 sqlite3 reader and writer (ros2_bag.cpp): `path` is the bag folder or one .db3 file.
BagMessages read_ros2_bag(const std::filesystem::path& path, const BagRoleChooser& choose);
// The ROS 2 MCAP reader and writer (mcap_bag.cpp): `path` is one .mcap file or a bag folder of them.
BagMessages read_mcap_bag(const std::filesystem::path& path, const BagRoleChooser& choose);

// What a writer puts in a bag, on the default topics /odom, /ground_truth, /scan, /imu,
// /tf_static.
struct BagContents {
  std::vector<BagPoseMessage> odom;
  // The type /odom is written as: kOdometryType, or velocity commands, kTwistType (no header: the
  // record time is the only time) or kTwistStampedType.
  std::string odom_type = kOdometryType;
  std::vector<BagPoseMessage> truth;
  std::vector<BagScanMessage> scans;
  std::vector<BagHeadingMessage> headings;
  std::vector<BagJointMessage> joints;  // on /joint_states
  std::vector<BagTransform> static_transforms;
};
// compression: "none", "bz2" or "lz4" (rosbag's chunk compression).
void write_ros1_bag(const BagContents& contents, const std::filesystem::path& path,
                    const std::string& compression = "none");
// Writes folder/metadata.yaml and folder/<name>_0.db3 (CDR, little-endian), as `ros2 bag record -o name`.
void write_ros2_bag(const BagContents& contents, const std::filesystem::path& folder, const std::string& name);
// Writes one .mcap file (profile ros2, CDR messages); compression of its chunks: "zstd" (what
// `ros2 bag record -s mcap` and the mcap CLI write), "lz4" or "none".
void write_mcap_bag(const BagContents& contents, const std::filesystem::path& path,
                    const std::string& compression = "zstd");

}  // namespace locbench::io
