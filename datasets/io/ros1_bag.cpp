// ROS 1 bags through Debian's rosbag_storage and the message headers' roscpp serialization. The
// only unit of the project that includes ROS headers (they bring Boost): compiled on its own, outside
// the unity batches (CMakeLists.txt).
#include <console_bridge/console.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
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

BagStamp stamp_of(const std_msgs::Header& h, const rosbag::MessageInstance& m, std::size_t index) {
  return {stamp_seconds(h.stamp.sec, h.stamp.nsec), stamp_seconds(m.getTime().sec, m.getTime().nsec), index};
}

// Every string and array length of a serialized message, checked against its size before
// roscpp deserializes it: roscpp resizes a vector to whatever length the bytes say (a corrupted
// LaserScan asked for 16 GB and spent minutes zero-filling it).
class LengthCheck {
 public:
  explicit LengthCheck(const std::vector<std::uint8_t>& bytes) : bytes_(bytes) {}
  void skip(std::uint64_t n) {
    if (n > bytes_.size() - at_) throw std::length_error("a field runs past the message's " + size());
    at_ += n;
  }
  std::uint32_t u32() {
    if (bytes_.size() - at_ < 4) skip(4);
    std::uint32_t v;
    std::memcpy(&v, bytes_.data() + at_, 4);
    at_ += 4;
    return v;
  }
  void string() { skip(u32()); }
  void array(std::uint64_t element) { skip(element * u32()); }
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
    if (at_ != bytes_.size()) {
      throw std::length_error(std::to_string(bytes_.size() - at_) + " bytes left over of the message's " + size());
    }
  }

 private:
  std::string size() const { return std::to_string(bytes_.size()) + " bytes"; }
  const std::vector<std::uint8_t>& bytes_;
  std::uint64_t at_ = 0;
};

void check_lengths(const std::vector<std::uint8_t>& bytes, const std::string& type) {
  LengthCheck c(bytes);
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
  }
  c.end();
}

// The message as T, after checking its type (md5 sum) and lengths; InputError otherwise.
template <class T>
boost::shared_ptr<T> as(const rosbag::MessageInstance& m, const std::filesystem::path& path, std::size_t index) {
  const std::string type = ros::message_traits::DataType<T>::value();
  const auto fail = [&](const std::string& what) {
    throw InputError(path.string(), 0,
                     "topic " + printable(m.getTopic()) + ", message " + std::to_string(index) + ": " + what);
  };
  if (m.getMD5Sum() != ros::message_traits::MD5Sum<T>::value()) {
    fail("a " + printable(m.getDataType()) + ", expected " + type);
  }
  std::vector<std::uint8_t> bytes(m.size());
  ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  m.write(out);
  try {
    check_lengths(bytes, type);
  } catch (const std::length_error& e) {
    fail(std::string("not a serialized ") + type + " (" + e.what() + ")");
  }
  auto msg = boost::make_shared<T>();
  ros::serialization::IStream in(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(in, *msg);
  return msg;
}

BagPoseMessage pose_message(const rosbag::MessageInstance& m, const std::string& type,
                            const std::filesystem::path& path, std::size_t index) {
  BagPoseMessage out;
  if (type == kOdometryType) {
    const auto o = as<nav_msgs::Odometry>(m, path, index);
    out.time = stamp_of(o->header, m, index);
    out.frame_id = o->header.frame_id;
    out.child_frame_id = o->child_frame_id;
    out.pose = planar(o->pose.pose);
    out.tv = o->twist.twist.linear.x;
    out.rv = o->twist.twist.angular.z;
  } else if (type == kPoseStampedType) {
    const auto p = as<geometry_msgs::PoseStamped>(m, path, index);
    out.time = stamp_of(p->header, m, index);
    out.frame_id = p->header.frame_id;
    out.pose = planar(p->pose);
  } else if (type == kPoseWithCovarianceStampedType) {
    const auto p = as<geometry_msgs::PoseWithCovarianceStamped>(m, path, index);
    out.time = stamp_of(p->header, m, index);
    out.frame_id = p->header.frame_id;
    out.pose = planar(p->pose.pose);
  } else {
    const auto t = as<geometry_msgs::TransformStamped>(m, path, index);
    out.time = stamp_of(t->header, m, index);
    out.frame_id = t->header.frame_id;
    out.child_frame_id = t->child_frame_id;
    out.pose = planar(t->transform);
  }
  return out;
}

BagScanMessage scan_message(const rosbag::MessageInstance& m, const std::filesystem::path& path, std::size_t index) {
  const auto s = as<sensor_msgs::LaserScan>(m, path, index);
  BagScanMessage out;
  out.time = stamp_of(s->header, m, index);
  out.frame_id = s->header.frame_id;
  out.angle_min = s->angle_min;
  out.angle_increment = s->angle_increment;
  out.range_min = s->range_min;
  out.range_max = s->range_max;
  out.ranges = std::move(s->ranges);
  return out;
}

// The bag's topics: one entry per topic (the first connection's type), counts and times from
// the index, without reading the chunks.
std::vector<BagTopic> bag_topics(const rosbag::Bag& bag) {
  std::map<std::string, std::string> types;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) types.emplace(c->topic, c->datatype);
  std::vector<BagTopic> out;
  for (const auto& [topic, type] : types) {
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    BagTopic t;
    t.name = printable(topic);
    t.type = type == "tf/tfMessage" ? kTfMessageType : printable(type);  // the same message under its ROS 1 tf name
    t.count = view.size();
    if (t.count > 0) {
      t.first_record = stamp_seconds(view.getBeginTime().sec, view.getBeginTime().nsec);
      t.last_record = stamp_seconds(view.getEndTime().sec, view.getEndTime().nsec);
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::string type_of(const std::vector<BagTopic>& topics, const std::string& name) {
  for (const BagTopic& t : topics) {
    if (t.name == name) return t.type;
  }
  return {};
}

BagMessages read_messages(const std::filesystem::path& path, const BagRoleChooser& choose) {
  rosbag::Bag bag;
  bag.open(path.string(), rosbag::bagmode::Read);
  BagMessages out;
  out.topics = bag_topics(bag);
  out.roles = choose(out.topics);
  const BagRoles& r = out.roles;
  std::vector<std::string> wanted = r.tf;
  for (const std::string* t : {&r.odom, &r.truth, &r.scan}) {
    if (!t->empty()) wanted.push_back(*t);
  }
  if (wanted.empty()) return out;
  const std::string truth_type = type_of(out.topics, r.truth);
  std::map<std::string, std::size_t> counts;
  std::set<std::pair<std::string, std::string>> seen_transforms;
  rosbag::View view(bag, rosbag::TopicQuery(wanted));
  for (const rosbag::MessageInstance& m : view) {
    const std::string& topic = m.getTopic();
    const std::size_t index = ++counts[topic];
    // One topic may play two roles (odometry from a simulator's perfect /odom as truth, say).
    if (topic == r.odom) out.odom.push_back(pose_message(m, kOdometryType, path, index));
    if (topic == r.truth) out.truth.push_back(pose_message(m, truth_type, path, index));
    if (topic == r.scan) out.scans.push_back(scan_message(m, path, index));
    if (std::find(r.tf.begin(), r.tf.end(), topic) != r.tf.end()) {
      const auto tf = as<tf2_msgs::TFMessage>(m, path, index);
      for (const geometry_msgs::TransformStamped& t : tf->transforms) {
        if (seen_transforms.emplace(t.header.frame_id, t.child_frame_id).second) {
          out.transforms.push_back({t.header.frame_id, t.child_frame_id, planar(t.transform)});
        }
      }
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
  silence_console_bridge();
  check_ros1_bag_structure(path);
  try {
    return read_messages(path, choose);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {  // rosbag::BagException, ros::serialization::StreamOverrunException, …
    throw InputError(path.string(), 0, "not a readable ROS 1 bag (expected rosbag format 2.0): " + printable(e.what()));
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
    bag.close();
  } catch (const std::exception& e) {
    throw InputError(path.string(), 0, std::string("cannot write the ROS 1 bag: ") + e.what());
  }
}

}  // namespace locbench::io
