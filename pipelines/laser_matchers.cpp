#include "pipelines/laser_matchers.h"

#include "algorithms/laser/eap_matcher.h"
#include "algorithms/laser/segment_grid_index.h"
#include "baselines/laser/extract_then_match.h"
#include "baselines/laser/options_json.h"
#include "core/errors.h"

namespace locbench::experiments {
nlohmann::json default_matcher_options() {
  nlohmann::json j;
  to_json(j["eap"], laser::EapOptions{});
  to_json(j["split_and_merge"], baselines::laser::SplitAndMergeMatcherOptions{});
  to_json(j["agglomerative"], baselines::laser::AgglomerativeMatcherOptions{});
  to_json(j["rwht"], baselines::laser::RwhtMatcherOptions{});
  return j;
}

std::vector<std::unique_ptr<laser::SegmentMatcher>> make_matchers(const std::vector<std::string>& which,
                                                                  const nlohmann::json& options, const LineMap* map) {
  std::vector<std::unique_ptr<laser::SegmentMatcher>> out;
  for (const std::string& name : which) {
    if (name == "eap") {
      out.push_back(std::make_unique<laser::EapMatcher>(options_of<laser::EapOptions>(options, "eap")));
    } else if (name == "eap_indexed") {
      if (!map) throw UsageError("eap_indexed needs the map to index");
      const auto o = options_of<laser::EapOptions>(options, "eap");
      laser::GridIndexOptions g;
      g.d_limit = o.d_limit;
      out.push_back(std::make_unique<laser::EapMatcher>(std::make_shared<const laser::SegmentGridIndex>(*map, g), o));
    } else if (name == "split_and_merge") {
      out.push_back(std::make_unique<baselines::laser::SplitAndMergeMatcher>(
          options_of<baselines::laser::SplitAndMergeMatcherOptions>(options, "split_and_merge")));
    } else if (name == "agglomerative") {
      out.push_back(std::make_unique<baselines::laser::AgglomerativeMatcher>(
          options_of<baselines::laser::AgglomerativeMatcherOptions>(options, "agglomerative")));
    } else if (name == "rwht") {
      out.push_back(std::make_unique<baselines::laser::RwhtMatcher>(
          options_of<baselines::laser::RwhtMatcherOptions>(options, "rwht")));
    } else {
      throw UsageError("unknown matcher '" + name +
                       "' (known: eap, eap_indexed, split_and_merge, agglomerative, rwht)");
    }
  }
  return out;
}

}  // namespace locbench::experiments
