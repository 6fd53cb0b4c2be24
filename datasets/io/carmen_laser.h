#pragma once
// How a CARMEN FLASER record maps to a Scan: the bearing convention and the PARAM records that
// give the maximum range and the laser's mounting pose.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/pose2.h"

namespace locbench::io {

// PARAM names read for FLASER scans. Maximum range [m]: the first of these present wins.
inline constexpr std::string_view kParamLaserMaxRange = "laser_front_laser_max_range";
inline constexpr std::string_view kParamRobotLaserMax = "robot_front_laser_max";
// Laser mounting in the robot frame: forward [m], left [m], rotation [rad]; 0 when absent.
inline constexpr std::string_view kParamLaserOffset = "robot_frontlaser_offset";
inline constexpr std::string_view kParamLaserSideOffset = "robot_frontlaser_side_offset";
inline constexpr std::string_view kParamLaserAngularOffset = "robot_frontlaser_angular_offset";
// Field of view and angular resolution of the front laser [deg in the log, CARMEN's
// carmen.ini convention]; when present they replace the FLASER convention below: the first beam
// at −fov/2, steps of `resolution` (or fov/(n−1) when only the field of view is given; centred
// steps when only the resolution is).
inline constexpr std::string_view kParamLaserFov = "laser_front_laser_fov";
inline constexpr std::string_view kParamLaserResolution = "laser_front_laser_resolution";
// SICK LMS convention when no PARAM gives the maximum range: readings ≥ 81.9 m are no return.
inline constexpr double kDefaultFlaserMaxRange = 81.9;

// Bearings [rad] of an n-beam FLASER scan: 180° starting at −90°; step π/(n−1) for odd n
// (181 → −90°…90° at 1°), π/n for even n (180 → −90°…89°). n = 1: one beam at −90°.
std::vector<double> flaser_bearings(std::size_t n);

// Scan fields that come from PARAM records rather than from the FLASER line.
struct CarmenLaserSetup {
  double max_range = kDefaultFlaserMaxRange;
  Pose2 sensor_pose;
  std::optional<double> fov;         // [rad], from kParamLaserFov
  std::optional<double> resolution;  // [rad], from kParamLaserResolution
};

// Bearings [rad] of an n-beam FLASER scan under `setup`: flaser_bearings(n) unless the setup
// declares a field of view or resolution (see kParamLaserFov).
std::vector<double> carmen_bearings(std::size_t n, const CarmenLaserSetup& setup);

// True for the PARAM names above (their values must be numbers; the max range positive).
bool is_laser_param(std::string_view name);
// Checks a laser PARAM value; returns an explanation of what is wrong, or nullopt if valid.
std::optional<std::string> laser_param_problem(std::string_view name, std::string_view value);
// The setup the PARAM records declare. Throws std::invalid_argument on an invalid value.
CarmenLaserSetup carmen_laser_setup(const std::map<std::string, std::string>& params);

}  // namespace locbench::io
