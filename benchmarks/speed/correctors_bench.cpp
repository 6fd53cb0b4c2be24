// Google Benchmark kernels of the scan-pair correctors of laser/real_logs (laser_correctors.h):
// one whole correction of a scan against the previous one per iteration — extraction of the
// previous scan's lines (split-and-merge) is done once outside the loop, as in the experiment
// where it is shared by the line-based correctors.
//   BM_Correct/<corrector>/sim: two 181-beam scans (σ = 5 mm) in the thesis's room, 0.3 m and 8°
//     apart, the guess off by (0.1 m, −0.08 m, 3°): always available, gated (speed_rules.json);
//   BM_Correct/<corrector>/intel: the first 200 consecutive-scan pairs of the Intel log (when
//     LOCBENCH_DATA has it; skipped otherwise), cycled, the odometry as the guess: per real scan.
//   BM_IntelReplay/<corrector>: the whole Intel log (13,631 scans) replayed once per iteration,
//     single-threaded: each scan's split-and-merge lines extracted, then the next scan corrected
//     against them from the odometry (13,630 pairs; skipped without the data). Target: under
//     1 s for EAP + solve in Release.
#include <benchmark/benchmark.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "baselines/laser/extract_then_match.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/catalog/data_root.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/sim/laser_model.h"
#include "datasets/sim/worlds.h"
#include "pipelines/laser_correctors.h"

namespace locbench::speed {
using io::odometry_trajectory;
using locbench::catalog::DatasetEntry, locbench::catalog::find_dataset, locbench::catalog::load_catalog_dataset;
namespace {

struct PairCase {
  Scan first, second;
  LineMap lines;  // of the first scan
  Pose2 guess;
};

LineMap lines_of(const Scan& s) {
  const baselines::laser::SplitAndMergeMatcher extractor;
  LineMap m;
  for (const auto& l : extractor.extract_lines(s).lines) {
    const Segment seg = l.fit.segment();
    if (seg.length() > 1e-6) m.segments.push_back(seg);
  }
  return m;
}

const std::vector<PairCase>& sim_pairs() {
  static const std::vector<PairCase> pairs = [] {
    sim::LaserConfig c;
    c.beams = 181;
    c.noise = mm(5.0);
    static const LineMap world = sim::room_world();  // the model keeps a reference to it
    sim::LaserModel laser(c, world, Rng(11));
    const Pose2 a(2.0, 1.0, deg(46.0)), b(2.2, 1.2, deg(54.0));
    PairCase p{laser.measure(a, 0.0), laser.measure(b, 0.2), {}, {}};
    p.lines = lines_of(p.first);
    p.guess = between(a, b) * Pose2(0.1, -0.08, deg(3.0));
    return std::vector<PairCase>{p};
  }();
  return pairs;
}

const std::vector<PairCase>& intel_pairs() {
  static const std::vector<PairCase> pairs = [] {
    std::vector<PairCase> out;
    const DatasetEntry* e = find_dataset("intel");
    if (!e || !std::filesystem::exists(catalog::data_root() / e->path)) return out;
    const Log log = load_catalog_dataset(*e, catalog::data_root());
    const Trajectory odom = odometry_trajectory(log);
    for (std::size_t i = 1; i < log.laser.size() && out.size() < 200; ++i) {
      const Scan& a = log.laser[i - 1].scan;
      const Scan& b = log.laser[i].scan;
      const auto o1 = odom.pose_at(a.timestamp), o2 = odom.pose_at(b.timestamp);
      if (!o1 || !o2) continue;
      out.push_back({a, b, lines_of(a), between(*o1, *o2)});
    }
    return out;
  }();
  return pairs;
}

// Every consecutive pair of the Intel log: the scans, and the odometry's relative motion.
struct Replay {
  std::vector<Scan> scans;
  std::vector<Pose2> guesses;  // guesses[i]: scan i+1 in scan i's robot frame
};

const Replay& intel_replay() {
  static const Replay replay = [] {
    Replay out;
    const DatasetEntry* e = find_dataset("intel");
    if (!e || !std::filesystem::exists(catalog::data_root() / e->path)) return out;
    const Log log = load_catalog_dataset(*e, catalog::data_root());
    const Trajectory odom = odometry_trajectory(log);
    std::optional<Pose2> previous;
    for (const auto& r : log.laser) {
      const auto o = odom.pose_at(r.scan.timestamp);
      if (!o) continue;
      if (previous) out.guesses.push_back(between(*previous, *o));
      out.scans.push_back(r.scan);
      previous = o;
    }
    return out;
  }();
  return replay;
}

void BM_IntelReplay(benchmark::State& state, const std::string& corrector) {
  const Replay& replay = intel_replay();
  if (replay.scans.size() < 2) {
    state.SkipWithError("intel log not found (set LOCBENCH_DATA)");
    return;
  }
  const auto c = experiments::make_correctors({corrector}, experiments::default_corrector_options());
  for (auto _ : state) {
    for (std::size_t i = 0; i + 1 < replay.scans.size(); ++i) {
      const LineMap lines = lines_of(replay.scans[i]);
      benchmark::DoNotOptimize(c.front()->correct(replay.scans[i], lines, replay.scans[i + 1], replay.guesses[i]));
    }
  }
  state.counters["scans"] = static_cast<double>(replay.scans.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * (replay.scans.size() - 1)));
}

void BM_Correct(benchmark::State& state, const std::string& corrector, bool real) {
  const auto& pairs = real ? intel_pairs() : sim_pairs();
  if (pairs.empty()) {
    state.SkipWithError("intel log not found (set LOCBENCH_DATA)");
    return;
  }
  const auto c = experiments::make_correctors({corrector}, experiments::default_corrector_options());
  std::size_t k = 0;
  for (auto _ : state) {
    const PairCase& p = pairs[k++ % pairs.size()];
    benchmark::DoNotOptimize(c.front()->correct(p.first, p.lines, p.second, p.guess));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

int register_all() {
  for (const char* name : {"eap_ch6_ls", "eap_iterated_pl", "pl_icp", "icp_point_to_point"}) {
    for (const bool real : {false, true}) {
      benchmark::RegisterBenchmark(("BM_Correct/" + std::string(name) + (real ? "/intel" : "/sim")).c_str(),
                                   [name = std::string(name), real](benchmark::State& s) { BM_Correct(s, name, real); })
          ->Unit(benchmark::kMicrosecond);
    }
  }
  for (const char* name : {"eap_ch6_ls", "eap_iterated_pl"}) {
    benchmark::RegisterBenchmark(("BM_IntelReplay/" + std::string(name)).c_str(), [name = std::string(name)](
                                                                                      benchmark::State& s) {
      BM_IntelReplay(s, name);
    })->Unit(benchmark::kMillisecond);
  }
  return 0;
}
[[maybe_unused]] const int kRegistered = register_all();

}  // namespace
}  // namespace locbench::speed
