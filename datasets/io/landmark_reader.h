#pragma once
// Readers of the two plain landmark formats any user's log can come with: a landmark map
// ("id x y [sigma_x sigma_y]" per line) and landmark observations ("t id range bearing" per
// line), and attach_landmarks, which puts both into a Log after checking they fit it.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/log.h"
#include "core/sensor_data.h"

namespace locbench::io {

// Reads a landmark map (plain or gzip): one landmark per line, `id x y` or
// `id x y sigma_x sigma_y` — id an integer, x, y [m] finite, σ [m] finite and ≥ 0 (0 when
// absent); '#' comments and blank lines skipped. A repeated id, a malformed line or more than
// limits::kLandmarkMapSize landmarks is an InputError naming the file, line and field.
// `id_name` names the first column in errors ("subject" for MRCLAM's Landmark_Groundtruth.dat).
std::vector<MapLandmark> read_landmark_map(const std::filesystem::path& path, std::string_view id_name = "id");
// The same for text in memory; `source_name` stands for the file name in errors.
std::vector<MapLandmark> parse_landmark_map(std::string_view text, const std::string& source_name);

// Landmark observations with the line each was read from, for errors found after reading.
struct LandmarkObservations {
  std::vector<LandmarkReading> readings;
  std::vector<std::size_t> lines;  // lines[i]: 1-based line of readings[i]; empty when built in code
};

// Reads landmark observations (plain or gzip): `t id range bearing` per line — t [s], id an
// integer, range [m] ≥ 0, bearing [rad] as written (finite); times must not decrease; '#'
// comments and blank lines skipped; at most limits::kLandmarkObservations lines.
LandmarkObservations read_landmark_observations(const std::filesystem::path& path);
LandmarkObservations parse_landmark_observations(std::string_view text, const std::string& source_name);

// Puts `map` into log.landmark_map and the observations into log.landmarks (both replaced),
// after checking that the map's ids are unique, that every observation's id is in the map and
// that no observation comes before the log's first odometry record (its first encoder record
// without odometry). An InputError names `map_file` or `observations_file` and the line.
void attach_landmarks(Log& log, std::vector<MapLandmark> map, LandmarkObservations observations,
                      const std::string& map_file, const std::string& observations_file);

// Reads and attaches the files; either path may be empty:
// - no map file: the log's own map (MRCLAM's Landmark_Groundtruth.dat) is kept, and
//   observations without any map are an InputError;
// - no observations file: the log's own observations are kept and checked against the new map
//   (observations of the robots an MRCLAM log names in mrclam_robot_subjects excepted).
void attach_landmark_files(Log& log, const std::filesystem::path& map_file,
                           const std::filesystem::path& observations_file);

}  // namespace locbench::io
