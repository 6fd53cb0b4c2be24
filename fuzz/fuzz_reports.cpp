// Reports and shards as `report`, `gate` and `merge` read them: schema first, then the model.
#include "core/json_file.h"
#include "fuzz/fuzz_input.h"
#include "reports/report_json.h"
#include "reports/schema_validation.h"
#include "reports/shard_report.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  return fuzz::accept_or_reject([&] {
    const nlohmann::json j = parse_json_text(fuzz::text(data, size), "fuzz.json");
    if (reports::validate_report_json(j).empty()) reports::report_from_json(j, "fuzz.json");
    if (reports::validate_shard_json(j).empty()) reports::shard_report_from_json(j, "fuzz.json");
  });
}
