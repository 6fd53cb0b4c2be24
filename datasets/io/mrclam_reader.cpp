#include "datasets/io/mrclam_reader.h"

#include <cctype>
#include <map>
#include <optional>
#include <vector>

#include "core/dead_reckoning.h"
#include "core/errors.h"
#include "datasets/io/data_lines.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {
namespace {

// folder/name or folder/name.gz, whichever exists.
std::optional<std::filesystem::path> find_data_file(const std::filesystem::path& folder, const std::string& name) {
  for (const auto& candidate : {folder / name, folder / (name + ".gz")}) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
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

}  // namespace

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

  std::map<int, int> subject_of_barcode;
  const auto barcode_file = find_data_file(folder, "Barcodes.dat");
  if (barcode_file) {
    for_each_row(*barcode_file, 2, false, [&](const auto& f, const FieldContext& ctx) {
      const int subject = parse_id(f[0], "subject", ctx);
      subject_of_barcode[parse_id(f[1], "barcode", ctx)] = subject;
    });
  }
  log.params[std::string(kParamMrclamMeasurementIds)] = barcode_file ? "subject" : "barcode";
  std::size_t unknown = 0;
  for_each_row(measurement_file, 4, true, [&](const auto& f, const FieldContext& ctx) {
    LandmarkReading r;
    r.t = parse_finite(f[0], "time", ctx);
    const int barcode = parse_id(f[1], "barcode", ctx);
    r.range = parse_finite(f[2], "range", ctx);
    r.bearing = parse_finite(f[3], "bearing", ctx);
    if (r.range < 0.0) fail_input(ctx, "range: expected a non-negative number [m], found " + quote_token(f[2]));
    if (barcode_file) {
      const auto it = subject_of_barcode.find(barcode);
      if (it == subject_of_barcode.end()) {
        ++unknown;
        return;
      }
      r.subject = it->second;
    } else {
      r.subject = barcode;
    }
    log.landmarks.push_back(r);
  });
  if (barcode_file) log.params[std::string(kParamMrclamUnknownBarcodes)] = std::to_string(unknown);
  return log;
}

}  // namespace locbench::io
