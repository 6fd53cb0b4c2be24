#include "datasets/sim/scenario_json.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "core/angle.h"
#include "core/enum_names.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "core/json_file.h"
#include "core/json_options.h"
#include "datasets/sim/motion_program.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_fields.h"

namespace locbench::sim {

using nlohmann::json;

namespace {

constexpr EnumNames<WorldKind, 5> kWorldKinds{{
    {WorldKind::kNone, "none"},
    {WorldKind::kRoom, "room"},
    {WorldKind::kCorridor, "corridor"},
    {WorldKind::kFile, "file"},
    {WorldKind::kInline, "inline"},
}};
constexpr EnumNames<MotionKind, 4> kMotionKinds{{
    {MotionKind::kStraight, "straight"},
    {MotionKind::kUmbmark, "umbmark"},
    {MotionKind::kWaypoints, "waypoints"},
    {MotionKind::kReplay, "replay"},
}};
constexpr EnumNames<SlipRateUnit, 2> kSlipUnits{{
    {SlipRateUnit::kPerSample, "per_sample"},
    {SlipRateUnit::kPerMetre, "per_metre"},
}};
constexpr EnumNames<DisturbanceZone::Shape, 2> kZoneShapes{{
    {DisturbanceZone::Shape::kRectangle, "rectangle"},
    {DisturbanceZone::Shape::kCircle, "circle"},
}};

template <typename E, std::size_t N>
void read_enum(StrictJsonReader& o, const char* key, const EnumNames<E, N>& table, E& out) {
  if (!o.has(key)) {
    o.raw(key);
    return;
  }
  std::string text;
  o.read(key, text);
  std::string allowed;
  for (const auto& [v, name] : table) {
    if (text == name) {
      out = v;
      return;
    }
    allowed += (allowed.empty() ? "" : ", ") + std::string(name);
  }
  o.fail(key, "unknown value '" + text + "' (expected one of: " + allowed + ")");
}

json vec(const Eigen::Vector2d& v) { return json::array({v.x(), v.y()}); }
json pose(const Pose2& p) { return json::array({p.x, p.y, p.theta}); }

// A group's own object: its fields (scenario_fields.h), and no other key.
template <class O>
void read_group(StrictJsonReader o, O& out) {
  read_fields(o, out);
  o.finish();
}

json zone_json(const DisturbanceZone& z) {
  json j = {{"shape", enum_name(kZoneShapes, z.shape)}, {"bias", z.bias}};
  if (z.shape == DisturbanceZone::Shape::kCircle) {
    j["center"] = vec(z.center);
    j["radius"] = z.radius;
  } else {
    j["min"] = vec(z.min);
    j["max"] = vec(z.max);
  }
  return j;
}
DisturbanceZone read_zone(const json& v, const std::string& path, const std::string& source) {
  StrictJsonReader o(v, path, source);
  DisturbanceZone z;
  read_enum(o, "shape", kZoneShapes, z.shape);
  o.read("bias", z.bias);
  if (z.shape == DisturbanceZone::Shape::kCircle) {
    o.read("center", z.center);
    o.read("radius", z.radius);
  } else {
    o.read("min", z.min);
    o.read("max", z.max);
  }
  o.finish();
  return z;
}

// The array `key`, when present, replaces `out`: each element `n` numbers, made into a T by
// make(numbers). `what` names the elements in the error for a non-array.
template <class T, class Make>
void read_rows(StrictJsonReader& o, const char* key, std::size_t n, const std::string& what, std::vector<T>& out,
               Make make) {
  const auto* rows = o.raw(key);
  if (rows == nullptr) return;
  if (!rows->is_array()) o.fail(key, "expected an array" + what + ", found " + json_type_name(*rows));
  out.clear();
  out.reserve(rows->size());
  for (std::size_t i = 0; i < rows->size(); ++i) {
    double v[4];
    read_numbers((*rows)[i], v, n, o.path_of(key) + "[" + std::to_string(i) + "]", o.source());
    out.push_back(make(v));
  }
}

void read_world(StrictJsonReader o, WorldConfig& w) {
  read_enum(o, "kind", kWorldKinds, w.kind);
  o.read("corridor_length", w.corridor_length);
  o.read("corridor_width", w.corridor_width);
  o.read("file", w.file);
  read_rows(o, "segments", 4, "", w.segments, [](const double* v) { return Eigen::Vector4d(v[0], v[1], v[2], v[3]); });
  o.finish();
}

void read_motion(StrictJsonReader o, MotionConfig& m) {
  read_enum(o, "kind", kMotionKinds, m.kind);
  o.read("distance", m.distance);
  o.read("side", m.side);
  o.read("runs", m.runs);
  read_rows(o, "waypoints", 2, "", m.waypoints, [](const double* v) { return Eigen::Vector2d(v[0], v[1]); });
  read_rows(o, "commands", 3, " of [t, v, omega]", m.commands, [](const double* v) {
    return ReplayCommand{v[0], v[1], v[2]};
  });
  o.finish();
}

void read_compass(StrictJsonReader o, CompassConfig& c) {
  read_fields(o, c.timing);  // timing sits beside the sensor's own fields
  o.read("resolution", c.resolution);
  o.read("noise", c.noise);
  o.read("bias", c.bias);
  if (const auto* zones = o.raw("zones")) {
    if (!zones->is_array()) o.fail("zones", "expected an array, found " + json_type_name(*zones));
    c.zones.clear();
    for (std::size_t i = 0; i < zones->size(); ++i) {
      c.zones.push_back(read_zone((*zones)[i], o.path_of("zones") + "[" + std::to_string(i) + "]", o.source()));
    }
  }
  o.finish();
}

void read_laser(StrictJsonReader o, LaserConfig& l) {
  read_fields(o, l.timing);
  o.read("beams", l.beams);
  o.read("first_bearing", l.first_bearing);
  o.read("last_bearing", l.last_bearing);
  o.read("max_range", l.max_range);
  o.read("noise", l.noise);
  o.read("range_offset", l.range_offset);
  o.read("range_scale", l.range_scale);
  o.read("dropout", l.dropout);
  o.read("spurious", l.spurious);
  o.read("mount", l.mount);
  o.finish();
}

}  // namespace

const char* to_string(WorldKind k) { return enum_name(kWorldKinds, k); }
const char* to_string(MotionKind k) { return enum_name(kMotionKinds, k); }
const char* to_string(SlipRateUnit u) { return enum_name(kSlipUnits, u); }

json to_json(const Scenario& s) {
  json segments = json::array();
  for (const auto& seg : s.world.segments) segments.push_back({seg[0], seg[1], seg[2], seg[3]});
  json waypoints = json::array();
  for (const auto& w : s.motion.waypoints) waypoints.push_back(vec(w));
  json commands = json::array();
  for (const auto& c : s.motion.commands) commands.push_back({c.t, c.v, c.omega});
  json zones = json::array();
  for (const auto& z : s.compass.zones) zones.push_back(zone_json(z));

  json compass = fields_to_json(s.compass.timing);
  compass.update(
      {{"resolution", s.compass.resolution}, {"noise", s.compass.noise}, {"bias", s.compass.bias}, {"zones", zones}});
  json laser = fields_to_json(s.laser.timing);
  laser.update({{"beams", s.laser.beams},
                {"first_bearing", s.laser.first_bearing},
                {"last_bearing", s.laser.last_bearing},
                {"max_range", s.laser.max_range},
                {"noise", s.laser.noise},
                {"range_offset", s.laser.range_offset},
                {"range_scale", s.laser.range_scale},
                {"dropout", s.laser.dropout},
                {"spurious", s.laser.spurious},
                {"mount", pose(s.laser.mount)}});

  return {
      {"name", s.name},
      {"description", s.description},
      {"world",
       {{"kind", to_string(s.world.kind)},
        {"corridor_length", s.world.corridor_length},
        {"corridor_width", s.world.corridor_width},
        {"file", s.world.file},
        {"segments", segments}}},
      {"start", pose(s.start)},
      {"robot",
       {{"nominal", fields_to_json(s.robot.nominal)},
        {"actual", fields_to_json(s.robot.actual)},
        {"encoder", {{"gear_ratio", s.robot.encoder.gear_ratio}, {"counts_per_rev", s.robot.encoder.counts_per_rev}}}}},
      {"drive",
       {{"speed", s.drive.speed},
        {"turn_rate", s.drive.turn_rate},
        {"pause", s.drive.pause},
        {"equal_wheel_ticks", s.drive.equal_wheel_ticks},
        {"response", fields_to_json(s.drive.response)}}},
      {"motion",
       {{"kind", to_string(s.motion.kind)},
        {"distance", s.motion.distance},
        {"side", s.motion.side},
        {"runs", s.motion.runs},
        {"waypoints", waypoints},
        {"commands", commands}}},
      {"physics", {{"step", s.physics.step}, {"trajectory_rate", s.physics.trajectory_rate}}},
      {"floor", {{"k_left", s.floor.k_left}, {"k_right", s.floor.k_right}}},
      {"motion_noise", fields_to_json(s.motion_noise)},
      {"slip",
       {{"unit", to_string(s.slip.unit)},
        {"straight", fields_to_json(s.slip.straight)},
        {"turn", fields_to_json(s.slip.turn)}}},
      {"encoders", fields_to_json(s.encoders.timing)},
      {"odometry", fields_to_json(s.odometry.timing)},
      {"compass", compass},
      {"laser", laser},
      {"truth", {{"rate", s.truth.rate}, {"noise_xy", s.truth.noise_xy}, {"noise_theta", s.truth.noise_theta}}},
      {"notes", s.notes},
  };
}

double estimated_duration(const Scenario& s) {
  double duration = 0.0;
  Eigen::Vector2d at(s.start.x, s.start.y);
  for (const Instruction& in : build_program(s.motion, s.drive, s.start)) {
    switch (in.kind) {
      case Instruction::Kind::kStraight: duration += std::abs(in.value) / s.drive.speed + s.drive.pause; break;
      case Instruction::Kind::kTurn: duration += std::abs(in.value) / s.drive.turn_rate; break;
      case Instruction::Kind::kPause: duration += in.value; break;
      case Instruction::Kind::kTurnToward: duration += kPi / s.drive.turn_rate; break;
      case Instruction::Kind::kDriveTo:
        duration += (in.target - at).norm() / s.drive.speed;
        at = in.target;
        break;
      case Instruction::Kind::kReset: at = Eigen::Vector2d(in.pose.x, in.pose.y); break;
      default: break;
    }
  }
  return duration;
}

void check_scenario_limits(const Scenario& s, const std::string& source) {
  using limits::check;
  check(s.laser.beams, limits::kSimLaserBeams, source, "laser.beams");
  check(std::max(std::abs(s.start.x), std::abs(s.start.y)), limits::kSimCoordinate, source, "start");
  for (std::size_t i = 0; i < s.motion.waypoints.size(); ++i) {
    check(s.motion.waypoints[i].cwiseAbs().maxCoeff(), limits::kSimCoordinate, source,
          "motion.waypoints[" + std::to_string(i) + "]");
  }
  for (std::size_t i = 0; i < s.world.segments.size(); ++i) {
    check(s.world.segments[i].cwiseAbs().maxCoeff(), limits::kSimCoordinate, source,
          "world.segments[" + std::to_string(i) + "]");
  }
  check(std::abs(s.motion.distance), limits::kSimDistance, source, "motion.distance");
  check(std::abs(s.motion.side), limits::kSimDistance, source, "motion.side");
  check(s.motion.runs, limits::kSimRuns, source, "motion.runs");
  // The work and records the motion's duration implies — all before a single step is simulated.
  const double duration = estimated_duration(s);
  check(duration, limits::kSimDuration, source,
        "the motion's duration (legs / drive.speed, turns / drive.turn_rate, pauses)");
  check(duration / s.physics.step, limits::kSimPhysicsSteps, source, "duration / physics.step");
  const std::pair<const char*, const SensorTiming*> sensors[] = {{"encoders.rate", &s.encoders.timing},
                                                                 {"odometry.rate", &s.odometry.timing},
                                                                 {"compass.rate", &s.compass.timing},
                                                                 {"laser.rate", &s.laser.timing}};
  for (const auto& [key, t] : sensors) {
    if (t->enabled) check(duration * t->rate, limits::kSimRecords, source, std::string("duration x ") + key);
  }
  check(duration * s.truth.rate, limits::kSimRecords, source, "duration x truth.rate");
  if (s.physics.trajectory_rate > 0.0) {
    check(duration * s.physics.trajectory_rate, limits::kSimRecords, source, "duration x physics.trajectory_rate");
  }
  if (s.laser.timing.enabled) {
    check(duration * s.laser.timing.rate * s.laser.beams, limits::kSimLaserValues, source,
          "duration x laser.rate x laser.beams");
  }
}

Scenario scenario_from_json(const json& j, const std::string& source) {
  StrictJsonReader top(j, "", source);
  Scenario s;
  if (top.has("preset")) {
    std::string name;
    top.read("preset", name);
    try {
      s = preset(name);
    } catch (const UsageError& e) {
      top.fail("preset", e.what());
    }
  } else {
    top.raw("preset");
  }
  top.read("name", s.name);
  top.read("description", s.description);
  read_world(top.object("world"), s.world);
  top.read("start", s.start);
  {
    StrictJsonReader robot = top.object("robot");
    read_group(robot.object("nominal"), s.robot.nominal);
    read_group(robot.object("actual"), s.robot.actual);
    StrictJsonReader enc = robot.object("encoder");
    enc.read("gear_ratio", s.robot.encoder.gear_ratio);
    enc.read("counts_per_rev", s.robot.encoder.counts_per_rev);
    enc.finish();
    robot.finish();
  }
  {
    StrictJsonReader drive = top.object("drive");
    drive.read("speed", s.drive.speed);
    drive.read("turn_rate", s.drive.turn_rate);
    drive.read("pause", s.drive.pause);
    drive.read("equal_wheel_ticks", s.drive.equal_wheel_ticks);
    read_group(drive.object("response"), s.drive.response);
    drive.finish();
  }
  read_motion(top.object("motion"), s.motion);
  {
    StrictJsonReader physics = top.object("physics");
    physics.read("step", s.physics.step);
    physics.read("trajectory_rate", s.physics.trajectory_rate);
    physics.finish();
  }
  {
    StrictJsonReader floor = top.object("floor");
    floor.read("k_left", s.floor.k_left);
    floor.read("k_right", s.floor.k_right);
    floor.finish();
  }
  read_group(top.object("motion_noise"), s.motion_noise);
  {
    StrictJsonReader slip = top.object("slip");
    read_enum(slip, "unit", kSlipUnits, s.slip.unit);
    read_group(slip.object("straight"), s.slip.straight);
    read_group(slip.object("turn"), s.slip.turn);
    slip.finish();
  }
  for (auto [key, timing] : {std::pair{"encoders", &s.encoders.timing}, std::pair{"odometry", &s.odometry.timing}}) {
    StrictJsonReader o = top.object(key);
    read_fields(o, *timing);
    o.finish();
  }
  read_compass(top.object("compass"), s.compass);
  read_laser(top.object("laser"), s.laser);
  {
    StrictJsonReader truth = top.object("truth");
    truth.read("rate", s.truth.rate);
    truth.read("noise_xy", s.truth.noise_xy);
    truth.read("noise_theta", s.truth.noise_theta);
    truth.finish();
  }
  if (const auto* notes = top.raw("notes")) {
    if (!notes->is_array()) top.fail("notes", "expected an array of strings, found " + json_type_name(*notes));
    s.notes.clear();
    for (std::size_t i = 0; i < notes->size(); ++i) {
      if (!(*notes)[i].is_string()) {
        top.fail("notes", "[" + std::to_string(i) + "]: expected a string, found " + json_type_name((*notes)[i]));
      }
      s.notes.push_back((*notes)[i].get<std::string>());
    }
  }
  top.finish();
  try {
    validate(s);
  } catch (const UsageError& e) {
    throw InputError(source, 0, e.what());
  }
  check_scenario_limits(s, source);
  return s;
}

Scenario load_scenario(const std::filesystem::path& path) {
  Scenario s = scenario_from_json(read_json_file(path.string()), path.string());
  // A relative world.file is relative to the scenario file's folder, not the working directory.
  if (s.world.kind == WorldKind::kFile && std::filesystem::path(s.world.file).is_relative() && path.has_parent_path()) {
    s.world.file = (path.parent_path() / s.world.file).lexically_normal().string();
  }
  return s;
}

}  // namespace locbench::sim
