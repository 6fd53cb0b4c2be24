#pragma once
// The record of one input a result was computed from: what it is called, where it was read, the
// checksum of its bytes, how many records it held and the time they span. Loaders fill it
// (datasets/catalog/log_spec.h); reports list it (reports::ExperimentResults::datasets) and the
// diagnosis report carries it as its "input".
#include <cstddef>
#include <string>

namespace locbench {

struct DatasetRef {
  std::string name;      // e.g. "sim/corridor", "aces"
  std::string path;      // file or folder read, or "simulated"
  std::string checksum;  // "crc32:…" of the file bytes (core/checksum.h), or of the scenario JSON when simulated
  std::size_t records = 0;
  double duration_s = 0.0;
};

}  // namespace locbench
