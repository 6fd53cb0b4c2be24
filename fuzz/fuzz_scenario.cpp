// Scenario and world JSON (simulate, match --map), with the input limits checked; a scenario
// that is accepted and short is simulated and its log written as CARMEN text, as `simulate`
// does (an even laser.beams once failed only there). Longer ones are left to the limits
// (time per input: the fuzzer's -timeout).
#include "core/json_file.h"
#include "core/json_options.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "datasets/sim/worlds.h"
#include "fuzz/fuzz_input.h"

namespace {

// Robot time and physics steps the fuzzer simulates per input (the limits allow far more).
constexpr double kMaxSimulatedSeconds = 60.0;
constexpr double kMaxPhysicsSteps = 1e5;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  const std::string t = fuzz::text(data, size);
  fuzz::accept_or_reject([&] {
    const sim::Scenario s = sim::scenario_from_json(parse_json_text(t, "fuzz.json"), "fuzz.json");
    const double duration = sim::estimated_duration(s);
    if (duration <= kMaxSimulatedSeconds && duration / s.physics.step <= kMaxPhysicsSteps) {
      (void)io::format_carmen_log(sim::simulate(s, 1).log);
    }
  });
  return fuzz::accept_or_reject([&] { sim::world_from_json(parse_json_text(t, "fuzz.json"), "fuzz.json"); });
}
