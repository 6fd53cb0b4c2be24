#include "algorithms/diagnosis/selection.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace locbench::diagnosis {

bool offset_resolved(double offset) { return std::abs(offset) > kOffsetResolution + 1e-12; }

Selection forward_select(std::size_t candidates, double nominal_nll,
                         const std::function<double(std::size_t)>& threshold,
                         const std::function<SelectionFit(const std::vector<std::size_t>&)>& fit,
                         const std::function<void(const RoundSets&)>& prepare) {
  Selection s;
  s.evidence.resize(candidates);
  double current = nominal_nll;
  for (;;) {
    std::size_t best = candidates;
    double best_margin = 0.0, best_nll = current;
    RoundSets round;
    for (std::size_t i = 0; i < candidates; ++i) {
      if (std::find(s.entered.begin(), s.entered.end(), i) != s.entered.end()) continue;
      round.push_back(s.entered);
      round.back().push_back(i);
    }
    if (prepare) prepare(round);
    for (const auto& active : round) {
      const std::size_t i = active.back();
      const SelectionFit f = fit(active);
      Evidence& e = s.evidence[i];
      e.lr = 2.0 * (current - f.nll);
      e.threshold = threshold(i);
      e.admissible = f.admissible;
      if (!f.admissible) continue;
      if (e.lr - e.threshold > best_margin) {
        best_margin = e.lr - e.threshold;
        best = i;
        best_nll = f.nll;
      }
    }
    if (best == candidates) break;
    s.entered.push_back(best);
    current = best_nll;
  }
  return s;
}

OffsetProfile profile_offset(const std::function<double(double)>& nll_fixed,
                             const std::function<double(double)>& nll_profiled, double dt, double range) {
  constexpr double kChi2_95 = 3.841458820694124;
  const double coarse = std::clamp(dt, 0.005, 0.05);
  const double fine = coarse / 10.0;
  const long span = static_cast<long>(std::floor(range / fine + 1e-9));
  std::map<long, double> fixed;  // fine-grid index → NLL with the others held
  auto at = [&](long k) {
    auto it = fixed.find(k);
    if (it != fixed.end()) return it->second;
    return fixed[k] = nll_fixed(static_cast<double>(k) * fine);
  };
  long best = 0;
  for (long k = -span; k <= span; k += 10) {
    if (at(k) < at(best)) best = k;
  }
  const long around = best;
  for (long k = std::max(-span, around - 20); k <= std::min(span, around + 20); ++k) {
    if (at(k) < at(best)) best = k;
  }
  OffsetProfile p;
  p.step = fine;
  p.value = static_cast<double>(best) * fine;
  p.nll = at(best);
  if (best > -span && best < span) {
    // Parabola through the best point and its neighbours.
    const double a = at(best - 1), b = at(best), c = at(best + 1);
    const double curvature = a - 2.0 * b + c;
    if (curvature > 0.0) {
      const double shift = 0.5 * (a - c) / curvature;  // in fine steps, |shift| ≤ 0.5
      const double x = (static_cast<double>(best) + shift) * fine;
      const double v = nll_fixed(x);
      if (v <= p.nll) {
        p.value = x;
        p.nll = v;
      }
    }
  }
  if (!nll_profiled) {
    p.lo = p.hi = p.value;
    return p;
  }
  // Interval: the profile (others re-fitted) walked outward from the optimum.
  const double minimum = nll_profiled(p.value);
  // Fine steps for the first ten, then growing by half each time (a flat profile is not walked
  // point by point).
  auto crossing = [&](int dir) {
    double inside = p.value, inside_dev = 0.0, offset = 0.0, step = fine;
    for (int k = 1; k <= 60; ++k) {
      offset += step;
      if (k >= 10) step *= 1.5;
      const double x = p.value + dir * offset;
      if (std::abs(x) > range) return dir * range;
      const double dev = 2.0 * (nll_profiled(x) - minimum);
      if (dev > kChi2_95) {
        const double f = (kChi2_95 - inside_dev) / std::max(dev - inside_dev, 1e-12);
        return inside + dir * std::clamp(f, 0.0, 1.0) * std::abs(x - inside);
      }
      inside = x;
      inside_dev = std::max(dev, 0.0);
    }
    return dir * range;
  };
  p.lo = crossing(-1);
  p.hi = crossing(+1);
  return p;
}

}  // namespace locbench::diagnosis
