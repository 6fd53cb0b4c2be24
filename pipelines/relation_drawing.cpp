#include "pipelines/relation_drawing.h"

#include <cmath>

#include "algorithms/pose_correction/iterated_correction.h"
#include "algorithms/pose_correction/pose_correction.h"
#include "pipelines/laser_correctors.h"
#include "pipelines/laser_matchers.h"

namespace locbench::experiments {
namespace {

// The scan's valid end points, placed by `pose` (robot pose in the first robot frame).
DrawnSeries scan_points(std::string name, const Scan& scan, const Pose2& pose) {
  DrawnSeries s{std::move(name), {}, {}};
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!scan.valid(i)) continue;
    const Eigen::Vector2d p = pose * (scan.sensor_pose * scan.point(i));
    s.x.push_back(p.x());
    s.y.push_back(p.y());
  }
  return s;
}

void add_segment(DrawnSeries& s, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  s.x.insert(s.x.end(), {a.x(), b.x()});
  s.y.insert(s.y.end(), {a.y(), b.y()});
}

DrawnSeries map_lines(const LineMap& lines) {
  DrawnSeries s{"first-scan lines", {}, {}};
  for (const Segment& seg : lines.segments) add_segment(s, seg.p1, seg.p2);
  return s;
}

// Each matched point (robot frame, placed by `pose`) joined to its foot on its map line.
DrawnSeries match_links(std::string name, const std::vector<laser::SegmentMatch>& matches, const LineMap& lines,
                        const Pose2& pose) {
  DrawnSeries s{std::move(name), {}, {}};
  for (const auto& m : matches) {
    if (m.map_segment >= lines.segments.size()) continue;
    const LineParams l = lines.segments[m.map_segment].line();
    const Eigen::Vector2d n(std::cos(l.beta), std::sin(l.beta));
    for (const auto& p : m.points) {
      const Eigen::Vector2d w = pose * p.robot;
      add_segment(s, w, w - (n.dot(w) - l.rho) * n);
    }
  }
  return s;
}

}  // namespace

DrawnRelation draw_relation(const Scan& first, const LineMap& first_lines, const Scan& second, const Pose2& odometry,
                            const Pose2& reference, const nlohmann::json& corrector_options) {
  const nlohmann::json defaults = default_corrector_options();
  const nlohmann::json& o = corrector_options.is_null() ? defaults : corrector_options;
  const auto eap =
      std::move(make_matchers({"eap"}, o.value("matcher_options", defaults.at("matcher_options"))).front());
  pose_correction::PoseCorrectionOptions ch6;
  if (o.contains("ch6")) from_json(o.at("ch6"), ch6);
  pose_correction::IteratedCorrectionOptions iterated;
  if (o.contains("iterated")) from_json(o.at("iterated"), iterated);

  DrawnRelation d;
  const auto error = [&](const Pose2& motion, double& translation, double& rotation) {
    const Pose2 e = between(reference, motion);
    translation = std::hypot(e.x, e.y);
    rotation = std::abs(e.theta);
  };
  error(odometry, d.odometry_translation, d.odometry_rotation);
  const DrawnSeries first_points = scan_points("first scan", first, Pose2::identity());
  const DrawnSeries lines = map_lines(first_lines);

  // Before: what eap_ch6_ls sees (one match at the odometry's pose, one solve).
  const laser::MatchResult at_odometry = eap->match(second, first_lines, odometry);
  d.one_shot_points = points_of(at_odometry.matches);
  d.before = {first_points, lines, scan_points("second scan at odometry", second, odometry),
              match_links("EAP matches", at_odometry.matches, first_lines, odometry)};
  Pose2 one_shot = odometry;
  if (!first_lines.segments.empty()) {
    one_shot =
        pose_correction::correct_pose(at_odometry.matches, first_lines, odometry, second.sensor_pose, ch6).corrected;
  }
  error(one_shot, d.one_shot_translation, d.one_shot_rotation);

  // After: the one-shot result, the iterated solve with its last matches, the reference.
  Pose2 after = odometry;
  std::vector<laser::SegmentMatch> last;
  if (!first_lines.segments.empty()) {
    auto c = pose_correction::iterated_point_to_line(*eap, second, first_lines, odometry, iterated);
    if (c.valid) {
      after = c.corrected;
      last = std::move(c.matches);
    }
  }
  d.iterated_points = points_of(last);
  error(after, d.iterated_translation, d.iterated_rotation);
  d.after = {first_points,
             lines,
             scan_points("second scan, eap_ch6_ls", second, one_shot),
             scan_points("second scan, eap_iterated_pl", second, after),
             scan_points("second scan, reference motion", second, reference),
             match_links("eap_iterated_pl matches", last, first_lines, after)};
  return d;
}

}  // namespace locbench::experiments
