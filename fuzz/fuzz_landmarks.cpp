// Plain landmark map and landmark observation readers, and attach_landmarks on what they read.
#include "datasets/io/landmark_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  const std::string text = fuzz::text(data, size);
  fuzz::accept_or_reject([&] { io::parse_landmark_map(text, "fuzz_map.txt"); });
  return fuzz::accept_or_reject([&] {
    io::LandmarkObservations obs = io::parse_landmark_observations(text, "fuzz_obs.txt");
    Log log;
    log.odometry.push_back({0.0, Pose2(), 0.0, 0.0});
    io::attach_landmarks(log, io::parse_landmark_map("6 0 0\n7 1 1 0.1 0.1\n", "map.txt"), std::move(obs), "map.txt",
                         "fuzz_obs.txt");
  });
}
