// Experiment laser/table_6_2: the d_limit sweep 50…400 mm at the thesis's pose, estimate
// (2100, 1100, 43°): matched segments, heading and position error after correction (Table 6.2),
// with EAP's two additions and with the thesis's acceptance rules alone. The set-up is shared
// with Tables 6.1, 6.3 and 6.4: harness/thesis_pose_tables.h.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/statistics.h"
#include "datasets/sim/worlds.h"
#include "experiment_framework/registry.h"
#include "pipelines/thesis_pose_tables.h"

namespace locbench::experiments::thesis_pose::laser_table_6_2 {

const ExperimentInfo kInfo{.name = "laser/table_6_2",
                           .description =
                               "The d_limit sweep 50…400 mm at the thesis pose, estimate (2100, 1100, 43°): matched "
                               "segments, heading and position error after correction (Table 6.2)"};

struct Row62 {
  int d_limit_mm;
  double segments, eo2;
  std::optional<double> ep2;
};
const Row62 kTable62[] = {{50, 2, -0.13, {}},      {75, 3, 0.09, {}},        {100, 3, 0.01, {}},
                          {125, 3, -0.19, {}},     {150, 5, 0.07, 54.34},    {175, 5, -0.01, 56.61},
                          {200, 6, 0.20, 70.13},   {225, 7, -1.20, 33.70},   {250, 8, -1.26, 39.46},
                          {275, 8, -1.54, 62.75},  {300, 10, -2.32, 62.30},  {325, 10, -2.18, 50.37},
                          {350, 10, -2.16, 40.26}, {375, 11, -4.22, 208.66}, {400, 12, -4.68, 212.80}};
constexpr std::size_t kRows62 = std::size(kTable62);

class Table62 final : public ThesisTableExperiment {
 public:
  using ThesisTableExperiment::ThesisTableExperiment;
  std::vector<double> row_values(const Setup& s, const Scan& scan, const LineMap& room) const override {
    const Pose2 est(2.1, 1.1, deg(43.0));
    std::vector<double> r;
    for (const Row62& row : kTable62) {
      laser::EapOptions o = s.eap;
      o.d_limit = mm(row.d_limit_mm);
      const Outcome c = correct_from(scan, room, est, o, pose_correction::PositionMethod::kPointToPoint);
      // The thesis's acceptance rules alone (no direction check, no trimming).
      laser::EapOptions t = o;
      t.max_direction_error = 0.0;
      t.trim_distance = 0.0;
      const Outcome u = correct_from(scan, room, est, t, pose_correction::PositionMethod::kPointToPoint);
      r.insert(r.end(), {c.matched_segments, c.heading_error_deg, c.position_error_mm, u.matched_segments,
                         u.heading_error_deg, u.position_error_mm});
    }
    return r;
  }
  void tabulate(const std::vector<Record>& recs, reports::ExperimentResults& out) const override {
    reports::PublishedComparison seg, eo, ep;
    seg.source = eo.source = ep.source = "thesis Table 6.2";
    seg.quantity = "matched segments by d_limit (mean over runs)";
    eo.quantity = "heading error after correction E_o² by d_limit (mean over runs)";
    ep.quantity =
        "position error after correction E_p² by d_limit (mean over the runs where the "
        "position was fixed; the thesis's × = not fixed)";
    seg.unit = "";
    eo.unit = "deg";
    ep.unit = "mm";
    std::vector<double> thesis_rules_heading;
    for (std::size_t i = 0; i < kRows62; ++i) {
      const Row62& row = kTable62[i];
      const std::string ds = fmt::format("room_dlimit_{}mm", row.d_limit_mm);
      const std::string label = fmt::format("d_limit = {} mm", row.d_limit_mm);
      add(out, "eap", ds, "matched_segments", "", column(recs, 6, i, 0), "stable");
      add(out, "eap_weighted_ls", ds, "heading_error_after", "deg", column(recs, 6, i, 1), "closer_to_zero");
      add(out, "eap_point_to_point", ds, "position_error_after", "mm", column(recs, 6, i, 2));
      add(out, "eap_thesis_rules", ds, "matched_segments", "", column(recs, 6, i, 3), "stable");
      add(out, "eap_thesis_rules_weighted_ls", ds, "heading_error_after", "deg", column(recs, 6, i, 4),
          "closer_to_zero");
      add(out, "eap_thesis_rules_point_to_point", ds, "position_error_after", "mm", column(recs, 6, i, 5));
      thesis_rules_heading.push_back(std::abs(finite_mean(column(recs, 6, i, 4)).first));
      seg.rows.push_back({label, row.segments, finite_mean(column(recs, 6, i, 0)).first});
      eo.rows.push_back({label, row.eo2, finite_mean(column(recs, 6, i, 1)).first});
      const auto [ep_mean, fixed] = finite_mean(column(recs, 6, i, 2));
      ep.rows.push_back({fmt::format("{} (fixed in {}/{} runs)", label, fixed, recs.size()), row.ep2,
                         fixed ? std::optional<double>(ep_mean) : std::nullopt});
    }
    const std::string why =
        "Our room's obstacle placement is a reconstruction, so which segments fall inside a "
        "given d_limit differs from the thesis's; the trend is the point: too small a d_limit "
        "loses segments (3° of heading error moves a point at 4 m by 0.21 m), too large a one "
        "admits points of neighbouring walls.";
    seg.note = eo.note = ep.note = why;
    seg.claim = "the number of matched segments grows from 2 to 10 as d_limit grows from 50 to 400 mm";
    eo.claim = "the heading error after correction stays within ±0.2° up to d_limit = 200 mm, then grows to −2°";
    ep.claim = "the position is fixed from d_limit = 150 mm, with 34–70 mm of error left";
    seg.tolerance = 1.0;
    seg.tolerance_basis = "one segment";
    eo.tolerance = 0.2;
    eo.tolerance_basis = "0.2°: the spread of the thesis's own rows below d_limit = 200 mm";
    ep.tolerance = 10.0;
    ep.tolerance_basis = "10 mm: two standard deviations of the LMS 200 range noise (σ = 5 mm)";
    out.published.push_back(std::move(seg));
    out.published.push_back(std::move(eo));
    out.published.push_back(std::move(ep));
    out.notes.push_back(fmt::format(
        "Our columns use EAP with its two additions (direction check, trimming; "
        "algorithms/laser/eap_matcher.h). With the thesis's acceptance rules alone the mean "
        "|E_o²| over the sweep is {:.2f}° (worst {:.2f}°), because a 3° heading error carries "
        "a neighbouring face's points into a short segment's band and the weighted LS takes "
        "their −87° or −18° as evidence (results eap_thesis_rules_*).",
        mean(thesis_rules_heading), *std::max_element(thesis_rules_heading.begin(), thesis_rules_heading.end())));
  }
};

const Registration<Table62> laser_table_6_2_registration(kInfo);

}  // namespace locbench::experiments::thesis_pose::laser_table_6_2
