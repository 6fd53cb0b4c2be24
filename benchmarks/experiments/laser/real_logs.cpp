// Experiment laser/real_logs: scan-pair correction on real SICK scans (Freiburg logs: ACES,
// Intel, MIT CSAIL, or any user's log with relations) against the hand-checked `.relations`.
// For every relation (t1, t2) — both stamps are scan stamps — each corrector (laser_correctors.h)
// registers the scan at t2 to the scan at t1 from the odometry's relative motion: the thesis's
// matchers with one pass of chapter 6 (the map being the split-and-merge lines of the first
// scan), EAP with an iterated joint point-to-line solve, PL-ICP and a plain point-to-point ICP.
// The relative-pose error of each corrected motion is reported beside raw odometry's on the same
// relations, with per-relation diagnostics (lines, matched points, position fixed) summarised
// in the notes: what the one-shot chapter-6 solve does wrong and where.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "baselines/laser/extract_then_match.h"
#include "core/errors.h"
#include "core/statistics.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/parallel_tasks.h"
#include "experiment_framework/plot_series.h"
#include "experiment_framework/registry.h"
#include "pipelines/laser_correctors.h"
#include "pipelines/real_log_harness.h"
#include "pipelines/real_scan_pairs.h"
#include "pipelines/relation_drawing.h"

namespace locbench::experiments::laser_real_logs {

const ExperimentInfo kInfo{
    .name = "laser/real_logs",
    .description =
        "Scan-to-previous-scan correction on real logs (Freiburg ACES, Intel, MIT CSAIL, or "
        "--log/--relations): relative-pose error of the thesis's matchers + chapter-6 least "
        "squares, EAP + iterated point-to-line, PL-ICP and point-to-point ICP against the "
        ".relations, beside raw odometry",
    .reading = {"The map of each pair for the *_ch6_ls and eap_* correctors is the split-and-merge lines "
                "of the first scan (one extractor for all matchers, so that only the matching differs); "
                "pl_icp and icp_point_to_point use the first scan's points. Every corrector starts from "
                "the odometry's relative motion. *_ch6_ls = one pass of chapter 6 (weighted-LS heading, "
                "point-to-point position; heading-only when the matched lines are parallel)."}};

struct Options {
  int runs = 1;  // not Monte-Carlo: one task per dataset
  nlohmann::json datasets = freiburg_logs();
  std::vector<std::string> matchers = {"eap", "split_and_merge", "agglomerative", "rwht"};
  std::vector<std::string> correctors = {
      "eap_ch6_rematched", "eap_ch6_heading_only", "eap_ch6_inverse_variance", "eap_iterated_pl", "pl_icp",
      "icp_point_to_point"};
  nlohmann::json corrector_options = default_corrector_options();
  std::string beam_angles = "log";
  nlohmann::json laser_mount = nullptr;
  double max_relation_dt_s = 30.0;
  std::size_t max_relations = 0;
  std::size_t draw_worst = 3;
  bool per_relation_values = true;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "unused: one task per dataset");
  v.field("datasets", o.datasets, "", Range{}, "catalog names or user files (real_log_harness.h)");
  v.field("matchers", o.matchers, "", Range{}, "matchers, each + chapter-6 least squares");
  v.field("correctors", o.correctors, "", Range{}, "further correctors (make_correctors)");
  v.field("corrector_options", o.corrector_options, "", Range{}, "each corrector's options");
  v.field("beam_angles", o.beam_angles, "", Range{}, "\"log\" or \"bag\"");
  v.field("laser_mount", o.laser_mount, "", Range{},
          "[x m, y m, θ rad] of the laser in the robot frame; null = the log's");
  v.field("max_relation_dt_s", o.max_relation_dt_s, "s", positive(), "longest relation evaluated");
  v.field("max_relations", o.max_relations, "", Range{}, "relations per log (0 = all)");
  v.field("draw_worst", o.draw_worst, "", Range{}, "relations drawn in the report, per log");
  v.flag("per_relation_values", o.per_relation_values,
         "each relation's error in the report (the rpe metrics' values), for checks by others");
}

struct Setup {
  std::vector<RealLogSpec> datasets;
  std::vector<std::string> methods;  // correctors, in order (odometry_raw is added first)
  // Made once per run and shared by every task: correct() is const and keeps no state.
  std::vector<std::unique_ptr<ScanPairCorrector>> correctors;
  nlohmann::json corrector_options;
  std::string beam_angles;
  std::optional<Pose2> laser_mount;  // overrides every scan's sensor_pose when set
  double max_dt = 0.0;
  std::size_t max_relations = 0;
  std::size_t draw_worst = 0;
  bool per_relation_values = true;
  nlohmann::json configuration;
};

struct Record {
  std::string status;  // "ok", "skipped", "failed"
  std::string reason;
  std::string path, checksum;  // the dataset read (reports::DatasetRef)
  std::size_t records = 0;
  double duration = 0.0;
  std::size_t relations = 0;
  // Per relation: t1, t2 and the number of lines split-and-merge found in the first scan.
  std::vector<double> t1, t2, lines;
  // [method][relation]; method 0 = odometry. Translation [m] and rotation [rad] errors, whether
  // the position was fixed (1/0), matched points.
  std::vector<std::vector<double>> translation, rotation, position_fixed, matched_points;
  // [method][relation]: |motion translation| − |reference translation| [m] (scale along the
  // path), and how far the corrector moved the odometry's translation [m].
  std::vector<std::vector<double>> length_error, moved;
  // [method][relation]: chapter-6 diagnostics (ScanPairCorrection; −1 = not applicable).
  std::vector<std::vector<double>> information_ratio, heading_spread;
  std::vector<double> reference_length;  // per relation [m]
  // The draw_worst relations with the largest eap_ch6_ls translation error (indices), drawn.
  std::vector<std::size_t> drawn_index;
  std::vector<DrawnRelation> drawn;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Record, status, reason, path, checksum, records, duration, relations, t1, t2, lines,
                                   translation, rotation, position_fixed, matched_points, length_error, moved,
                                   information_ratio, heading_spread, reference_length, drawn_index, drawn)

std::string interval(std::span<const double> v, double scale, int digits) {
  if (v.empty()) return "none";
  const Summary s = summarize(v);
  return fmt::format("{:.{}f} [{:.{}f}, {:.{}f}]", scale * s.mean, digits, scale * s.ci95_low, digits,
                     scale * s.ci95_high, digits);
}

std::vector<double> subset(const std::vector<double>& v, const std::vector<bool>& keep) {
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (keep[i]) out.push_back(v[i]);
  }
  return out;
}

// Diagnosis thresholds (reported, not used by any corrector).
constexpr double kWeakPosition = 0.02;
constexpr double kHeadingSpread = 0.0349066;  // 2°

class LaserRealLogs final : public MonteCarloExperiment<Options, Setup> {
 public:
  Setup setup(const Options& o, const McPlan&) const override {
    Setup s;
    s.datasets = real_log_specs(o.datasets, name());
    for (const auto& m : o.matchers) s.methods.push_back(m + "_ch6_ls");
    for (const auto& c : o.correctors) s.methods.push_back(c);
    s.corrector_options = o.corrector_options;
    s.correctors = make_correctors(s.methods, s.corrector_options);  // validates names and options
    s.beam_angles = o.beam_angles;
    if (s.beam_angles != "log" && s.beam_angles != "bag") {
      throw UsageError(name() + ": beam_angles: expected \"log\" or \"bag\", found \"" + s.beam_angles + "\"");
    }
    if (const auto& m = o.laser_mount; !m.is_null()) {
      if (!m.is_array() || m.size() != 3 || !m[0].is_number() || !m[1].is_number() || !m[2].is_number()) {
        throw UsageError(name() + ": laser_mount: expected [x, y, theta] or null");
      }
      s.laser_mount = Pose2(m[0].get<double>(), m[1].get<double>(), m[2].get<double>());
    }
    s.max_dt = o.max_relation_dt_s;
    s.max_relations = o.max_relations;
    s.draw_worst = o.draw_worst;
    s.per_relation_values = o.per_relation_values;
    s.configuration = options_json(o);
    return s;
  }
  int tasks(const Setup& s, const McPlan&) const override { return static_cast<int>(s.datasets.size()); }

  nlohmann::json run_task(const Setup& s, const McPlan& plan, int task) const override {
    Record rec;
    LoadedRealLog loaded = load_real_log(s.datasets[static_cast<std::size_t>(task)], plan.data_root);
    record_load(loaded, rec);
    rec.duration = loaded.dataset.duration_s;
    if (loaded.status != "ok") return rec;
    Log& log = loaded.log;
    apply_beam_angles(log, s.beam_angles);
    if (s.laser_mount) {
      for (auto& l : log.laser) l.scan.sensor_pose = *s.laser_mount;
    }
    const auto& correctors = s.correctors;
    const baselines::laser::SplitAndMergeMatcher extractor;
    const std::size_t methods = 1 + correctors.size();
    rec.translation.assign(methods, {});
    rec.rotation.assign(methods, {});
    rec.position_fixed.assign(methods, {});
    rec.matched_points.assign(methods, {});
    rec.length_error.assign(methods, {});
    rec.moved.assign(methods, {});
    rec.information_ratio.assign(methods, {});
    rec.heading_spread.assign(methods, {});
    // Every pair is recorded; the worst ones are drawn afterwards.
    const std::vector<RelationScanPair> pairs = relation_scan_pairs(log, s.max_dt, s.max_relations);
    // The pairs are independent: corrected on the run's threads, recorded in order (the same
    // report for any number of threads).
    struct PairCorrections {
      std::size_t lines = 0;  // split-and-merge's lines in the first scan
      std::vector<ScanPairCorrection> by_corrector;
    };
    std::vector<PairCorrections> corrected(pairs.size());
    parallel_tasks(plan.threads, pairs.size(), [&](std::size_t i) {
      const RelationScanPair& p = pairs[i];
      const Scan& first = log.laser[p.first].scan;
      const LineMap map = lines_as_map(extractor.extract_lines(first));
      corrected[i].lines = map.segments.size();
      for (const auto& c : correctors) {
        corrected[i].by_corrector.push_back(c->correct(first, map, log.laser[p.second].scan, p.odometry));
      }
    });
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const RelationScanPair& p = pairs[i];
      const Relation& r = log.relations[p.relation];
      const Pose2 estimate = p.odometry;
      const auto record = [&](std::size_t method, const ScanPairCorrection& c) {
        const Pose2 e = between(r.delta, c.motion);
        rec.translation[method].push_back(std::hypot(e.x, e.y));
        rec.rotation[method].push_back(std::abs(e.theta));
        rec.position_fixed[method].push_back(c.position_fixed ? 1.0 : 0.0);
        rec.matched_points[method].push_back(static_cast<double>(c.matched_points));
        rec.length_error[method].push_back(c.motion.translation().norm() - r.delta.translation().norm());
        const Pose2 moved = between(estimate, c.motion);
        rec.moved[method].push_back(std::hypot(moved.x, moved.y));
        rec.information_ratio[method].push_back(c.position_information_ratio);
        rec.heading_spread[method].push_back(c.heading_spread);
      };
      ScanPairCorrection odometry;
      odometry.motion = estimate;
      record(0, odometry);
      for (std::size_t m = 0; m < correctors.size(); ++m) record(1 + m, corrected[i].by_corrector[m]);
      rec.t1.push_back(r.t1);
      rec.t2.push_back(r.t2);
      rec.lines.push_back(static_cast<double>(corrected[i].lines));
      rec.reference_length.push_back(r.delta.translation().norm());
      ++rec.relations;
    }
    if (rec.relations == 0) {
      rec.status = "failed";
      rec.reason = "no relation pairs two scans inside the odometry's span";
      return rec;
    }
    // The worst relations of the one-shot solve (eap_ch6_ls), or of odometry without it.
    const auto one_shot = std::find(s.methods.begin(), s.methods.end(), "eap_ch6_ls");
    const std::size_t worst_of =
        one_shot == s.methods.end() ? 0 : 1 + static_cast<std::size_t>(one_shot - s.methods.begin());
    std::vector<std::size_t> order(rec.relations);
    std::iota(order.begin(), order.end(), 0);
    const std::size_t k = std::min(s.draw_worst, order.size());
    std::partial_sort(
        order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k), order.end(),
        [&](std::size_t x, std::size_t y) { return rec.translation[worst_of][x] > rec.translation[worst_of][y]; });
    for (std::size_t i = 0; i < k; ++i) {
      const RelationScanPair& p = pairs[order[i]];
      const Scan& first = log.laser[p.first].scan;
      rec.drawn_index.push_back(order[i]);
      rec.drawn.push_back(draw_relation(first, lines_as_map(extractor.extract_lines(first)), log.laser[p.second].scan,
                                        p.odometry, log.relations[p.relation].delta, s.corrector_options));
    }
    return rec;
  }

  reports::ExperimentResults summarise(const Setup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    (void)plan;
    reports::ExperimentResults out = start_results(s.configuration);
    for (std::size_t d = 0; d < records.size(); ++d) {
      const Record r = records[d].get<Record>();
      const std::string& ds = s.datasets[d].name;
      if (r.status != "ok") {
        out.cases.push_back({"laser/" + ds, r.status, r.reason});
        continue;
      }
      out.datasets.push_back({ds, r.path, r.checksum, r.records, r.duration});
      std::string line = fmt::format("{} ({} relations), mean RPE [95% CI], mm / deg:", ds, r.relations);
      for (std::size_t m = 0; m <= s.methods.size(); ++m) {
        const std::string method = m == 0 ? "odometry_raw" : s.methods[m - 1];
        out.results.push_back(reports::make_metric(method, ds, "rpe_translation", "m", "freiburg_relations",
                                                   r.translation[m], s.per_relation_values));
        out.results.push_back(reports::make_metric(method, ds, "rpe_rotation", "rad", "freiburg_relations",
                                                   r.rotation[m], s.per_relation_values));
        line += fmt::format(" {} {} / {}", method, interval(r.translation[m], 1e3, 1),
                            interval(r.rotation[m], to_deg(1.0), 2));
        if (m > 0) {
          line += fmt::format(" (position fixed {:.0f}%)", 100.0 * mean(r.position_fixed[m]));
        }
        line += ";";
      }
      out.notes.push_back(line);
      out.notes.push_back(verdict(s, r, ds, out));
      out.notes.push_back(diagnosis(s, r, ds));
      out.notes.push_back(scale_check(s, r, ds));
      // Error distributions per method (thinned to 200 order statistics each).
      std::vector<std::string> methods{"odometry_raw"};
      methods.insert(methods.end(), s.methods.begin(), s.methods.end());
      for (reports::Plot& p : relative_pose_error_cdfs(ds, "relative-pose", methods, r.translation, r.rotation,
                                                       fmt::format("{} relations", r.relations))) {
        out.plots.push_back(std::move(p));
      }
      for (std::size_t k = 0; k < r.drawn.size(); ++k) {
        for (reports::Plot& p : relation_plots(ds, r, k)) out.plots.push_back(std::move(p));
      }
    }
    return out;
  }

 private:
  // The reference against the two sensors: mean |translation| − |reference translation| (a
  // scale disagreement along the path) and how far each corrector moved the odometry. When wheels
  // and laser agree with each other better than either agrees with the reference, the
  // translation error is the reference's.
  static std::string scale_check(const Setup& s, const Record& r, const std::string& ds) {
    std::string text = fmt::format(
        "{} scale check (reference relations {} mm long on average): mean |motion| − |reference| "
        "[95% CI], mm, and mean translation moved from odometry, mm:",
        ds, interval(r.reference_length, 1e3, 0));
    for (std::size_t m = 0; m <= s.methods.size(); ++m) {
      const std::string method = m == 0 ? "odometry_raw" : s.methods[m - 1];
      text += fmt::format(" {} {} / {:.1f};", method, interval(r.length_error[m], 1e3, 1), 1e3 * mean(r.moved[m]));
    }
    return text;
  }

  // Against raw odometry on the same relations, per corrector: paired differences (corrector −
  // odometry) as metrics, and whether the corrector beats odometry in heading (the 95% intervals
  // of the two means separated) and is no worse in translation (the paired difference's 95%
  // interval reaches 0 or below).
  static std::string verdict(const Setup& s, const Record& r, const std::string& ds, reports::ExperimentResults& out) {
    std::string text = fmt::format(
        "{} against odometry (paired differences over {} relations, mean [95% CI], mm / deg; "
        "heading beaten = the 95% intervals of the means separated; translation better / WORSE = "
        "separated either way, no worse = overlapping and the paired interval reaching ≤ 0):",
        ds, r.relations);
    const Summary ot = summarize(r.translation[0]), orot = summarize(r.rotation[0]);
    for (std::size_t m = 1; m <= s.methods.size(); ++m) {
      std::vector<double> dt(r.relations), dr(r.relations);
      for (std::size_t i = 0; i < r.relations; ++i) {
        dt[i] = r.translation[m][i] - r.translation[0][i];
        dr[i] = r.rotation[m][i] - r.rotation[0][i];
      }
      const std::string& method = s.methods[m - 1];
      out.results.push_back(
          reports::make_metric(method, ds, "rpe_translation_minus_odometry", "m", "freiburg_relations", dt, false));
      out.results.push_back(
          reports::make_metric(method, ds, "rpe_rotation_minus_odometry", "rad", "freiburg_relations", dr, false));
      const Summary t = summarize(r.translation[m]), rot = summarize(r.rotation[m]);
      const Summary pt = summarize(dt);
      const bool heading = rot.ci95_high < orot.ci95_low;
      std::string translation = "no worse";
      if (t.ci95_high < ot.ci95_low) {
        translation = "better";
      } else if (t.ci95_low > ot.ci95_high) {
        translation = "WORSE";
      } else if (pt.ci95_low > 0.0) {
        translation = "worse by the paired interval only (the intervals of the means overlap)";
      }
      text += fmt::format(" {}: Δ {} / {} — heading {}, translation {};", method, interval(dt, 1e3, 1),
                          interval(dr, to_deg(1.0), 2), heading ? "beaten" : "NOT beaten", translation);
    }
    return text;
  }

  // The k-th drawn relation as two "scan_pair" plots: before (odometry + the EAP matches the
  // one-shot solve uses) and after (one-shot, iterated and reference placements).
  static std::vector<reports::Plot> relation_plots(const std::string& ds, const Record& r, std::size_t k) {
    const DrawnRelation& d = r.drawn[k];
    const std::size_t i = r.drawn_index[k];
    const auto plot = [&](const char* stage, std::string title, const std::vector<DrawnSeries>& ss) {
      reports::Plot p;
      p.name = fmt::format("worst_relation_{}_{}_{}", ds, k + 1, stage);
      p.kind = "scan_pair";
      p.title = std::move(title);
      p.x_label = "x (first robot frame)";
      p.x_unit = "m";
      p.y_label = "y";
      p.y_unit = "m";
      for (const DrawnSeries& s : ss) p.series.push_back({s.name, s.x, s.y});
      p.note = fmt::format(
          "{}: relation {:.3f} → {:.3f} s, {:.0f} lines in the first scan, worst "
          "{} of eap_ch6_ls by translation error",
          ds, r.t1[i], r.t2[i], r.lines[i], k + 1);
      return p;
    };
    return {plot("before",
                 fmt::format("{} #{} before: odometry {:.0f} mm / {:.2f}°, {} EAP-matched points", ds, k + 1,
                             1e3 * d.odometry_translation, to_deg(d.odometry_rotation), d.one_shot_points),
                 d.before),
            plot("after",
                 fmt::format("{} #{} after: eap_ch6_ls {:.0f} mm / {:.2f}°, eap_iterated_pl "
                             "{:.0f} mm / {:.2f}°",
                             ds, k + 1, 1e3 * d.one_shot_translation, to_deg(d.one_shot_rotation),
                             1e3 * d.iterated_translation, to_deg(d.iterated_rotation)),
                 d.after)};
  }

  // Where the one-shot chapter-6 correction (eap_ch6_ls) goes wrong, from the per-relation data.
  static std::string diagnosis(const Setup& s, const Record& r, const std::string& ds) {
    const auto index = [&](const std::string& m) -> std::optional<std::size_t> {
      const auto it = std::find(s.methods.begin(), s.methods.end(), m);
      if (it == s.methods.end()) return std::nullopt;
      return 1 + static_cast<std::size_t>(it - s.methods.begin());
    };
    const auto one_shot = index("eap_ch6_ls");
    if (!one_shot) return ds + ": no eap_ch6_ls to diagnose.";
    const std::size_t e = *one_shot;
    std::vector<bool> fixed(r.relations), not_fixed(r.relations);
    for (std::size_t i = 0; i < r.relations; ++i) {
      fixed[i] = r.position_fixed[e][i] > 0.5;
      not_fixed[i] = !fixed[i];
    }
    std::string out = fmt::format(
        "{} diagnosis of eap_ch6_ls: {:.1f} lines in the first scan and {:.0f} matched points per "
        "relation (means); position fixed in {:.0f}% — there its translation error is {} mm "
        "(odometry {} mm on the same relations), heading-only elsewhere: {} mm (odometry {} mm).",
        ds, mean(r.lines), mean(r.matched_points[e]), 100.0 * mean(r.position_fixed[e]),
        interval(subset(r.translation[e], fixed), 1e3, 1), interval(subset(r.translation[0], fixed), 1e3, 1),
        interval(subset(r.translation[e], not_fixed), 1e3, 1), interval(subset(r.translation[0], not_fixed), 1e3, 1));
    // Why: the position fixes whose normal matrix is nearly singular, and the headings whose
    // segments disagree.
    std::vector<bool> weak(r.relations), strong(r.relations), spread(r.relations), agree(r.relations);
    for (std::size_t i = 0; i < r.relations; ++i) {
      const double q = r.information_ratio[e][i];
      weak[i] = q >= 0.0 && q < kWeakPosition;
      strong[i] = q >= kWeakPosition;
      const double h = r.heading_spread[e][i];
      spread[i] = h > kHeadingSpread;
      agree[i] = h >= 0.0 && h <= kHeadingSpread;
    }
    const auto count = [](const std::vector<bool>& v) { return std::count(v.begin(), v.end(), true); };
    out += fmt::format(
        " Position fixes with a nearly singular normal matrix (eigenvalue ratio < {}, the "
        "threshold below which eap_iterated_pl keeps a direction): {} of {} — translation error "
        "{} mm (odometry {} mm); the other {}: {} mm (odometry {} mm). Headings whose matched "
        "segments disagree (weighted spread of Δθ_i > {:.0f}°): {} — heading error {}° (odometry "
        "{}°); the other {}: {}° (odometry {}°).",
        kWeakPosition, count(weak), count(weak) + count(strong), interval(subset(r.translation[e], weak), 1e3, 1),
        interval(subset(r.translation[0], weak), 1e3, 1), count(strong),
        interval(subset(r.translation[e], strong), 1e3, 1), interval(subset(r.translation[0], strong), 1e3, 1),
        to_deg(kHeadingSpread), count(spread), interval(subset(r.rotation[e], spread), to_deg(1.0), 2),
        interval(subset(r.rotation[0], spread), to_deg(1.0), 2), count(agree),
        interval(subset(r.rotation[e], agree), to_deg(1.0), 2), interval(subset(r.rotation[0], agree), to_deg(1.0), 2));
    if (const auto ivw = index("eap_ch6_inverse_variance")) {
      out += fmt::format(
          " The same EAP matches and one pass with the segments' headings weighted by their "
          "inverse variance instead of eq. 6.18 (eap_ch6_inverse_variance): {} mm / {}° against "
          "eap_ch6_ls's {} mm / {}°.",
          interval(r.translation[*ivw], 1e3, 1), interval(r.rotation[*ivw], to_deg(1.0), 2),
          interval(r.translation[e], 1e3, 1), interval(r.rotation[e], to_deg(1.0), 2));
    }
    // The worst relations of the one-shot solve, with the other correctors on them.
    std::vector<std::size_t> order(r.relations);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return r.translation[e][a] > r.translation[e][b]; });
    out +=
        " Worst relations (t1 → t2: lines, matched points, error mm / deg of odometry, "
        "eap_ch6_ls";
    const auto iterated = index("eap_iterated_pl");
    const auto pl = index("pl_icp");
    if (iterated) out += ", eap_iterated_pl";
    if (pl) out += ", pl_icp";
    out += "):";
    for (std::size_t k = 0; k < std::min<std::size_t>(5, order.size()); ++k) {
      const std::size_t i = order[k];
      out += fmt::format(" {:.3f} → {:.3f}: {:.0f}, {:.0f}, {:.0f}/{:.2f}, {:.0f}/{:.2f}", r.t1[i], r.t2[i], r.lines[i],
                         r.matched_points[e][i], 1e3 * r.translation[0][i], to_deg(r.rotation[0][i]),
                         1e3 * r.translation[e][i], to_deg(r.rotation[e][i]));
      for (const auto& m : {iterated, pl}) {
        if (m) out += fmt::format(", {:.0f}/{:.2f}", 1e3 * r.translation[*m][i], to_deg(r.rotation[*m][i]));
      }
      out += ";";
    }
    return out;
  }
};

const Registration<LaserRealLogs> laser_real_logs_registration(kInfo);

}  // namespace locbench::experiments::laser_real_logs
