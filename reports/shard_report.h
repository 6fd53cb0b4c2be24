#pragma once
// A shard report: what one machine of a batch job computed for one experiment — the per-task
// records of its shard (`locbench run EXPERIMENT --shard K/N`), not results. `locbench merge`
// checks that the shards belong together and rebuilds the full report from all records
// through the experiment's own summary step. Schema: reports/shard.schema.json
// ("locbench.shard/1").
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "reports/report.h"

namespace locbench::reports {

inline constexpr const char* kShardSchema = "locbench.shard/1";

struct ShardRecord {
  int task = 0;
  nlohmann::json record;  // the experiment's per-task record
};

struct ShardReport {
  Provenance provenance;
  std::string experiment;
  std::string description;
  nlohmann::json configuration = nlohmann::json::object();  // as given: defaults + overrides
  std::uint64_t seed = 1;
  std::optional<int> runs;           // --runs, when given
  int index = 1;                     // K (1-based)
  int count = 1;                     // N
  int tasks = 0;                     // tasks of the whole experiment
  std::vector<ShardRecord> records;  // this shard's tasks, ascending
};

nlohmann::json to_json(const ShardReport& shard);
// InputError naming `source` on a missing or mistyped field.
ShardReport shard_report_from_json(const nlohmann::json& j, const std::string& source);
std::filesystem::path write_shard_report(const ShardReport& shard, const std::filesystem::path& path);
ShardReport read_shard_report(const std::filesystem::path& path);

// JSON has no NaN or infinity (nlohmann writes them as null): these replace every non-finite
// number by {"nonfinite": "nan" | "inf" | "-inf"} and back, so a record's text round-trips
// exactly.
nlohmann::json encode_nonfinite(const nlohmann::json& j);
nlohmann::json decode_nonfinite(const nlohmann::json& j);
// A record as it reads back from its JSON text (the same bytes a shard file holds), so a
// single-machine run and a merge summarise identical records.
nlohmann::json canonical_record(const nlohmann::json& record);

}  // namespace locbench::reports
