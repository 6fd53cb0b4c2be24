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

}  // namespace locbench
