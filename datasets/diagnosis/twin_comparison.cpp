#include "datasets/diagnosis/twin_comparison.h"

#include <fmt/format.h>

#include <cmath>

#include "algorithms/core/errors.h"
#include "algorithms/core/rng.h"
#include "datasets/diagnosis/twin_residuals.h"

namespace locbench::sim {

std::vector<ComponentComparison> compare_twins(const Log& real, const Twin& twin, double window_s, int runs,
                                               std::uint64_t seed) {
  const WindowResiduals r = nominal_residuals(real, window_s);
  const std::string window = r.reference == "relations" ? "relations" : fmt::format("{:g}s", window_s);
  constexpr std::array<const char*, 3> kNames{"x", "y", "theta"};
  std::vector<ComponentComparison> out(3);
  for (int c = 0; c < 3; ++c) {
    out[static_cast<std::size_t>(c)].window = window;
    out[static_cast<std::size_t>(c)].component = kNames[static_cast<std::size_t>(c)];
  }
  for (int run = 0; run < runs; ++run) {
    const std::uint64_t s = Rng::derive_seed(seed, static_cast<std::uint64_t>(run));
    const auto rn = nominal_residuals(twin_log(twin.nominal, s, real, twin.time_origin), window_s, twin.time_origin);
    const auto re = nominal_residuals(twin_log(twin.extended, s, real, twin.time_origin), window_s, twin.time_origin);
    const auto pn = pair_windows(r, rn), pe = pair_windows(r, re);
    if (pn.empty() || pe.empty()) {
      throw InputError(real.source.empty() ? real.name : real.source, 0,
                       "no window of the twin lines up in time with the log's; cannot compare them");
    }
    for (int c = 0; c < 3; ++c) {
      auto& o = out[static_cast<std::size_t>(c)];
      if (run == 0) o.real = component(r, c, pn, true);
      for (double v : component(rn, c, pn, false)) o.nominal_twin.push_back(v);
      for (double v : component(re, c, pe, false)) o.extended_twin.push_back(v);
    }
  }
  for (auto& o : out) {
    o.nominal = ks_two_sample(o.real, o.nominal_twin);
    o.extended = ks_two_sample(o.real, o.extended_twin);
  }
  return out;
}

}  // namespace locbench::sim
