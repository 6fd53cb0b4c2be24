#pragma once
// Short dataset names derived from file names, for Log::name.
#include <filesystem>
#include <string>

namespace locbench::io {

// The file name without ".gz" and without a known format extension (.clf, .log, .carmen,
// .relations, .dat, .txt, .tum, and a ROS bag's .bag or .db3): "…/aces.from_bag.clf.gz" → "aces.from_bag".
std::string dataset_name_from_file(const std::filesystem::path& path);

}  // namespace locbench::io
