#include "pipelines/noise_filters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "algorithms/filters/compass_ekf.h"
#include "algorithms/filters/compass_odometry_input.h"
#include "algorithms/filters/consistency.h"
#include "baselines/filters/fixed_q_ekf.h"
#include "baselines/filters/sage_husa_aekf.h"
#include "baselines/filters/vb_akf.h"
#include "core/dead_reckoning.h"
#include "datasets/sim/scenario_json.h"

namespace locbench::experiments {
using locbench::baselines::filters::FixedQEkf, locbench::baselines::filters::FixedQEkfOptions,
    locbench::baselines::filters::SageHusaAekf, locbench::baselines::filters::SageHusaOptions,
    locbench::baselines::filters::VbAkf, locbench::baselines::filters::VbAkfOptions;
using locbench::filters::CompassEkf, locbench::filters::CompassEkfOptions, locbench::filters::CompassOdometrySample,
    locbench::filters::ConsistencySummary, locbench::filters::nees, locbench::filters::nis,
    locbench::filters::pair_encoder_compass, locbench::filters::pose_nees, locbench::filters::summarize_consistency;

nlohmann::json default_filter_options(const Eigen::Vector3d& initial_covariance) {
  CompassEkfOptions adaptive;
  adaptive.initial_covariance = initial_covariance;
  FixedQEkfOptions fixed;
  fixed.initial_covariance = initial_covariance;
  SageHusaOptions sage;
  sage.initial_covariance = initial_covariance;
  VbAkfOptions vb;
  vb.initial_covariance = initial_covariance;
  return {{"fixed_q_ekf", fixed}, {"adaptive_model_ekf", adaptive}, {"sage_husa_aekf", sage}, {"vb_akf", vb}};
}

FilterRun run_noise_filters(const sim::SimulationResult& result, const nlohmann::json& filter_options) {
  const auto model = result.log.nominal_model();
  if (!model || result.log.encoders.size() < 2) throw std::logic_error("run without encoders");
  const Trajectory truth = sim::true_trajectory(result);
  // The compass is read at the encoder poll (both 4 Hz on the Trilobot); pair within half a
  // period.
  const auto samples = pair_encoder_compass(result.log.encoders, result.log.compass, *model, 0.125);
  const auto start = truth.pose_at(result.log.encoders.front().t);
  if (!start) throw std::logic_error("first encoder sample outside the truth");
  const double B = model->wheelbase;

  const auto fixed = filter_options.at("fixed_q_ekf").get<FixedQEkfOptions>();
  const auto adaptive = filter_options.at("adaptive_model_ekf").get<CompassEkfOptions>();
  const auto sage = filter_options.at("sage_husa_aekf").get<SageHusaOptions>();
  const auto vb = filter_options.at("vb_akf").get<VbAkfOptions>();
  FixedQEkf f0(fixed, B, *start);
  CompassEkf f1(adaptive, B, *start);
  SageHusaAekf f2(sage, B, *start);
  VbAkf f3(vb, B, *start);

  FilterRun run;
  CompassFilterStep last[kNoiseFilters];
  double t_last = 0.0;
  for (const CompassOdometrySample& s : samples) {
    const auto tp = truth.pose_at(s.t);
    if (!tp) break;
    last[0] = f0.step(s.u, s.compass);
    last[1] = f1.step(s.u, s.compass);
    last[2] = f2.step(s.u, s.compass).filter;
    last[3] = f3.step(s.u, s.compass).filter;
    t_last = s.t;
    for (int f = 0; f < kNoiseFilters; ++f) {
      run.estimates[f].push_back({s.t, last[f].pose()});
      run.nees[f].push_back(pose_nees(*tp, last[f].mean, last[f].covariance));
      if (last[f].updated) run.nis[f].push_back(nis(last[f].innovation, last[f].innovation_variance));
    }
  }
  const Pose2 end = *truth.pose_at(t_last);
  run.truth = truth;
  run.odometry = dead_reckon_encoders(result.log.encoders, *model, *start);
  for (int f = 0; f < kNoiseFilters; ++f) {
    const Pose2 e = between(end, last[f].pose());
    run.final_position_error[f] = std::hypot(e.x, e.y);
    run.final_heading_error[f] = std::abs(e.theta);
  }
  return run;
}

FilterRecord record_of(const FilterRun& r, const sim::SimulationResult& sim) {
  FilterRecord x;
  x.final_error = r.final_position_error;
  x.heading_error = r.final_heading_error;
  x.nees = r.nees;
  x.nis = r.nis;
  x.records = sim.log.record_count();
  x.duration = sim.duration;
  return x;
}

void collect(const FilterRecord& r, FilterSamples& s) {
  for (int f = 0; f < kNoiseFilters; ++f) {
    s.final_error[f].push_back(r.final_error[f]);
    s.heading_error[f].push_back(r.heading_error[f]);
    s.nees[f].push_back(r.nees[f]);
    s.nis[f].push_back(r.nis[f]);
  }
}

std::vector<std::vector<double>> common_length(std::vector<std::vector<double>> v) {
  std::size_t n = std::numeric_limits<std::size_t>::max();
  for (const auto& x : v) n = std::min(n, x.size());
  for (auto& x : v) x.resize(n);
  return v;
}

void add_filter_results(reports::ExperimentResults& out, const std::string& dataset, const FilterSamples& s) {
  for (int f = 0; f < kNoiseFilters; ++f) {
    const std::string& m = kNoiseFilterNames[f];
    out.results.push_back(
        reports::make_metric(m, dataset, "final_position_error", "m", "monte_carlo_runs", s.final_error[f]));
    out.results.push_back(
        reports::make_metric(m, dataset, "final_heading_error", "rad", "monte_carlo_runs", s.heading_error[f]));
    const ConsistencySummary nees = summarize_consistency(common_length(s.nees[f]), 3);
    const ConsistencySummary nis = summarize_consistency(common_length(s.nis[f]), 1);
    out.results.push_back(reports::make_metric(m, dataset, "nees_time_average", "", "time_steps", nees.average, false));
    out.results.push_back(reports::make_metric(m, dataset, "nis_time_average", "", "time_steps", nis.average, false));
    out.notes.push_back(
        fmt::format("{} on {}: average NEES inside its 95% χ² band [{:.2f}, {:.2f}] (3 dof, {} runs) at "
                    "{:.0f}% of steps ({:.0f}% above: over-confident, {:.0f}% below: conservative); NIS "
                    "inside [{:.2f}, {:.2f}] at {:.0f}% of updates.",
                    m, dataset, nees.bounds.lower, nees.bounds.upper, nees.runs, 100 * nees.fraction_inside,
                    100 * nees.fraction_above, 100 * nees.fraction_below, nis.bounds.lower, nis.bounds.upper,
                    100 * nis.fraction_inside));
  }
}

}  // namespace locbench::experiments
