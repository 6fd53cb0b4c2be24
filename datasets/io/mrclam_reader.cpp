#include "datasets/io/mrclam_reader.h"

#include <cctype>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "core/dead_reckoning.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "datasets/io/data_lines.h"
#include "datasets/io/landmark_reader.h"
#include "datasets/io/number_format.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {
namespace {

// folder/name or folder/name.gz, whichever exists.
std::optional<std::filesystem::path> find_data_file(const std::filesystem::path& folder, const std::string& name) {
  for (const auto& candidate : {folder / name, folder / (name + ".gz")}) {
    std::error_code ec;
    // Whatever is there (a FIFO too): the input opener then says what it is and what was expected.
    if (std::filesystem::exists(candidate, ec)) return candidate;
  }
  return std::nullopt;
}

std::filesystem::path require_data_file(const std::filesystem::path& folder, const std::string& name) {
  if (auto p = find_data_file(folder, name)) return *p;
  throw InputError((folder / name).string(), 0, "missing MRCLAM file (looked for " + name + " and " + name + ".gz)");
}

// Calls on_row(fields, ctx) for each data line, after checking the field count and, when
// `timed`, that the first field (time) does not decrease.
template <typename OnRow>
void for_each_row(const std::filesystem::path& path, std::size_t field_count, bool timed, OnRow on_row) {
  LineReader reader(path);
  double last_t = 0.0;
  std::size_t last_line = 0;
  for_each_data_line(reader, field_count, [&](const std::vector<std::string_view>& tokens, const FieldContext& ctx) {
    if (timed) {
      const double t = parse_finite(tokens[0], "time", ctx);
      if (last_line != 0 && t < last_t) {
        fail_input(ctx,
                   "time goes back: line " + std::to_string(last_line) + " has a later time; times must not decrease");
      }
      last_t = t;
      last_line = ctx.line;
    }
    on_row(tokens, ctx);
  });
}

int parse_id(std::string_view token, std::string_view field, const FieldContext& ctx) {
  const std::int64_t v = parse_int64(token, field, ctx);
  if (v < 0 || v > 1'000'000) {
    fail_input(ctx, std::string(field) + ": expected an identifier in 0..1000000, found " + quote_token(token));
  }
  return static_cast<int>(v);
}

std::string dataset_label(const std::filesystem::path& folder) {
  std::string name = folder.filename().string();
  if (name.empty()) name = folder.parent_path().filename().string();  // "…/MRCLAM_Dataset6/"
  const std::string prefix = "MRCLAM_Dataset";
  if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size()) {
    return "mrclam" + name.substr(prefix.size());
  }
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

// "1,2,3,4,5": every N with a RobotN_Odometry.dat[.gz] in the folder, ascending.
std::string robot_subjects_text(const std::filesystem::path& folder) {
  std::set<int> robots;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    const std::size_t end = name.find("_Odometry.dat");
    if (name.rfind("Robot", 0) != 0 || end == std::string::npos || end <= 5) continue;
    const std::string rest = name.substr(end);
    if (rest != "_Odometry.dat" && rest != "_Odometry.dat.gz") continue;
    std::int64_t n = 0;
    const std::string_view digits = std::string_view(name).substr(5, end - 5);
    if (digits[0] >= '0' && digits[0] <= '9' && try_parse_int64(digits, n) && n >= 1 && n <= 1'000'000) {
      robots.insert(static_cast<int>(n));
    }
  }
  std::string out;
  for (int r : robots) out += (out.empty() ? "" : ",") + std::to_string(r);
  return out;
}

// RobotN_Measurement.dat → log.landmarks (after the odometry and the landmark map are read).
void read_measurements(const std::filesystem::path& folder, const std::filesystem::path& measurement_file, Log& log) {
  std::map<int, int> subject_of_barcode;
  const auto barcode_file = find_data_file(folder, "Barcodes.dat");
  if (barcode_file) {
    for_each_row(*barcode_file, 2, false, [&](const auto& f, const FieldContext& ctx) {
      const int subject = parse_id(f[0], "subject", ctx);
      subject_of_barcode[parse_id(f[1], "barcode", ctx)] = subject;
    });
  } else if (!log.landmark_map.empty()) {
    throw InputError((folder / "Barcodes.dat").string(), 0,
                     "missing MRCLAM file: Landmark_Groundtruth.dat lists subjects, and the measurements' barcodes "
                     "need Barcodes.dat to name them");
  }
  log.params[std::string(kParamMrclamMeasurementIds)] = barcode_file ? "subject" : "barcode";
  std::set<int> known;  // map landmarks and robots; empty: no check (no map)
  if (!log.landmark_map.empty()) {
    known = mrclam_robot_subjects(log);
    for (const MapLandmark& m : log.landmark_map) known.insert(m.id);
  }
  const double* first_odometry = log.odometry.empty() ? nullptr : &log.odometry.front().t;
  std::size_t total = 0, unknown = 0, first_unknown_line = 0;
  int first_unknown_barcode = 0;
  for_each_row(measurement_file, 4, true, [&](const auto& f, const FieldContext& ctx) {
    limits::check(static_cast<double>(++total), limits::kLandmarkObservations, ctx.file, "measurements");
    LandmarkReading r;
    r.t = parse_finite(f[0], "time", ctx);
    const int barcode = parse_id(f[1], "barcode", ctx);
    r.range = parse_finite(f[2], "range", ctx);
    r.bearing = parse_finite(f[3], "bearing", ctx);
    if (r.range < 0.0) fail_input(ctx, "range: expected a non-negative number [m], found " + quote_token(f[2]));
    if (first_odometry && r.t < *first_odometry) {
      fail_input(ctx,
                 "time: " + number_text(r.t) + " before the first odometry record at " + number_text(*first_odometry));
    }
    r.subject = barcode;
    if (barcode_file) {
      const auto it = subject_of_barcode.find(barcode);
      if (it == subject_of_barcode.end()) {
        if (unknown++ == 0) {
          first_unknown_line = ctx.line;
          first_unknown_barcode = barcode;
        }
        return;
      }
      r.subject = it->second;
    }
    if (!known.empty() && !known.count(r.subject)) {
      fail_input(ctx, "subject: " + std::to_string(r.subject) + " (barcode " + std::to_string(barcode) +
                          ") is neither a landmark of Landmark_Groundtruth.dat nor a robot (robots: " +
                          log.params[std::string(kParamMrclamRobotSubjects)] + ")");
    }
    log.landmarks.push_back(r);
  });
  // Camera misreads: a few unknown barcodes are dropped (dataset 6: at most 3 of 2399); more
  // than 1% of the measurements means the wrong Barcodes.dat.
  if (unknown * 100 > total) {
    throw InputError(measurement_file.string(), first_unknown_line,
                     "barcode: " + std::to_string(first_unknown_barcode) + " is not in Barcodes.dat, and " +
                         std::to_string(unknown) + " of " + std::to_string(total) +
                         " measurements have unknown barcodes: more than the 1% the reader drops as camera misreads");
  }
  if (barcode_file) log.params[std::string(kParamMrclamUnknownBarcodes)] = std::to_string(unknown);
}

}  // namespace

std::set<int> mrclam_robot_subjects(const Log& log) {
  std::set<int> out;
  const auto it = log.params.find(std::string(kParamMrclamRobotSubjects));
  if (it == log.params.end()) return out;
  std::string_view rest = it->second;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    std::int64_t n = 0;
    if (try_parse_int64(rest.substr(0, comma), n)) out.insert(static_cast<int>(n));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return out;
}

Log read_mrclam_robot(const std::filesystem::path& folder, int robot) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    throw InputError(folder.string(), 0, "expected an MRCLAM dataset folder");
  }
  if (robot < 1) {
    throw InputError(folder.string(), 0, "robot number must be 1 or more, got " + std::to_string(robot));
  }
  const std::string stem = "Robot" + std::to_string(robot) + "_";
  const auto odometry_file = require_data_file(folder, stem + "Odometry.dat");
  const auto truth_file = require_data_file(folder, stem + "Groundtruth.dat");
  const auto measurement_file = require_data_file(folder, stem + "Measurement.dat");

  Log log;
  log.name = dataset_label(folder) + "/robot" + std::to_string(robot);
  log.source = folder.string() + "#robot" + std::to_string(robot);
  log.params[std::string(kParamMrclamRobot)] = std::to_string(robot);

  for_each_row(truth_file, 4, true, [&](const auto& f, const FieldContext& ctx) {
    log.truth.push_back(
        {parse_finite(f[0], "time", ctx),
         Pose2(parse_finite(f[1], "x", ctx), parse_finite(f[2], "y", ctx), parse_finite(f[3], "orientation", ctx)),
         Pose2()});
  });

  for_each_row(odometry_file, 3, true, [&](const auto& f, const FieldContext& ctx) {
    OdometryReading r;
    r.t = parse_finite(f[0], "time", ctx);
    r.tv = parse_finite(f[1], "forward velocity", ctx);
    r.rv = parse_finite(f[2], "angular velocity", ctx);
    log.odometry.push_back(r);
  });
  if (!log.odometry.empty()) {
    Pose2 start;
    if (!log.truth.empty()) {
      const double t0 = log.odometry.front().t;
      if (const auto p = interpolate_truth(log, t0)) {
        start = *p;
      } else {
        start = t0 < log.truth.front().t ? log.truth.front().pose : log.truth.back().pose;
      }
    }
    const Trajectory traj = dead_reckon_velocities(log.odometry, start);
    for (std::size_t i = 0; i < log.odometry.size(); ++i) log.odometry[i].pose = traj.poses()[i].pose;
  }

  log.params[std::string(kParamMrclamRobotSubjects)] = robot_subjects_text(folder);
  if (const auto map_file = find_data_file(folder, "Landmark_Groundtruth.dat")) {
    log.landmark_map = read_landmark_map(*map_file, "subject");
  }
  read_measurements(folder, measurement_file, log);
  return log;
}

}  // namespace locbench::io
