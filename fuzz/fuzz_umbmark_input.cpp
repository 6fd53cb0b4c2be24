// The UMBmark measurement JSON a person fills in.
#include "datasets/io/umbmark_input_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return locbench::fuzz::accept_or_reject(
      [&] { locbench::io::parse_umbmark_input(locbench::fuzz::text(data, size), "fuzz.json"); });
}
