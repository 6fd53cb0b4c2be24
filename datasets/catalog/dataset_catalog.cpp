#include "datasets/catalog/dataset_catalog.h"

#include "core/errors.h"
#include "datasets/io/log_loader.h"

namespace locbench::catalog {
using io::attach_relations, io::load_log;

const std::vector<DatasetEntry>& dataset_catalog() {
  static const std::vector<DatasetEntry> entries = [] {
    std::vector<DatasetEntry> e;
    const std::string clf = "slam_benchmark/clf/", rel = "slam_benchmark/relations/";
    e.push_back({"aces", clf + "aces.from_bag.clf.gz", rel + "aces.relations.gz",
                 "ACES building, Pioneer + SICK LMS, 180 beams; Freiburg relations", ""});
    e.push_back({"intel", clf + "intel.from_bag.clf.gz", rel + "intel.relations.gz",
                 "Intel Research Lab, Pioneer + SICK LMS, 180 beams; Freiburg relations", ""});
    e.push_back({"mit_csail", clf + "mit-csail.clf.gz", rel + "mit-csail.relations.gz",
                 "MIT CSAIL, 361 beams, odometry only in FLASER; Freiburg relations", ""});
    for (int r = 1; r <= 5; ++r) {
      e.push_back({"mrclam6_robot" + std::to_string(r), "mrclam/MRCLAM_Dataset6#robot" + std::to_string(r), "",
                   "UTIAS MRCLAM 6, iRobot Create " + std::to_string(r) +
                       ": velocity odometry, Vicon ground truth, landmark sightings",
                   ""});
    }
    // Not logs: wheel speeds or ticks with reference motions, read as calibration samples.
    const std::string calib =
        "load_catalog_calibration_records (calibration records, not a log; calibration_catalog.h)";
    e.push_back({"censi_khepera", "calibration/censi_khepera", "",
                 "Khepera III wheel speeds + scan-matched motions (Censi et al. 2013)", calib});
    e.push_back({"grisetti_diffdrive", "calibration/grisetti_diffdrive", "",
                 "differential-drive ticks with relative reference motions", calib});
    e.push_back({"stachniss_ls_calib", "calibration/stachniss_ls_calib", "",
                 "odometry vs scan-matched relative motions", calib});
    e.push_back(
        {"breezyslam_mines", "wheel_ticks_lidar/breezyslam_mines", "", "wheel ticks + Hokuyo URG-04LX, no ground truth",
         "a scan-matching reference (not written: the log has no ground truth or compass to diagnose against)"});
    e.push_back({"kam3k_queens", "laser_scans/kam3k_queens", "", "single 541-beam SICK scans of a hallway",
                 "the laser issue (#5)"});
    return e;
  }();
  return entries;
}

const DatasetEntry* find_dataset(const std::string& name) {
  for (const DatasetEntry& e : dataset_catalog()) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

Log load_catalog_dataset(const DatasetEntry& entry, const std::filesystem::path& root) {
  if (!entry.reader_pending.empty()) {
    throw UsageError("dataset " + entry.name + ": no reader yet (arrives with " + entry.reader_pending + ")");
  }
  // An MRCLAM spec carries a "#robotN" suffix after the folder.
  const std::string spec = (root / entry.path).string();
  const std::string file = spec.substr(0, spec.find('#'));
  if (!std::filesystem::exists(file)) {
    throw InputError(file, 0, "dataset " + entry.name + " not found (set LOCBENCH_DATA)");
  }
  Log log = load_log(spec);
  log.name = entry.name;
  if (!entry.relations.empty()) attach_relations(log, root / entry.relations);
  return log;
}

}  // namespace locbench::catalog
