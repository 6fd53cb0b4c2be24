#include "datasets/catalog/calibration_catalog.h"

#include <algorithm>

#include "core/errors.h"
#include "datasets/io/censi_tuple_reader.h"
#include "datasets/io/relative_motion_reader.h"

namespace locbench::catalog {
using io::read_censi_tuples, io::read_relative_motion_pairs, io::read_tick_motions;
namespace {

// folder/name or folder/name.gz, whichever exists; InputError naming both otherwise.
std::filesystem::path data_file(const std::filesystem::path& folder, const std::string& name) {
  for (const auto& candidate : {folder / name, folder / (name + ".gz")}) {
    std::error_code ec;
    // Whatever is there (a FIFO too): the input opener then says what it is and what was expected.
    if (std::filesystem::exists(candidate, ec)) return candidate;
  }
  throw InputError((folder / name).string(), 0,
                   "missing calibration file (looked for " + name + " and " + name + ".gz)");
}

}  // namespace

bool is_calibration_dataset(const DatasetEntry& entry) {
  return entry.name == "censi_khepera" || entry.name == "grisetti_diffdrive" || entry.name == "stachniss_ls_calib";
}

std::vector<std::string> calibration_dataset_parts(const DatasetEntry& entry) {
  if (entry.name == "censi_khepera") {
    return {"lstraight", "lstraight_0", "lstraight_1", "lstraight_2", "l90", "l90_0", "l90_1", "l90_2"};
  }
  return {""};
}

CalibrationRecords load_catalog_calibration_records(const DatasetEntry& entry, const std::filesystem::path& root,
                                                    const std::string& part) {
  if (!is_calibration_dataset(entry)) {
    throw UsageError("dataset " + entry.name + " is not a calibration data set");
  }
  const auto parts = calibration_dataset_parts(entry);
  if (std::find(parts.begin(), parts.end(), part) == parts.end()) {
    std::string list;
    for (const auto& p : parts) list += (list.empty() ? "" : ", ") + p;
    throw UsageError("dataset " + entry.name + ": unknown part \"" + part + "\" (parts: " + list + ")");
  }
  const std::filesystem::path folder = root / entry.path;
  if (!std::filesystem::exists(folder)) {
    throw InputError(folder.string(), 0, "dataset " + entry.name + " not found (set LOCBENCH_DATA)");
  }
  CalibrationRecords d;
  if (entry.name == "censi_khepera") {
    const auto file = data_file(folder, part + ".tuple");
    d.wheel_speed_tuples = read_censi_tuples(file);
    d.source = file.string();
  } else if (entry.name == "grisetti_diffdrive") {
    const auto file = data_file(folder, "differential_drive_calibration.txt");
    d.tick_motions = read_tick_motions(file);
    d.source = file.string();
  } else {
    const auto odom = data_file(folder, "odom_motions.txt");
    const auto ref = data_file(folder, "scanmatched_motions.txt");
    d.motion_pairs = read_relative_motion_pairs(odom, ref);
    d.source = odom.string() + " + " + ref.string();
  }
  return d;
}

}  // namespace locbench::catalog
