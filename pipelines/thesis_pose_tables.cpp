#include "pipelines/thesis_pose_tables.h"

#include <fmt/format.h>

#include <cmath>

#include "core/checksum.h"
#include "datasets/sim/laser_model.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/worlds.h"

namespace locbench::experiments::thesis_pose {

Scan thesis_scan(std::uint64_t seed, const LineMap& room) {
  const sim::Scenario s = sim::preset("room_laser");
  sim::LaserModel laser(s.laser, room, Rng(seed));
  return laser.measure(kThesisPose, 0.0);
}

Outcome correct_from(const Scan& scan, const LineMap& room, const Pose2& estimate, const laser::EapOptions& eap,
                     pose_correction::PositionMethod method) {
  const laser::EapMatcher matcher(eap);
  const laser::MatchResult m = matcher.match(scan, room, estimate);
  pose_correction::PoseCorrectionOptions o;
  o.position.method = method;
  const pose_correction::PoseCorrection c =
      pose_correction::correct_pose(m.matches, room, estimate, scan.sensor_pose, o);
  Outcome out;
  out.matched_segments = static_cast<double>(m.matches.size());
  out.heading_error_deg = to_deg(angle_diff(c.corrected.theta, kThesisPose.theta));
  out.position_error_mm =
      c.position_fixed ? to_mm(std::hypot(c.corrected.x - kThesisPose.x, c.corrected.y - kThesisPose.y)) : std::nan("");
  return out;
}

double e_p1_mm(const Pose2& estimate) {
  return to_mm(std::hypot(estimate.x - kThesisPose.x, estimate.y - kThesisPose.y));
}

std::pair<double, std::size_t> finite_mean(const std::vector<double>& v) {
  double s = 0.0;
  std::size_t n = 0;
  for (double x : v) {
    if (std::isfinite(x)) {
      s += x;
      ++n;
    }
  }
  return {n ? s / static_cast<double>(n) : std::nan(""), n};
}

Setup ThesisTableExperiment::setup(const TableOptions& o, const McPlan& plan) const {
  return {o.eap, recorded(o, plan)};
}

nlohmann::json ThesisTableExperiment::run_task(const Setup& s, const McPlan& plan, int k) const {
  const LineMap room = sim::room_world();
  return Record{row_values(s, thesis_scan(plan.run_seed(k), room), room)};
}

reports::ExperimentResults ThesisTableExperiment::summarise(const Setup& s, const McPlan& plan,
                                                            const std::vector<nlohmann::json>& records) const {
  const auto recs = records_of(records);
  reports::ExperimentResults out = start(s, plan, recs.size());
  tabulate(recs, out);
  return out;
}

reports::ExperimentResults ThesisTableExperiment::start(const Setup& s, const McPlan& plan, std::size_t runs) const {
  reports::ExperimentResults out = start_results(s.configuration);
  for (std::size_t k = 0; k < runs; ++k) out.seeds.push_back(plan.run_seed(static_cast<int>(k)));
  out.datasets.push_back(
      {"sim/room_laser", "simulated", text_checksum(sim::to_json(sim::preset("room_laser")).dump()), runs, 0.0});
  return out;
}

std::vector<double> ThesisTableExperiment::column(const std::vector<Record>& recs, std::size_t width, std::size_t row,
                                                  std::size_t col) {
  std::vector<double> v;
  for (const Record& r : recs) v.push_back(r.values[row * width + col]);
  return v;
}

std::vector<Record> ThesisTableExperiment::records_of(const std::vector<nlohmann::json>& j) {
  std::vector<Record> r;
  for (const auto& x : j) r.push_back(x.get<Record>());
  return r;
}

std::vector<reports::PublishedComparison> ThesisTableExperiment::thesis_tables(
    const std::string& source, const std::string& unit, const std::vector<std::string>& quantities) {
  std::vector<reports::PublishedComparison> tables(quantities.size());
  for (std::size_t i = 0; i < quantities.size(); ++i) {
    tables[i].source = source;
    tables[i].quantity = quantities[i];
    tables[i].unit = unit;
  }
  return tables;
}

void ThesisTableExperiment::publish(reports::ExperimentResults& out, std::vector<reports::PublishedComparison> tables,
                                    const std::string& note, double tolerance, const std::string& tolerance_basis) {
  for (reports::PublishedComparison& t : tables) {
    t.note = note;
    t.tolerance = tolerance;
    t.tolerance_basis = tolerance_basis;
    out.published.push_back(std::move(t));
  }
}

void ThesisTableExperiment::add(reports::ExperimentResults& out, const std::string& method, const std::string& ds,
                                const std::string& variant, const std::string& unit, std::vector<double> v,
                                const char* better) {
  std::vector<double> f;
  for (double x : v) {
    if (std::isfinite(x)) f.push_back(x);
  }
  if (f.empty()) return;
  reports::MetricResult m = reports::make_metric(method, ds, variant, unit, "monte_carlo_runs", f);
  m.better = better;
  if (f.size() < v.size()) {
    m.note = fmt::format("position fixed in {} of {} runs", f.size(), v.size());
  }
  out.results.push_back(std::move(m));
}

}  // namespace locbench::experiments::thesis_pose
