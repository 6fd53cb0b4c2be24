#include "datasets/io/carmen_laser.h"

#include <stdexcept>

#include "core/scan.h"
#include "core/units.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {

std::vector<double> flaser_bearings(std::size_t n) {
  if (n == 0) return {};
  const double first = -0.5 * kPi;
  if (n % 2 == 1) return even_bearings(n, first, 0.5 * kPi);
  return even_bearings(n, first, first + kPi * static_cast<double>(n - 1) / static_cast<double>(n));
}

std::vector<double> carmen_bearings(std::size_t n, const CarmenLaserSetup& setup) {
  if (n == 0) return {};
  if (!setup.fov && !setup.resolution) return flaser_bearings(n);
  const double span = static_cast<double>(n - 1);
  const double step = setup.resolution ? *setup.resolution : (n > 1 ? *setup.fov / span : 0.0);
  const double first = setup.fov ? -0.5 * *setup.fov : -0.5 * step * span;
  return even_bearings(n, first, first + step * span);
}

bool is_laser_param(std::string_view name) {
  return name == kParamLaserMaxRange || name == kParamRobotLaserMax || name == kParamLaserOffset ||
         name == kParamLaserSideOffset || name == kParamLaserAngularOffset || name == kParamLaserFov ||
         name == kParamLaserResolution;
}

std::optional<std::string> laser_param_problem(std::string_view name, std::string_view value) {
  if (!is_laser_param(name)) return std::nullopt;
  double v = 0.0;
  if (!try_parse_finite(value, v)) {
    return "expected a finite number, found " + quote_token(value);
  }
  if ((name == kParamLaserMaxRange || name == kParamRobotLaserMax) && !(v > 0.0)) {
    return "expected a positive maximum range [m], found " + quote_token(value);
  }
  if (name == kParamLaserFov && !(v > 0.0 && v <= 360.0)) {
    return "expected a field of view in (0, 360] degrees, found " + quote_token(value);
  }
  if (name == kParamLaserResolution && !(v > 0.0 && v <= 180.0)) {
    return "expected an angular resolution in (0, 180] degrees, found " + quote_token(value);
  }
  return std::nullopt;
}

CarmenLaserSetup carmen_laser_setup(const std::map<std::string, std::string>& params) {
  auto number = [&](std::string_view name) -> std::optional<double> {
    const auto it = params.find(std::string(name));
    if (it == params.end()) return std::nullopt;
    if (const auto problem = laser_param_problem(name, it->second)) {
      throw std::invalid_argument("PARAM " + std::string(name) + ": " + *problem);
    }
    double v = 0.0;
    try_parse_finite(it->second, v);
    return v;
  };
  CarmenLaserSetup s;
  if (const auto r = number(kParamLaserMaxRange)) {
    s.max_range = *r;
  } else if (const auto r2 = number(kParamRobotLaserMax)) {
    s.max_range = *r2;
  }
  const double x = number(kParamLaserOffset).value_or(0.0);
  const double y = number(kParamLaserSideOffset).value_or(0.0);
  const double th = number(kParamLaserAngularOffset).value_or(0.0);
  s.sensor_pose = Pose2(x, y, th);
  if (const auto f = number(kParamLaserFov)) s.fov = deg(*f);
  if (const auto r = number(kParamLaserResolution)) s.resolution = deg(*r);
  return s;
}

}  // namespace locbench::io
