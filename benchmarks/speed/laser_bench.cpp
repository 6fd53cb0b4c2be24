// Google Benchmark kernels of the chapter-5 matchers: one whole scan-to-map match (points →
// matched segments with their fitted lines) per iteration, for EAP (plain and indexed), the
// split-and-merge and agglomerative extract-then-match pipelines and the RWHT.
//   BM_Match_<matcher>/n/m: n beams over ±90° (181, 361, 721, 1441) against m segments
//   (tiled copies of the thesis's room: 14, 98, 994, 9996 segments), from the thesis pose
//   (2.0, 1.0, 46°) with the estimate off by (0.1 m, 0.1 m, −3°) as in Table 6.2. The n sweep
//   at m = 14 fits the complexity in n (BM_..._BigO rows); the m sweep at n = 181 shows the
//   cost against map size. Counters: segments matched, `work` (inner-loop tests), and bytes of
//   the match result (memory per scan; the grid index's own size is `index_bytes`).
//   BM_Match_band_reference/181/14: the floor of any EAP — the bare band tests |n·p − c| ≤ d_limit
//   (5.5) of the same points (under the same estimate) against the same segments, nothing else.
// Targets (181 beams, 14 segments): EAP within 3× of the band reference;
// ≥ 20× faster than agglomerative and ≥ 3× faster than split-and-merge, on this scan and on
// the first 200 scans of ACES and Intel (BM_RealScans below); indexed EAP at 10 000 segments
// within 1.2× of its 14-segment time. Compare ratios within one run
// (benchmarks/reference_results/speed_rules.json, `make bench-gate`).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "algorithms/laser/eap_matcher.h"
#include "algorithms/laser/segment_grid_index.h"
#include "baselines/laser/extract_then_match.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/catalog/data_root.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/io/scan_json_reader.h"
#include "datasets/sim/laser_model.h"
#include "datasets/sim/worlds.h"

namespace locbench::speed {
using io::read_scan_json;
using locbench::catalog::DatasetEntry, locbench::catalog::find_dataset, locbench::catalog::load_catalog_dataset;
namespace {

const Pose2 kTruth(2.0, 1.0, deg(46.0));
const Pose2 kEstimate(2.1, 1.1, deg(43.0));

int rooms_for(int m) { return m <= 14 ? 1 : (m + 13) / 14; }

const LineMap& world(int m) {
  static std::map<int, LineMap> cache;
  auto it = cache.find(m);
  if (it == cache.end()) it = cache.emplace(m, sim::tiled_rooms(rooms_for(m))).first;
  return it->second;
}

const Scan& scan(int n) {
  static std::map<int, Scan> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    sim::LaserConfig c;
    c.timing.enabled = true;
    c.beams = n;
    c.noise = mm(5.0);
    sim::LaserModel laser(c, world(14), Rng(7));
    it = cache.emplace(n, laser.measure(kTruth, 0.0)).first;
  }
  return it->second;
}

std::size_t result_bytes(const laser::MatchResult& r) {
  std::size_t b = sizeof(r) + r.matches.capacity() * sizeof(laser::SegmentMatch);
  for (const auto& m : r.matches) b += m.points.capacity() * sizeof(laser::ScanPoint);
  return b;
}

void run(benchmark::State& state, const laser::SegmentMatcher& matcher, const LineMap& map) {
  const Scan& s = scan(static_cast<int>(state.range(0)));
  laser::MatchResult r;
  for (auto _ : state) {
    r = matcher.match(s, map, kEstimate);
    benchmark::DoNotOptimize(r);
  }
  state.SetComplexityN(state.range(0));
  state.counters["segments_matched"] = static_cast<double>(r.matches.size());
  state.counters["work"] = static_cast<double>(r.work);
  state.counters["result_bytes"] = static_cast<double>(result_bytes(r));
  state.counters["map_segments"] = static_cast<double>(map.segments.size());
}

void BM_Match_eap(benchmark::State& state) { run(state, laser::EapMatcher(), world(static_cast<int>(state.range(1)))); }
void BM_Match_eap_indexed(benchmark::State& state) {
  const LineMap& map = world(static_cast<int>(state.range(1)));
  static std::map<int, std::shared_ptr<const laser::SegmentGridIndex>> indices;
  auto& index = indices[static_cast<int>(state.range(1))];
  if (!index) index = std::make_shared<const laser::SegmentGridIndex>(map);
  state.counters["index_bytes"] = static_cast<double>(index->entries() * sizeof(std::uint32_t));
  run(state, laser::EapMatcher(index), index->map());
}
// The reference kernel: n·m band tests over flat arrays — points precomputed, segments as their
// unit normal n and c = n·P1 — counting the points inside each band (the count is what EAP's
// first stage learns). The compiler vectorises it; EAP is reported as a multiple of it.
void BM_Match_band_reference(benchmark::State& state) {
  const Scan& s = scan(static_cast<int>(state.range(0)));
  const LineMap& map = world(static_cast<int>(state.range(1)));
  const double d_limit = laser::EapOptions{}.d_limit;
  std::vector<double> px, py, nx, ny, c;
  for (const laser::ScanPoint& p : laser::scan_points(s, kEstimate)) {
    px.push_back(p.world.x());
    py.push_back(p.world.y());
  }
  for (const Segment& seg : map.segments) {
    const Eigen::Vector2d d = (seg.p2 - seg.p1).normalized();
    nx.push_back(-d.y());
    ny.push_back(d.x());
    c.push_back(nx.back() * seg.p1.x() + ny.back() * seg.p1.y());
  }
  const std::size_t n = px.size(), m = c.size();
  std::size_t inside = 0;
  for (auto _ : state) {
    inside = 0;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < m; ++j) {
        inside += std::abs(nx[j] * px[i] + ny[j] * py[i] - c[j]) <= d_limit;
      }
    }
    benchmark::DoNotOptimize(inside);
  }
  state.counters["work"] = static_cast<double>(n * m);
  state.counters["inside_band"] = static_cast<double>(inside);
  state.counters["map_segments"] = static_cast<double>(m);
}
void BM_Match_split_and_merge(benchmark::State& state) {
  run(state, baselines::laser::SplitAndMergeMatcher(), world(static_cast<int>(state.range(1))));
}
void BM_Match_agglomerative(benchmark::State& state) {
  run(state, baselines::laser::AgglomerativeMatcher(), world(static_cast<int>(state.range(1))));
}
void BM_Match_rwht(benchmark::State& state) {
  run(state, baselines::laser::RwhtMatcher(), world(static_cast<int>(state.range(1))));
}

// n sweep at the room (complexity in n), then m sweep at 181 beams.
void beams_sweep(benchmark::internal::Benchmark* b) {
  for (int n : {181, 361, 721, 1441}) b->Args({n, 14});
  b->Complexity();
}
void map_sweep(benchmark::internal::Benchmark* b) {
  for (int m : {98, 994, 9996}) b->Args({181, m});
}

BENCHMARK(BM_Match_band_reference)->Args({181, 14});
BENCHMARK(BM_Match_eap)->Apply(beams_sweep);
BENCHMARK(BM_Match_eap_indexed)->Apply(beams_sweep);
BENCHMARK(BM_Match_split_and_merge)->Apply(beams_sweep);
BENCHMARK(BM_Match_agglomerative)->Apply(beams_sweep);
BENCHMARK(BM_Match_rwht)->Apply(beams_sweep);
BENCHMARK(BM_Match_eap)->Name("BM_Match_eap_mapsize")->Apply(map_sweep);
BENCHMARK(BM_Match_eap_indexed)->Name("BM_Match_eap_indexed_mapsize")->Apply(map_sweep);
BENCHMARK(BM_Match_split_and_merge)->Name("BM_Match_split_and_merge_mapsize")->Apply(map_sweep);

// ---- Real scans: every extractor on the first 200 FLASER scans of each Freiburg log and on the
// three Queens hallway scans (541 beams over 270°), read from $LOCBENCH_DATA; skipped with a
// message when the data are absent. Time per iteration covers all the dataset's scans
// (counter `scans`); EAP matches each scan against its own split-and-merge lines (a map of the
// right size and shape for that scan, built outside the timed loop).
constexpr std::size_t kRealScans = 200;

const std::vector<Scan>* real_scans(const std::string& dataset) {
  static std::map<std::string, std::vector<Scan>> cache;
  if (auto it = cache.find(dataset); it != cache.end()) return &it->second;
  std::vector<Scan> scans;
  try {
    if (dataset == "queens") {
      for (int i = 1; i <= 3; ++i) {
        const auto p = catalog::data_root() / ("laser_scans/kam3k_queens/laser_scan_" + std::to_string(i) + ".json.gz");
        if (!std::filesystem::exists(p)) return nullptr;
        scans.push_back(read_scan_json(p));
      }
    } else {
      const DatasetEntry* e = find_dataset(dataset);
      if (!e || !std::filesystem::exists(catalog::data_root() / e->path)) return nullptr;
      const Log log = load_catalog_dataset(*e, catalog::data_root());
      for (std::size_t i = 0; i < log.laser.size() && i < kRealScans; ++i) scans.push_back(log.laser[i].scan);
    }
  } catch (const std::exception&) {
    return nullptr;
  }
  return &cache.emplace(dataset, std::move(scans)).first->second;
}

void BM_RealScans(benchmark::State& state, const std::string& dataset, const std::string& method) {
  const std::vector<Scan>* scans = real_scans(dataset);
  if (!scans || scans->empty()) {
    state.SkipWithError(
        ("dataset " + dataset + " not found under " + catalog::data_root().string() + " (set LOCBENCH_DATA)").c_str());
    return;
  }
  const baselines::laser::SplitAndMergeMatcher sm;
  const baselines::laser::AgglomerativeMatcher agg;
  const baselines::laser::RwhtMatcher rwht;
  const laser::EapMatcher eap;
  std::vector<LineMap> own_lines;
  if (method == "eap") {
    for (const Scan& s : *scans) {
      LineMap m;
      for (const auto& l : sm.extract_lines(s).lines) m.segments.push_back(l.fit.segment());
      own_lines.push_back(std::move(m));
    }
  }
  std::size_t lines = 0;
  for (auto _ : state) {
    lines = 0;
    for (std::size_t i = 0; i < scans->size(); ++i) {
      const Scan& s = (*scans)[i];
      if (method == "split_and_merge") lines += sm.extract_lines(s).lines.size();
      if (method == "agglomerative") lines += agg.extract_lines(s).lines.size();
      if (method == "rwht") lines += rwht.extract_lines(s).lines.size();
      if (method == "eap") lines += eap.match(s, own_lines[i], Pose2()).matches.size();
    }
    benchmark::DoNotOptimize(lines);
  }
  state.counters["scans"] = static_cast<double>(scans->size());
  state.counters["beams"] = static_cast<double>(scans->front().ranges.size());
  state.counters["lines_per_scan"] = static_cast<double>(lines) / static_cast<double>(scans->size());
  state.counters["per_scan"] = benchmark::Counter(static_cast<double>(state.iterations() * scans->size()),
                                                  benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const bool kRealScanBenchmarks = [] {
  for (const char* dataset : {"aces", "intel", "mit_csail", "queens"}) {
    for (const char* method : {"eap", "split_and_merge", "agglomerative", "rwht"}) {
      benchmark::RegisterBenchmark(
          (std::string("BM_RealScans/") + dataset + "/" + method).c_str(),
          [d = std::string(dataset), m = std::string(method)](benchmark::State& st) { BM_RealScans(st, d, m); })
          ->Unit(benchmark::kMicrosecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace locbench::speed
