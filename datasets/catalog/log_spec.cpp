#include "datasets/catalog/log_spec.h"

#include "core/checksum.h"
#include "datasets/io/bag_log.h"
#include "datasets/io/landmark_reader.h"
#include "datasets/io/log_loader.h"
#include "datasets/io/tum_reader.h"

namespace locbench::catalog {
namespace {

// The log's TRUEPOS replaced by a TUM trajectory.
void replace_truth(Log& log, const std::filesystem::path& tum_file) {
  log.truth.clear();
  const Trajectory reference = io::read_tum(tum_file);
  for (const StampedPose& p : reference.poses()) {
    TruePose truth;
    truth.t = p.t;
    truth.pose = p.pose;
    log.truth.push_back(truth);
  }
}

}  // namespace

std::string catalog_log_spec(const DatasetEntry& entry, const std::filesystem::path& root) {
  return (root / entry.path).string();
}

std::filesystem::path log_spec_file(const std::string& spec) { return io::log_spec_path(spec); }

LoadedLog load_log_spec(const LogSpec& spec, const std::filesystem::path& root) {
  LoadedLog out;
  out.entry = find_dataset(spec.log);
  if (out.entry != nullptr) {
    out.log = load_catalog_dataset(*out.entry, root);
    out.dataset.path = catalog_log_spec(*out.entry, root);
  } else {
    out.log = io::load_log(spec.log);
    out.dataset.path = spec.log;
  }
  if (!spec.relations.empty()) io::attach_relations(out.log, spec.relations);
  if (!spec.ground_truth.empty()) replace_truth(out.log, spec.ground_truth);
  io::attach_landmark_files(out.log, spec.landmark_map, spec.landmark_observations);
  out.dataset.name = !spec.name.empty() ? spec.name : out.entry != nullptr ? out.entry->name : spec.log;
  out.dataset.checksum = file_checksum(log_spec_file(out.dataset.path));
  out.dataset.records = out.log.record_count();
  const auto [t0, t1] = out.log.time_span();
  out.dataset.duration_s = t1 - t0;
  return out;
}

}  // namespace locbench::catalog
