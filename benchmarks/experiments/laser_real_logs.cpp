// Experiment laser/real_logs: the matchers and chapter 6's least squares on real SICK scans
// (Freiburg logs: ACES, Intel, MIT CSAIL) against the hand-checked `.relations`. For every
// relation (t1, t2) — both stamps are scan stamps — the lines split-and-merge extracts from the
// scan at t1 (in its robot frame) are the map; the scan at t2 is matched against that map from
// the odometry's relative motion as the estimate, by each matcher, and corrected with the
// weighted-LS heading and point-to-point position (eq. 6.13–6.38). The relative-pose error of
// each corrected motion is reported beside raw odometry's on the same relations.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>

#include "algorithms/core/errors.h"
#include "algorithms/pose_correction/pose_correction.h"
#include "baselines/laser/extract_then_match.h"
#include "benchmarks/experiments/experiments_list.h"
#include "benchmarks/experiments/laser_matchers.h"
#include "benchmarks/experiments/monte_carlo.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/io/odometry_interpolation.h"
#include "reports/checksum.h"

namespace locbench::experiments {
namespace {

struct Setup {
  std::vector<std::string> datasets;
  std::vector<std::string> matchers;
  nlohmann::json matcher_options;
  double max_dt = 0.0;
  std::size_t max_relations = 0;
  nlohmann::json configuration;
};

struct Record {
  std::string status;  // "ok", "skipped", "failed"
  std::string reason;
  std::string path, checksum;
  std::size_t records = 0;
  double duration = 0.0;
  std::size_t relations = 0;
  // [method][relation]: translation [m] and rotation [rad] errors; method 0 = odometry.
  std::vector<std::vector<double>> translation, rotation;
  std::vector<double> position_fixed;  // per matcher: fraction of relations
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Record, status, reason, path, checksum, records, duration,
                                   relations, translation, rotation, position_fixed)

// A map of the lines extracted from one scan, in its robot frame.
LineMap lines_as_map(const laser::ExtractionResult& lines) {
  LineMap m;
  m.name = "previous_scan";
  for (const laser::ExtractedLine& l : lines.lines) {
    const Segment s = l.fit.segment();
    if (s.length() > 1e-6) m.segments.push_back(s);
  }
  return m;
}

// The scan stamped t (within 1 ms: mit-csail's relations print 5 decimals, its scans 6).
std::optional<std::size_t> scan_near(const std::map<double, std::size_t>& scans, double t) {
  auto it = scans.lower_bound(t - 1e-3);
  if (it == scans.end() || it->first > t + 1e-3) return std::nullopt;
  auto best = it;
  for (; it != scans.end() && it->first <= t + 1e-3; ++it) {
    if (std::abs(it->first - t) < std::abs(best->first - t)) best = it;
  }
  return best->second;
}

class LaserRealLogs final : public MonteCarloExperiment<Setup> {
 public:
  std::string name() const override { return "laser/real_logs"; }
  std::string description() const override {
    return "Scan-to-previous-scan matching on the Freiburg logs (ACES, Intel, MIT CSAIL): "
           "relative-pose error of each matcher + chapter-6 least squares against the "
           ".relations, beside raw odometry";
  }
  nlohmann::json default_config() const override {
    return {{"runs", 1},  // not Monte-Carlo: one task per dataset
            {"datasets", {"aces", "intel", "mit_csail"}},
            {"matchers", {"eap", "split_and_merge", "agglomerative", "rwht"}},
            {"matcher_options", default_matcher_options()},
            {"max_relation_dt_s", 30.0},
            {"max_relations", 0}};  // 0 = all
  }
  Setup setup(const nlohmann::json& config, const McPlan& plan) const override {
    Setup s;
    s.datasets = config.at("datasets").get<std::vector<std::string>>();
    s.matchers = config.at("matchers").get<std::vector<std::string>>();
    s.matcher_options = config.at("matcher_options");
    make_matchers(s.matchers, s.matcher_options, nullptr);
    s.max_dt = config.at("max_relation_dt_s").get<double>();
    s.max_relations = config.at("max_relations").get<std::size_t>();
    for (const auto& d : s.datasets) {
      if (!find_dataset(d)) throw UsageError(name() + ": unknown dataset \"" + d + "\"");
    }
    s.configuration = config;
    (void)plan;
    return s;
  }
  int tasks(const Setup& s, const McPlan&) const override {
    return static_cast<int>(s.datasets.size());
  }

  nlohmann::json run_task(const Setup& s, const McPlan& plan, int task) const override {
    Record rec;
    const DatasetEntry& entry = *find_dataset(s.datasets[static_cast<std::size_t>(task)]);
    const std::string path = (plan.data_root / entry.path).string();
    const std::string file = path.substr(0, path.find('#'));
    rec.path = path;
    if (!std::filesystem::exists(file)) {
      rec.status = "skipped";
      rec.reason = "dataset not found at " + path + " (set LOCBENCH_DATA)";
      return rec;
    }
    Log log;
    try {
      log = load_catalog_dataset(entry, plan.data_root);
    } catch (const InputError& e) {
      rec.status = "failed";
      rec.reason = e.what();
      return rec;
    }
    rec.checksum = reports::file_checksum(file);
    rec.records = log.record_count();
    const auto [t0, t1] = log.time_span();
    rec.duration = t1 - t0;
    const Trajectory odom = odometry_trajectory(log);
    std::map<double, std::size_t> scan_at;
    for (std::size_t i = 0; i < log.laser.size(); ++i) scan_at[log.laser[i].scan.timestamp] = i;
    const auto matchers = make_matchers(s.matchers, s.matcher_options, nullptr);
    const laser::SplitAndMergeMatcher extractor;
    const std::size_t methods = 1 + matchers.size();
    rec.translation.assign(methods, {});
    rec.rotation.assign(methods, {});
    std::vector<double> fixed(matchers.size(), 0.0);
    for (const Relation& r : log.relations) {
      if (s.max_relations && rec.relations >= s.max_relations) break;
      if (r.t2 - r.t1 > s.max_dt) continue;
      const auto a = scan_near(scan_at, r.t1), b = scan_near(scan_at, r.t2);
      const auto o1 = odom.pose_at(r.t1), o2 = odom.pose_at(r.t2);
      if (!a || !b || !o1 || !o2) continue;
      const Scan& first = log.laser[*a].scan;
      const Scan& second = log.laser[*b].scan;
      const LineMap map = lines_as_map(extractor.extract_lines(first));
      const Pose2 estimate = between(*o1, *o2);
      const auto record_error = [&](std::size_t method, const Pose2& motion) {
        const Pose2 e = between(r.delta, motion);
        rec.translation[method].push_back(std::hypot(e.x, e.y));
        rec.rotation[method].push_back(std::abs(e.theta));
      };
      record_error(0, estimate);
      for (std::size_t m = 0; m < matchers.size(); ++m) {
        Pose2 motion = estimate;
        if (!map.segments.empty()) {
          const laser::MatchResult match = matchers[m]->match(second, map, estimate);
          const auto c = pose_correction::correct_pose(match.matches, map, estimate, second.sensor_pose);
          motion = c.corrected;
          if (c.position_fixed) fixed[m] += 1.0;
        }
        record_error(1 + m, motion);
      }
      ++rec.relations;
    }
    for (double& f : fixed) f = rec.relations ? f / static_cast<double>(rec.relations) : 0.0;
    rec.position_fixed = fixed;
    rec.status = rec.relations ? "ok" : "failed";
    if (!rec.relations) rec.reason = "no relation pairs two scans inside the odometry's span";
    return rec;
  }

  reports::ExperimentResults summarise(const Setup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    (void)plan;
    reports::ExperimentResults out;
    out.experiment = name();
    out.description = description();
    out.configuration = s.configuration;
    for (std::size_t d = 0; d < records.size(); ++d) {
      const Record r = records[d].get<Record>();
      const std::string& ds = s.datasets[d];
      if (r.status != "ok") {
        out.cases.push_back({"laser/" + ds, r.status, r.reason});
        continue;
      }
      out.datasets.push_back({ds, r.path, r.checksum, r.records, r.duration});
      std::string line = fmt::format("{} ({} relations): odometry {:.1f} mm / {:.2f}°", ds,
                                     r.relations, 1e3 * mean(r.translation[0]),
                                     to_deg(mean(r.rotation[0])));
      for (std::size_t m = 0; m <= s.matchers.size(); ++m) {
        const std::string method = m == 0 ? "odometry_raw" : s.matchers[m - 1] + "_ch6_ls";
        out.results.push_back(reports::make_metric(method, ds, "rpe_translation", "m",
                                                   "freiburg_relations", r.translation[m], false));
        out.results.push_back(reports::make_metric(method, ds, "rpe_rotation", "rad",
                                                   "freiburg_relations", r.rotation[m], false));
        if (m > 0) {
          line += fmt::format("; {} {:.1f} mm / {:.2f}° (position fixed in {:.0f}%)",
                              s.matchers[m - 1], 1e3 * mean(r.translation[m]),
                              to_deg(mean(r.rotation[m])), 100.0 * r.position_fixed[m - 1]);
        }
      }
      out.notes.push_back(line + " (mean errors).");
    }
    out.notes.push_back(
        "The map of each pair is the split-and-merge lines of the first scan (one extractor for "
        "all matchers, so that only the matching differs); the estimate is the odometry's "
        "relative motion; corrections are one pass of chapter 6 (weighted-LS heading, "
        "point-to-point position; heading-only when the matched lines are parallel).");
    return out;
  }
};

}  // namespace

std::unique_ptr<Experiment> make_laser_real_logs() { return std::make_unique<LaserRealLogs>(); }

}  // namespace locbench::experiments
