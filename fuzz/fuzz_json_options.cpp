// The JSON-option layer: user options merged over the defaults (--options, --config, --set) and
// read into every laser matcher's option structs.
#include "core/json_file.h"
#include "datasets/sim/worlds.h"
#include "experiment_framework/experiment.h"
#include "fuzz/fuzz_input.h"
#include "pipelines/laser_matchers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  return fuzz::accept_or_reject([&] {
    const nlohmann::json user = parse_json_text(fuzz::text(data, size), "fuzz.json");
    const nlohmann::json options = experiments::merge_config(experiments::default_matcher_options(), user);
    static const LineMap map = sim::room_world();
    experiments::make_matchers({"eap", "eap_indexed", "split_and_merge", "agglomerative", "rwht"}, options, &map);
  });
}
