#pragma once
// Loads any supported log from a path-like spec, choosing the reader from the name.
#include <filesystem>
#include <string>

#include "core/log.h"

namespace locbench::io {

// Accepted specs:
// - a CARMEN log file *.clf, *.log or *.carmen, optionally gzip-compressed (*.clf.gz, …);
// - a Freiburg relations file *.relations(.gz): a Log holding only the relations;
// - an MRCLAM dataset folder with an optional robot suffix: "…/MRCLAM_Dataset6#robot2"
//   (robot 1 without a suffix);
// - a ROS 1 bag *.bag or a ROS 2 sqlite3 bag (folder or .db3), topics chosen after '#':
//   "run.bag#odom=/wheel_odom,truth=/vicon/pose" (datasets/io/bag_log.h).
// Throws InputError for anything else (naming the accepted formats) and for malformed input.
Log load_log(const std::string& spec);

// Reads a relations file (plain or gzip) into log.relations, replacing any already there.
void attach_relations(Log& log, const std::filesystem::path& relations_path);

}  // namespace locbench::io
