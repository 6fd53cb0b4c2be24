#include "datasets/io/ros2_cdr.h"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/BadParamException.h>
#include <fastcdr/exceptions/Exception.h>
#include <fastcdr/exceptions/NotEnoughMemoryException.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include "core/ascii.h"
#include "core/errors.h"

namespace locbench::io {
namespace {

using eprosima::fastcdr::Cdr;
using eprosima::fastcdr::FastBuffer;

// ---- CDR ------------------------------------------------------------------------------------

// One serialized message: the encapsulation header first, then the fields in declaration order.
class CdrReader {
 public:
  CdrReader(const char* data, std::size_t size)
      : buffer_(const_cast<char*>(data), size), cdr_(buffer_, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR) {
    cdr_.read_encapsulation();
  }
  double f64() {
    double v = 0.0;
    cdr_.deserialize(v);
    return v;
  }
  float f32() {
    float v = 0.0F;
    cdr_.deserialize(v);
    return v;
  }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    cdr_.deserialize(v);
    return v;
  }
  std::string str() {
    std::string s;
    cdr_.deserialize(s);
    return s;
  }
  std::vector<float> floats() {
    std::vector<float> v;
    cdr_.deserialize(v);  // checks the length against the bytes left before allocating
    return v;
  }
  std::vector<double> doubles() {
    std::vector<double> v;
    cdr_.deserialize(v);
    return v;
  }
  std::vector<std::string> strings() {
    const std::uint32_t n = u32();
    if (n > bytes_left()) throw eprosima::fastcdr::exception::NotEnoughMemoryException("names");
    std::vector<std::string> v;
    for (std::uint32_t i = 0; i < n; ++i) v.push_back(str());
    return v;
  }
  void skip_f64(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) f64();
  }
  std::size_t bytes_left() const { return buffer_.getBufferSize() - cdr_.getSerializedDataLength(); }
  // A message of another type may decode without running out of bytes: more than the last
  // field's alignment left over says it was not this type.
  void expect_end() const {
    if (bytes_left() > 7) {
      throw eprosima::fastcdr::exception::BadParamException("bytes left over after the last field");
    }
  }

  // std_msgs/Header: builtin_interfaces/Time stamp (int32 sec, uint32 nanosec), string frame_id.
  double header(std::string& frame_id) {
    std::int32_t sec = 0;
    cdr_.deserialize(sec);
    const double t = stamp_seconds(sec, u32());
    frame_id = str();
    return t;
  }
  // geometry_msgs/Pose (Point, Quaternion) or Transform (Vector3, Quaternion), in the plane.
  PlanarPose pose() {
    std::array<double, 7> v{};
    for (double& x : v) x = f64();
    return planar_pose(v[0], v[1], v[3], v[4], v[5], v[6]);
  }

 private:
  FastBuffer buffer_;
  Cdr cdr_;
};

class CdrWriter {
 public:
  CdrWriter() : cdr_(buffer_, Cdr::LITTLE_ENDIANNESS, Cdr::DDS_CDR) { cdr_.serialize_encapsulation(); }
  template <class T>
  CdrWriter& operator<<(const T& v) {
    cdr_ << v;
    return *this;
  }
  void header(double t, const std::string& frame_id) {
    double sec = std::floor(t);
    auto nsec = static_cast<std::int64_t>(std::llround((t - sec) * 1e9));
    if (nsec >= 1000000000) {
      sec += 1.0;
      nsec -= 1000000000;
    }
    cdr_ << static_cast<std::int32_t>(sec) << static_cast<std::uint32_t>(nsec) << frame_id;
  }
  void pose(const PlanarPose& p) {
    cdr_ << p.x << p.y << 0.0;
    quaternion(p.yaw);
  }
  void quaternion(double yaw) { cdr_ << 0.0 << 0.0 << std::sin(yaw / 2.0) << std::cos(yaw / 2.0); }
  void zeros(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) cdr_ << 0.0;
  }
  std::pair<const char*, std::size_t> bytes() const { return {buffer_.getBuffer(), cdr_.getSerializedDataLength()}; }

 private:
  FastBuffer buffer_;
  Cdr cdr_;
};

// ---- decoding -------------------------------------------------------------------------------

// geometry_msgs/Twist (linear, angular: 3 doubles each), after TwistStamped's header.
BagPoseMessage decode_twist(CdrReader& r, bool stamped) {
  BagPoseMessage m;
  if (stamped) m.time.stamp = r.header(m.frame_id);
  m.velocity_only = true;
  m.tv = r.f64();
  r.skip_f64(4);
  m.rv = r.f64();
  return m;
}

BagPoseMessage decode_pose(CdrReader& r, const std::string& type) {
  if (type == kTwistType || type == kTwistStampedType) return decode_twist(r, type == kTwistStampedType);
  BagPoseMessage m;
  m.time.stamp = r.header(m.frame_id);
  if (type == kOdometryType) {
    m.child_frame_id = r.str();
    m.pose = r.pose();
    r.skip_f64(36);  // covariance
    m.tv = r.f64();
    r.skip_f64(4);
    m.rv = r.f64();
    r.skip_f64(36);
  } else if (type == kPoseStampedType) {
    m.pose = r.pose();
  } else if (type == kPoseWithCovarianceStampedType) {
    m.pose = r.pose();
    r.skip_f64(36);
  } else {  // kTransformStampedType
    m.child_frame_id = r.str();
    m.pose = r.pose();
  }
  return m;
}

BagScanMessage decode_scan(CdrReader& r) {
  BagScanMessage m;
  m.time.stamp = r.header(m.frame_id);
  m.angle_min = r.f32();
  r.f32();  // angle_max
  m.angle_increment = r.f32();
  r.f32();  // time_increment
  r.f32();  // scan_time
  m.range_min = r.f32();
  m.range_max = r.f32();
  m.ranges = r.floats();
  r.floats();  // intensities
  return m;
}

// sensor_msgs/Imu: header, orientation, its covariance, angular velocity, linear acceleration
// (each with a covariance).
BagHeadingMessage decode_imu(CdrReader& r) {
  BagHeadingMessage m;
  m.time.stamp = r.header(m.frame_id);
  std::array<double, 4> q{};
  for (double& x : q) x = r.f64();
  m.yaw = planar_pose(0.0, 0.0, q[0], q[1], q[2], q[3]).yaw;
  m.has_orientation = r.f64() != -1.0;  // orientation_covariance[0]
  r.skip_f64(8 + 3 + 9 + 3 + 9);
  return m;
}

// sensor_msgs/JointState: header, name[], position[], velocity[], effort[].
BagJointMessage decode_joints(CdrReader& r) {
  BagJointMessage m;
  std::string frame;
  m.time.stamp = r.header(frame);
  m.names = r.strings();
  m.positions = r.doubles();
  r.doubles();  // velocity
  r.doubles();  // effort
  return m;
}

void decode_transforms(CdrReader& r, std::set<std::pair<std::string, std::string>>& seen,
                       std::vector<BagTransform>& out) {
  const std::uint32_t n = r.u32();
  if (n > r.bytes_left()) throw eprosima::fastcdr::exception::NotEnoughMemoryException("transforms");
  for (std::uint32_t i = 0; i < n; ++i) {
    BagTransform t;
    r.header(t.parent);
    t.child = r.str();
    t.pose = r.pose();
    if (seen.emplace(t.parent, t.child).second) out.push_back(std::move(t));
  }
}

std::int64_t nanoseconds(double t) { return std::llround(t * 1e9); }

template <class F>
void add(Ros2Serialized& out, std::size_t topic, double time, F&& serialize) {
  CdrWriter w;
  serialize(w);
  const auto [p, n] = w.bytes();
  out.messages.push_back({topic, nanoseconds(time), std::string(p, n)});
  ++out.topics[topic].count;
}

}  // namespace

std::string ros1_type_name(std::string type) {
  const auto at = type.find("/msg/");
  if (at != std::string::npos) type.erase(at, 4);
  return type;
}

bool Ros2MessageDecoder::wants(const std::string& topic) const {
  const BagRoles& r = out_.roles;
  return topic == r.odom || topic == r.truth || topic == r.scan || topic == r.heading || topic == r.joints ||
         std::find(r.tf.begin(), r.tf.end(), topic) != r.tf.end();
}

void Ros2MessageDecoder::check_format(const std::string& topic, const std::string& format) const {
  if (wants(topic) && ascii_lowercase(format) != "cdr") {
    throw InputError(file_.string(), 0,
                     "topic " + topic + ": serialization format \"" + printable(format) + "\" (expected cdr)");
  }
}

void Ros2MessageDecoder::add(const std::string& topic, const std::string& type, std::int64_t record_ns,
                             const char* data, std::size_t size) {
  const BagRoles& r = out_.roles;
  if (!wants(topic)) return;
  const std::size_t index = ++counts_[topic];
  const double record_time = nanoseconds_to_seconds(record_ns);
  // One message decoded into `into`, every byte used, stamped with its record time and number.
  const auto decode = [&](auto& into, auto&& decoder) {
    CdrReader reader(data, size);
    into.push_back(decoder(reader));
    reader.expect_end();
    into.back().time = {into.back().time.stamp, record_time, index};
  };
  try {
    if (topic == r.odom) {
      if (type != kOdometryType && type != kTwistType && type != kTwistStampedType) {
        throw InputError(file_.string(), 0,
                         "topic " + topic + ": a " + type + ", expected " + kOdometryType + ", " + kTwistType + " or " +
                             kTwistStampedType);
      }
      decode(out_.odom, [&](CdrReader& reader) { return decode_pose(reader, type); });
    }
    if (topic == r.truth) decode(out_.truth, [&](CdrReader& reader) { return decode_pose(reader, type); });
    if (topic == r.scan) decode(out_.scans, decode_scan);
    if (topic == r.joints) decode(out_.joints, decode_joints);
    if (topic == r.heading) decode(out_.headings, decode_imu);
    if (std::find(r.tf.begin(), r.tf.end(), topic) != r.tf.end()) {
      CdrReader reader(data, size);
      decode_transforms(reader, seen_, out_.transforms);
      reader.expect_end();
    }
  } catch (const eprosima::fastcdr::exception::Exception& e) {
    throw InputError(file_.string(), 0,
                     "topic " + topic + ", message " + std::to_string(index) + ": not a CDR-serialized " + type + " (" +
                         std::to_string(size) + " bytes: " + printable(e.what()) + ")");
  }
}

Ros2Serialized serialize_ros2(const BagContents& c) {
  Ros2Serialized out;
  out.topics = {{"/tf_static", "tf2_msgs/msg/TFMessage"},
                {"/odom", "nav_msgs/msg/Odometry"},
                {"/ground_truth", "geometry_msgs/msg/PoseStamped"},
                {"/scan", "sensor_msgs/msg/LaserScan"},
                {"/imu", "sensor_msgs/msg/Imu"},
                {"/joint_states", "sensor_msgs/msg/JointState"}};
  if (!c.static_transforms.empty()) {
    add(out, 0, 0.0, [&](CdrWriter& w) {
      w << static_cast<std::uint32_t>(c.static_transforms.size());
      for (const BagTransform& t : c.static_transforms) {
        w.header(0.0, t.parent);
        w << t.child;
        w.pose(t.pose);
      }
    });
  }
  if (c.odom_type == kTwistType) out.topics[1].type = "geometry_msgs/msg/Twist";
  if (c.odom_type == kTwistStampedType) out.topics[1].type = "geometry_msgs/msg/TwistStamped";
  for (const BagPoseMessage& m : c.odom) {
    if (c.odom_type != kOdometryType) {
      add(out, 1, m.time.record_time, [&](CdrWriter& w) {
        if (c.odom_type == kTwistStampedType) w.header(m.time.stamp, m.frame_id);
        w << m.tv << 0.0 << 0.0 << 0.0 << 0.0 << m.rv;
      });
      continue;
    }
    add(out, 1, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, m.frame_id);
      w << m.child_frame_id;
      w.pose(m.pose);
      w.zeros(36);
      w << m.tv << 0.0 << 0.0 << 0.0 << 0.0 << m.rv;
      w.zeros(36);
    });
  }
  for (const BagPoseMessage& m : c.truth) {
    add(out, 2, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, m.frame_id);
      w.pose(m.pose);
    });
  }
  for (const BagScanMessage& m : c.scans) {
    add(out, 3, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, m.frame_id);
      const double n = static_cast<double>(m.ranges.size());
      w << static_cast<float>(m.angle_min) << static_cast<float>(m.angle_min + m.angle_increment * (n - 1))
        << static_cast<float>(m.angle_increment) << 0.0F << 0.0F << static_cast<float>(m.range_min)
        << static_cast<float>(m.range_max) << m.ranges << std::vector<float>{};
    });
  }
  for (const BagHeadingMessage& m : c.headings) {
    add(out, 4, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, m.frame_id);
      w.quaternion(m.yaw);
      w << (m.has_orientation ? 0.0 : -1.0);  // orientation_covariance[0]
      w.zeros(8 + 3 + 9 + 3 + 9);             // covariances, angular velocity, linear acceleration
    });
  }
  for (const BagJointMessage& m : c.joints) {
    add(out, 5, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, "");
      w << m.names << m.positions << std::vector<double>{} << std::vector<double>{};
    });
  }
  std::stable_sort(out.messages.begin(), out.messages.end(),
                   [](const Ros2Message& a, const Ros2Message& b) { return a.time < b.time; });
  return out;
}

}  // namespace locbench::io
