#pragma once
// The scan-to-map matchers the laser experiments compare, built from one configuration object
// {"eap": EapOptions, "split_and_merge": …, "agglomerative": …, "rwht": …} (each matcher's
// options as JSON; a missing key keeps that matcher's defaults). Internal to the experiments.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/laser/segment_match.h"
#include "core/line_map.h"

namespace locbench::experiments {

// The options under `key` of a configuration object; a missing key keeps the defaults.
template <typename Options>
Options options_of(const nlohmann::json& all, const char* key) {
  Options o{};
  if (all.contains(key)) from_json(all.at(key), o);
  return o;
}

// Every matcher's default options, keyed by its name.
nlohmann::json default_matcher_options();

// The matchers named in `which` (in that order) with options from `options`; "eap_indexed" is
// the EAP matcher with a grid index built for `map` (required for it). UsageError for an unknown
// name.
std::vector<std::unique_ptr<laser::SegmentMatcher>> make_matchers(const std::vector<std::string>& which,
                                                                  const nlohmann::json& options,
                                                                  const LineMap* map = nullptr);

}  // namespace locbench::experiments
