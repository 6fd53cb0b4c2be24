// A one-off measurement, built by run.sh and not by the project: Censi's CSM (sm_icp, point-to-
// line) against locbench's PL-ICP on the relation pairs of laser/real_logs (Intel, ACES, the
// odometry as the first guess), in one process, alternating, each pair's time the minimum of 5
// repetitions. CSM runs with its own defaults (sm_options) except where locbench's PL-ICP has the
// same setting: 50 iterations, correspondences within 0.5 m, 90% kept, the same tolerances, no
// restart, no covariance. Errors against the relations, as laser/real_logs computes them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <vector>

#include "baselines/laser/extract_then_match.h"
#include "datasets/catalog/data_root.h"
#include "datasets/catalog/dataset_catalog.h"
#include "pipelines/laser_correctors.h"
#include "pipelines/real_scan_pairs.h"

#include <csm/csm_all.h>
extern "C" {
#include <options/options.h>
void sm_options(struct sm_params* p, struct option* ops);
}
#undef min
#undef max
using namespace locbench;
using Clock = std::chrono::steady_clock;

static LDP to_ld(const Scan& s) {
  const int n = static_cast<int>(s.ranges.size());
  LDP ld = ld_alloc_new(n);
  ld->min_theta = s.bearings.front();
  ld->max_theta = s.bearings.back();
  for (int i = 0; i < n; ++i) {
    ld->theta[i] = s.bearings[i];
    ld->readings[i] = s.valid(i) ? s.ranges[i] : NAN;
    ld->valid[i] = s.valid(i) ? 1 : 0;
    ld->cluster[i] = -1;
  }
  for (int k = 0; k < 3; ++k) ld->odometry[k] = ld->estimate[k] = ld->true_pose[k] = 0.0;
  return ld;
}

struct Stats {
  std::vector<double> us, terr, rerr, iters;
};
static void print(const char* name, Stats& s) {
  std::vector<double> t = s.us;
  std::sort(t.begin(), t.end());
  auto q = [&](double p) { return t[std::min(t.size() - 1, static_cast<std::size_t>(p * t.size()))]; };
  auto mean = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); };
  std::printf("  %-9s mean %7.1f us  median %7.1f  p90 %7.1f  p99 %7.1f | error %6.2f mm %6.4f deg | iterations %.2f\n",
              name, mean(s.us), q(0.5), q(0.9), q(0.99), 1000 * mean(s.terr), mean(s.rerr) * 180 / M_PI, mean(s.iters));
}

int main() {
  for (const char* name : {"intel", "aces"}) {
    const auto* e = catalog::find_dataset(name);
    if (!std::filesystem::exists(catalog::data_root() / e->path)) {
      std::fprintf(stderr, "%s: not under %s (set LOCBENCH_DATA)\n", name, catalog::data_root().c_str());
      return 2;
    }
    Log log = catalog::load_catalog_dataset(*e, catalog::data_root());
    experiments::apply_beam_angles(log, "log");
    const auto correctors = experiments::make_correctors({"pl_icp"}, experiments::default_corrector_options());
    const baselines::laser::SplitAndMergeMatcher extractor;
    struct option* ops = options_allocate(100);
    struct sm_params params;
    sm_options(&params, ops);
    params.max_iterations = 50;            // locbench's cap
    params.max_correspondence_dist = 0.5;  // as locbench's
    params.outliers_maxPerc = 0.9;         // locbench's keep_fraction
    params.epsilon_xy = 1e-5;
    params.epsilon_theta = 1e-6;
    params.max_angular_correction_deg = 90;
    params.max_linear_correction = 2.0;
    params.restart = 0;
    params.do_compute_covariance = 0;
    params.use_corr_tricks = 1;
    params.use_point_to_line_distance = 1;
    params.min_reading = 0.0;
    params.max_reading = 1000.0;
    params.laser[0] = params.laser[1] = params.laser[2] = 0.0;
    Stats lb, csm;
    // laser/real_logs' pairs (its max_relation_dt_s 30 s).
    const std::vector<experiments::RelationScanPair> pairs = experiments::relation_scan_pairs(log, 30.0);
    for (const experiments::RelationScanPair& p : pairs) {
      const Relation& r = log.relations[p.relation];
      const Scan& first = log.laser[p.first].scan;
      const Scan& second = log.laser[p.second].scan;
      const LineMap map = experiments::lines_as_map(extractor.extract_lines(first));
      const Pose2 guess = p.odometry;
      const Pose2 mount = first.sensor_pose;
      const Pose2 guess_laser = mount.inverse() * guess * mount;
      double best_lb = 1e30, best_csm = 1e30;
      experiments::ScanPairCorrection c{};
      struct sm_result res {};
      for (int rep = 0; rep < 5; ++rep) {
        auto t0 = Clock::now();
        c = correctors.front()->correct(first, map, second, guess);
        auto t1 = Clock::now();
        best_lb = std::min(best_lb, std::chrono::duration<double, std::micro>(t1 - t0).count());
        LDP ref = to_ld(first), sens = to_ld(second);
        params.laser_ref = ref;
        params.laser_sens = sens;
        params.first_guess[0] = guess_laser.x;
        params.first_guess[1] = guess_laser.y;
        params.first_guess[2] = guess_laser.theta;
        t0 = Clock::now();
        sm_icp(&params, &res);
        t1 = Clock::now();
        best_csm = std::min(best_csm, std::chrono::duration<double, std::micro>(t1 - t0).count());
        ld_free(ref);
        ld_free(sens);
      }
      const Pose2 el = between(r.delta, c.motion);
      lb.us.push_back(best_lb);
      lb.terr.push_back(std::hypot(el.x, el.y));
      lb.rerr.push_back(std::abs(el.theta));
      lb.iters.push_back(c.iterations);
      const Pose2 motion_csm = res.valid ? mount * Pose2(res.x[0], res.x[1], res.x[2]) * mount.inverse() : guess;
      const Pose2 ec = between(r.delta, motion_csm);
      csm.us.push_back(best_csm);
      csm.terr.push_back(std::hypot(ec.x, ec.y));
      csm.rerr.push_back(std::abs(ec.theta));
      csm.iters.push_back(res.iterations);
    }
    std::printf("%s: %zu relation pairs\n", name, pairs.size());
    print("locbench", lb);
    print("CSM", csm);
  }
  return 0;
}
