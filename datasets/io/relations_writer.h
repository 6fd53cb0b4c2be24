#pragma once
// Writer of Freiburg relation files ("t1 t2 x y z roll pitch yaw", z = roll = pitch = 0).
#include <filesystem>
#include <string>
#include <vector>

#include "core/sensor_data.h"

namespace locbench::io {

// Writes one line per relation, numbers in shortest round-trip form; gzip when the path ends in
// ".gz". Throws std::invalid_argument for non-finite values, InputError if it cannot write.
void write_relations(const std::vector<Relation>& relations, const std::filesystem::path& path);

// The same text in memory.
std::string format_relations(const std::vector<Relation>& relations);

}  // namespace locbench::io
