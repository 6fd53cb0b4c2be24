#pragma once
// Shared by the experiments laser/table_6_1, laser/table_6_2 and laser/tables_6_3_6_4: chapter 6's
// pose correction from EAP-matched segments at the thesis's pose in the 8 m room (§6.3.3,
// §6.4.1, §6.6.1). The robot stands at (2000 mm, 1000 mm, 46°); each Monte-Carlo run draws one
// LMS 200 scan (σ = 5 mm, +15 mm systematic offset: preset room_laser), the EAP matcher matches
// it under the erroneous estimate of the table row, and the heading (weighted LS, eq.
// 6.13–6.20) and position (point-to-line 6.22–6.27 or point-to-point 6.28–6.38) corrections are
// applied. E_o = heading error [deg] and E_p = position error [mm], before (1) and after (2), as
// the thesis defines them. The room's obstacle placement is ours (its figure is lost), so the
// published rows are a reference for the trend, not digit-for-digit targets.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "algorithms/laser/eap_matcher.h"
#include "algorithms/pose_correction/pose_correction.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/scan.h"
#include "core/units.h"
#include "experiment_framework/monte_carlo.h"

namespace locbench::experiments::thesis_pose {

inline const Pose2 kThesisPose(2.0, 1.0, deg(46.0));

// One scan of the room from the thesis pose, run k.
Scan thesis_scan(std::uint64_t seed, const LineMap& room);

struct Outcome {
  double heading_error_deg = 0.0;  // E_o², signed [deg]
  double position_error_mm = 0.0;  // E_p² [mm]; NaN when the position was not fixed
  double matched_segments = 0.0;
};

// EAP match of `scan` under `estimate`, then heading and position correction by `method`.
Outcome correct_from(const Scan& scan, const LineMap& room, const Pose2& estimate, const laser::EapOptions& eap,
                     pose_correction::PositionMethod method);

// E_p¹: the estimate's position error [mm].
double e_p1_mm(const Pose2& estimate);

// The three tables' configuration.
struct TableOptions {
  int runs = 10;
  laser::EapOptions eap;
};
template <class V>
void visit_fields(V& v, TableOptions& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs (one scan each)");
  v.nested("eap", o.eap, "EAP matcher (algorithms/laser/eap_matcher.h)");
}

struct Setup {
  laser::EapOptions eap;
  nlohmann::json configuration;
};
struct Record {
  std::vector<double> values;  // per table row: the row's outcome numbers, flattened
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Record, values)

// Mean of the finite values, and how many there were.
std::pair<double, std::size_t> finite_mean(const std::vector<double>& v);

// Shared shape of the three table experiments.
class ThesisTableExperiment : public MonteCarloExperiment<TableOptions, Setup> {
 public:
  Setup setup(const TableOptions& o, const McPlan& plan) const override;
  // Run k: one scan of the room from the thesis pose, then the table's rows.
  nlohmann::json run_task(const Setup& s, const McPlan& plan, int k) const final;
  reports::ExperimentResults summarise(const Setup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const final;

 protected:
  // One run's numbers, the rows' flattened (Record::values), from its scan of the room.
  virtual std::vector<double> row_values(const Setup& s, const Scan& scan, const LineMap& room) const = 0;
  // The table's metrics, published comparisons and notes from every run's record.
  virtual void tabulate(const std::vector<Record>& recs, reports::ExperimentResults& out) const = 0;
  reports::ExperimentResults start(const Setup& s, const McPlan& plan, std::size_t runs) const;
  // Metric over runs from column `col` of rows of width `width`, row `row`.
  static std::vector<double> column(const std::vector<Record>& recs, std::size_t width, std::size_t row,
                                    std::size_t col);
  static std::vector<Record> records_of(const std::vector<nlohmann::json>& j);
  static void add(reports::ExperimentResults& out, const std::string& method, const std::string& ds,
                  const std::string& variant, const std::string& unit, std::vector<double> v,
                  const char* better = "lower");
  // The thesis's table `source` beside ours: one comparison per quantity, all in `unit`.
  static std::vector<reports::PublishedComparison> thesis_tables(const std::string& source, const std::string& unit,
                                                                 const std::vector<std::string>& quantities);
  // Moves `tables` to out.published, each with the same note, tolerance and tolerance basis.
  static void publish(reports::ExperimentResults& out, std::vector<reports::PublishedComparison> tables,
                      const std::string& note, double tolerance, const std::string& tolerance_basis);
};

}  // namespace locbench::experiments::thesis_pose
