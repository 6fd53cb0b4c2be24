// Experiment global/sim: global localization from an unknown start, tracking once converged and
// recovery after a kidnapping, on simulated worlds (the thesis's 8 m room, a 16 m corridor and
// random rooms). Per task (one world × one Monte-Carlo run) a Pioneer with an LMS 200 drives
// two random waypoint tours in the world; the second is spliced after the first with the
// odometry continuing smoothly (the robot is carried away: a kidnapping). Methods:
//   mcl                  Monte Carlo localization (KLD-sampling, random-particle injection), start unknown
//   grid_markov          grid Markov localization (default 0.2 m × 0.2 m × 5°), start unknown
//   ekf_eap              the chapter-6 EKF with EAP matches, started at the true pose
//   kalman_line_features the slides' line-feature Kalman localizer, started at the true pose
// Converged = the estimate stays within 0.5 m and 0.35 rad of the truth from then to the end of
// the tour (configurable). Tracking error = RMS over the second half of the first tour, counted
// for runs in which the method had converged by then.
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/checksum.h"
#include "core/errors.h"
#include "core/statistics.h"
#include "core/units.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"
#include "datasets/sim/worlds.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/registry.h"
#include "pipelines/global_harness.h"

namespace locbench::experiments::global_sim {

const ExperimentInfo kInfo{
    .name = "global/sim",
    .description =
        "Global localization (MCL, grid Markov) from an unknown start, tracking once converged "
        "and kidnap recovery, against the chapter-6 EKF and the line-feature Kalman localizer "
        "started at the truth; simulated room, corridor and random rooms",
    .in_default_suite = false,  // ~1 min in Release
    .reading = {"The Kalman trackers start at the true pose (they cannot localize globally), so their "
                "'success' is that they stayed converged; after the kidnapping their linearised update "
                "matches the scan against the wrong part of the map. Tracking RMS counts only runs that "
                "had converged by the middle of the first tour (n in each result)."}};

using global::ScanStep;

const char* const kWorlds[] = {"room", "corridor", "random_room"};
constexpr int kWorldCount = 3;

struct MethodRecord {
  double converged = 0.0;                                                     // 1/0, first tour
  double time_to_convergence = std::numeric_limits<double>::quiet_NaN();      // [s]
  double distance_to_convergence = std::numeric_limits<double>::quiet_NaN();  // [m]
  double rms_position = std::numeric_limits<double>::quiet_NaN();             // second half of tour 1 [m]
  double rms_heading = std::numeric_limits<double>::quiet_NaN();              // [rad]
  double recovered = 0.0;                                                     // 1/0 after the kidnapping
  double recovery_time = std::numeric_limits<double>::quiet_NaN();            // [s]
  double recovery_distance = std::numeric_limits<double>::quiet_NaN();        // [m]
  double memory_bytes = 0.0;
  double hypotheses = 0.0;  // at the end
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(MethodRecord, converged, time_to_convergence, distance_to_convergence, rms_position,
                                   rms_heading, recovered, recovery_time, recovery_distance, memory_bytes, hypotheses)

struct Record {
  int world = 0;
  std::size_t steps_first = 0, steps = 0, segments = 0;
  double duration = 0.0, kidnap_distance = 0.0;
  std::vector<MethodRecord> methods;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Record, world, steps_first, steps, segments, duration, kidnap_distance, methods)

// JSON records cannot hold NaN: encode "not applicable" as null.
nlohmann::json encode(const Record& r) {
  nlohmann::json j = r;
  for (auto& m : j["methods"]) {
    for (auto& [k, v] : m.items()) {
      if (v.is_number_float() && std::isnan(v.get<double>())) v = nullptr;
    }
  }
  return j;
}
Record decode(nlohmann::json j) {
  for (auto& m : j["methods"]) {
    for (auto& [k, v] : m.items()) {
      if (v.is_null()) v = std::numeric_limits<double>::quiet_NaN();
    }
  }
  return j.get<Record>();
}

LineMap make_world(int world, double corridor_length, Rng& rng) {
  if (world == 0) return sim::room_world();
  if (world == 1) return sim::corridor_world(corridor_length, 1.8);
  return sim::random_room(rng);
}

bool clear_path(const LineMap& w, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.05)));
  for (int i = 0; i <= n; ++i) {
    if (!sim::in_free_space(w, a + (b - a) * (static_cast<double>(i) / n), margin)) return false;
  }
  return true;
}

Eigen::Vector2d free_point(const LineMap& w, Rng& rng, double margin) {
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (const Segment& s : w.segments) {
    x0 = std::min({x0, s.p1.x(), s.p2.x()});
    y0 = std::min({y0, s.p1.y(), s.p2.y()});
    x1 = std::max({x1, s.p1.x(), s.p2.x()});
    y1 = std::max({y1, s.p1.y(), s.p2.y()});
  }
  for (int i = 0; i < 10000; ++i) {
    const Eigen::Vector2d p{rng.uniform(x0, x1), rng.uniform(y0, y1)};
    if (sim::in_free_space(w, p, margin)) return p;
  }
  throw std::logic_error("global/sim: no free point in the world");
}

// A waypoint tour in `w` from a random free start: waypoints ≥ 2 m apart, straight legs clear.
sim::Scenario tour(const LineMap& w, int waypoints, Rng& rng) {
  sim::Scenario s = sim::preset("room_laser");
  s.name = "global_tour";
  s.world.kind = sim::WorldKind::kInline;
  s.world.segments.clear();
  for (const Segment& g : w.segments) s.world.segments.emplace_back(g.p1.x(), g.p1.y(), g.p2.x(), g.p2.y());
  const double margin = 0.4;
  Eigen::Vector2d at = free_point(w, rng, margin);
  s.start = Pose2(at.x(), at.y(), rng.uniform(-kPi, kPi));
  s.motion.waypoints.clear();
  for (int k = 0; k < waypoints; ++k) {
    for (int attempt = 0; attempt < 500; ++attempt) {
      const Eigen::Vector2d p = free_point(w, rng, margin);
      if ((p - at).norm() >= 2.0 && clear_path(w, at, p, margin)) {
        s.motion.waypoints.push_back(p);
        at = p;
        break;
      }
    }
  }
  if (s.motion.waypoints.empty()) throw std::logic_error("global/sim: no reachable waypoint");
  return s;
}

struct Options : global::MethodComparisonOptions {
  int runs = 3;
  int waypoints = 4;
  double corridor_length_m = 16.0;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs per world");
  global::visit_method_comparison_fields(v, o);
  v.field("waypoints", o.waypoints, "", at_least(1), "waypoints of each random tour");
  v.field("corridor_length_m", o.corridor_length_m, "m", at_least(4.0), "the corridor world's length");
}

// The options and what is computed once from them.
struct Setup : Options {
  explicit Setup(const Options& o) : Options(o) {}
  global::ConvergenceCriterion criterion;
  nlohmann::json configuration;
};

class GlobalSim final : public MonteCarloExperiment<Options, Setup> {
 public:
  Setup setup(const Options& o, const McPlan& plan) const override {
    Setup s(o);
    s.criterion = o.criterion();
    // Validate every method's options now (UsageError names the key).
    const LineMap probe = sim::room_world();
    for (const auto& m : s.methods) global::make_localizer(m, probe, s.method_options, Pose2{}, 1);
    s.configuration = recorded(o, plan);
    return s;
  }
  int tasks(const Setup&, const McPlan& plan) const override { return plan.runs * kWorldCount; }

  nlohmann::json run_task(const Setup& s, const McPlan& plan, int task) const override {
    const std::uint64_t seed = plan.run_seed(task / kWorldCount);
    Record rec;
    rec.world = task % kWorldCount;
    Rng rng = Rng::stream(seed, 100 + static_cast<std::uint64_t>(rec.world));
    const LineMap world = make_world(rec.world, s.corridor_length_m, rng);
    const sim::SimulationResult ra = sim::simulate(tour(world, s.waypoints, rng), Rng::derive_seed(seed, 1));
    const sim::SimulationResult rb = sim::simulate(tour(world, s.waypoints, rng), Rng::derive_seed(seed, 2));
    const std::vector<ScanStep> a = global::scan_steps(ra.log);
    const std::vector<ScanStep> steps = global::splice_kidnapping(a, global::scan_steps(rb.log));
    const std::size_t na = a.size(), n = steps.size();
    rec.steps_first = na;
    rec.steps = n;
    rec.segments = world.segments.size();
    rec.duration = steps.back().t - steps.front().t;
    rec.kidnap_distance = translation_distance(*steps[na - 1].reference, *steps[na].reference);
    for (std::size_t m = 0; m < s.methods.size(); ++m) {
      auto loc = global::make_localizer(s.methods[m], world, s.method_options, steps.front().reference,
                                        Rng::derive_seed(seed, 10 + m));
      const std::vector<Pose2> est = global::run_localizer(*loc, steps, 0, n);
      MethodRecord r;
      if (const auto c = global::converged_from(est, steps, 0, na, s.criterion)) {
        r.converged = 1.0;
        r.time_to_convergence = steps[*c].t - steps[0].t;
        r.distance_to_convergence = global::path_length(steps, 0, *c);
        if (*c <= na / 2) {
          const global::TrackingRms rms = global::tracking_rms(est, steps, na / 2, na);
          r.rms_position = rms.position;
          r.rms_heading = rms.heading;
        }
      }
      if (const auto c = global::converged_from(est, steps, na, n, s.criterion)) {
        r.recovered = 1.0;
        r.recovery_time = steps[na + *c].t - steps[na].t;
        r.recovery_distance = global::path_length(steps, na, na + *c);
      }
      r.memory_bytes = static_cast<double>(loc->memory_bytes());
      r.hypotheses = static_cast<double>(loc->hypotheses());
      rec.methods.push_back(r);
    }
    return encode(rec);
  }

  reports::ExperimentResults summarise(const Setup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(s.configuration);
    for (int k = 0; k < plan.runs; ++k) out.seeds.push_back(plan.run_seed(k));
    std::vector<Record> recs;
    for (const auto& j : records) recs.push_back(decode(j));
    for (int w = 0; w < kWorldCount; ++w) {
      const std::string ds = std::string("sim_") + kWorlds[w];
      std::size_t steps = 0;
      double duration = 0.0;
      for (const Record& r : recs) {
        if (r.world != w) continue;
        steps += r.steps;
        duration += r.duration;
      }
      out.datasets.push_back({"sim/global_" + std::string(kWorlds[w]), "simulated",
                              text_checksum(s.configuration.dump() + kWorlds[w]), steps, duration});
      for (std::size_t m = 0; m < s.methods.size(); ++m) {
        const std::string& method = s.methods[m];
        const bool global_method = global::is_global_method(method);
        global::MethodRunSamples samples;
        std::vector<double> hyp;
        for (const Record& r : recs) {
          if (r.world != w) continue;
          const MethodRecord& x = r.methods[m];
          samples.converged.push_back(x.converged);
          samples.recovered.push_back(x.recovered);
          samples.memory.push_back(x.memory_bytes);
          hyp.push_back(x.hypotheses);
          const auto add = [](std::vector<double>& v, double value) {
            if (std::isfinite(value)) v.push_back(value);
          };
          add(samples.time_to_convergence, x.time_to_convergence);
          add(samples.distance_to_convergence, x.distance_to_convergence);
          add(samples.rms_position, x.rms_position);
          add(samples.rms_heading, x.rms_heading);
          add(samples.recovery_time, x.recovery_time);
          add(samples.recovery_distance, x.recovery_distance);
        }
        global::add_method_metrics(out, method, ds, samples);
        if (!hyp.empty()) {
          reports::MetricResult h =
              reports::make_metric(method, ds, global_method && method == "mcl" ? "particles_at_end" : "hypotheses", "",
                                   "monte_carlo_runs", hyp);
          h.better = "stable";
          out.results.push_back(std::move(h));
        }
      }
    }
    const auto mean_of = [&](const std::string& method, int w, double MethodRecord::*field) {
      std::vector<double> v;
      for (const Record& r : recs) {
        if (r.world != w) continue;
        for (std::size_t m = 0; m < s.methods.size(); ++m) {
          if (s.methods[m] == method && std::isfinite(r.methods[m].*field)) v.push_back(r.methods[m].*field);
        }
      }
      return v.empty() ? std::numeric_limits<double>::quiet_NaN() : mean(v);
    };
    for (int w = 0; w < kWorldCount; ++w) {
      std::string line = fmt::format("{} ({} runs):", kWorlds[w], plan.runs);
      for (const auto& m : s.methods) {
        line += fmt::format(
            " {}: success {:.0f}%, converged after {:.1f} s / {:.1f} m, tracking RMS {:.0f} mm, "
            "kidnap recovery {:.0f}% ({:.1f} s);",
            m, 100.0 * mean_of(m, w, &MethodRecord::converged), mean_of(m, w, &MethodRecord::time_to_convergence),
            mean_of(m, w, &MethodRecord::distance_to_convergence), to_mm(mean_of(m, w, &MethodRecord::rms_position)),
            100.0 * mean_of(m, w, &MethodRecord::recovered), mean_of(m, w, &MethodRecord::recovery_time));
      }
      out.notes.push_back(line);
    }
    return out;
  }
};

const Registration<GlobalSim> global_sim_registration(kInfo);

}  // namespace locbench::experiments::global_sim
