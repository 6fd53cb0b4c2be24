#pragma once
// The one way a verb or an experiment turns "a name, a catalog entry or a file" into a Log:
// load_log_spec reads the log (and the companion files a user gives), and fills the record
// reports list for it — name, path, checksum of the bytes, records and time span.
//
// The checksum is file_checksum (core/checksum.h) of what the spec names — the file as stored
// (the .gz itself), or every file of a folder (an MRCLAM dataset, a ROS 2 bag) — taken here
// once, right after the read. It is not folded into the readers' own pass: they hand gzip files
// to zlib's gz* reader, which reads the stored bytes itself; a folder's checksum covers files
// the reader never opens (the other MRCLAM robots, a bag's metadata); and sqlite reads a ROS 2
// bag through its own file layer. The second pass finds the bytes in the page cache.
#include <filesystem>
#include <string>

#include "core/dataset_ref.h"
#include "core/log.h"
#include "datasets/catalog/dataset_catalog.h"

namespace locbench::catalog {

struct LogSpec {
  std::string name;  // the dataset's name in results; empty: the catalog name, or `log` as given
  // A catalog name (`locbench list`: "aces", "mrclam6_robot2") or any load_log spec: a CARMEN
  // file, a relations file, an MRCLAM folder "…/MRCLAM_Dataset6#robot2", a ROS bag
  // "run.bag#odom=/wheel_odom,truth=/vicon/pose" (datasets/io/log_loader.h).
  std::string log;
  std::string relations;              // optional: Freiburg relations, replacing the log's own
  std::string ground_truth;           // optional: a TUM trajectory, replacing the log's TRUEPOS
  std::string landmark_map;           // optional: id x y [sigma_x sigma_y]
  std::string landmark_observations;  // optional: t id range bearing
};

struct LoadedLog {
  Log log;
  DatasetRef dataset;                   // name, path read, checksum, records, duration
  const DatasetEntry* entry = nullptr;  // the catalog entry when `log` names one
};

// Loads `spec` (catalog data from under `root`). A catalog name wins over a file of the same
// name. InputError for a missing or malformed file (catalog data absent: "dataset … not found
// (set LOCBENCH_DATA)"); UsageError for a catalog entry without a log reader (the calibration
// data sets: calibration_catalog.h).
LoadedLog load_log_spec(const LogSpec& spec, const std::filesystem::path& root);

// The load_log spec of a catalog entry under `root` ("…/MRCLAM_Dataset6#robot1").
std::string catalog_log_spec(const DatasetEntry& entry, const std::filesystem::path& root);
// The file or folder a load_log spec reads ("folder#robot2" → "folder"; io::log_spec_path).
std::filesystem::path log_spec_file(const std::string& spec);

}  // namespace locbench::catalog
