#include "reports/shard_report.h"

#include "core/output_file.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>

#include "core/errors.h"
#include "core/json_file.h"
#include "reports/report_json.h"

namespace locbench::reports {
namespace {
using nlohmann::json;

template <typename T>
T get(const json& j, const char* key, const std::string& source) {
  if (!j.is_object() || !j.contains(key)) {
    throw InputError(source, 0, std::string("shard report: missing field \"") + key + "\"");
  }
  try {
    return j.at(key).get<T>();
  } catch (const json::exception&) {
    throw InputError(source, 0, std::string("shard report: field \"") + key + "\" has the wrong type");
  }
}

}  // namespace

// j with every value for which replace() returns a replacement replaced, the others (arrays and
// objects recursively) kept.
template <typename Replace>
json map_values(const json& j, const Replace& replace) {
  if (std::optional<json> r = replace(j)) return *r;
  if (j.is_array() || j.is_object()) {
    json out = j;
    for (auto it = out.begin(); it != out.end(); ++it) *it = map_values(*it, replace);
    return out;
  }
  return j;
}

json encode_nonfinite(const json& j) {
  return map_values(j, [](const json& v) -> std::optional<json> {
    if (!v.is_number_float() || std::isfinite(v.get<double>())) return std::nullopt;
    const double x = v.get<double>();
    return json{{"nonfinite", std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf")}};
  });
}

json decode_nonfinite(const json& j) {
  return map_values(j, [](const json& v) -> std::optional<json> {
    if (!(v.is_object() && v.size() == 1 && v.contains("nonfinite") && v["nonfinite"].is_string())) {
      return std::nullopt;
    }
    const std::string& s = v["nonfinite"].get_ref<const std::string&>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
    return std::nullopt;
  });
}

json canonical_record(const json& record) { return decode_nonfinite(json::parse(encode_nonfinite(record).dump())); }

json to_json(const ShardReport& s) {
  json records = json::array();
  for (const ShardRecord& r : s.records) {
    records.push_back({{"task", r.task}, {"record", encode_nonfinite(r.record)}});
  }
  return {{"schema", kShardSchema},
          {"context", provenance_to_json(s.provenance)},
          {"experiment", {{"name", s.experiment}, {"description", s.description}}},
          {"configuration", s.configuration},
          {"seed", s.seed},
          {"runs", s.runs ? json(*s.runs) : json(nullptr)},
          {"shard", {{"index", s.index}, {"count", s.count}, {"tasks", s.tasks}}},
          {"records", records}};
}

ShardReport shard_report_from_json(const json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, 0, "expected a JSON object (a locbench shard)");
  const auto schema = get<std::string>(j, "schema", source);
  if (schema != kShardSchema) {
    throw InputError(source, 0,
                     "expected schema \"" + std::string(kShardSchema) + "\", found \"" + schema + "\"" +
                         (schema == kReportSchema ? " (a full report, not a shard)" : ""));
  }
  ShardReport s;
  s.provenance = provenance_from_json(get<json>(j, "context", source), source);
  const json e = get<json>(j, "experiment", source);
  s.experiment = get<std::string>(e, "name", source);
  s.description = get<std::string>(e, "description", source);
  s.configuration = get<json>(j, "configuration", source);
  s.seed = get<std::uint64_t>(j, "seed", source);
  const json runs = get<json>(j, "runs", source);
  if (!runs.is_null()) s.runs = get<int>(j, "runs", source);
  const json sh = get<json>(j, "shard", source);
  s.index = get<int>(sh, "index", source);
  s.count = get<int>(sh, "count", source);
  s.tasks = get<int>(sh, "tasks", source);
  for (const json& r : get<json>(j, "records", source)) {
    s.records.push_back({get<int>(r, "task", source), decode_nonfinite(get<json>(r, "record", source))});
  }
  return s;
}

std::filesystem::path write_shard_report(const ShardReport& shard, const std::filesystem::path& path) {
  write_file_atomically(path, to_json(shard).dump(1) + "\n");
  return path;
}

ShardReport read_shard_report(const std::filesystem::path& path) {
  return shard_report_from_json(read_json_file(path, "shard report (JSON)"), path.string());
}

}  // namespace locbench::reports
