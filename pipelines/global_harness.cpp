#include "pipelines/global_harness.h"

#include <cmath>

#include "algorithms/laser/eap_matcher.h"
#include "algorithms/pose_correction/ekf_tracker.h"
#include "baselines/global/grid_markov.h"
#include "baselines/global/monte_carlo_localization.h"
#include "baselines/laser/extract_then_match.h"
#include "baselines/laser/options_json.h"
#include "baselines/localization/line_feature_kalman_localizer.h"
#include "baselines/localization/line_observation.h"
#include "core/diff_drive_odometry.h"
#include "core/errors.h"
#include "datasets/io/odometry_interpolation.h"

namespace locbench::experiments::global {
using io::interpolate_odometry, io::interpolate_truth;

std::vector<ScanStep> scan_steps(const Log& log) {
  std::vector<ScanStep> out;
  const bool truth = !log.truth.empty();
  for (const LaserReading& l : log.laser) {
    const auto odo = interpolate_odometry(log, l.scan.timestamp);
    if (!odo) continue;
    ScanStep s{l.scan.timestamp, *odo, &l.scan, std::nullopt};
    if (truth) {
      s.reference = interpolate_truth(log, l.scan.timestamp);
      if (!s.reference) continue;
    }
    out.push_back(s);
  }
  return out;
}

std::vector<ScanStep> splice_kidnapping(std::vector<ScanStep> a, const std::vector<ScanStep>& b) {
  if (a.empty() || b.empty()) return a;
  const Pose2 end = a.back().odometry, b0 = b.front().odometry;
  const double shift = a.back().t + 0.2 - b.front().t;
  for (ScanStep s : b) {
    s.odometry = end * between(b0, s.odometry);
    s.t += shift;
    a.push_back(s);
  }
  return a;
}

bool is_global_method(const std::string& name) { return name == "mcl" || name == "grid_markov"; }

namespace {

// Odometry increment between two odometry poses as wheel travel under wheelbase B (ΔD along the
// mean heading, Δθ = (U_R − U_L)/B): what the Kalman trackers' prediction takes.
WheelDisplacement wheels_between(const Pose2& a, const Pose2& b, double wheelbase) {
  const double dth = angle_diff(b.theta, a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double along = dx * std::cos(a.theta + dth / 2.0) + dy * std::sin(a.theta + dth / 2.0);
  return {along - dth * wheelbase / 2.0, along + dth * wheelbase / 2.0};
}

class MclLocalizer final : public Localizer {
 public:
  MclLocalizer(const LineMap& map, const locbench::baselines::global::MclOptions& o, std::uint64_t seed)
      : mcl_(map, o, seed) {}
  void step(const ScanStep& s) override { mcl_.update(s.odometry, *s.scan); }
  Pose2 pose() const override { return mcl_.estimate(); }
  std::size_t memory_bytes() const override { return mcl_.memory_bytes(); }
  std::size_t hypotheses() const override { return mcl_.particle_count(); }

 private:
  locbench::baselines::global::MonteCarloLocalization mcl_;
};

class GridLocalizer final : public Localizer {
 public:
  GridLocalizer(const LineMap& map, const locbench::baselines::global::GridMarkovOptions& o) : grid_(map, o) {}
  void step(const ScanStep& s) override {
    if (grid_.update(s.odometry, *s.scan)) estimate_ = grid_.estimate();
  }
  Pose2 pose() const override { return estimate_; }
  std::size_t memory_bytes() const override { return grid_.memory_bytes(); }
  std::size_t hypotheses() const override { return grid_.cell_count(); }

 private:
  locbench::baselines::global::GridMarkov grid_;
  Pose2 estimate_;
};

class EkfEapLocalizer final : public Localizer {
 public:
  EkfEapLocalizer(const LineMap& map, const nlohmann::json& o, const Pose2& start, double wheelbase)
      : map_(map),
        eap_(o.at("eap").get<laser::EapOptions>()),
        ekf_(o.at("tracker").get<pose_correction::EkfTrackerOptions>(), wheelbase, start),
        wheelbase_(wheelbase) {}
  void step(const ScanStep& s) override {
    if (last_) ekf_.predict(wheels_between(*last_, s.odometry, wheelbase_));
    last_ = s.odometry;
    ekf_.correct(*s.scan, map_, eap_);
  }
  Pose2 pose() const override { return ekf_.pose(); }
  std::size_t memory_bytes() const override { return sizeof(*this); }
  std::size_t hypotheses() const override { return 1; }

 private:
  const LineMap& map_;
  laser::EapMatcher eap_;
  pose_correction::EkfTracker ekf_;
  double wheelbase_;
  std::optional<Pose2> last_;
};

class LineKalmanLocalizer final : public Localizer {
 public:
  LineKalmanLocalizer(const LineMap& map, const nlohmann::json& o, const Pose2& start, double wheelbase)
      : map_(map),
        sm_(o.at("split_and_merge").get<baselines::laser::SplitAndMergeMatcherOptions>()),
        kf_(o.at("line_kalman").get<baselines::localization::LineFeatureKalmanOptions>(), wheelbase, start),
        wheelbase_(wheelbase) {}
  void step(const ScanStep& s) override {
    if (last_) kf_.predict(wheels_between(*last_, s.odometry, wheelbase_));
    last_ = s.odometry;
    std::vector<baselines::localization::LineObservation> obs;
    for (const baselines::laser::ExtractedLine& l : sm_.extract_lines(*s.scan).lines) {
      std::vector<Eigen::Vector2d> pts;
      for (const laser::ScanPoint& p : l.points) pts.push_back(p.robot);
      obs.push_back(baselines::localization::line_observation(pts));
    }
    kf_.update(obs, map_);
  }
  Pose2 pose() const override { return kf_.pose(); }
  std::size_t memory_bytes() const override { return sizeof(*this); }
  std::size_t hypotheses() const override { return 1; }

 private:
  const LineMap& map_;
  baselines::laser::SplitAndMergeMatcher sm_;
  baselines::localization::LineFeatureKalmanLocalizer kf_;
  double wheelbase_;
  std::optional<Pose2> last_;
};

}  // namespace

nlohmann::json default_method_options() {
  nlohmann::json mcl, grid, eap, tracker, sm, lk;
  locbench::baselines::global::to_json(mcl, locbench::baselines::global::MclOptions{});
  locbench::baselines::global::to_json(grid, locbench::baselines::global::GridMarkovOptions{});
  to_json(eap, laser::EapOptions{});
  to_json(tracker, pose_correction::EkfTrackerOptions{});
  to_json(sm, baselines::laser::SplitAndMergeMatcherOptions{});
  to_json(lk, baselines::localization::LineFeatureKalmanOptions{});
  return {{"mcl", mcl},
          {"grid_markov", grid},
          {"ekf_eap", {{"eap", eap}, {"tracker", tracker}}},
          {"kalman_line_features", {{"split_and_merge", sm}, {"line_kalman", lk}}},
          {"wheelbase", 0.33}};
}

std::unique_ptr<Localizer> make_localizer(const std::string& name, const LineMap& map, const nlohmann::json& options,
                                          const std::optional<Pose2>& start, std::uint64_t seed) {
  if (name == "mcl") {
    locbench::baselines::global::MclOptions o;
    locbench::baselines::global::from_json(options.at("mcl"), o);
    return std::make_unique<MclLocalizer>(map, o, seed);
  }
  if (name == "grid_markov") {
    locbench::baselines::global::GridMarkovOptions o;
    locbench::baselines::global::from_json(options.at("grid_markov"), o);
    return std::make_unique<GridLocalizer>(map, o);
  }
  const bool ekf = name == "ekf_eap";
  if (!ekf && name != "kalman_line_features") {
    throw UsageError("unknown localization method '" + name +
                     "' (known: mcl, grid_markov, ekf_eap, kalman_line_features)");
  }
  if (!start) throw UsageError(name + " tracks from a known start pose: give one");
  const double b = options.at("wheelbase").get<double>();
  if (ekf) return std::make_unique<EkfEapLocalizer>(map, options.at("ekf_eap"), *start, b);
  return std::make_unique<LineKalmanLocalizer>(map, options.at("kalman_line_features"), *start, b);
}

std::vector<Pose2> run_localizer(Localizer& l, const std::vector<ScanStep>& steps, std::size_t begin, std::size_t end) {
  std::vector<Pose2> out;
  out.reserve(end - begin);
  for (std::size_t i = begin; i < end; ++i) {
    l.step(steps[i]);
    out.push_back(l.pose());
  }
  return out;
}

std::optional<std::size_t> converged_from(const std::vector<Pose2>& est, const std::vector<ScanStep>& steps,
                                          std::size_t begin, std::size_t end, const ConvergenceCriterion& c) {
  std::optional<std::size_t> from;
  for (std::size_t i = begin; i < end; ++i) {
    const Pose2& r = *steps[i].reference;
    const Pose2& e = est[i];
    const bool ok = translation_distance(e, r) < c.position && std::abs(angle_diff(e.theta, r.theta)) < c.heading;
    if (!ok) {
      from.reset();
    } else if (!from) {
      from = i - begin;
    }
  }
  return from;
}

TrackingRms tracking_rms(const std::vector<Pose2>& est, const std::vector<ScanStep>& steps, std::size_t begin,
                         std::size_t end) {
  double sp = 0.0, sh = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    sp += std::pow(translation_distance(est[i], *steps[i].reference), 2);
    sh += std::pow(angle_diff(est[i].theta, steps[i].reference->theta), 2);
  }
  return {std::sqrt(sp / static_cast<double>(end - begin)), std::sqrt(sh / static_cast<double>(end - begin))};
}

void add_method_metrics(reports::ExperimentResults& out, const std::string& method, const std::string& dataset,
                        const MethodRunSamples& s) {
  const auto metric = [&](const char* variant, const char* unit, const std::vector<double>& v, const char* better) {
    if (v.empty()) return;
    reports::MetricResult r = reports::make_metric(method, dataset, variant, unit, "monte_carlo_runs", v);
    r.better = better;
    out.results.push_back(std::move(r));
  };
  if (is_global_method(method)) {
    metric("global_success_rate", "", s.converged, "higher");
    metric("time_to_convergence", "s", s.time_to_convergence, "lower");
    metric("distance_to_convergence", "m", s.distance_to_convergence, "lower");
  }
  metric("tracking_rms_position", "m", s.rms_position, "lower");
  metric("tracking_rms_heading", "rad", s.rms_heading, "lower");
  metric("kidnap_recovery_rate", "", s.recovered, "higher");
  metric("kidnap_recovery_time", "s", s.recovery_time, "lower");
  metric("kidnap_recovery_distance", "m", s.recovery_distance, "lower");
  metric("memory", "bytes", s.memory, "lower");
}

double path_length(const std::vector<ScanStep>& steps, std::size_t a, std::size_t b) {
  double d = 0.0;
  for (std::size_t i = a + 1; i <= b && i < steps.size(); ++i) {
    d += translation_distance(*steps[i - 1].reference, *steps[i].reference);
  }
  return d;
}

LineMap map_from_scans(const std::vector<ScanStep>& steps, double t0, double t1, int every) {
  if (every < 1) throw UsageError("map_from_scans: every must be ≥ 1");
  const baselines::laser::SplitAndMergeMatcher sm{baselines::laser::SplitAndMergeMatcherOptions{}};
  LineMap m;
  m.name = "scan_lines";
  int k = 0;
  for (const ScanStep& s : steps) {
    if (s.t < t0 || s.t > t1) continue;
    if (k++ % every != 0) continue;
    for (const baselines::laser::ExtractedLine& l : sm.extract_lines(*s.scan).lines) {
      const Segment r = l.fit.segment();
      if (r.length() < 0.3) continue;
      m.segments.push_back({s.odometry * r.p1, s.odometry * r.p2});
    }
  }
  return m;
}

}  // namespace locbench::experiments::global
