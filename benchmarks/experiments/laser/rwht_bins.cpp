// Experiment laser/rwht_bins: the Range Weighted Hough Transform's accuracy–cost trade-off
// across its angle and range bin sizes, as the thesis argues (§1.2.1.4). Per Monte-Carlo run one
// LMS 200 scan of the 8 m room from the thesis pose (σ = 5 mm, no systematic offset, so only
// the bins and the noise act), extracted map-free in the sensor frame for every bin pair. Each
// extracted line is paired with the map segment most of its points really hit (the simulator's
// per-beam truth) and compared with that segment's true line in the sensor frame: the peak
// cell's centre (the bins' own accuracy) and the least-squares refit. Cost: accumulator cells
// and work (votes + cells + point–line tests); time is measured by locbench_speed.
#include <fmt/format.h>

#include <cmath>
#include <map>

#include "baselines/laser/rwht.h"
#include "core/checksum.h"
#include "core/statistics.h"
#include "core/units.h"
#include "datasets/sim/laser_model.h"
#include "datasets/sim/worlds.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/registry.h"
#include "pipelines/laser_scan_truth.h"

namespace locbench::experiments::laser_rwht_bins {

const ExperimentInfo kInfo{
    .name = "laser/rwht_bins",
    .description =
        "RWHT accuracy against cost across angle and range bin sizes (room, thesis pose): "
        "peak-cell and refitted line errors, segments found, accumulator cells, work",
    .reading = {"The thesis's claim holds for the Hough estimate itself (the peak cell's line is off by "
                "about half a bin), but after the least-squares refit of each peak's points the line "
                "errors no longer depend on the bins, as long as a peak still gathers the wall's points: "
                "the bins then set only the cost (cells grow as 1/(Δα·Δr)) and, when too coarse, which "
                "walls are found."}};

const Pose2 kPose(2.0, 1.0, deg(46.0));
constexpr int kValues = 7;  // per bin pair: peak |Δρ|, |Δβ|, refit |Δρ|, |Δβ|, recall, cells, work
const char* const kNames[kValues] = {
    "peak_rho_error", "peak_beta_error", "refit_rho_error", "refit_beta_error", "segment_recall", "cells", "work"};
const char* const kUnits[kValues] = {"m", "rad", "m", "rad", "", "", ""};
const char* const kBetter[kValues] = {"lower", "lower", "lower", "lower", "higher", "lower", "lower"};

struct Options {
  int runs = 5;
  std::vector<double> angle_bins_deg = {0.25, 0.5, 1.0, 2.0, 4.0};
  std::vector<double> range_bins_cm = {1.25, 2.5, 5.0, 10.0, 20.0};
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs");
  v.field("angle_bins_deg", o.angle_bins_deg, "deg", positive(), "the accumulator's angle bins");
  v.field("range_bins_cm", o.range_bins_cm, "cm", positive(), "the accumulator's range bins");
}

struct Setup {
  std::vector<double> angle_bins;  // [rad]
  std::vector<double> range_bins;  // [m]
  nlohmann::json configuration;
};
struct Record {
  std::vector<double> values;  // [angle][range][kValues], NaN when no line was paired
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Record, values)

// (ρ, β) difference of two lines, either normal direction.
std::pair<double, double> line_difference(const LineParams& a, const LineParams& b) {
  double db = std::abs(angle_diff(a.beta, b.beta));
  double dr = std::abs(a.rho - b.rho);
  const double db2 = std::abs(angle_diff(a.beta + kPi, b.beta));
  if (db2 < db) {
    db = db2;
    dr = std::abs(-a.rho - b.rho);
  }
  return {dr, db};
}

class LaserRwhtBins final : public MonteCarloExperiment<Options, Setup> {
 public:
  Setup setup(const Options& o, const McPlan& plan) const override {
    Setup s;
    for (double a : o.angle_bins_deg) s.angle_bins.push_back(deg(a));
    for (double r : o.range_bins_cm) s.range_bins.push_back(r / 100.0);
    if (s.angle_bins.empty() || s.range_bins.empty()) {
      throw UsageError(name() + ": angle_bins_deg and range_bins_cm must not be empty");
    }
    s.configuration = recorded(o, plan);
    return s;
  }

  nlohmann::json run_task(const Setup& s, const McPlan& plan, int k) const override {
    const LineMap room = sim::room_world();
    sim::LaserConfig lc;
    lc.timing.enabled = true;
    lc.noise = mm(5.0);
    sim::LaserModel laser(lc, room, Rng(plan.run_seed(k)));
    const sim::LabelledScan scan = laser.measure_labelled(kPose, 0.0);
    const auto points = laser::scan_points(scan.scan, Pose2());
    const Pose2 to_sensor = kPose.inverse();
    Record rec;
    for (double ab : s.angle_bins) {
      for (double rb : s.range_bins) {
        baselines::laser::RwhtOptions o;
        o.angle_bin = ab;
        o.range_bin = rb;
        const baselines::laser::RwhtExtraction x =
            baselines::laser::rwht_lines(points, baselines::laser::LineFrame::robot, o);
        std::vector<double> pr, pb, fr, fb;
        std::vector<bool> found(room.segments.size(), false);
        for (std::size_t i = 0; i < x.extraction.lines.size(); ++i) {
          const auto& line = x.extraction.lines[i];
          std::map<int, int> votes;
          for (const auto& p : line.points) ++votes[scan.segment[p.beam]];
          int best = -1, count = 0;
          for (const auto& [seg, c] : votes) {
            if (seg >= 0 && c > count) {
              best = seg;
              count = c;
            }
          }
          if (best < 0 || 2 * count <= static_cast<int>(line.points.size())) continue;
          const Segment& m = room.segments[static_cast<std::size_t>(best)];
          const LineParams truth = Segment{to_sensor * m.p1, to_sensor * m.p2}.line();
          const auto [dr1, db1] = line_difference(x.peaks[x.line_peak[i]].cell, truth);
          const auto [dr2, db2] = line_difference(line.fit.line, truth);
          pr.push_back(dr1);
          pb.push_back(db1);
          fr.push_back(dr2);
          fb.push_back(db2);
          found[static_cast<std::size_t>(best)] = true;
        }
        laser::MatchResult as_matches;  // reuse the detectability rule of the other experiments
        const MatchScore score = score_match(as_matches, room, scan.segment, scan.scan, kPose);
        std::size_t detected = 0;
        for (bool f : found) detected += f;
        const double recall = score.detectable ? static_cast<double>(detected) / score.detectable : 1.0;
        const auto avg = [](const std::vector<double>& v) { return v.empty() ? std::nan("") : mean(v); };
        rec.values.insert(rec.values.end(), {avg(pr), avg(pb), avg(fr), avg(fb), recall, static_cast<double>(x.cells),
                                             static_cast<double>(x.extraction.work)});
      }
    }
    return rec;
  }

  reports::ExperimentResults summarise(const Setup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(s.configuration);
    std::vector<Record> recs;
    for (std::size_t k = 0; k < records.size(); ++k) {
      out.seeds.push_back(plan.run_seed(static_cast<int>(k)));
      recs.push_back(records[k].get<Record>());
    }
    out.datasets.push_back({"sim/room", "simulated", text_checksum("room_world"), records.size(), 0.0});
    std::size_t at = 0;
    std::string line = "Mean over runs (peak cell → refit, |Δρ| mm / |Δβ|°; cells):";
    for (double ab : s.angle_bins) {
      for (double rb : s.range_bins) {
        const std::string ds = reports::key_part(fmt::format("room_a{}deg_r{}cm", to_deg(ab), 100 * rb));
        double m[kValues];
        for (int q = 0; q < kValues; ++q, ++at) {
          std::vector<double> v;
          for (const Record& r : recs) {
            if (std::isfinite(r.values[at])) v.push_back(r.values[at]);
          }
          m[q] = v.empty() ? std::nan("") : mean(v);
          if (v.empty()) continue;
          reports::MetricResult metric = reports::make_metric("rwht", ds, kNames[q], kUnits[q], "monte_carlo_runs", v);
          metric.better = kBetter[q];
          out.results.push_back(std::move(metric));
        }
        line += fmt::format(" {}°×{} cm: {:.1f}/{:.2f} → {:.1f}/{:.2f}, {:.0f};", to_deg(ab), 100 * rb, to_mm(m[0]),
                            to_deg(m[1]), to_mm(m[2]), to_deg(m[3]), m[5]);
      }
    }
    out.notes.push_back(line);
    return out;
  }
};

const Registration<LaserRwhtBins> laser_rwht_bins_registration(kInfo);

}  // namespace locbench::experiments::laser_rwht_bins
