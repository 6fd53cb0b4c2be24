#pragma once
// Reading the catalog's calibration data sets (censi_khepera, grisetti_diffdrive,
// stachniss_ls_calib) as their records; algorithms/calibration's calibration_data_from_records
// makes ML-calibration samples of them. They are not logs: load_catalog_dataset names this
// function for them.
#include <filesystem>
#include <string>
#include <vector>

#include "core/calibration_records.h"
#include "datasets/catalog/dataset_catalog.h"

namespace locbench::catalog {

// True for the entries read by load_catalog_calibration_records.
bool is_calibration_dataset(const DatasetEntry& entry);

// The parts of a calibration data set: censi_khepera's tuple files "lstraight", "lstraight_0",
// "lstraight_1", "lstraight_2", "l90", "l90_0", "l90_1", "l90_2" (configurations A and B of
// Censi et al. and their three subsets); {""} for the others.
std::vector<std::string> calibration_dataset_parts(const DatasetEntry& entry);

// Reads `part` of a calibration data set from under `root` (files plain or .gz):
// - censi_khepera: <part>.tuple → wheel_speed_tuples;
// - grisetti_diffdrive: differential_drive_calibration.txt → tick_motions;
// - stachniss_ls_calib: odom_motions.txt + scanmatched_motions.txt → motion_pairs.
// CalibrationRecords::source names the file(s). Throws UsageError for an entry that is not a
// calibration data set or an unknown part (listing the parts), InputError for missing or
// malformed files.
CalibrationRecords load_catalog_calibration_records(const DatasetEntry& entry, const std::filesystem::path& root,
                                                    const std::string& part = "");

}  // namespace locbench::catalog
