// Freiburg .relations reader.
#include "datasets/io/relations_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return locbench::fuzz::accept_or_reject(
      [&] { locbench::io::parse_relations(locbench::fuzz::text(data, size), "fuzz.relations"); });
}
