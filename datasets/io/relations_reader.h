#pragma once
// Reader of Freiburg SLAM-benchmark relation files: "t1 t2 x y z roll pitch yaw" per line.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/sensor_data.h"

namespace locbench::io {

// Reads a .relations file (plain or gzip): each line becomes Relation{t1, t2, Pose2(x, y, yaw)};
// z, roll and pitch must be numbers and are ignored. '#' comments and blank lines are skipped.
// Throws InputError (file, line, expectation) on malformed or unreadable input.
std::vector<Relation> read_relations(const std::filesystem::path& path);

// The same for text in memory; `source_name` stands for the file name in errors.
std::vector<Relation> parse_relations(std::string_view text, const std::string& source_name);

}  // namespace locbench::io
