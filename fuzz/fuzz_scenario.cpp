// Scenario and world JSON (simulate, match --map), with the input limits checked.
#include "core/json_file.h"
#include "core/json_options.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/worlds.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  const std::string t = fuzz::text(data, size);
  fuzz::accept_or_reject([&] { sim::scenario_from_json(parse_json_text(t, "fuzz.json"), "fuzz.json"); });
  return fuzz::accept_or_reject([&] { sim::world_from_json(parse_json_text(t, "fuzz.json"), "fuzz.json"); });
}
