#pragma once
// The scan-pair correctors the real-scan experiments compare, behind one interface: given the
// first scan (and the lines extracted from it, the "map"), the second scan and the odometry's
// relative motion, return the corrected relative motion. Internal to the experiments.
//
// Names (stable result keys):
//   "<matcher>_ch6_ls"      matcher (eap, split_and_merge, agglomerative, rwht) + one pass of
//                           chapter 6 (heading LS, then point-to-point position), the thesis;
//   "eap_ch6_rematched"     EAP + chapter 6, re-matched from each corrected pose until it stops
//                           moving (diagnosis: is the one-shot solve the weak link?);
//   "eap_ch6_heading_only"  EAP + chapter 6's heading only, position = odometry (diagnosis);
//   "eap_ch6_inverse_variance"  EAP + one pass of chapter 6 with the segments' headings weighted
//                           by their inverse variance instead of eq. 6.18 (diagnosis: is the
//                           thesis's weight the weak link?);
//   "eap_iterated_pl"       EAP matches + iterated joint point-to-line Gauss–Newton
//                           (algorithms/pose_correction/iterated_correction.h);
//   "pl_icp"                PL-ICP (Censi 2008), baselines/laser/pl_icp.h;
//   "icp_point_to_point"    plain trimmed point-to-point ICP, the same loop: the check.
#include <cstddef>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/laser/segment_match.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::experiments {

struct ScanPairCorrection {
  Pose2 motion;  // corrected second-scan robot pose in the first robot frame
  bool heading_fixed = false;
  bool position_fixed = false;  // false: the position is the odometry's (or unobservable)
  std::size_t matched_points = 0;
  std::size_t matched_segments = 0;  // map lines used (0 for the ICPs)
  int iterations = 0;
  // Chapter-6 correctors only (−1 otherwise), for the diagnosis of laser/real_logs:
  // smallest / largest eigenvalue of the position normal matrix [k3 k4; k4 k5] (eq. 6.37) —
  // how well the matched lines fix the position in its worst direction —, and the weighted
  // spread √Σ w_i (Δθ_i − Δθ̂)² of the per-segment headings (eq. 6.17–6.20) [rad].
  double position_information_ratio = -1.0;
  double heading_spread = -1.0;
};

class ScanPairCorrector {
 public:
  virtual ~ScanPairCorrector() = default;
  virtual std::string name() const = 0;
  virtual ScanPairCorrection correct(const Scan& first, const LineMap& first_lines, const Scan& second,
                                     const Pose2& odometry) const = 0;
};

// Every corrector option with its defaults:
// {"matcher_options": {...}, "ch6": PoseCorrectionOptions, "rematch_iterations": 10,
//  "iterated": IteratedCorrectionOptions, "pl_icp": PlIcpOptions,
//  "icp_point_to_point": PlIcpOptions (metric point_to_point)}.
nlohmann::json default_corrector_options();

// The correctors named in `which`, in order; UsageError for an unknown name or invalid options.
// Their correct() is const and keeps no state: one set may serve several threads at once.
std::vector<std::unique_ptr<ScanPairCorrector>> make_correctors(const std::vector<std::string>& which,
                                                                const nlohmann::json& options);

// How many times make_correctors has been called in this process (for tests).
std::size_t make_correctors_calls();

// The scan points behind a set of segment matches.
std::size_t points_of(const std::vector<laser::SegmentMatch>& matches);

}  // namespace locbench::experiments
