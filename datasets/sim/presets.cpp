#include "datasets/sim/presets.h"

#include "core/errors.h"
#include "core/units.h"

namespace locbench::sim {
namespace {

// The thesis's Trilobot. Its true geometry is the indirect Kalman filter's estimate (§3.5,
// Table 3.3): D_L = 88.8192 mm, D_R = 89.2493 mm, B = 197.93 mm. With 22 counts per wheel
// revolution the ch. 2 calibration D_L = 88.50 mm, D_R = 88.93 mm gives the thesis's 12.64 and
// 12.70 mm per tick (§4.3); the true wheels give 12.68 and 12.74 mm per tick.
RobotConfig trilobot(const WheelGeometry& nominal) {
  RobotConfig r;
  r.nominal = nominal;
  r.actual = {mm(88.8192), mm(89.2493), mm(197.93)};
  r.encoder = {1.0, 22.0};
  return r;
}

// A Pioneer 2-DXe: 40000 counts per wheel revolution on 193.5 mm wheels gives the thesis's
// 0.0152 mm per tick (§4.3); wheelbase 330 mm. The true robot is off by 0.1% per wheel and
// 2 mm in wheelbase.
RobotConfig pioneer() {
  RobotConfig r;
  r.nominal = {mm(193.5), mm(193.5), mm(330.0)};
  r.actual = {mm(193.3), mm(193.7), mm(332.0)};
  r.encoder = {1.0, 40000.0};
  return r;
}

SensorTiming at(double rate, double jitter = 0.0) { return SensorTiming{true, rate, 0.0, jitter}; }

// Pioneer with a SICK LMS 200 (§5.4): 181 beams over ±90°, 5 Hz, σ = 5 mm, the datasheet's
// 15 mm systematic error as a constant offset, 8 m range (millimetre mode), mounted at the
// robot centre (the thesis's scans originate at the robot pose).
Scenario pioneer_with_laser() {
  Scenario s;
  s.robot = pioneer();
  s.drive.speed = 0.2;
  s.drive.turn_rate = deg(30.0);
  s.floor = {0.002, 0.002};
  s.slip.straight = {0.01, 0.05, 0.15};
  s.slip.turn = {0.05, 0.05, 0.15};
  s.encoders.timing = at(10.0);
  s.odometry.timing = at(10.0);
  s.laser.timing = at(5.0);
  s.laser.noise = mm(5.0);
  s.laser.range_offset = mm(15.0);
  s.truth.rate = 10.0;
  return s;
}

// The Trilobot with its compass, as the thesis ran it: floor noise k_l = k_r = 0.005 √m (§4.5),
// heavy slip in on-the-spot turns (§2.4), encoders and a 2° compass polled over a serial line
// every 0.25 s (the instants jitter by ~30 ms).
Scenario trilobot_with_compass(const WheelGeometry& nominal) {
  Scenario s;
  s.robot = trilobot(nominal);
  s.floor = {0.005, 0.005};
  s.slip.turn = {0.5, 0.1, 0.4};
  s.encoders.timing = at(4.0, 0.03);
  s.compass.timing = at(4.0, 0.03);
  s.compass.resolution = deg(2.0);
  s.compass.noise = deg(0.5);
  s.truth.rate = 4.0;
  return s;
}

Scenario ideal() {
  Scenario s;
  s.name = "ideal";
  s.description = "noise-free robot, true = nominal, 10 m straight; whole-tick geometry";
  s.odometry.timing = at(10.0);
  s.compass.timing = at(10.0);
  return s;
}

Scenario corridor() {
  Scenario s = trilobot_with_compass({mm(88.50), mm(88.93), mm(197.93)});  // the ch. 2 calibration
  s.name = "corridor";
  s.description =
      "Trilobot, 10 m straight at 0.25 m/s in a 1.8 m corridor, 4 Hz encoders + 2° compass (ch. "
      "3/4)";
  s.world.kind = WorldKind::kCorridor;
  s.world.corridor_length = 12.0;
  s.world.corridor_width = 1.8;
  s.start = Pose2(1.0, 0.0, 0.0);
  s.drive.speed = 0.25;
  s.motion.kind = MotionKind::kStraight;
  s.motion.distance = 10.0;
  s.slip.straight = {0.03, 0.05, 0.25};
  return s;
}

Scenario umbmark_trilobot() {
  // Uncalibrated: equal nominal wheels.
  Scenario s = trilobot_with_compass({mm(88.5), mm(88.5), mm(198.0)});
  s.name = "umbmark_trilobot";
  s.description = "Trilobot UMBmark: 1.6 m square at 120 mm/s, 5 CW + 5 CCW, uncalibrated, turn slip (ch. 2)";
  s.drive.speed = 0.12;
  s.drive.turn_rate = deg(30.0);
  s.motion.kind = MotionKind::kUmbmark;
  s.motion.side = 1.6;
  s.motion.runs = 5;
  s.slip.straight = {0.02, 0.05, 0.15};  // on A0 paper: little slip on straight legs
  return s;
}

Scenario umbmark_borenstein() {
  Scenario s;
  s.name = "umbmark_borenstein";
  s.description = "LabMate-like UMBmark: 4 m square, 5 CW + 5 CCW, fine encoders, E_d = 1.0025, E_b = 1.01";
  // 2048-count encoders behind a 43.8:1 gear: 89702 counts per revolution of a 150 mm wheel
  // (5.25 µm per tick). True wheels keep the nominal mean: D_R/D_L = 1.0025.
  s.robot.nominal = {mm(150.0), mm(150.0), mm(340.0)};
  s.robot.actual = {mm(150.0 * (1.0 - 0.0025 / 2.0025)), mm(150.0 * (1.0 + 0.0025 / 2.0025)), mm(343.4)};
  s.robot.encoder = {43.8, 2048.0};
  s.drive.speed = 0.2;
  s.drive.turn_rate = deg(30.0);
  s.motion.kind = MotionKind::kUmbmark;
  s.motion.side = 4.0;
  s.motion.runs = 5;
  s.floor = {0.001, 0.001};
  s.encoders.timing = at(10.0);
  s.truth.rate = 10.0;
  return s;
}

Scenario room_laser() {
  Scenario s = pioneer_with_laser();
  s.name = "room_laser";
  s.description = "Pioneer 2-DXe + LMS 200 in the 8 m room from (2.0, 1.0, 46°), 200 mm/s, ~65 s (ch. 5/6)";
  s.world.kind = WorldKind::kRoom;
  s.start = Pose2(2.0, 1.0, deg(46.0));
  s.motion.kind = MotionKind::kWaypoints;
  s.motion.waypoints = {{3.0, 2.5}, {7.0, 2.5}, {7.0, 7.0}};
  return s;
}

Scenario corridor_laser() {
  Scenario s = pioneer_with_laser();
  s.name = "corridor_laser";
  s.description = "Pioneer 2-DXe + LMS 200, 10 m straight at 200 mm/s in a 1.8 m corridor (ch. 6, Table 6.5)";
  s.world.kind = WorldKind::kCorridor;
  s.world.corridor_length = 12.0;
  s.world.corridor_width = 1.8;
  s.start = Pose2(1.0, 0.0, 0.0);
  s.motion.kind = MotionKind::kStraight;
  s.motion.distance = 10.0;
  return s;
}

struct Entry {
  const char* name;
  Scenario (*make)();
};
constexpr Entry kPresets[] = {
    {"ideal", ideal},
    {"corridor", corridor},
    {"umbmark_trilobot", umbmark_trilobot},
    {"umbmark_borenstein", umbmark_borenstein},
    {"room_laser", room_laser},
    {"corridor_laser", corridor_laser},
};

}  // namespace

std::vector<PresetInfo> preset_list() {
  std::vector<PresetInfo> out;
  for (const auto& e : kPresets) out.push_back({e.name, e.make().description});
  return out;
}

Scenario preset(const std::string& name) {
  std::string known;
  for (const auto& e : kPresets) {
    if (name == e.name) return e.make();
    known += (known.empty() ? "" : ", ") + std::string(e.name);
  }
  throw UsageError("unknown simulator preset '" + name + "' (known: " + known + ")");
}

}  // namespace locbench::sim
