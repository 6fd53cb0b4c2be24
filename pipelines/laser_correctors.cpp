#include "pipelines/laser_correctors.h"

#include <Eigen/Core>
#include <atomic>
#include <cmath>

#include "algorithms/pose_correction/iterated_correction.h"
#include "algorithms/pose_correction/pose_correction.h"
#include "baselines/laser/pl_icp.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/linear_algebra.h"
#include "pipelines/laser_matchers.h"

namespace locbench::experiments {
namespace {

using pose_correction::PoseCorrectionOptions;

// The diagnostics of a chapter-6 correction (laser_correctors.h).
void diagnose(const pose_correction::PoseCorrection& c, ScanPairCorrection& out) {
  out.heading_spread = -1.0;
  out.position_information_ratio = -1.0;
  if (c.heading_fixed) {
    double ss = 0.0;
    for (const auto& s : c.orientation.segments) ss += s.weight * std::pow(s.delta - c.orientation.delta, 2);
    out.heading_spread = std::sqrt(ss);
  }
  if (c.position_fixed) {
    // The covariance is s² A⁻¹: its eigenvalues are in the inverse ratio of A's.
    const Eigen::Vector2d values = linalg::symmetric_eigen2(c.position.covariance).values;
    const double hi = values.maxCoeff();
    out.position_information_ratio = hi > 0.0 ? values.minCoeff() / hi : 0.0;
  }
}

// A corrector that registers the second scan to the first scan's lines; with no lines it keeps the
// odometry's relative motion.
class LineMapCorrector : public ScanPairCorrector {
 public:
  explicit LineMapCorrector(std::string name) : name_(std::move(name)) {}
  std::string name() const final { return name_; }
  ScanPairCorrection correct(const Scan&, const LineMap& map, const Scan& second, const Pose2& odometry) const final {
    ScanPairCorrection out;
    out.motion = odometry;
    if (!map.segments.empty()) correct_to(map, second, odometry, out);
    return out;
  }

 private:
  // `out` starts as the odometry's motion and nothing matched.
  virtual void correct_to(const LineMap& map, const Scan& second, const Pose2& odometry,
                          ScanPairCorrection& out) const = 0;
  std::string name_;
};

// matcher + one pass of chapter 6 (or heading only, or re-matched until it stops moving).
class Chapter6 final : public LineMapCorrector {
 public:
  enum class Mode { kOneShot, kHeadingOnly, kRematched };
  Chapter6(std::string name, std::unique_ptr<laser::SegmentMatcher> matcher, PoseCorrectionOptions options, Mode mode,
           int rematch_iterations)
      : LineMapCorrector(std::move(name)),
        matcher_(std::move(matcher)),
        options_(options),
        mode_(mode),
        rematch_(rematch_iterations) {}

 private:
  void correct_to(const LineMap& map, const Scan& second, const Pose2& odometry,
                  ScanPairCorrection& out) const override {
    Pose2 pose = odometry;
    const int passes = mode_ == Mode::kRematched ? rematch_ : 1;
    for (int k = 0; k < passes; ++k) {
      const laser::MatchResult m = matcher_->match(second, map, pose);
      const auto c = pose_correction::correct_pose(m.matches, map, pose, second.sensor_pose, options_);
      out.iterations = k + 1;
      out.matched_points = points_of(m.matches);
      out.matched_segments = c.segments_used;
      out.heading_fixed = c.heading_fixed;
      diagnose(c, out);
      if (mode_ == Mode::kHeadingOnly) {
        out.motion = Pose2(pose.x, pose.y, c.corrected.theta);
        return;
      }
      out.position_fixed = c.position_fixed;
      const double dt = std::hypot(c.corrected.x - pose.x, c.corrected.y - pose.y);
      const double dth = std::abs(angle_diff(c.corrected.theta, pose.theta));
      pose = c.corrected;
      if (dt < 1e-4 && dth < 1e-5) break;
    }
    out.motion = pose;
  }

  std::unique_ptr<laser::SegmentMatcher> matcher_;
  PoseCorrectionOptions options_;
  Mode mode_;
  int rematch_;
};

class IteratedPointToLine final : public LineMapCorrector {
 public:
  IteratedPointToLine(std::string name, std::unique_ptr<laser::SegmentMatcher> matcher,
                      pose_correction::IteratedCorrectionOptions options)
      : LineMapCorrector(std::move(name)), matcher_(std::move(matcher)), options_(options) {}

 private:
  void correct_to(const LineMap& map, const Scan& second, const Pose2& odometry,
                  ScanPairCorrection& out) const override {
    const auto c = pose_correction::iterated_point_to_line(*matcher_, second, map, odometry, options_);
    out.iterations = c.iterations;
    out.matched_points = c.points_used;
    out.matched_segments = c.segments_used;
    if (!c.valid) return;
    out.motion = c.corrected;
    out.heading_fixed = true;
    out.position_fixed = !c.degenerate;
  }

  std::unique_ptr<laser::SegmentMatcher> matcher_;
  pose_correction::IteratedCorrectionOptions options_;
};

class Icp final : public ScanPairCorrector {
 public:
  Icp(std::string name, baselines::laser::PlIcpOptions options) : name_(std::move(name)), options_(options) {}
  std::string name() const override { return name_; }
  ScanPairCorrection correct(const Scan& first, const LineMap&, const Scan& second,
                             const Pose2& odometry) const override {
    const baselines::laser::PlIcpResult r = baselines::laser::pl_icp(first, second, odometry, options_);
    ScanPairCorrection out;
    out.motion = r.motion;
    out.heading_fixed = r.valid;
    out.position_fixed = r.valid && !r.degenerate;
    out.matched_points = r.correspondences;
    out.iterations = r.iterations;
    return out;
  }

 private:
  std::string name_;
  baselines::laser::PlIcpOptions options_;
};

std::atomic<std::size_t> correctors_calls{0};

}  // namespace

nlohmann::json default_corrector_options() {
  nlohmann::json j;
  j["matcher_options"] = default_matcher_options();
  to_json(j["ch6"], PoseCorrectionOptions{});
  j["rematch_iterations"] = 10;
  to_json(j["iterated"], pose_correction::IteratedCorrectionOptions{});
  to_json(j["pl_icp"], baselines::laser::PlIcpOptions{});
  baselines::laser::PlIcpOptions p2p;
  p2p.metric = baselines::laser::IcpMetric::kPointToPoint;
  to_json(j["icp_point_to_point"], p2p);
  return j;
}

std::vector<std::unique_ptr<ScanPairCorrector>> make_correctors(const std::vector<std::string>& which,
                                                                const nlohmann::json& options) {
  ++correctors_calls;
  const nlohmann::json defaults = default_corrector_options();
  const nlohmann::json& o = options.is_null() ? defaults : options;
  const nlohmann::json matcher_options = o.value("matcher_options", defaults.at("matcher_options"));
  const auto ch6 = options_of<PoseCorrectionOptions>(o, "ch6");
  const int rematch = o.value("rematch_iterations", 10);
  if (rematch < 1) throw UsageError("rematch_iterations: must be >= 1");
  std::vector<std::unique_ptr<ScanPairCorrector>> out;
  const auto matcher = [&](const std::string& m) { return std::move(make_matchers({m}, matcher_options).front()); };
  const std::string suffix = "_ch6_ls";
  for (const std::string& name : which) {
    if (name.size() > suffix.size() && name.ends_with(suffix)) {
      out.push_back(std::make_unique<Chapter6>(name, matcher(name.substr(0, name.size() - suffix.size())), ch6,
                                               Chapter6::Mode::kOneShot, 1));
    } else if (name == "eap_ch6_rematched") {
      out.push_back(std::make_unique<Chapter6>(name, matcher("eap"), ch6, Chapter6::Mode::kRematched, rematch));
    } else if (name == "eap_ch6_heading_only") {
      out.push_back(std::make_unique<Chapter6>(name, matcher("eap"), ch6, Chapter6::Mode::kHeadingOnly, 1));
    } else if (name == "eap_ch6_inverse_variance") {
      PoseCorrectionOptions o6 = ch6;
      o6.orientation.weighting = pose_correction::OrientationWeighting::kInverseVariance;
      out.push_back(std::make_unique<Chapter6>(name, matcher("eap"), o6, Chapter6::Mode::kOneShot, 1));
    } else if (name == "eap_iterated_pl") {
      out.push_back(std::make_unique<IteratedPointToLine>(
          name, matcher("eap"), options_of<pose_correction::IteratedCorrectionOptions>(o, "iterated")));
    } else if (name == "pl_icp") {
      out.push_back(std::make_unique<Icp>(name, options_of<baselines::laser::PlIcpOptions>(o, "pl_icp")));
    } else if (name == "icp_point_to_point") {
      baselines::laser::PlIcpOptions p;
      p.metric = baselines::laser::IcpMetric::kPointToPoint;
      if (o.contains("icp_point_to_point")) from_json(o.at("icp_point_to_point"), p);
      out.push_back(std::make_unique<Icp>(name, p));
    } else {
      throw UsageError("unknown corrector '" + name +
                       "' (known: <matcher>_ch6_ls, eap_ch6_rematched, eap_ch6_heading_only, "
                       "eap_ch6_inverse_variance, eap_iterated_pl, pl_icp, icp_point_to_point)");
    }
  }
  return out;
}

std::size_t make_correctors_calls() { return correctors_calls.load(); }

std::size_t points_of(const std::vector<laser::SegmentMatch>& matches) {
  std::size_t n = 0;
  for (const auto& m : matches) n += m.points.size();
  return n;
}

}  // namespace locbench::experiments
