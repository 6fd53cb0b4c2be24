#pragma once
// One relation of laser/real_logs drawn for the report: the evidence behind a correction, in the
// first scan's robot frame [m]. "Before": the first scan's points and split-and-merge lines, the
// second scan placed by the odometry and the EAP matches made there — exactly what the one-shot
// chapter-6 solve (eap_ch6_ls) works from. "After": the same map with the second scan placed by
// eap_ch6_ls, by EAP + iterated point-to-line (with its last matches) and by the relation's
// reference motion. Internal to the experiments.
//
// Series follow the report's "scan_pair" plot kind (reports/report.h): a series whose name ends
// in "lines" or "matches" holds segments as consecutive point pairs; any other holds points.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/line_map.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::experiments {

struct DrawnSeries {
  std::string name;
  std::vector<double> x, y;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DrawnSeries, name, x, y)

struct DrawnRelation {
  std::vector<DrawnSeries> before, after;
  // Relative-pose errors against the reference motion [m], [rad].
  double odometry_translation = 0.0, odometry_rotation = 0.0;
  double one_shot_translation = 0.0, one_shot_rotation = 0.0;
  double iterated_translation = 0.0, iterated_rotation = 0.0;
  std::size_t one_shot_points = 0, iterated_points = 0;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DrawnRelation, before, after, odometry_translation, odometry_rotation,
                                   one_shot_translation, one_shot_rotation, iterated_translation, iterated_rotation,
                                   one_shot_points, iterated_points)

// Draws the relation (first, second) whose odometry motion is `odometry` and reference motion
// `reference`; `first_lines` are the first scan's lines; `corrector_options` as
// laser_correctors.h's default_corrector_options() (its "matcher_options".eap, "ch6" and
// "iterated").
DrawnRelation draw_relation(const Scan& first, const LineMap& first_lines, const Scan& second, const Pose2& odometry,
                            const Pose2& reference, const nlohmann::json& corrector_options);

}  // namespace locbench::experiments
