#pragma once
// The two search procedures every channel shares, written once:
//  - forward selection of catalog causes by likelihood ratio (Bonferroni over the candidates);
//  - the time-offset profile, to a fraction of the reference's sample period, with a 95%
//    interval from the profile deviance, and the fit that alternates it with the other
//    parameters (fit_with_offset_profile);
// and the rule that says when an offset is resolved at all.
#include <cmath>
#include <cstddef>
#include <functional>
#include <type_traits>
#include <vector>

namespace locbench::diagnosis {

// Offsets up to this size are not reported as a cause (nor lead/lag as structure): simulated logs
// with nothing hidden show ±2–3 ms offsets (motion starts sampled on a jittered clock).
inline constexpr double kOffsetResolution = 0.005;  // [s]
bool offset_resolved(double offset);

struct Evidence {
  double lr = 0.0;         // 2·(NLL without − NLL with), in the round the candidate last competed
  double threshold = 0.0;  // χ²_k(1 − α/m)
  bool admissible = true;  // e.g. an offset within the resolution cannot enter
};

struct Selection {
  std::vector<std::size_t> entered;  // candidate indices in order of entry
  std::vector<Evidence> evidence;    // per candidate
};

// Candidates enter one at a time, the one with the largest LR − threshold margin first, while
// some margin is positive. `fit(active)` returns the NLL of the model with those candidates
// (indices) active, and whether the last candidate's fit is admissible; `threshold(i)` is
// candidate i's χ² quantile. `prepare`, when given, is called with every active set of a round
// before `fit` is asked for any of them (a caller can fit them side by side).
struct SelectionFit {
  double nll = 0.0;
  bool admissible = true;
};
using RoundSets = std::vector<std::vector<std::size_t>>;
Selection forward_select(std::size_t candidates, double nominal_nll,
                         const std::function<double(std::size_t)>& threshold,
                         const std::function<SelectionFit(const std::vector<std::size_t>&)>& fit,
                         const std::function<void(const RoundSets&)>& prepare = {});

// Offset profile over ±`range` s. The likelihood is bumpy between the reference's samples (the
// reference is interpolated between them), so it is scanned, not descended: a coarse grid of step
// clamp(dt, 5 ms, 50 ms) with `nll_fixed` (other parameters held), a fine grid of a tenth of that
// around the best (`nll_fixed` again), and a parabola through the best fine point and its
// neighbours. The 95% interval is where the profile deviance 2·(NLL − min) crosses χ²₁(0.95) =
// 3.84, walked outward in fine steps with `nll_profiled` (other parameters re-fitted at each
// offset) and interpolated linearly between steps; without `nll_profiled`, no interval (lo = hi).
struct OffsetProfile {
  double value = 0.0, lo = 0.0, hi = 0.0;  // [s]
  double nll = 0.0;                        // at `value`, other parameters held
  double step = 0.0;                       // the fine grid's step [s]
};
OffsetProfile profile_offset(const std::function<double(double)>& nll_fixed,
                             const std::function<double(double)>& nll_profiled, double dt, double range = 0.5);

// A channel's fit with a free time offset, alternating: `fit_held(model)` fits the other
// parameters at the model's offset, then the offset is profiled with them held, until the offset
// moves less than half a fine step (judged from the `min_rounds`-th profile on, at most 4
// profiles); then the offset's 95% interval from `refit(model)`, the NLL with the other
// parameters re-fitted at the model's offset (empty: no interval). `Fit` has `model` (with
// `time_offset`), `offset`, `has_offset` and `nll`; `nll(model)` is the channel's likelihood with
// every parameter held. Each channel's fits (compass, odometry, landmark) use it.
template <class Fit, class Model, class FitHeld, class Nll>
Fit fit_with_offset_profile(const Model& start, const FitHeld& fit_held,
                            const std::type_identity_t<std::function<double(const Model&)>>& refit, const Nll& nll,
                            double dt, int min_rounds) {
  auto at_offset = [&nll](const Model& held) {
    return [&nll, held](double o) {
      Model m = held;
      m.time_offset = o;
      return nll(m);
    };
  };
  Fit f = fit_held(start);
  for (int round = 0; round < 4; ++round) {
    const Model held = f.model;
    const OffsetProfile prof = profile_offset(at_offset(held), {}, dt);
    const double moved = std::abs(prof.value - held.time_offset);
    Model next = held;
    next.time_offset = prof.value;
    f = fit_held(next);
    if (round + 1 >= min_rounds && moved < 0.5 * prof.step) break;
  }
  const Model best = f.model;
  std::function<double(double)> profiled;
  if (refit) {
    profiled = [&](double o) {
      Model m = best;
      m.time_offset = o;
      return refit(m);
    };
  }
  f.offset = profile_offset(at_offset(best), profiled, dt);
  f.model.time_offset = f.offset.value;
  f.has_offset = true;
  f.nll = nll(f.model);
  return f;
}

}  // namespace locbench::diagnosis
