#pragma once
// The real datasets locbench knows, where they sit under the data root, and how to load them.
#include <filesystem>
#include <string>
#include <vector>

#include "core/log.h"

namespace locbench::catalog {

struct DatasetEntry {
  std::string name;       // short stable name used in result keys, e.g. "aces"
  std::string path;       // relative to the data root
  std::string relations;  // relative path of reference relations, or empty
  std::string description;
  // Empty when `load_catalog_dataset` can read it; otherwise what reads it (a function, or the
  // issue that brings its reader). The calibration data sets (censi_khepera, grisetti_diffdrive,
  // stachniss_ls_calib) are read by load_catalog_calibration_records (calibration_catalog.h).
  std::string reader_pending;
};

// Every dataset of ../shared/datasets (see its README), in a fixed order.
const std::vector<DatasetEntry>& dataset_catalog();
// The entry called `name`; nullptr when there is none.
const DatasetEntry* find_dataset(const std::string& name);

// Loads an entry (with its relations attached) from under `root`; InputError if absent or
// malformed, UsageError if no reader exists for it yet.
Log load_catalog_dataset(const DatasetEntry& entry, const std::filesystem::path& root);

}  // namespace locbench::catalog
