#pragma once
// Writers of the plain landmark formats read by landmark_reader.h: a landmark map
// ("id x y sigma_x sigma_y") and landmark observations ("t id range bearing").
#include <filesystem>
#include <string>
#include <vector>

#include "core/sensor_data.h"

namespace locbench::io {

// A '#' header, then one line per landmark `id x y sigma_x sigma_y`, numbers in the shortest
// form that reads back to the same double. Throws std::invalid_argument for a non-finite number
// or a negative σ.
std::string format_landmark_map(const std::vector<MapLandmark>& map);
// A '#' header, then one line per observation `t id range bearing`. Throws
// std::invalid_argument for a non-finite number, a negative range or times going back.
std::string format_landmark_observations(const std::vector<LandmarkReading>& observations);

// The same written atomically to `path` (gzip when it ends in .gz); InputError when the file
// cannot be written.
void write_landmark_map(const std::vector<MapLandmark>& map, const std::filesystem::path& path);
void write_landmark_observations(const std::vector<LandmarkReading>& observations, const std::filesystem::path& path);

}  // namespace locbench::io
