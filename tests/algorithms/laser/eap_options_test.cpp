// EapOptions state their fields once: JSON both ways, range checks and the README's table.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "algorithms/laser/eap_matcher.h"
#include "core/errors.h"
#include "tests/options_error_message.h"

namespace locbench::laser {
namespace {

std::string error_of(const nlohmann::json& j) { return testing::options_error_message<EapOptions>(j); }

TEST(EapOptions, JsonRoundTripsEveryField) {
  EapOptions o;
  o.d_limit = 0.15;
  o.claim_order = ClaimOrder::kMapOrder;
  o.weighting.rho_min = 0.7;
  o.remove_claimed = false;
  const nlohmann::json j = o;
  EapOptions back;
  from_json(j, back);
  EXPECT_EQ(nlohmann::json(back), j);
  EXPECT_EQ(back.claim_order, ClaimOrder::kMapOrder);
  EXPECT_EQ(back.weighting.rho_min, 0.7);
}

TEST(EapOptions, BadValuesAreRejectedNamingTheKeyAndWhatWasExpected) {
  EXPECT_EQ(error_of({{"d_limt", 0.2}}).rfind("EapOptions.d_limt: unknown key (expected one of: d_limit, ", 0), 0u);
  EXPECT_EQ(error_of({{"d_limit", "20 cm"}}), "EapOptions.d_limit: expected a number, found string");
  EXPECT_EQ(error_of({{"d_limit", -0.2}}), "EapOptions.d_limit: expected > 0 m, got -0.2");
  EXPECT_EQ(error_of({{"max_direction_error", 2.0}}),
            "EapOptions.max_direction_error: expected a number in [0, 1.5707963267948966) rad, got 2.0");
  EXPECT_EQ(error_of({{"weighting", {{"rho_min", 0.0}}}}),
            "EapOptions.weighting: HoughWeight.rho_min: expected > 0 m, got 0.0");
  EXPECT_EQ(error_of({{"claim_order", "random"}}),
            "EapOptions.claim_order: claim_order must be \"nearest_segment\" or \"map_order\", got \"random\"");
}

TEST(EapOptions, TheReadmeTableIsTheOneTheFieldsGive) {
  const char* root = std::getenv("LOCBENCH_SOURCE_DIR");
  std::ifstream in(std::string(root ? root : ".") + "/algorithms/laser/README.md");
  ASSERT_TRUE(in) << "algorithms/laser/README.md not found (run from the source root)";
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(eap_options_table()), std::string::npos)
      << "algorithms/laser/README.md should hold this table:\n"
      << eap_options_table();
}

}  // namespace
}  // namespace locbench::laser
