#include "pipelines/landmark_family.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "algorithms/filters/consistency.h"
#include "core/enum_names.h"
#include "core/errors.h"
#include "core/statistics.h"

namespace locbench::experiments::landmarks {
namespace {

constexpr EnumNames<TuningCriterion, 3> kCriteria{{{TuningCriterion::kLogScore, "log_score"},
                                                   {TuningCriterion::kRmse, "rmse"},
                                                   {TuningCriterion::kConsistentLogScore, "consistent_log_score"}}};

// The observations' true times under a sensor model: where the steps are cut.
std::vector<double> observation_times(const TrackingData& data, const LandmarkSensorModel& sensor) {
  std::vector<double> t;
  t.reserve(data.observations.size());
  for (const Observation& o : data.observations) t.push_back(o.t - sensor.time_offset);
  return t;
}

// The motion each method predicts with on one part of a log: the logged motion (no model), the
// nominal model's and the diagnosed model's.
struct PartMotion {
  std::vector<MotionStep> logged, nominal, diagnosed;
};
PartMotion part_motion(const TrackingData& data, const FilterModels& m, const LandmarkSensorModel& plain) {
  PartMotion p;
  p.logged = model_motion(data, diagnosis::OdometryModel{}, m.noise_window_s, observation_times(data, plain));
  p.nominal = model_motion(data, m.nominal_motion, m.noise_window_s, observation_times(data, m.nominal_sensor));
  p.diagnosed = model_motion(data, m.diagnosed_motion, m.noise_window_s, observation_times(data, m.diagnosed_sensor));
  return p;
}

MethodSetup base_setup(Method method, const PartMotion& motion, const FilterModels& m, const FamilyOptions& o) {
  MethodSetup s;
  s.method = method;
  s.fixed_q_per_s = o.fixed_q_per_s;
  s.adaptive = o.adaptive;
  s.initial_sigma = o.initial_sigma;
  switch (method) {
    case Method::kNominalModel:
      s.motion = &motion.nominal;
      s.sensor = m.nominal_sensor;
      s.sensor.structure = {};  // white
      break;
    case Method::kDiagnosedModel:
      s.motion = &motion.diagnosed;
      s.sensor = m.diagnosed_sensor;
      if (!o.correlated_sensor_noise) s.sensor.structure = {};
      if (o.correlated_motion_noise) s.motion_structure = m.diagnosed_motion_structure;
      s.noise_window_s = m.noise_window_s;
      s.stall = stall_loss_process(m.diagnosed_motion, m.noise_window_s, s.motion_structure.stall_persistence);
      break;
    default:
      s.motion = &motion.logged;
      s.sensor = m.nominal_sensor;
      s.sensor.time_offset = 0.0;
  }
  return s;
}

const std::vector<double>& knobs(Method m, const FamilyOptions& o) {
  if (m == Method::kSageHusa) return o.sage_husa_forgetting;
  if (m == Method::kVbAkf) return o.vb_forgetting;
  return o.r_scales;
}

}  // namespace

const char* to_string(TuningCriterion c) { return enum_name(kCriteria, c); }
TuningCriterion tuning_criterion_from_string(const std::string& s) {
  return enum_value(kCriteria, s, "tuning criterion must be");
}

filters::ChiSquareInterval tuning_nees_band(double duration_s, const FamilyOptions& options) {
  const double blocks = std::max(1.0, std::ceil(duration_s / options.nees_block_s));
  return filters::average_chi_square_interval(3, static_cast<int>(blocks), 0.95);
}

std::size_t choose_setting(const std::vector<GridRun>& runs, const filters::ChiSquareInterval& band,
                           TuningCriterion criterion, double rmse_tolerance) {
  std::size_t pick = 0;  // the first when every setting diverged (reported as such)
  if (criterion == TuningCriterion::kLogScore) {
    for (std::size_t i = 0; i < runs.size(); ++i)
      if (runs[i].log_score < runs[pick].log_score) pick = i;
    return pick;
  }
  if (criterion == TuningCriterion::kConsistentLogScore) {
    auto consistent = [&](const GridRun& r) { return std::isfinite(r.rmse) && band.contains(r.nees); };
    const bool any_consistent = std::any_of(runs.begin(), runs.end(), consistent);
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (any_consistent && !consistent(runs[i])) continue;
      if (!best || runs[i].log_score < runs[*best].log_score) best = i;
    }
    return best.value_or(0);
  }
  // The lowest RMSE; among the settings within `rmse_tolerance` of it, the most consistent one
  // (NEES inside its band first, then closest to 3 on a log scale).
  double lowest = std::numeric_limits<double>::infinity();
  for (const GridRun& r : runs) lowest = std::min(lowest, r.rmse);
  double best_distance = std::numeric_limits<double>::infinity(), best_rmse = best_distance;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const GridRun& r = runs[i];
    if (!(r.rmse <= lowest * (1.0 + rmse_tolerance)) && !(r.rmse == lowest)) continue;
    const double distance = !(std::isfinite(r.nees) && r.nees > 0.0) ? 1e300
                            : band.contains(r.nees)                  ? 0.0
                                                                     : std::abs(std::log(r.nees / 3.0));
    if (distance < best_distance || (distance == best_distance && r.rmse < best_rmse)) {
      best_distance = distance;
      best_rmse = r.rmse;
      pick = i;
    }
  }
  return pick;
}

namespace {

// One run over several parts, as if end to end: the steps of `b` after those of `a`.
void append(TrackResult& a, const TrackResult& b) {
  const auto join = [](std::vector<double>& x, const std::vector<double>& y) { x.insert(x.end(), y.begin(), y.end()); };
  join(a.t, b.t);
  join(a.position_error, b.position_error);
  join(a.heading_error, b.heading_error);
  join(a.nees, b.nees);
  join(a.log_det_covariance, b.log_det_covariance);
  a.observations += b.observations;
  a.used += b.used;
  a.gated += b.gated;
  a.recoveries += b.recoveries;
  a.finite = a.finite && b.finite;
  a.diverged = a.diverged || b.diverged;
}

// The setting (q, k) of `method` run over every tuning part with that part's models.
struct PartRuns {
  TrackResult result;
  Eigen::Vector2d level_reference = Eigen::Vector2d::Zero();  // the parts' mean
};
PartRuns run_parts(Method method, double q, double k, const std::vector<TuningPart>& parts,
                   const std::vector<PartMotion>& motions, const FamilyOptions& options) {
  PartRuns out;
  const bool tracks_level = options.track_noise_level && method == Method::kDiagnosedModel;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    MethodSetup s = base_setup(method, motions[p], parts[p].models, options);
    s.process_scale = q;
    s.knob = k;
    if (tracks_level) {
      MethodSetup reference = s;
      reference.measure_innovation_level = true;
      s.level_reference = track(parts[p].data, reference, options.gate).innovation_sigma;
      out.level_reference += s.level_reference / static_cast<double>(parts.size());
    }
    const TrackResult r = track(parts[p].data, s, options.gate);
    if (p == 0) {
      out.result = r;
    } else {
      append(out.result, r);
    }
  }
  return out;
}

}  // namespace

std::vector<MethodScore> tune_and_score(const std::vector<TuningPart>& tuning, const TrackingData& test,
                                        const FilterModels& models, const FamilyOptions& options) {
  if (tuning.empty()) throw UsageError("tune_and_score: no tuning part");
  std::vector<PartMotion> motions;
  double duration = 0.0;
  for (const TuningPart& p : tuning) {
    motions.push_back(part_motion(p.data, p.models, p.models.nominal_sensor));
    duration += p.data.to - p.data.from;
  }
  const filters::ChiSquareInterval band = tuning_nees_band(duration, options);
  std::vector<MethodScore> scores;
  for (Method method : kMethods) {
    std::vector<GridRun> runs;
    std::vector<Eigen::Vector2d> level_references;
    for (double q : options.process_scales) {
      for (double k : knobs(method, options)) {
        const PartRuns pr = run_parts(method, q, k, tuning, motions, options);
        const TrackResult& r = pr.result;
        const double inf = std::numeric_limits<double>::infinity();
        runs.push_back(
            {q, k, r.diverged ? inf : r.position_rmse(), r.nees.empty() ? inf : mean(r.nees), r.log_score()});
        level_references.push_back(pr.level_reference);
      }
    }
    const std::size_t i = choose_setting(runs, band, options.criterion, options.rmse_tolerance);
    MethodScore best;
    best.method = method;
    best.grid_runs = runs.size();
    best.process_scale = runs[i].process_scale;
    best.knob = runs[i].knob;
    best.tuning_rmse = runs[i].rmse;
    best.tuning_nees = runs[i].nees;
    best.tuning_log_score = runs[i].log_score;
    best.consistent_setting = band.contains(runs[i].nees);
    best.level_reference = level_references[i];
    scores.push_back(std::move(best));
  }
  const std::vector<TrackResult> heldout = run_tuned(test, scores, models, options);
  for (std::size_t i = 0; i < scores.size(); ++i) scores[i].heldout = heldout[i];
  return scores;
}

std::vector<MethodScore> tune_and_score(const TrackingData& train, const TrackingData& test, const FilterModels& models,
                                        const FamilyOptions& options) {
  return tune_and_score(std::vector<TuningPart>{{train, models}}, test, models, options);
}

TrackResult dead_reckoning(const TrackingData& data, const GatePolicy& gate) {
  TrackingData blind = data;
  blind.observations.clear();
  const auto steps = model_motion(blind, diagnosis::OdometryModel{}, 1.0, {});
  MethodSetup s;
  s.method = Method::kFixedQ;
  s.motion = &steps;
  return track(blind, s, gate);
}

std::vector<TrackResult> run_tuned(const TrackingData& data, const std::vector<MethodScore>& tuned,
                                   const FilterModels& models, const FamilyOptions& options) {
  const PartMotion motion = part_motion(data, models, models.nominal_sensor);
  std::vector<TrackResult> out;
  out.reserve(tuned.size());
  for (const MethodScore& m : tuned) {
    MethodSetup s = base_setup(m.method, motion, models, options);
    s.process_scale = m.process_scale;
    s.knob = m.knob;
    s.level_reference = m.level_reference;
    out.push_back(track(data, s, options.gate));
  }
  return out;
}

}  // namespace locbench::experiments::landmarks
