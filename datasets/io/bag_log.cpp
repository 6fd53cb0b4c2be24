#include "datasets/io/bag_log.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iterator>
#include <map>
#include <utility>

#include "core/ascii.h"
#include "core/dead_reckoning.h"
#include "core/errors.h"
#include "core/units.h"
#include "datasets/io/dataset_name.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {

PlanarPose planar_pose(double x, double y, double qx, double qy, double qz, double qw) {
  if (qx != 0.0 || qy != 0.0) {
    // Yaw of a 3D rotation (z-y-x Euler angles), as tf2::getYaw.
    return {x, y, std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))};
  }
  // A rotation about z: (qz, qw) = (sin θ/2, cos θ/2). Several doubles next to 2 atan2(qz, qw) may
  // write as exactly these numbers (2 atan2 alone misses the heading written in 8% of cases). Of
  // those, one with a short decimal form (≤ 15 digits: a log's "-0.804468") if there is one, else
  // the nearest: a heading written to a bag, from a text log or a computation, reads back as the
  // same double.
  const double yaw = 2.0 * std::atan2(qz, qw);
  const auto writes_as = [&](double t) { return std::sin(t / 2.0) == qz && std::cos(t / 2.0) == qw; };
  const auto short_decimal = [](double t) {
    char text[32];
    const char* end = std::to_chars(text, text + sizeof text, t, std::chars_format::scientific).ptr;
    const char* e = std::find(static_cast<const char*>(text), end, 'e');
    return std::count_if(static_cast<const char*>(text), e, [](char c) { return c >= '0' && c <= '9'; }) <= 15;
  };
  std::optional<double> nearest, shortest;
  if (writes_as(yaw)) {
    nearest = yaw;
    if (short_decimal(yaw)) shortest = yaw;
  }
  double below = yaw, above = yaw;
  for (int step = 0; step < 4; ++step) {  // nearest first
    below = std::nextafter(below, -INFINITY);
    above = std::nextafter(above, INFINITY);
    for (const double t : {below, above}) {
      if (!writes_as(t)) continue;
      if (!nearest) nearest = t;
      if (!shortest && short_decimal(t)) shortest = t;
    }
  }
  return {x, y, shortest.value_or(nearest.value_or(yaw))};
}

namespace {

Pose2 pose2(const PlanarPose& p) { return {p.x, p.y, p.yaw}; }
PlanarPose planar(const Pose2& p) { return {p.x, p.y, p.theta}; }

constexpr const char* kChoose =
    "choose topics with LOG#odom=TOPIC,truth=TOPIC,scan=TOPIC,heading=TOPIC,joints=TOPIC (none: off; "
    "base=FRAME,laser=FRAME for the mount)";

std::optional<BagFormat> bag_format(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    bool metadata = std::filesystem::exists(path / "metadata.yaml", ec), sqlite = false, mcap = false;
    for (const auto& e : std::filesystem::directory_iterator(path, ec)) {
      const std::string name = ascii_lowercase(e.path().filename().string());
      sqlite = sqlite || name.ends_with(".db3");
      mcap = mcap || name.ends_with(".mcap") || name.ends_with(".mcap.zstd") || name.ends_with(".mcap.lz4");
    }
    if (mcap && !sqlite) return BagFormat::kMcap;
    if (metadata || sqlite) return BagFormat::kRos2;
    return std::nullopt;
  }
  const std::string ext = ascii_lowercase(path.extension().string());
  if (ext == ".bag") return BagFormat::kRos1;
  if (ext == ".db3") return BagFormat::kRos2;
  if (ext == ".mcap") return BagFormat::kMcap;
  return std::nullopt;
}

std::string with_slash(std::string topic) { return topic.empty() || topic[0] == '/' ? topic : "/" + topic; }

// ---- choosing topics ------------------------------------------------------------------------

struct Role {
  const char* key;   // in the spec: odom, truth, scan
  const char* what;  // in messages
  const std::optional<std::string>* chosen;
  std::vector<std::string> defaults;
  std::vector<std::string> types;
};

std::string joined(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

std::string topic_list(const std::vector<BagTopic>& topics) {
  std::vector<std::string> names;
  for (const BagTopic& t : topics) names.push_back(t.name + " (" + t.type + ")");
  return names.empty() ? "the bag has no topics" : "topics: " + joined(names);
}

const BagTopic* find_topic(const std::vector<BagTopic>& topics, const std::string& name) {
  for (const BagTopic& t : topics) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

// The topic for a role: the chosen one, checked, or the first default present. A topic of an
// unexpected type is an error whether chosen or by default (it would be read as something it is not).
std::string choose_role(const Role& role, const std::vector<BagTopic>& topics, const std::string& file) {
  const auto check = [&](const BagTopic& t, const std::string& how) {
    if (std::find(role.types.begin(), role.types.end(), t.type) == role.types.end()) {
      throw InputError(file, 0,
                       fmt::format("topic {} ({}) is a {}, expected {} for the {}; {}", t.name, how, t.type,
                                   joined(role.types, " or "), role.what, kChoose));
    }
    if (t.count == 0) throw InputError(file, 0, fmt::format("topic {} ({}) has no messages", t.name, how));
    return t.name;
  };
  if (*role.chosen) {
    if ((*role.chosen)->empty()) return {};
    const BagTopic* t = find_topic(topics, **role.chosen);
    if (!t) {
      throw InputError(
          file, 0, fmt::format("#{}={}: no such topic in the bag ({})", role.key, **role.chosen, topic_list(topics)));
    }
    return check(*t, std::string("#") + role.key + "=");
  }
  for (const std::string& name : role.defaults) {
    if (const BagTopic* t = find_topic(topics, name)) return check(*t, "a default");
  }
  return {};
}

std::vector<Role> roles_of(const BagSpec& spec) {
  const auto list = [](const auto& names) { return std::vector<std::string>(std::begin(names), std::end(names)); };
  return {
      {"odom", "odometry", &spec.odom, list(kDefaultOdometryTopics), {kOdometryType, kTwistStampedType, kTwistType}},
      {"truth",
       "ground truth",
       &spec.truth,
       list(kDefaultTruthTopics),
       {kPoseStampedType, kOdometryType, kPoseWithCovarianceStampedType, kTransformStampedType}},
      {"scan", "laser scans", &spec.scan, list(kDefaultScanTopics), {kLaserScanType}},
      {"heading", "heading", &spec.heading, list(kDefaultHeadingTopics), {kImuType}},
      {"joints", "wheel joints", &spec.joints, list(kDefaultJointTopics), {kJointStateType}}};
}

BagRoles choose_roles(const BagSpec& spec, const std::vector<BagTopic>& topics, bool need_odometry) {
  const std::string file = spec.path.string();
  const std::vector<Role> roles = roles_of(spec);
  BagRoles out;
  out.odom = choose_role(roles[0], topics, file);
  out.truth = choose_role(roles[1], topics, file);
  out.scan = choose_role(roles[2], topics, file);
  out.heading = choose_role(roles[3], topics, file);
  out.joints = choose_role(roles[4], topics, file);
  if (need_odometry && out.odom.empty()) {
    throw InputError(file, 0,
                     fmt::format("no odometry topic: none of {} is in the bag ({}); {}", joined(roles[0].defaults),
                                 topic_list(topics), kChoose));
  }
  for (const char* tf : kTfTopics) {
    const BagTopic* t = find_topic(topics, tf);
    if (t && t->type == kTfMessageType) out.tf.push_back(tf);
  }
  return out;
}

BagMessages read_bag(const BagSpec& spec, bool need_odometry) {
  const BagRoleChooser choose = [&](const std::vector<BagTopic>& topics) {
    return choose_roles(spec, topics, need_odometry);
  };
  switch (spec.format) {
    case BagFormat::kRos1: return read_ros1_bag(spec.path, choose);
    case BagFormat::kRos2: return read_ros2_bag(spec.path, choose);
    case BagFormat::kMcap: return read_mcap_bag(spec.path, choose);
  }
  throw std::logic_error("read_bag: unknown format");
}

// ---- time -----------------------------------------------------------------------------------

// The times a topic's messages are used at: the header stamps, or the record times when no
// message has its stamp set (all zero). Throws for stamps out of order or not finite.
template <class Message>
std::vector<double> message_times(const std::vector<Message>& messages, const std::string& topic,
                                  const std::string& file) {
  const bool unset =
      std::all_of(messages.begin(), messages.end(), [](const Message& m) { return m.time.stamp == 0.0; });
  std::vector<double> t;
  t.reserve(messages.size());
  for (const Message& m : messages) {
    t.push_back(unset ? m.time.record_time : m.time.stamp);
    if (!std::isfinite(t.back())) {
      throw InputError(file, 0, fmt::format("topic {}, message {}: time is not a finite number", topic, m.time.index));
    }
    if (t.size() >= 2 && t.back() < t[t.size() - 2]) {
      throw InputError(file, 0,
                       fmt::format("topic {}, message {}: header stamp {:.9f} s is before the previous message's "
                                   "{:.9f} s (expected stamps in time order)",
                                   topic, m.time.index, t.back(), t[t.size() - 2]));
    }
  }
  return t;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// A note when a topic's header stamps and record times disagree by more than one sample period.
template <class Message>
std::optional<std::string> stamp_note(const std::vector<Message>& messages, const std::string& topic) {
  if (messages.size() < 2) return std::nullopt;
  if (std::all_of(messages.begin(), messages.end(), [](const Message& m) { return m.time.stamp == 0.0; })) {
    return fmt::format("{}: header stamps are not set (all zero): the record times are used", topic);
  }
  std::vector<double> periods;
  double worst = 0.0;
  std::size_t worst_at = 0;
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const double lag = std::abs(messages[i].time.record_time - messages[i].time.stamp);
    if (lag > worst) worst = lag, worst_at = messages[i].time.index;
    if (i > 0 && messages[i].time.stamp > messages[i - 1].time.stamp) {
      periods.push_back(messages[i].time.stamp - messages[i - 1].time.stamp);
    }
  }
  const double period = median(periods);
  if (!(worst > period)) return std::nullopt;
  return fmt::format(
      "{}: header stamps differ from the record times by up to {:.3g} s (message {}), more than one sample period "
      "({:.3g} s): the header stamps are used",
      topic, worst, worst_at, period);
}

// ---- the laser mount ------------------------------------------------------------------------

// The pose of `child` in `parent` along the transform tree (child → its parent → …), or nullopt.
std::optional<Pose2> frame_in(const std::vector<BagTransform>& transforms, const std::string& parent,
                              std::string child) {
  Pose2 pose = Pose2::identity();
  for (std::size_t hops = 0; hops <= transforms.size(); ++hops) {
    if (child == parent) return pose;
    const auto t =
        std::find_if(transforms.begin(), transforms.end(), [&](const BagTransform& x) { return x.child == child; });
    if (t == transforms.end()) return std::nullopt;
    pose = pose2(t->pose) * pose;
    child = t->parent;
  }
  return std::nullopt;  // a loop
}

std::string strip_slash(std::string frame) { return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame; }

struct Mount {
  Pose2 pose;
  std::string how;
};

Mount laser_mount(const BagSpec& spec, const BagMessages& m) {
  std::vector<BagTransform> transforms = m.transforms;
  for (BagTransform& t : transforms) t.parent = strip_slash(t.parent), t.child = strip_slash(t.child);
  std::string base = strip_slash(spec.base_frame);
  if (base.empty() && !m.odom.empty()) base = strip_slash(m.odom.front().child_frame_id);
  if (base.empty()) base = "base_link";
  const std::string laser = strip_slash(spec.laser_frame.empty() ? m.scans.front().frame_id : spec.laser_frame);
  if (const auto pose = frame_in(transforms, base, laser)) {
    return {*pose, fmt::format("laser mount {} in {} from {}: x = {:.4g} m, y = {:.4g} m, θ = {:.4g} rad",
                               printable(laser), printable(base), joined(m.roles.tf), pose->x, pose->y, pose->theta)};
  }
  const std::string missing = fmt::format("laser mount: no transform from {} to {} in {}", printable(base),
                                          laser.empty() ? "(no frame_id)" : printable(laser),
                                          m.roles.tf.empty() ? "the bag (no /tf_static or /tf)" : joined(m.roles.tf));
  if (!spec.base_frame.empty() || !spec.laser_frame.empty()) {  // frames the user named: theirs must be there
    throw InputError(spec.path.string(), 0, missing + " (expected the frames named by #base= and #laser=)");
  }
  return {Pose2::identity(),
          missing + ": the laser is taken to sit at the base frame (#base=FRAME,laser=FRAME to name the frames)"};
}

// ---- wheel joints ---------------------------------------------------------------------------

// The wheel joint of a side: the one named, or the first name holding the side's word.
std::string wheel_joint(const BagSpec& spec, const BagMessages& m, bool left) {
  const std::string& named = left ? spec.left_joint : spec.right_joint;
  if (!named.empty()) return named;
  const char* word = left ? "left" : "right";
  for (const std::string& name : m.joints.front().names) {
    if (ascii_lowercase(name).find(word) != std::string::npos) return name;
  }
  throw InputError(spec.path.string(), 0,
                   fmt::format("topic {}: no joint name holds \"{}\" (names: {}; expected #left=JOINT,right=JOINT)",
                               m.roles.joints, word, printable(joined(m.joints.front().names))));
}

// ENCODER records from the wheel joints' angles, and the nominal model's PARAM records when the
// radius and the wheelbase are given.
void add_wheel_encoders(const BagSpec& spec, const BagMessages& m, Log& log) {
  if (m.joints.empty()) return;
  const std::string file = spec.path.string();
  const std::string left = wheel_joint(spec, m, true), right = wheel_joint(spec, m, false);
  const std::vector<double> t = message_times(m.joints, m.roles.joints, file);
  const double per_rad = spec.ticks_per_rev / (2.0 * kPi);
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    const BagJointMessage& j = m.joints[i];
    const auto ticks = [&](const std::string& name) {
      const auto at = std::find(j.names.begin(), j.names.end(), name);
      const auto k = static_cast<std::size_t>(at - j.names.begin());
      if (at == j.names.end() || k >= j.positions.size()) {
        throw InputError(file, 0,
                         fmt::format("topic {}, message {}: no position of joint {} (expected it in every message)",
                                     m.roles.joints, j.time.index, printable(name)));
      }
      const double v = j.positions[k] * per_rad;
      if (!std::isfinite(v) || std::abs(v) > 1e15) {
        throw InputError(file, 0,
                         fmt::format("topic {}, message {}: joint {} at {} rad (expected a finite wheel angle)",
                                     m.roles.joints, j.time.index, printable(name), j.positions[k]));
      }
      return static_cast<std::int64_t>(std::llround(v));
    };
    log.encoders.push_back({t[i], ticks(left), ticks(right)});
  }
  if (spec.left_radius > 0.0 && spec.right_radius > 0.0 && spec.wheelbase > 0.0) {
    const auto per_tick = [&](double r) { return fmt::format("{:.17g}", 2.0 * kPi * r / spec.ticks_per_rev); };
    log.params[kParamMetersPerTickLeft] = per_tick(spec.left_radius);
    log.params[kParamMetersPerTickRight] = per_tick(spec.right_radius);
    log.params[kParamWheelbase] = fmt::format("{:.17g}", spec.wheelbase);
  }
}

std::string role_name(const BagRoles& r, const std::string& topic) {
  std::vector<std::string> roles;
  if (topic == r.odom) roles.push_back("odometry (ODOM)");
  if (topic == r.truth) roles.push_back("truth (TRUEPOS)");
  if (topic == r.scan) roles.push_back("scan (FLASER)");
  if (topic == r.heading) roles.push_back("heading (COMPASS)");
  if (topic == r.joints) roles.push_back("wheel joints (ENCODER)");
  if (std::find(r.tf.begin(), r.tf.end(), topic) != r.tf.end()) roles.push_back("laser mount");
  return joined(roles);
}

}  // namespace

std::string log_spec_path(const std::string& spec) {
  const auto hash = spec.rfind('#');
  if (hash == std::string::npos) return spec;
  const std::string suffix = ascii_lowercase(spec.substr(hash + 1));
  if (suffix.rfind("robot", 0) == 0 || suffix.find('=') != std::string::npos) return spec.substr(0, hash);
  return spec;
}

namespace {

// The keys after a bag's '#' that choose a topic ("none": no topic), and the field each sets.
constexpr std::pair<const char*, std::optional<std::string> BagSpec::*> kTopicKeys[] = {{"odom", &BagSpec::odom},
                                                                                        {"truth", &BagSpec::truth},
                                                                                        {"scan", &BagSpec::scan},
                                                                                        {"heading", &BagSpec::heading},
                                                                                        {"joints", &BagSpec::joints}};
// The keys that name a joint or a frame.
constexpr std::pair<const char*, std::string BagSpec::*> kNameKeys[] = {{"left", &BagSpec::left_joint},
                                                                        {"right", &BagSpec::right_joint},
                                                                        {"base", &BagSpec::base_frame},
                                                                        {"laser", &BagSpec::laser_frame}};

}  // namespace

std::optional<BagSpec> parse_bag_spec(const std::string& spec) {
  const std::string file = log_spec_path(spec);
  const auto format = bag_format(file);
  if (!format) return std::nullopt;
  BagSpec out;
  out.path = file;
  out.format = *format;
  if (file.size() == spec.size()) return out;
  const std::string choices = spec.substr(file.size() + 1);
  std::size_t start = 0;
  while (start <= choices.size()) {
    const std::size_t end = std::min(choices.find(',', start), choices.size());
    const std::string item = choices.substr(start, end - start);
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq), value = eq == std::string::npos ? "" : item.substr(eq + 1);
    const auto bad = [&](const std::string& what) {
      throw InputError(
          spec, 0,
          fmt::format("'{}' after '#': {} (expected key=value pairs separated by commas, keys odom, truth, "
                      "scan, heading, joints, left, right, ticks_per_rev, radius, left_radius, right_radius, "
                      "wheelbase, base, laser; e.g. "
                      "run.bag#odom=/wheel_odom,truth=/vicon/pose)",
                      item, what));
    };
    if (eq == std::string::npos || value.empty()) bad("no value");
    const std::string topic = value == "none" ? "" : with_slash(value);
    const auto named = [&](const auto& keys) {
      return std::find_if(std::begin(keys), std::end(keys), [&](const auto& k) { return key == k.first; });
    };
    if (const auto t = named(kTopicKeys); t != std::end(kTopicKeys)) {
      out.*(t->second) = topic;
    } else if (const auto n = named(kNameKeys); n != std::end(kNameKeys)) {
      out.*(n->second) = value;
    } else if (key == "ticks_per_rev" || key == "radius" || key == "left_radius" || key == "right_radius" ||
               key == "wheelbase") {
      double v = 0.0;
      if (!try_parse_finite(value, v) || !(v > 0.0) || v > 1e12) bad("not a positive number");
      if (key == "ticks_per_rev") out.ticks_per_rev = v;
      if (key == "radius" || key == "left_radius") out.left_radius = v;
      if (key == "radius" || key == "right_radius") out.right_radius = v;
      if (key == "wheelbase") out.wheelbase = v;
    } else {
      bad("unknown key \"" + key + "\"");
    }
    start = end + 1;
  }
  return out;
}

Log read_bag_log(const BagSpec& spec) {
  const std::string file = spec.path.string();
  const BagMessages m = read_bag(spec, true);
  Log log;
  log.name = dataset_name_from_file(spec.path);
  log.source = file;
  const std::vector<double> odom_t = message_times(m.odom, m.roles.odom, file);
  for (std::size_t i = 0; i < m.odom.size(); ++i) {
    log.odometry.push_back({odom_t[i], pose2(m.odom[i].pose), m.odom[i].tv, m.odom[i].rv});
  }
  if (!m.odom.empty() && m.odom.front().velocity_only) {
    // Velocity commands: the pose each ODOM record carries is their dead reckoning from the origin
    // (each command held until the next), as a velocity log's (MRCLAM's) is.
    const Trajectory poses = dead_reckon_velocities(log.odometry, Pose2::identity());
    for (std::size_t i = 0; i < log.odometry.size() && i < poses.size(); ++i)
      log.odometry[i].pose = poses.poses()[i].pose;
  }
  const std::vector<double> truth_t = message_times(m.truth, m.roles.truth, file);
  for (std::size_t i = 0; i < m.truth.size(); ++i) {
    TruePose p;
    p.t = truth_t[i];
    p.pose = pose2(m.truth[i].pose);
    log.truth.push_back(p);
  }
  const std::vector<double> heading_t = message_times(m.headings, m.roles.heading, file);
  for (std::size_t i = 0; i < m.headings.size(); ++i) {
    if (!m.headings[i].has_orientation) {
      throw InputError(file, 0,
                       fmt::format("topic {}, message {}: the IMU gives no orientation (orientation_covariance[0] = "
                                   "-1; expected an IMU with an orientation estimate, or #heading=none)",
                                   m.roles.heading, m.headings[i].time.index));
    }
    log.compass.push_back({heading_t[i], m.headings[i].yaw});
  }
  add_wheel_encoders(spec, m, log);
  if (!m.scans.empty()) {
    const Pose2 mount = laser_mount(spec, m).pose;
    const std::vector<double> scan_t = message_times(m.scans, m.roles.scan, file);
    for (std::size_t i = 0; i < m.scans.size(); ++i) {
      const BagScanMessage& s = m.scans[i];
      if (!(s.range_max > 0.0) || !std::isfinite(s.range_max) || !std::isfinite(s.angle_min) ||
          !std::isfinite(s.angle_increment)) {
        throw InputError(file, 0,
                         fmt::format("topic {}, message {}: range_max {} , angle_min {}, angle_increment {} (expected "
                                     "finite numbers, range_max > 0)",
                                     m.roles.scan, s.time.index, s.range_max, s.angle_min, s.angle_increment));
      }
      LaserReading r;
      r.scan.timestamp = scan_t[i];
      r.scan.max_range = s.range_max;
      r.scan.sensor_pose = mount;
      r.scan.ranges.reserve(s.ranges.size());
      r.scan.bearings.reserve(s.ranges.size());
      const auto far = static_cast<float>(s.range_max);
      for (std::size_t k = 0; k < s.ranges.size(); ++k) {
        const float v = s.ranges[k];
        // ROS: a range outside [range_min, range_max] (or inf, NaN) is no return.
        const bool none = !std::isfinite(v) || v >= far || v < static_cast<float>(s.range_min);
        r.scan.ranges.push_back(none ? s.range_max : static_cast<double>(v));
        r.scan.bearings.push_back(s.angle_min + static_cast<double>(k) * s.angle_increment);
      }
      r.odom_pose = interpolate_odometry(log, r.scan.timestamp).value_or(Pose2::identity());
      r.pose = r.odom_pose;
      log.laser.push_back(std::move(r));
    }
  }
  return log;
}

BagDescription describe_bag(const BagSpec& spec) {
  const BagMessages m = read_bag(spec, false);
  BagDescription out;
  out.format = spec.format == BagFormat::kRos1   ? "ROS 1 bag"
               : spec.format == BagFormat::kRos2 ? "ROS 2 bag (sqlite3)"
                                                 : "ROS 2 bag (MCAP)";
  for (const BagTopic& t : m.topics) {
    BagTopicUse u;
    u.topic = t;
    u.role = role_name(m.roles, t.name);
    if (t.count >= 2 && t.last_record > t.first_record) {
      u.rate = static_cast<double>(t.count - 1) / (t.last_record - t.first_record);
    }
    out.topics.push_back(std::move(u));
  }
  const std::vector<Role> roles = roles_of(spec);
  const std::string* chosen[] = {&m.roles.odom, &m.roles.truth, &m.roles.scan, &m.roles.heading, &m.roles.joints};
  for (std::size_t i = 0; i < roles.size(); ++i) {
    if (!chosen[i]->empty()) continue;
    out.notes.push_back(*roles[i].chosen ? fmt::format("{}: off (#{}=none)", roles[i].what, roles[i].key)
                                         : fmt::format("{}: none of the default topics {} is in the bag", roles[i].what,
                                                       joined(roles[i].defaults)));
  }
  if (const auto n = stamp_note(m.odom, m.roles.odom)) out.notes.push_back(*n);
  if (const auto n = stamp_note(m.truth, m.roles.truth)) out.notes.push_back(*n);
  if (const auto n = stamp_note(m.scans, m.roles.scan)) out.notes.push_back(*n);
  if (const auto n = stamp_note(m.headings, m.roles.heading)) out.notes.push_back(*n);
  if (const auto n = stamp_note(m.joints, m.roles.joints)) out.notes.push_back(*n);
  if (!m.joints.empty()) {
    out.notes.push_back(fmt::format("wheel joints {} and {} → ENCODER at {:.10g} ticks per revolution; {}",
                                    wheel_joint(spec, m, true), wheel_joint(spec, m, false), spec.ticks_per_rev,
                                    spec.left_radius > 0.0 && spec.right_radius > 0.0 && spec.wheelbase > 0.0
                                        ? fmt::format("nominal model: radii {} m (left), {} m (right), wheelbase {} m",
                                                      spec.left_radius, spec.right_radius, spec.wheelbase)
                                        : std::string("no nominal model (#radius=R,wheelbase=B give one; left_radius=, "
                                                      "right_radius= for unequal wheels)")));
  }
  if (!m.scans.empty()) out.notes.push_back(laser_mount(spec, m).how);
  out.notes.push_back(kChoose);
  return out;
}

BagContents bag_contents(const Log& log) {
  BagContents c;
  std::vector<OdometryReading> odometry = log.odometry;
  const std::optional<NominalModel> model = log.nominal_model();
  if (odometry.empty() && log.encoders.size() >= 2 && model) {
    // What a ROS robot's /odom would hold: the encoders dead-reckoned with the nominal model,
    // velocities over each interval.
    const Trajectory dead_reckoned = dead_reckon_encoders(log.encoders, *model, Pose2::identity());
    const std::vector<StampedPose>& poses = dead_reckoned.poses();
    for (std::size_t i = 0; i < poses.size(); ++i) {
      OdometryReading r{poses[i].t, poses[i].pose, 0.0, 0.0};
      if (i > 0 && poses[i].t > poses[i - 1].t) {
        const Pose2 d = between(poses[i - 1].pose, poses[i].pose);
        r.tv = d.x / (poses[i].t - poses[i - 1].t);
        r.rv = d.theta / (poses[i].t - poses[i - 1].t);
      }
      odometry.push_back(r);
    }
  }
  for (const OdometryReading& r : odometry) {
    BagPoseMessage m;
    m.time = {r.t, r.t, 0};
    m.frame_id = "odom";
    m.child_frame_id = "base_link";
    m.pose = planar(r.pose);
    m.tv = r.tv;
    m.rv = r.rv;
    c.odom.push_back(m);
  }
  for (const TruePose& p : log.truth) {
    BagPoseMessage m;
    m.time = {p.t, p.t, 0};
    m.frame_id = "map";
    m.pose = planar(p.pose);
    c.truth.push_back(m);
  }
  for (const CompassReading& r : log.compass) {
    BagHeadingMessage m;
    m.time = {r.t, r.t, 0};
    m.frame_id = "imu";
    m.yaw = r.heading;
    c.headings.push_back(m);
  }
  for (const LaserReading& r : log.laser) {
    const Scan& s = r.scan;
    BagScanMessage m;
    m.time = {s.timestamp, s.timestamp, 0};
    m.frame_id = "laser";
    m.angle_min = s.bearings.empty() ? 0.0 : s.bearings.front();
    m.angle_increment = s.bearings.size() < 2
                            ? 0.0
                            : (s.bearings.back() - s.bearings.front()) / static_cast<double>(s.bearings.size() - 1);
    m.range_min = 0.0;
    m.range_max = s.max_range;
    for (const double v : s.ranges) m.ranges.push_back(static_cast<float>(v));
    c.scans.push_back(std::move(m));
  }
  if (!log.laser.empty())
    c.static_transforms.push_back({"base_link", "laser", planar(log.laser.front().scan.sensor_pose)});
  return c;
}

void write_bag_log(const Log& log, const std::filesystem::path& target, BagFormat format) {
  std::filesystem::path path = target;
  if (path.filename().empty()) path = path.parent_path();  // "run/"
  std::error_code ec;
  std::filesystem::path partial = path;
  partial += ".partial";
  std::filesystem::remove_all(partial, ec);
  if (format == BagFormat::kRos1) {
    write_ros1_bag(bag_contents(log), partial);
  } else if (format == BagFormat::kMcap) {
    write_mcap_bag(bag_contents(log), partial);
  } else {
    if (std::filesystem::exists(path, ec)) {
      throw InputError(path.string(), 0, "exists already (expected a new folder for the ROS 2 bag)");
    }
    write_ros2_bag(bag_contents(log), partial, path.filename().string());
  }
  if (!ec) std::filesystem::rename(partial, path, ec);
  if (ec) throw InputError(path.string(), 0, "cannot write: " + ec.message());
}

}  // namespace locbench::io
