// Google Benchmark kernels showing that reading a ROS bag is not the bottleneck. One synthetic run
// — 20,000 LaserScans of 1,081 ranges (the bulk, ~87 MB), odometry at 50 Hz, a ground truth at 10
// Hz — is written once as a ROS 1 bag, a ROS 2 sqlite3 bag and MCAP files (zstd chunks, and
// uncompressed), then read as a log two ways: every topic, and only the odometry and the truth
// (`#scan=none`: the scans stay in the file). LOCBENCH_BAG_BENCH_SCANS sets the number of scans
// (default 20,000; 240,000 make 2.0 GB ROS 1 and uncompressed MCAP files, a 0.97 GB zstd MCAP
// file). BM_ReadFileBytes reads the same file's bytes and nothing else (what `cat` does), so the
// ratio of a reader's bytes per second to it, measured in the same run, is the reader's cost. Bytes
// per second are the file's size over the time.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>  // getpid

#include "datasets/io/bag_log.h"
#include "datasets/io/log_loader.h"

namespace locbench::speed {
namespace {

constexpr int kDefaultScans = 20000;
constexpr int kBeams = 1081;

// The number of scans: LOCBENCH_BAG_BENCH_SCANS when it is a whole number from 1 to 10^6.
int scan_count() {
  const char* text = std::getenv("LOCBENCH_BAG_BENCH_SCANS");
  if (!text) return kDefaultScans;
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || n < 1 || n > 1000000) {
    std::fprintf(stderr, "LOCBENCH_BAG_BENCH_SCANS=%s: expected a whole number from 1 to 1000000\n", text);
    std::exit(2);
  }
  return static_cast<int>(n);
}

io::BagContents synthetic_run() {
  io::BagContents c;
  const double scan_period = 0.1;
  std::uint64_t noise = 1;
  const int scans = scan_count();
  for (int i = 0; i < scans; ++i) {
    const double t = 1000.0 + scan_period * i;
    io::BagScanMessage s;
    s.time = {t, t, 0};
    s.frame_id = "laser";
    s.angle_min = -2.35619;
    s.angle_increment = 4.71239 / (kBeams - 1);
    s.range_min = 0.02;
    s.range_max = 30.0;
    s.ranges.resize(kBeams);
    // A wall at 2–3 m with 1 cm of noise (a fixed-seed generator): ranges that compress as a
    // real scan's do, not as a repeated pattern.
    for (int k = 0; k < kBeams; ++k) {
      noise = noise * 6364136223846793005ULL + 1442695040888963407ULL;
      const double jitter = static_cast<double>(noise >> 40) / static_cast<double>(1ULL << 24) - 0.5;
      s.ranges[k] = static_cast<float>(2.0 + std::sin(0.01 * k + 0.001 * i) + 0.02 * jitter);
    }
    c.scans.push_back(std::move(s));
    for (int j = 0; j < 5; ++j) {  // 50 Hz odometry
      const double to = t + 0.02 * j;
      io::BagPoseMessage o;
      o.time = {to, to, 0};
      o.frame_id = "odom";
      o.child_frame_id = "base_link";
      o.pose = {0.1 * to, 0.0, 0.0};
      o.tv = 0.1;
      c.odom.push_back(o);
    }
    io::BagPoseMessage g;
    g.time = {t, t, 0};
    g.frame_id = "map";
    g.pose = {0.1 * t, 0.0, 0.0};
    c.truth.push_back(g);
  }
  return c;
}

// The bags, written once into a temporary folder (removed at exit).
struct Bags {
  std::filesystem::path dir;
  std::filesystem::path ros1, ros2, mcap_zstd, mcap_none;
  Bags() {
    dir = std::filesystem::temp_directory_path() / ("locbench_bag_bench_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const io::BagContents c = synthetic_run();
    ros1 = dir / "run.bag";
    io::write_ros1_bag(c, ros1);
    io::write_ros2_bag(c, dir / "run2", "run2");
    ros2 = dir / "run2" / "run2_0.db3";
    mcap_zstd = dir / "zstd.mcap";
    io::write_mcap_bag(c, mcap_zstd, "zstd");
    mcap_none = dir / "none.mcap";
    io::write_mcap_bag(c, mcap_none, "none");
  }
  ~Bags() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  const std::filesystem::path& file(int which) const {
    return which == 0 ? ros1 : which == 1 ? ros2 : which == 2 ? mcap_zstd : mcap_none;
  }
  // What load_log is given: the .db3 file for the sqlite3 bag (the folder would do as well).
  std::string spec(int which) const { return file(which).string(); }
};

const Bags& bags() {
  static const Bags b;
  return b;
}

const char* kNames[] = {"ros1", "ros2_sqlite3", "mcap_zstd", "mcap_uncompressed"};

void BM_ReadFileBytes(benchmark::State& state) {
  const auto& path = bags().file(static_cast<int>(state.range(0)));
  std::vector<char> buffer(1 << 20);
  std::size_t total = 0;
  for (auto _ : state) {
    std::ifstream in(path, std::ios::binary);
    while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
      total += static_cast<std::size_t>(in.gcount());
    benchmark::DoNotOptimize(total);
  }
  state.SetLabel(kNames[state.range(0)]);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(path)));
}

void BM_ReadBagLog(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const bool scans = state.range(1) != 0;
  const std::string spec = bags().spec(which) + (scans ? "" : "#scan=none");
  for (auto _ : state) {
    const Log log = io::load_log(spec);
    benchmark::DoNotOptimize(log.odometry.size());
  }
  state.SetLabel(std::string(kNames[which]) + (scans ? ", every topic" : ", odometry and truth only"));
  state.SetBytesProcessed(
      static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(bags().file(which))));
}

BENCHMARK(BM_ReadFileBytes)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadBagLog)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace locbench::speed
