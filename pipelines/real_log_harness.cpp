#include "pipelines/real_log_harness.h"

#include <algorithm>
#include <cctype>
#include <future>
#include <iterator>
#include <map>
#include <mutex>
#include <set>

#include "core/errors.h"
#include "core/input_file.h"
#include "core/input_limits.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/catalog/log_spec.h"

namespace locbench::experiments {
using locbench::catalog::find_dataset;
namespace {

std::string string_field(const nlohmann::json& item, const char* key, const std::string& where) {
  if (!item.contains(key)) return {};
  const nlohmann::json& v = item.at(key);
  if (!v.is_string() || v.get<std::string>().empty()) {
    throw UsageError(where + "." + key + ": expected a non-empty string (a file path)");
  }
  return v.get<std::string>();
}

// A dataset name that is one word of a result name: no '/', no "..", no control characters.
bool is_plain_name(const std::string& name) {
  if (name.empty() || name.front() == '.' || name.size() > 128) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':' || c == '+';
  });
}

// The log of a spec may be a file or an MRCLAM folder (load_log judges which).
void require_log(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, 0, "cannot open the log (no such file or folder)");
}

// Through the input opener: a missing file, a folder, a FIFO or a device is named as such.
void require_file(const std::string& path, const char* what) {
  InputFile(path, what, static_cast<std::uint64_t>(limits::kInputFileBytes.max));
}

// Where the "#robotN" suffix of a load_log spec starts ("folder#robot2" → 6), npos without one.
std::size_t robot_suffix_at(const std::string& spec) {
  const std::size_t hash = spec.rfind('#');
  if (hash == std::string::npos) return hash;
  std::string suffix = spec.substr(hash + 1, 5);
  for (char& c : suffix) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return suffix == "robot" ? hash : std::string::npos;
}

// The file part of a load_log spec ("folder#robot2" → "folder", "run.bag#odom=/o" → "run.bag").
std::string file_of(const std::string& spec) { return catalog::log_spec_file(spec).string(); }

constexpr const char* kKeys[] = {"name", "log", "relations", "ground_truth", "landmark_map", "landmark_observations"};

}  // namespace

std::vector<RealLogSpec> real_log_specs(const nlohmann::json& datasets, const std::string& experiment) {
  if (!datasets.is_array()) {
    throw UsageError(experiment +
                     ": datasets: expected an array of catalog names or "
                     "{\"name\", \"log\", \"relations\", \"ground_truth\"} objects");
  }
  std::vector<RealLogSpec> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < datasets.size(); ++i) {
    const nlohmann::json& item = datasets[i];
    const std::string where = experiment + ": datasets[" + std::to_string(i) + "]";
    RealLogSpec s;
    if (item.is_string()) {
      s.name = item.get<std::string>();
    } else if (item.is_object()) {
      for (const auto& [key, value] : item.items()) {
        (void)value;
        if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys)) {
          throw UsageError(where + ": unknown key \"" + key +
                           "\" (expected name, log, relations, ground_truth, landmark_map, landmark_observations)");
        }
      }
      s.name = string_field(item, "name", where);
      s.log = string_field(item, "log", where);
      s.relations = string_field(item, "relations", where);
      s.ground_truth = string_field(item, "ground_truth", where);
      s.landmark_map = string_field(item, "landmark_map", where);
      s.landmark_observations = string_field(item, "landmark_observations", where);
      s.from_catalog = s.log.empty();
      if (s.from_catalog && (!s.relations.empty() || !s.ground_truth.empty() || !s.landmark_map.empty() ||
                             !s.landmark_observations.empty())) {
        throw UsageError(where + ": relations, ground_truth or landmark files given without a \"log\"");
      }
    } else {
      throw UsageError(where + ": expected a catalog name or an object, found a " + std::string(item.type_name()));
    }
    if (s.name.empty()) throw UsageError(where + ": needs a \"name\" (the key of its results)");
    if (!is_plain_name(s.name)) {
      throw UsageError(where + ": dataset name \"" + s.name +
                       "\": expected letters, digits and _ - . : + only, not starting with a dot (it is the "
                       "middle part of result names, method/dataset/variant, and never a path)");
    }
    if (s.from_catalog && !find_dataset(s.name)) {
      throw UsageError(where + ": unknown dataset \"" + s.name + "\" (see `locbench list`, or give a \"log\" file)");
    }
    if (!s.from_catalog) {
      require_log(file_of(s.log));
      if (!s.relations.empty()) require_file(s.relations, "relations file");
      if (!s.ground_truth.empty()) require_file(s.ground_truth, "ground-truth file");
      if (!s.landmark_map.empty()) require_file(s.landmark_map, "landmark map");
      if (!s.landmark_observations.empty()) require_file(s.landmark_observations, "landmark observations file");
    }
    if (!names.insert(s.name).second) {
      throw UsageError(where + ": dataset name \"" + s.name + "\" is used twice");
    }
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<std::string> real_log_names(const std::vector<RealLogSpec>& specs) {
  std::vector<std::string> out;
  for (const auto& s : specs) out.push_back(s.name);
  return out;
}

namespace {

LoadedRealLog read_real_log(const RealLogSpec& spec, const std::filesystem::path& data_root) {
  LoadedRealLog out;
  const catalog::LogSpec load{spec.name,         spec.from_catalog ? spec.name : spec.log,
                              spec.relations,    spec.ground_truth,
                              spec.landmark_map, spec.landmark_observations};
  try {
    auto [log, dataset, entry] = catalog::load_log_spec(load, data_root);
    out.log = std::move(log);
    out.dataset = std::move(dataset);
  } catch (const InputError& e) {
    if (!spec.from_catalog) throw;
    out.status = "failed";
    out.reason = e.what();
  }
  return out;
}

// The catalog's logs as read once in this process: several experiments of a suite read the same
// log, and the catalog's data are read in place, never written. Keyed by the log's file (or
// folder) with its size and modification time, so a log that changes is read again; a user's
// files are read at every call. The read itself starts no parallel work, so a thread that waits
// here for another's read can never be the one that read is waiting for.
class CatalogLogCache {
 public:
  LoadedRealLog load(const RealLogSpec& spec, const std::filesystem::path& data_root, const std::string& path) {
    std::shared_future<LoadedRealLog> entry;
    std::promise<LoadedRealLog> promise;
    {
      const std::lock_guard lock(mutex_);
      const auto [it, inserted] = entries_.try_emplace(key(spec, path), promise.get_future().share());
      entry = it->second;
      if (!inserted) return entry.get();  // waits while another thread reads it
    }
    try {
      promise.set_value(read_real_log(spec, data_root));  // a catalog log's InputError is a "failed" value
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
    return entry.get();
  }

 private:
  static std::string key(const RealLogSpec& spec, const std::string& path) {
    const std::filesystem::path file = catalog::log_spec_file(path);
    std::error_code ec;
    const auto size = std::filesystem::is_regular_file(file, ec) ? std::filesystem::file_size(file, ec) : 0;
    const auto stamp = std::filesystem::last_write_time(file, ec).time_since_epoch().count();
    return spec.name + "\n" + path + "\n" + std::to_string(size) + "\n" + std::to_string(stamp);
  }
  std::mutex mutex_;
  std::map<std::string, std::shared_future<LoadedRealLog>> entries_;
};

}  // namespace

LoadedRealLog load_real_log(const RealLogSpec& spec, const std::filesystem::path& data_root) {
  if (!spec.from_catalog) return read_real_log(spec, data_root);
  const std::string path = catalog::catalog_log_spec(*find_dataset(spec.name), data_root);
  if (!std::filesystem::exists(catalog::log_spec_file(path))) {
    LoadedRealLog out;
    out.status = "skipped";
    out.reason = "dataset not found at " + path + " (set LOCBENCH_DATA)";
    out.dataset.path = path;
    return out;
  }
  static CatalogLogCache cache;
  return cache.load(spec, data_root, path);
}

void for_each_real_log(
    const std::vector<RealLogSpec>& specs, const RunOptions& options, const std::string& case_prefix,
    reports::ExperimentResults& out,
    const std::function<void(const RealLogSpec&, const LoadedRealLog&, reports::ExperimentResults&)>& run) {
  for (std::size_t i = 0; i < specs.size(); ++i) {
    options.report_progress(static_cast<double>(i) / static_cast<double>(specs.size()));
    const LoadedRealLog loaded = load_real_log(specs[i], options.data_root);
    if (loaded.status != "ok") {
      out.cases.push_back({case_prefix + "/" + specs[i].name, loaded.status, loaded.reason});
      continue;
    }
    out.datasets.push_back(loaded.dataset);
    run(specs[i], loaded, out);
  }
  options.report_progress(1.0);
}

std::optional<nlohmann::json> real_log_cli_override(const std::string& log, const std::string& relations,
                                                    const std::string& ground_truth, const std::string& landmark_map,
                                                    const std::string& landmark_observations) {
  if (log.empty()) return std::nullopt;
  std::filesystem::path file(file_of(log));
  if (file.filename().empty()) file = file.parent_path();  // "…/MRCLAM_Dataset6/#robot2"
  std::string name = file.filename().string();
  name = name.substr(0, name.find('.'));
  if (name.empty()) name = "log";
  const std::size_t hash = robot_suffix_at(log);
  if (hash != std::string::npos) name += "_" + log.substr(hash + 1);  // "MRCLAM_Dataset6_robot2"
  for (char& c : name) {  // a plain name (is_plain_name) from any file name: "my log" → "my_log"
    if (!is_plain_name(std::string(1, c))) c = '_';
  }
  nlohmann::json item = {{"name", name}, {"log", log}};
  if (!relations.empty()) item["relations"] = relations;
  if (!ground_truth.empty()) item["ground_truth"] = ground_truth;
  if (!landmark_map.empty()) item["landmark_map"] = landmark_map;
  if (!landmark_observations.empty()) item["landmark_observations"] = landmark_observations;
  return nlohmann::json{{"datasets", nlohmann::json::array({item})}};
}

bool takes_real_logs(const nlohmann::json& default_config) {
  return default_config.is_object() && default_config.contains("datasets") && default_config.at("datasets").is_array();
}

}  // namespace locbench::experiments
