#pragma once
// Test harness shared by the filter tests: runs a compass EKF over simulated corridor runs and
// collects NEES, NIS and the final position error.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "algorithms/filters/compass_odometry_input.h"
#include "algorithms/filters/consistency.h"
#include "algorithms/filters/quantization_noise.h"
#include "core/compass_ekf_model.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"

namespace locbench::test {

// The corridor preset with exactly the noise the filters model: true wheels = nominal, no slip,
// 1000× finer encoders (quantization negligible), white compass noise σ = 1° without
// quantization, no clock jitter (every encoder sample has its compass reading). Floor noise
// k_l = k_r = 0.005 √m as in the preset.
inline sim::Scenario matched_corridor() {
  sim::Scenario s = sim::preset("corridor");
  s.robot.actual = s.robot.nominal;
  s.slip.straight.rate = 0.0;
  s.slip.turn.rate = 0.0;
  s.robot.encoder.counts_per_rev *= 1000.0;
  s.compass.resolution = 0.0;
  s.compass.noise = deg(1.0);
  s.compass.timing.jitter = 0.0;
  s.encoders.timing.jitter = 0.0;
  return s;
}
inline constexpr double kMatchedCompassSigma = deg(1.0);
inline constexpr double kFloorK = 0.005;

// Metres per tick of the matched corridor's left encoder (for σ = C/√6).
inline double matched_tick(const sim::Scenario& s) {
  return s.robot.params().meters_per_tick(s.robot.nominal.diameter_left);
}

template <class Step>
const CompassFilterStep& filter_part(const Step& s) {
  if constexpr (requires { s.filter; }) {
    return s.filter;
  } else {
    return s;
  }
}

struct RunTrace {
  std::vector<double> nees;  // per sample
  std::vector<double> nis;   // per sample with a compass update
  double final_error = 0.0;  // [m], eq. 4.46
};

// Runs one filter (made by make(wheelbase, start)) over a simulated run; the filter starts at
// the true pose of the first encoder sample, as the thesis's robot starts from a known pose.
template <class Make>
RunTrace run_filter(const sim::SimulationResult& res, Make make, std::size_t max_steps = 100000) {
  const NominalModel model = *res.log.nominal_model();
  const auto steps = filters::pair_encoder_compass(res.log.encoders, res.log.compass, model, 0.125);
  auto filter = make(model.wheelbase, res.wheel_samples.front().pose);
  RunTrace t;
  Vector3 last = to_vector(res.wheel_samples.front().pose);
  std::size_t last_index = 0;  // encoder sample of `last`
  for (std::size_t k = 0; k < steps.size() && k < max_steps; ++k) {
    const auto out = filter.step(steps[k].u, steps[k].compass);
    const CompassFilterStep& f = filter_part(out);
    t.nees.push_back(filters::pose_nees(res.wheel_samples[steps[k].encoder_index].pose, f.mean, f.covariance));
    if (f.updated) t.nis.push_back(filters::nis(f.innovation, f.innovation_variance));
    last = f.mean;
    last_index = steps[k].encoder_index;
  }
  const Pose2 truth = res.wheel_samples[last_index].pose;
  t.final_error = std::hypot(last(0) - truth.x, last(1) - truth.y);
  return t;
}

struct MonteCarlo {
  filters::ConsistencySummary nees;
  filters::ConsistencySummary nis;
  std::vector<double> final_errors;
};

inline std::vector<sim::SimulationResult> simulate_runs(const sim::Scenario& scenario, int runs, std::uint64_t seed0) {
  std::vector<sim::SimulationResult> out;
  for (int r = 0; r < runs; ++r) {
    out.push_back(sim::simulate(scenario, seed0 + static_cast<std::uint64_t>(r)));
  }
  return out;
}

// NEES and NIS series over the runs, cut to `steps` samples (and to the shortest run).
template <class Make>
MonteCarlo monte_carlo(const std::vector<sim::SimulationResult>& runs, std::size_t steps, Make make) {
  std::vector<std::vector<double>> nees, nis_runs;
  MonteCarlo mc;
  for (const auto& res : runs) {
    RunTrace t = run_filter(res, make, steps);
    nees.push_back(std::move(t.nees));
    nis_runs.push_back(std::move(t.nis));
    mc.final_errors.push_back(t.final_error);
  }
  auto cut = [](std::vector<std::vector<double>>& v) {
    std::size_t n = v.front().size();
    for (const auto& r : v) n = std::min(n, r.size());
    for (auto& r : v) r.resize(n);
  };
  cut(nees);
  cut(nis_runs);
  mc.nees = filters::summarize_consistency(nees, 3);
  mc.nis = filters::summarize_consistency(nis_runs, 1);
  return mc;
}

}  // namespace locbench::test
