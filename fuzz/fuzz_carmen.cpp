// CARMEN log reader (ENCODER, ODOM, TRUEPOS, COMPASS, FLASER, PARAM records).
#include "datasets/io/carmen_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return locbench::fuzz::accept_or_reject(
      [&] { locbench::io::parse_carmen_log(locbench::fuzz::text(data, size), "fuzz.clf"); });
}
