#include "core/log.h"

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace locbench {
namespace {
std::optional<double> param_double(const std::map<std::string, std::string>& p, const char* name) {
  const auto it = p.find(name);
  if (it == p.end()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0') return std::nullopt;
  return v;
}
}  // namespace

std::optional<NominalModel> Log::nominal_model() const {
  const auto l = param_double(params, kParamMetersPerTickLeft);
  const auto r = param_double(params, kParamMetersPerTickRight);
  const auto b = param_double(params, kParamWheelbase);
  if (!l || !r || !b) return std::nullopt;
  return NominalModel{*l, *r, *b};
}

std::pair<double, double> Log::time_span() const {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  auto see = [&](double t) {
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  };
  for (const auto& r : encoders) see(r.t);
  for (const auto& r : odometry) see(r.t);
  for (const auto& r : compass) see(r.t);
  for (const auto& r : laser) see(r.scan.timestamp);
  for (const auto& r : truth) see(r.t);
  for (const auto& r : relations) {
    see(r.t1);
    see(r.t2);
  }
  for (const auto& r : landmarks) see(r.t);
  if (lo > hi) return {0.0, 0.0};
  return {lo, hi};
}

std::size_t Log::record_count() const {
  return params.size() + encoders.size() + odometry.size() + compass.size() + laser.size() + truth.size() +
         relations.size() + landmarks.size();
}

Log restrict_log(const Log& log, double from, double to) {
  Log out;
  out.name = log.name;
  out.source = log.source;
  out.params = log.params;
  out.landmark_map = log.landmark_map;
  const auto in = [&](double t) { return t >= from && t <= to; };
  for (const auto& r : log.encoders)
    if (in(r.t)) out.encoders.push_back(r);
  for (const auto& r : log.odometry)
    if (in(r.t)) out.odometry.push_back(r);
  for (const auto& r : log.compass)
    if (in(r.t)) out.compass.push_back(r);
  for (const auto& r : log.truth)
    if (in(r.t)) out.truth.push_back(r);
  for (const auto& r : log.relations)
    if (in(r.t1) && in(r.t2)) out.relations.push_back(r);
  for (const auto& r : log.landmarks)
    if (in(r.t)) out.landmarks.push_back(r);
  if (log.odometry.empty() && log.encoders.empty()) {
    for (const auto& r : log.laser) {
      if (!in(r.scan.timestamp)) continue;
      LaserReading l;
      l.scan.timestamp = r.scan.timestamp;
      l.pose = r.pose;
      l.odom_pose = r.odom_pose;
      out.laser.push_back(l);
    }
  }
  return out;
}

}  // namespace locbench
