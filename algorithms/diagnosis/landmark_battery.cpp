#include "algorithms/diagnosis/landmark_battery.h"

#include <cmath>
#include <map>

#include "core/chi_square.h"

namespace locbench::diagnosis {

ResidualTest landmark_dependence_test(const std::vector<double>& z, const std::vector<int>& landmark,
                                      const std::string& residual) {
  ResidualTest t{"landmark_dependence", residual, "landmark", "chi2"};
  std::map<int, std::pair<double, std::size_t>> sums;
  for (std::size_t i = 0; i < z.size(); ++i) {
    auto& s = sums[landmark[i]];
    s.first += z[i];
    ++s.second;
  }
  double total = 0.0;
  std::size_t n = 0, groups = 0;
  for (const auto& [k, s] : sums) {
    if (s.second < 5) continue;
    total += s.first;
    n += s.second;
    ++groups;
  }
  if (groups < 2) return t;
  const double mean = total / static_cast<double>(n);
  double chi2 = 0.0, largest = 0.0;
  for (const auto& [k, s] : sums) {
    if (s.second < 5) continue;
    const double dev = s.first / static_cast<double>(s.second) - mean;
    chi2 += static_cast<double>(s.second) * dev * dev;
    largest = std::max(largest, std::abs(dev));
  }
  t.value = chi2;
  t.strength = largest;  // the largest landmark's mean deviation, in σ
  t.p_value = chi_square_upper_tail(ChiSquareDof(static_cast<double>(groups - 1)), chi2);
  return t;
}

std::vector<ResidualTest> landmark_battery(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry,
                                           const LandmarkModel& m, const std::vector<std::size_t>& index) {
  std::vector<double> zr, zb, rho, off_axis, turn, turn_speed;
  std::vector<int> lm;
  for (std::size_t i : index) {
    const LandmarkResidual r = landmark_residual(d, i, geometry[i], m);
    if (!r.valid) continue;
    zr.push_back(r.range / std::sqrt(r.var_range));
    zb.push_back(r.bearing / std::sqrt(r.var_bearing));
    rho.push_back(r.rho);
    off_axis.push_back(r.rho * r.phi * r.phi);
    turn.push_back(geometry[i].turn_rate);
    turn_speed.push_back(std::abs(geometry[i].turn_rate));
    lm.push_back(d.landmark[i]);
  }
  std::vector<ResidualTest> out;
  if (zr.size() < 8) return out;
  out.push_back(bias_test(zr, kLandmarkRange));
  out.push_back(bias_test(zb, kLandmarkBearing));
  out.push_back(dependence_test(zr, rho, "range_dependence", kLandmarkRange, "predicted range"));
  out.push_back(dependence_test(zr, off_axis, "off_axis_dependence", kLandmarkRange, "ρ·φ² (range off the axis)"));
  out.push_back(heteroscedasticity_test(zr, rho, kLandmarkRange, "predicted range"));
  out.push_back(heteroscedasticity_test(zb, turn_speed, kLandmarkBearing, "|turn rate|"));
  out.push_back(heavy_tail_test(zr, kLandmarkRange));
  out.push_back(heavy_tail_test(zb, kLandmarkBearing));
  out.push_back(dependence_test(zb, turn, "lead_lag", kLandmarkBearing, "turn rate"));
  out.push_back(landmark_dependence_test(zr, lm, kLandmarkRange));
  out.push_back(landmark_dependence_test(zb, lm, kLandmarkBearing));
  return out;
}

}  // namespace locbench::diagnosis
