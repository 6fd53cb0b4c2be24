#include <gtest/gtest.h>

#include <random>
#include <regex>
#include <set>
#include <string>

#include "reports/gnuplot_svg.h"

namespace locbench::reports {
namespace {

std::set<std::string> ids_by_regex(const std::string& svg) {
  static const std::regex id_re(R"re(\bid=(['"])([^'"]+)\1)re");
  std::set<std::string> ids;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), id_re); it != std::sregex_iterator(); ++it) {
    ids.insert((*it)[2].str());
  }
  return ids;
}

TEST(ElementIds, FindsQuotedIdsAndSkipsAttributesEndingInId) {
  const std::string svg = "<svg id='a'><g grid=\"x\" id=\"b c\"/><p id='' d='M0'/><q _id='d'/><r id=e/></svg>";
  EXPECT_EQ(element_ids(svg), (std::set<std::string>{"a", "b c"}));
}

TEST(ElementIds, AgreeWithTheRegularExpressionOnRandomText) {
  // Text from the characters that matter ('i', 'd', '=', both quotes, a word character, a
  // separator): 5,000 strings of up to 40 characters, seeded.
  const std::string alphabet = "id='\"x _<";
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1), length(0, 40);
  int with_ids = 0;
  for (int n = 0; n < 5000; ++n) {
    std::string s;
    for (std::size_t k = length(rng); k > 0; --k) s += alphabet[pick(rng)];
    if (n % 3 == 0) s.insert(s.size() / 2, "id='q'");  // at least one id in a third of them
    const std::set<std::string> expected = ids_by_regex(s);
    with_ids += expected.empty() ? 0 : 1;
    ASSERT_EQ(element_ids(s), expected) << "text: " << s;
  }
  EXPECT_GT(with_ids, 500);  // 972 of them: the comparison is not vacuous
}

}  // namespace
}  // namespace locbench::reports
