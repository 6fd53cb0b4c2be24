#pragma once
// The two search procedures every channel shares, written once:
//  - forward selection of catalog causes by likelihood ratio (Bonferroni over the candidates);
//  - the time-offset profile, to a fraction of the reference's sample period, with a 95%
//    interval from the profile deviance;
// and the rule that says when an offset is resolved at all.
#include <cstddef>
#include <functional>
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
// candidate i's χ² quantile.
struct SelectionFit {
  double nll = 0.0;
  bool admissible = true;
};
Selection forward_select(std::size_t candidates, double nominal_nll,
                         const std::function<double(std::size_t)>& threshold,
                         const std::function<SelectionFit(const std::vector<std::size_t>&)>& fit);

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

}  // namespace locbench::diagnosis
