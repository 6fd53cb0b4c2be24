// Censi's calibration data: wheel-speed tuples, published results, tick motions.
#include "datasets/io/censi_results_reader.h"
#include "datasets/io/censi_tuple_reader.h"
#include "datasets/io/relative_motion_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  const std::string t = fuzz::text(data, size);
  fuzz::accept_or_reject([&] { io::parse_censi_tuples(t, "fuzz.tuple"); });
  fuzz::accept_or_reject([&] { io::parse_censi_results(t, "fuzz.results"); });
  return fuzz::accept_or_reject([&] { io::parse_tick_motions(t, "fuzz.ticks"); });
}
