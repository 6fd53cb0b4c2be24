// ROS 1 bags: the records walked by ros1_bag_records.cpp, the messages deserialized by the message
// headers' roscpp serialization; written (tests, `simulate --ros1-bag`) by Debian's rosbag_storage.
// The only unit of the project that includes ROS headers (they bring Boost): compiled on its own,
// outside the unity batches, as C++17 (CMakeLists.txt).
#include <console_bridge/console.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/TwistStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>
#include <boost/make_shared.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/errors.h"  // C++17 as well
#include "datasets/io/bag_messages.h"
#include "datasets/io/ros1_bag_records.h"

namespace locbench::io {
namespace {

// rosbag_storage reports through console_bridge on stderr; locbench reports its own errors.
void silence_console_bridge() { console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE); }

PlanarPose planar(const geometry_msgs::Pose& p) {
  return planar_pose(p.position.x, p.position.y, p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w);
}

PlanarPose planar(const geometry_msgs::Transform& t) {
  return planar_pose(t.translation.x, t.translation.y, t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w);
}

// One message record of a chosen topic.
struct RawMessage {
  const Ros1Connection& connection;
  double record_time;
  std::size_t index;  // on its topic, 1-based
  const std::uint8_t* data;
  std::uint32_t size;
};

BagStamp stamp_of(const std_msgs::Header& h, const RawMessage& m) {
  return {stamp_seconds(h.stamp.sec, h.stamp.nsec), m.record_time, m.index};
}

// The header's stamp and frame into `out`.
template <class Message>
void read_header(Message& out, const std_msgs::Header& h, const RawMessage& m) {
  out.time = stamp_of(h, m);
  out.frame_id = h.frame_id;
}

// Every string and array length of a serialized message, checked against its size before
// roscpp deserializes it: roscpp resizes a vector to whatever length the bytes say (a corrupted
// LaserScan asked for 16 GB and spent minutes zero-filling it).
class LengthCheck {
 public:
  LengthCheck(const std::uint8_t* data, std::uint32_t size) : data_(data), size_(size) {}
  void skip(std::uint64_t n) {
    if (n > size_ - at_) throw std::length_error("a field runs past the message's " + size());
    at_ += n;
  }
  std::uint32_t u32() {
    if (size_ - at_ < 4) skip(4);
    std::uint32_t v;
    std::memcpy(&v, data_ + at_, 4);
    at_ += 4;
    return v;
  }
  void string() { skip(u32()); }
  void array(std::uint64_t element) { skip(element * u32()); }
  void strings() {
    for (std::uint32_t n = u32(); n > 0; --n) string();
  }
  void header() {
    skip(12);  // seq, stamp
    string();  // frame_id
  }
  void transform_stamped() {
    header();
    string();  // child_frame_id
    skip(7 * 8);
  }
  void end() const {
    if (at_ != size_)
      throw std::length_error(std::to_string(size_ - at_) + " bytes left over of the message's " + size());
  }

 private:
  std::string size() const { return std::to_string(size_) + " bytes"; }
  const std::uint8_t* data_;
  std::uint64_t size_;
  std::uint64_t at_ = 0;
};

void check_lengths(const RawMessage& m, const std::string& type) {
  LengthCheck c(m.data, m.size);
  if (type == kOdometryType) {
    c.header();
    c.string();
    c.skip((7 + 36 + 6 + 36) * 8);
  } else if (type == kPoseStampedType) {
    c.header();
    c.skip(7 * 8);
  } else if (type == kPoseWithCovarianceStampedType) {
    c.header();
    c.skip((7 + 36) * 8);
  } else if (type == kTransformStampedType) {
    c.transform_stamped();
  } else if (type == kLaserScanType) {
    c.header();
    c.skip(7 * 4);
    c.array(4);  // ranges
    c.array(4);  // intensities
  } else if (type == kTfMessageType) {
    for (std::uint32_t n = c.u32(); n > 0; --n) c.transform_stamped();
  } else if (type == kTwistType) {
    c.skip(6 * 8);
  } else if (type == kTwistStampedType) {
    c.header();
    c.skip(6 * 8);
  } else if (type == kJointStateType) {
    c.header();
    c.strings();
    c.array(8);  // position
    c.array(8);  // velocity
    c.array(8);  // effort
  } else if (type == kImuType) {
    c.header();
    c.skip((4 + 9 + 3 + 9 + 3 + 9) * 8);
  }
  c.end();
}

// The message as T, after checking its type (md5 sum) and lengths; InputError otherwise.
template <class T>
boost::shared_ptr<T> as(const RawMessage& m, const std::filesystem::path& path) {
  const std::string type = ros::message_traits::DataType<T>::value();
  const auto fail = [&](const std::string& what) {
    throw InputError(path.string(), 0,
                     "topic " + printable(m.connection.topic) + ", message " + std::to_string(m.index) + ": " + what);
  };
  if (m.connection.md5sum != ros::message_traits::MD5Sum<T>::value()) {
    fail("a " + printable(m.connection.type) + ", expected " + type);
  }
  try {
    check_lengths(m, type);
  } catch (const std::length_error& e) {
    fail(std::string("not a serialized ") + type + " (" + e.what() + ")");
  }
  auto msg = boost::make_shared<T>();
  ros::serialization::IStream in(const_cast<std::uint8_t*>(m.data), m.size);  // only read
  ros::serialization::deserialize(in, *msg);
  return msg;
}

BagPoseMessage pose_message(const RawMessage& m, const std::string& type, const std::filesystem::path& path) {
  BagPoseMessage out;
  if (type == kTwistType || type == kTwistStampedType) {  // velocity commands
    out.velocity_only = true;
    geometry_msgs::Twist t;
    if (type == kTwistStampedType) {
      const auto s = as<geometry_msgs::TwistStamped>(m, path);
      read_header(out, s->header, m);
      t = s->twist;
    } else {
      t = *as<geometry_msgs::Twist>(m, path);
      out.time = {0.0, m.record_time, m.index};  // no header: the record time is used
    }
    out.tv = t.linear.x;
    out.rv = t.angular.z;
  } else if (type == kOdometryType) {
    const auto o = as<nav_msgs::Odometry>(m, path);
    read_header(out, o->header, m);
    out.child_frame_id = o->child_frame_id;
    out.pose = planar(o->pose.pose);
    out.tv = o->twist.twist.linear.x;
    out.rv = o->twist.twist.angular.z;
  } else if (type == kPoseStampedType) {
    const auto p = as<geometry_msgs::PoseStamped>(m, path);
    read_header(out, p->header, m);
    out.pose = planar(p->pose);
  } else if (type == kPoseWithCovarianceStampedType) {
    const auto p = as<geometry_msgs::PoseWithCovarianceStamped>(m, path);
    read_header(out, p->header, m);
    out.pose = planar(p->pose.pose);
  } else {
    const auto t = as<geometry_msgs::TransformStamped>(m, path);
    read_header(out, t->header, m);
    out.child_frame_id = t->child_frame_id;
    out.pose = planar(t->transform);
  }
  return out;
}

BagScanMessage scan_message(const RawMessage& m, const std::filesystem::path& path) {
  const auto s = as<sensor_msgs::LaserScan>(m, path);
  BagScanMessage out;
  read_header(out, s->header, m);
  out.angle_min = s->angle_min;
  out.angle_increment = s->angle_increment;
  out.range_min = s->range_min;
  out.range_max = s->range_max;
  out.ranges = std::move(s->ranges);
  return out;
}

BagHeadingMessage heading_message(const RawMessage& m, const std::filesystem::path& path) {
  const auto i = as<sensor_msgs::Imu>(m, path);
  BagHeadingMessage out;
  read_header(out, i->header, m);
  const auto& q = i->orientation;
  out.yaw = planar_pose(0.0, 0.0, q.x, q.y, q.z, q.w).yaw;
  out.has_orientation = i->orientation_covariance[0] != -1.0;
  return out;
}

BagJointMessage joint_message(const RawMessage& m, const std::filesystem::path& path) {
  const auto j = as<sensor_msgs::JointState>(m, path);
  BagJointMessage out;
  out.time = stamp_of(j->header, m);
  out.names = std::move(j->name);
  out.positions = std::move(j->position);
  return out;
}

std::string type_name(const std::string& type) {
  return type == "tf/tfMessage" ? kTfMessageType : printable(type);  // the same message under its ROS 1 tf name
}

BagMessages read_messages(const std::filesystem::path& path, const BagRoleChooser& choose) {
  BagMessages out;
  std::map<std::uint32_t, Ros1Connection> connections;
  std::map<std::string, std::size_t> counts;  // messages seen per topic
  std::map<std::string, BagTopic*> by_name;   // into out.topics
  std::set<std::pair<std::string, std::string>> seen_transforms;
  std::string truth_type, odom_type;
  const auto chosen = [&](const std::map<std::uint32_t, Ros1Connection>& all) {
    connections = all;
    std::map<std::string, BagTopic> topics;  // one entry per topic: the first connection's type
    for (const auto& [id, c] : all) {
      BagTopic& t = topics[printable(c.topic)];
      t.name = printable(c.topic);
      if (t.type.empty()) t.type = type_name(c.type);
      t.count += c.count;
    }
    for (auto& [name, t] : topics) out.topics.push_back(t);
    for (BagTopic& t : out.topics) by_name[t.name] = &t;
    out.roles = choose(out.topics);
    if (by_name.count(out.roles.truth)) truth_type = by_name[out.roles.truth]->type;
    if (by_name.count(out.roles.odom)) odom_type = by_name[out.roles.odom]->type;
    return true;
  };
  const auto visit = [&](std::uint32_t id, std::uint32_t sec, std::uint32_t nsec, const std::uint8_t* data,
                         std::uint32_t size) {
    const auto c = connections.find(id);
    if (c == connections.end()) {
      throw InputError(path.string(), 0,
                       "a message of connection " + std::to_string(id) + ", which the bag does not declare");
    }
    const std::string topic = printable(c->second.topic);  // as out.topics names it
    const double record_time = stamp_seconds(sec, nsec);
    const std::size_t index = ++counts[topic];
    if (BagTopic* t = by_name.count(topic) ? by_name[topic] : nullptr) {
      if (index == 1) t->first_record = record_time;
      t->first_record = std::min(t->first_record, record_time);
      t->last_record = std::max(t->last_record, record_time);
    }
    const BagRoles& r = out.roles;
    const RawMessage m{c->second, record_time, index, data, size};
    // One topic may play two roles (odometry from a simulator's perfect /odom as truth, say).
    if (topic == r.odom) out.odom.push_back(pose_message(m, odom_type, path));
    if (topic == r.truth) out.truth.push_back(pose_message(m, truth_type, path));
    if (topic == r.scan) out.scans.push_back(scan_message(m, path));
    if (topic == r.heading) out.headings.push_back(heading_message(m, path));
    if (topic == r.joints) out.joints.push_back(joint_message(m, path));
    if (std::find(r.tf.begin(), r.tf.end(), topic) != r.tf.end()) {
      const auto tf = as<tf2_msgs::TFMessage>(m, path);
      for (const geometry_msgs::TransformStamped& t : tf->transforms) {
        if (seen_transforms.emplace(t.header.frame_id, t.child_frame_id).second) {
          out.transforms.push_back({t.header.frame_id, t.child_frame_id, planar(t.transform)});
        }
      }
    }
  };
  read_ros1_records(path, chosen, visit);
  for (const BagTopic& t : out.topics) {
    if (counts[t.name] != t.count) {
      throw InputError(path.string(), 0,
                       "topic " + t.name + ": " + std::to_string(counts[t.name]) + " messages, the index says " +
                           std::to_string(t.count) + " (a damaged bag: `rosbag reindex` rebuilds the index)");
    }
  }
  return out;
}

std_msgs::Header header(const BagPoseMessage& m) {
  std_msgs::Header h;
  h.stamp.fromSec(m.time.stamp);
  h.frame_id = m.frame_id;
  return h;
}

geometry_msgs::Pose pose3(const PlanarPose& p) {
  geometry_msgs::Pose out;
  out.position.x = p.x;
  out.position.y = p.y;
  out.orientation.z = std::sin(p.yaw / 2.0);
  out.orientation.w = std::cos(p.yaw / 2.0);
  return out;
}

// A bag's record time: the stamp, but at least ROS 1's smallest time (rosbag refuses 0).
ros::Time record_time(double stamp) { return std::max(ros::Time().fromSec(stamp), ros::TIME_MIN); }

}  // namespace

BagMessages read_ros1_bag(const std::filesystem::path& path, const BagRoleChooser& choose) {
  try {
    return read_messages(path, choose);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {  // ros::serialization::StreamOverrunException, std::bad_alloc, …
    throw InputError(path.string(), 0, "not a readable ROS 1 bag: " + printable(e.what()));
  }
}

void write_ros1_bag(const BagContents& c, const std::filesystem::path& path, const std::string& compression) {
  silence_console_bridge();
  try {
    rosbag::Bag bag(path.string(), rosbag::bagmode::Write);
    bag.setCompression(compression == "bz2"   ? rosbag::compression::BZ2
                       : compression == "lz4" ? rosbag::compression::LZ4
                                              : rosbag::compression::Uncompressed);
    if (!c.static_transforms.empty()) {
      tf2_msgs::TFMessage tf;
      for (const BagTransform& t : c.static_transforms) {
        geometry_msgs::TransformStamped s;
        s.header.frame_id = t.parent;
        s.child_frame_id = t.child;
        const geometry_msgs::Pose p = pose3(t.pose);
        s.transform.translation.x = p.position.x;
        s.transform.translation.y = p.position.y;
        s.transform.rotation = p.orientation;
        tf.transforms.push_back(s);
      }
      bag.write("/tf_static", ros::TIME_MIN, tf);
    }
    for (const BagPoseMessage& m : c.odom) {
      if (c.odom_type != kOdometryType) {
        geometry_msgs::TwistStamped t;
        t.header = header(m);
        t.twist.linear.x = m.tv;
        t.twist.angular.z = m.rv;
        if (c.odom_type == kTwistStampedType) {
          bag.write("/odom", record_time(m.time.record_time), t);
        } else {
          bag.write("/odom", record_time(m.time.record_time), t.twist);
        }
        continue;
      }
      nav_msgs::Odometry o;
      o.header = header(m);
      o.child_frame_id = m.child_frame_id;
      o.pose.pose = pose3(m.pose);
      o.twist.twist.linear.x = m.tv;
      o.twist.twist.angular.z = m.rv;
      bag.write("/odom", record_time(m.time.record_time), o);
    }
    for (const BagPoseMessage& m : c.truth) {
      geometry_msgs::PoseStamped p;
      p.header = header(m);
      p.pose = pose3(m.pose);
      bag.write("/ground_truth", record_time(m.time.record_time), p);
    }
    for (const BagScanMessage& m : c.scans) {
      sensor_msgs::LaserScan s;
      s.header.stamp.fromSec(m.time.stamp);
      s.header.frame_id = m.frame_id;
      s.angle_min = static_cast<float>(m.angle_min);
      s.angle_increment = static_cast<float>(m.angle_increment);
      s.angle_max = static_cast<float>(m.angle_min + m.angle_increment * (static_cast<double>(m.ranges.size()) - 1));
      s.range_min = static_cast<float>(m.range_min);
      s.range_max = static_cast<float>(m.range_max);
      s.ranges = m.ranges;
      bag.write("/scan", record_time(m.time.record_time), s);
    }
    for (const BagJointMessage& m : c.joints) {
      sensor_msgs::JointState j;
      j.header.stamp.fromSec(m.time.stamp);
      j.name = m.names;
      j.position = m.positions;
      bag.write("/joint_states", record_time(m.time.record_time), j);
    }
    for (const BagHeadingMessage& m : c.headings) {
      sensor_msgs::Imu i;
      i.header.stamp.fromSec(m.time.stamp);
      i.header.frame_id = m.frame_id;
      i.orientation = pose3({0.0, 0.0, m.yaw}).orientation;
      i.orientation_covariance[0] = m.has_orientation ? 0.0 : -1.0;
      bag.write("/imu", record_time(m.time.record_time), i);
    }
    bag.close();
  } catch (const std::exception& e) {
    throw InputError(path.string(), 0, std::string("cannot write the ROS 1 bag: ") + e.what());
  }
}

}  // namespace locbench::io
