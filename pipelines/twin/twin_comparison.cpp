#include "pipelines/twin/twin_comparison.h"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.h"
#include "core/rng.h"
#include "pipelines/twin/twin_residuals.h"

namespace locbench::sim {

std::vector<ComponentComparison> compare_twins(const Log& real, const Twin& twin, const std::vector<double>& windows_s,
                                               int runs, std::uint64_t seed) {
  std::vector<diagnosis::MotionData> window_sets;
  for (double w : windows_s) {
    window_sets.push_back(w == twin.residual_window_s ? twin.residual_windows : residual_windows(real, w));
    if (window_sets.back().reference == diagnosis::ReferenceKind::kRelations) break;  // one window per relation
  }
  // Each twin is simulated once per run; its truth is read over every window set.
  const std::size_t sets_n = window_sets.size();
  std::vector<std::vector<std::vector<std::array<double, 3>>>> nominal(sets_n), extended(sets_n);
  for (int run = 0; run < runs; ++run) {
    const std::uint64_t s = Rng::derive_seed(seed, static_cast<std::uint64_t>(run));
    const Log n = twin_log(twin.nominal, s, real), e = twin_log(twin.extended, s, real);
    for (std::size_t k = 0; k < sets_n; ++k) {
      nominal[k].push_back(twin_residuals(window_sets[k], n, twin.time_origin));
      extended[k].push_back(twin_residuals(window_sets[k], e, twin.time_origin));
    }
  }
  constexpr std::array<const char*, 3> kNames{"x", "y", "theta"};
  std::vector<ComponentComparison> out;
  for (std::size_t k = 0; k < sets_n; ++k) {
    const auto r = nominal_residuals(window_sets[k]);
    std::vector<const std::vector<std::array<double, 3>>*> sets{&r};
    for (const auto& v : nominal[k]) sets.push_back(&v);
    for (const auto& v : extended[k]) sets.push_back(&v);
    const std::string window = window_sets[k].reference == diagnosis::ReferenceKind::kRelations
                                   ? "relations"
                                   : fmt::format("{:g}s", windows_s[k]);
    for (int c = 0; c < 3; ++c) {
      const auto v = common_component(sets, c);
      if (v[0].size() < 5) {
        throw InputError(
            real.source.empty() ? real.name : real.source, 0,
            fmt::format("only {} {} windows of the log are covered by its twins' reference; cannot compare them",
                        v[0].size(), window));
      }
      ComponentComparison o;
      o.window = window;
      o.component = kNames[static_cast<std::size_t>(c)];
      o.real = v[0];
      for (int run = 0; run < runs; ++run) {
        const auto& vn = v[static_cast<std::size_t>(1 + run)];
        const auto& ve = v[static_cast<std::size_t>(1 + runs + run)];
        o.nominal_twin.insert(o.nominal_twin.end(), vn.begin(), vn.end());
        o.extended_twin.insert(o.extended_twin.end(), ve.begin(), ve.end());
      }
      o.nominal = ks_two_sample(o.real, o.nominal_twin);
      o.extended = ks_two_sample(o.real, o.extended_twin);
      out.push_back(std::move(o));
    }
  }
  return out;
}

}  // namespace locbench::sim
