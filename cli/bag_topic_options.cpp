#include "cli/bag_topic_options.h"

#include <utility>
#include <vector>

#include "core/errors.h"
#include "datasets/io/bag_log.h"

namespace locbench::cli {

void add_bag_topic_options(CLI::App* cmd, BagTopicArgs& topics) {
  const char* group = "ROS bag topics (LOG a .bag, .db3, .mcap or ROS 2 bag folder; none: off)";
  cmd->add_option("--odom", topics.odom, "Odometry topic, nav_msgs/Odometry (default /odom, /wheel_odom)")
      ->group(group);
  cmd->add_option("--truth", topics.truth,
                  "Ground-truth topic: PoseStamped, PoseWithCovarianceStamped, TransformStamped or Odometry")
      ->group(group);
  cmd->add_option("--scan", topics.scan, "Laser topic, sensor_msgs/LaserScan (default /scan, /base_scan)")
      ->group(group);
  cmd->add_option("--heading", topics.heading, "Heading topic, sensor_msgs/Imu (default /imu, /imu/data)")
      ->group(group);
  cmd->add_option("--joints", topics.joints,
                  "Wheel-joint topic, sensor_msgs/JointState, as ENCODER (default /joint_states; wheels, resolution "
                  "and radii after LOG#: left=,right=,ticks_per_rev=,radius=,wheelbase=)")
      ->group(group);
}

std::string with_bag_topics(const std::string& spec, const BagTopicArgs& topics) {
  const std::vector<std::pair<const char*, const std::string*>> given{{"odom", &topics.odom},
                                                                      {"truth", &topics.truth},
                                                                      {"scan", &topics.scan},
                                                                      {"heading", &topics.heading},
                                                                      {"joints", &topics.joints}};
  std::string pairs;
  for (const auto& [key, value] : given) {
    if (value->empty()) continue;
    pairs += (pairs.empty() ? "" : ",") + std::string(key) + "=" + *value;
  }
  if (pairs.empty()) return spec;
  if (!io::parse_bag_spec(spec)) {
    throw UsageError("--odom, --truth, --scan, --heading and --joints choose a ROS bag's topics, and " + spec +
                     " is not a bag (expected a .bag, .db3 or .mcap file, or a ROS 2 bag folder)");
  }
  return spec + (io::log_spec_path(spec) == spec ? "#" : ",") + pairs;
}

}  // namespace locbench::cli
