#pragma once
// Loading the catalog's calibration data sets (censi_khepera, grisetti_diffdrive,
// stachniss_ls_calib) as ML-calibration samples. They are not logs: load_catalog_dataset names
// this function for them.
#include <filesystem>
#include <string>
#include <vector>

#include "algorithms/calibration/calibration_data.h"
#include "datasets/catalog/dataset_catalog.h"

namespace locbench::catalog {

// True for the entries loaded by load_catalog_calibration_data.
bool is_calibration_dataset(const DatasetEntry& entry);

// The parts of a calibration data set: censi_khepera's tuple files "lstraight", "lstraight_0",
// "lstraight_1", "lstraight_2", "l90", "l90_0", "l90_1", "l90_2" (configurations A and B of
// Censi et al. and their three subsets); {""} for the others.
std::vector<std::string> calibration_dataset_parts(const DatasetEntry& entry);

// Loads `part` of a calibration data set from under `root` (files plain or .gz):
// - censi_khepera: <part>.tuple → calibration_data_from_wheel_speed_tuples;
// - grisetti_diffdrive: differential_drive_calibration.txt → calibration_data_from_tick_motions;
// - stachniss_ls_calib: odom_motions.txt + scanmatched_motions.txt →
//   calibration_data_from_motion_pairs.
// CalibrationData::source names the file(s). Throws UsageError for an entry that is not a
// calibration data set or an unknown part (listing the parts), InputError for missing or
// malformed files.
calibration::CalibrationData load_catalog_calibration_data(const DatasetEntry& entry, const std::filesystem::path& root,
                                                           const std::string& part = "");

}  // namespace locbench::catalog
