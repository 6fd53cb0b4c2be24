// Residual histograms (diagnose H.json): reading, limits, and the fits on what is accepted.
#include "algorithms/diagnosis/diagnosis.h"
#include "core/json_file.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  return fuzz::accept_or_reject([&] {
    const auto h = diagnosis::read_histogram(parse_json_text(fuzz::text(data, size), "fuzz.json"), "fuzz.json");
    if (h.counts.size() <= 64) diagnosis::diagnose_histogram(h, "fuzz.json");
  });
}
