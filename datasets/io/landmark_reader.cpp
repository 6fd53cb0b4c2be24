#include "datasets/io/landmark_reader.h"

#include <cstdint>
#include <limits>
#include <map>
#include <set>

#include "core/errors.h"
#include "core/input_limits.h"
#include "datasets/io/data_lines.h"
#include "datasets/io/mrclam_reader.h"
#include "datasets/io/number_format.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {
namespace {

int parse_landmark_id(std::string_view token, std::string_view field, const FieldContext& ctx) {
  const std::int64_t v = parse_int64(token, field, ctx);
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
    fail_input(ctx,
               std::string(field) + ": expected an integer in −2147483648..2147483647, found " + quote_token(token));
  }
  return static_cast<int>(v);
}

double parse_sigma(std::string_view token, std::string_view field, const FieldContext& ctx) {
  const double v = parse_finite(token, field, ctx);
  if (v < 0.0)
    fail_input(ctx, std::string(field) + ": expected a non-negative number [m], found " + quote_token(token));
  return v;
}

std::vector<MapLandmark> read_map_lines(LineReader& reader, std::string_view id_name) {
  std::vector<MapLandmark> out;
  std::map<int, std::size_t> line_of_id;
  for_each_data_line(reader, [&](const std::vector<std::string_view>& f, const FieldContext& ctx) {
    if (f.size() != 3 && f.size() != 5) {
      fail_input(ctx, "expected 3 fields (" + std::string(id_name) + " x y) or 5 (" + std::string(id_name) +
                          " x y sigma_x sigma_y), found " + std::to_string(f.size()));
    }
    limits::check(static_cast<double>(out.size() + 1), limits::kLandmarkMapSize, reader.source(), "landmarks");
    MapLandmark m;
    m.id = parse_landmark_id(f[0], id_name, ctx);
    m.x = parse_finite(f[1], "x", ctx);
    m.y = parse_finite(f[2], "y", ctx);
    if (f.size() == 5) {
      m.sigma_x = parse_sigma(f[3], "sigma_x", ctx);
      m.sigma_y = parse_sigma(f[4], "sigma_y", ctx);
    }
    const auto [it, fresh] = line_of_id.emplace(m.id, ctx.line);
    if (!fresh) {
      fail_input(ctx, std::string(id_name) + ": " + std::to_string(m.id) + " is listed twice (first at line " +
                          std::to_string(it->second) + "); landmark ids must be unique");
    }
    out.push_back(m);
  });
  return out;
}

LandmarkObservations read_observation_lines(LineReader& reader) {
  LandmarkObservations out;
  for_each_data_line(reader, 4, [&](const std::vector<std::string_view>& f, const FieldContext& ctx) {
    limits::check(static_cast<double>(out.readings.size() + 1), limits::kLandmarkObservations, reader.source(),
                  "observations");
    LandmarkReading r;
    r.t = parse_finite(f[0], "time", ctx);
    r.subject = parse_landmark_id(f[1], "id", ctx);
    r.range = parse_finite(f[2], "range", ctx);
    r.bearing = parse_finite(f[3], "bearing", ctx);
    if (r.range < 0.0) fail_input(ctx, "range: expected a non-negative number [m], found " + quote_token(f[2]));
    if (!out.readings.empty() && r.t < out.readings.back().t) {
      fail_input(ctx, "time: " + number_text(r.t) + " goes back: line " + std::to_string(out.lines.back()) +
                          " has time " + number_text(out.readings.back().t) + "; times must not decrease");
    }
    out.readings.push_back(r);
    out.lines.push_back(ctx.line);
  });
  return out;
}

// Time of the log's first odometry record (its first encoder record without odometry).
const double* first_motion_time(const Log& log) {
  if (!log.odometry.empty()) return &log.odometry.front().t;
  if (!log.encoders.empty()) return &log.encoders.front().t;
  return nullptr;
}

void check_unique_ids(const std::vector<MapLandmark>& map, const std::string& map_file) {
  std::set<int> ids;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (!ids.insert(map[i].id).second) {
      throw InputError(map_file, 0,
                       "id: " + std::to_string(map[i].id) + " is listed twice (landmark " + std::to_string(i + 1) +
                           "); landmark ids must be unique");
    }
  }
}

}  // namespace

std::vector<MapLandmark> read_landmark_map(const std::filesystem::path& path, std::string_view id_name) {
  return read_lines_of(path, [&](LineReader& r) { return read_map_lines(r, id_name); });
}

std::vector<MapLandmark> parse_landmark_map(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, [](LineReader& r) { return read_map_lines(r, "id"); });
}

LandmarkObservations read_landmark_observations(const std::filesystem::path& path) {
  return read_lines_of(path, read_observation_lines);
}

LandmarkObservations parse_landmark_observations(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, read_observation_lines);
}

void attach_landmarks(Log& log, std::vector<MapLandmark> map, LandmarkObservations observations,
                      const std::string& map_file, const std::string& observations_file) {
  check_unique_ids(map, map_file);
  std::set<int> ids;
  for (const MapLandmark& m : map) ids.insert(m.id);
  const double* t0 = first_motion_time(log);
  const auto& readings = observations.readings;
  for (std::size_t i = 0; i < readings.size(); ++i) {
    const std::size_t line = i < observations.lines.size() ? observations.lines[i] : 0;
    if (!ids.count(readings[i].subject)) {
      const std::string when = line > 0 ? "" : " (observed at t = " + number_text(readings[i].t) + " s)";
      throw InputError(
          observations_file, line,
          "id: " + std::to_string(readings[i].subject) + when + " is not a landmark of the map " + map_file);
    }
    if (t0 && readings[i].t < *t0) {
      throw InputError(observations_file, line,
                       "time: " + number_text(readings[i].t) + " before the first odometry record at " +
                           number_text(*t0) + " of " + log.source);
    }
  }
  log.landmark_map = std::move(map);
  log.landmarks = std::move(observations.readings);
}

void attach_landmark_files(Log& log, const std::filesystem::path& map_file,
                           const std::filesystem::path& observations_file) {
  if (map_file.empty() && observations_file.empty()) return;
  if (!observations_file.empty()) {
    if (map_file.empty() && log.landmark_map.empty()) {
      throw InputError(observations_file.string(), 0,
                       "landmark observations need a landmark map (--landmark-map / \"landmark_map\"), and " +
                           log.source + " has none");
    }
    std::vector<MapLandmark> map = map_file.empty() ? log.landmark_map : read_landmark_map(map_file);
    const std::string map_name = map_file.empty() ? log.source : map_file.string();
    attach_landmarks(log, std::move(map), read_landmark_observations(observations_file), map_name,
                     observations_file.string());
    return;
  }
  // A new map for the log's own observations: those of robots are not landmarks.
  std::vector<MapLandmark> map = read_landmark_map(map_file);
  const std::set<int> robots = mrclam_robot_subjects(log);
  std::vector<LandmarkReading> all = log.landmarks;
  LandmarkObservations own;
  for (const LandmarkReading& r : all) {
    if (!robots.count(r.subject)) own.readings.push_back(r);
  }
  attach_landmarks(log, std::move(map), std::move(own), map_file.string(), log.source);
  log.landmarks = std::move(all);
}

}  // namespace locbench::io
