#include "datasets/io/log_loader.h"

#include <cctype>
#include <optional>
#include <string_view>

#include "core/ascii.h"
#include "core/errors.h"
#include "datasets/io/bag_log.h"
#include "datasets/io/carmen_reader.h"
#include "datasets/io/dataset_name.h"
#include "datasets/io/mrclam_reader.h"
#include "datasets/io/relations_reader.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {
namespace {

constexpr const char* kAccepted =
    "accepted: a CARMEN log (.clf, .log or .carmen, optionally .gz), a relations file "
    "(.relations or .relations.gz), an MRCLAM dataset folder with an optional #robotN suffix, a ROS 1 bag (.bag) or "
    "a ROS 2 bag (a folder with metadata.yaml and .db3 or .mcap files, or one .db3 or .mcap file), topics chosen by "
    "#odom=…,truth=…,scan=…";

// The extension that names the format: ".clf" for "aces.clf.gz".
std::string format_extension(const std::filesystem::path& path) {
  std::filesystem::path p = path.filename();
  if (ascii_lowercase(p.extension().string()) == ".gz") p = p.stem();
  return ascii_lowercase(p.extension().string());
}

// "#robotN" at the end of a spec → N; nullopt if there is no such suffix.
std::optional<int> robot_suffix(const std::string& spec, std::size_t hash) {
  const std::string suffix = ascii_lowercase(spec.substr(hash + 1));
  if (suffix.rfind("robot", 0) != 0) return std::nullopt;
  std::int64_t n = 0;
  const std::string_view digits = std::string_view(suffix).substr(5);
  if (digits.empty() || digits[0] == '+' || digits[0] == '-' || !try_parse_int64(digits, n) || n < 1 || n > 1000) {
    return std::nullopt;
  }
  return static_cast<int>(n);
}

// True if the folder holds some RobotN_Odometry.dat(.gz).
bool looks_like_mrclam(const std::filesystem::path& folder) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("Robot", 0) == 0 && name.find("_Odometry.dat") != std::string::npos) return true;
  }
  return false;
}

}  // namespace

Log load_log(const std::string& spec) {
  if (const auto bag = parse_bag_spec(spec)) {
    std::error_code ec;
    if (!std::filesystem::exists(bag->path, ec)) {
      throw InputError(bag->path.string(), 0, std::string("no such file or folder (") + kAccepted + ")");
    }
    return read_bag_log(*bag);
  }
  std::filesystem::path path(spec);
  int robot = 1;
  const auto hash = spec.rfind('#');
  bool has_robot = false;
  if (hash != std::string::npos) {
    if (const auto n = robot_suffix(spec, hash)) {
      path = spec.substr(0, hash);
      robot = *n;
      has_robot = true;
    }
  }
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw InputError(path.string(), 0, std::string("no such file or folder (") + kAccepted + ")");
  }
  if (std::filesystem::is_directory(path, ec)) {
    if (!looks_like_mrclam(path)) {
      throw InputError(path.string(), 0,
                       std::string("not an MRCLAM dataset folder: no RobotN_Odometry.dat (") + kAccepted + ")");
    }
    return read_mrclam_robot(path, robot);
  }
  if (has_robot) {
    throw InputError(spec, 0, std::string("a #robotN suffix needs an MRCLAM dataset folder (") + kAccepted + ")");
  }
  const std::string ext = format_extension(path);
  if (ext == ".clf" || ext == ".log" || ext == ".carmen") return read_carmen_log(path);
  if (ext == ".relations") {
    Log log;
    log.relations = read_relations(path);
    log.name = dataset_name_from_file(path);
    log.source = path.string();
    return log;
  }
  throw InputError(path.string(), 0, std::string("unrecognised log format (") + kAccepted + ")");
}

void attach_relations(Log& log, const std::filesystem::path& relations_path) {
  log.relations = read_relations(relations_path);
}

}  // namespace locbench::io
