#include "core/enum_names.h"

#include <gtest/gtest.h>

namespace locbench {
namespace {

enum class Shape { kRound, kSquare, kOval, kUnlisted };
constexpr EnumNames<Shape, 3> kShapes{{{Shape::kRound, "round"}, {Shape::kSquare, "square"}, {Shape::kOval, "oval"}}};

TEST(EnumNames, NameAndValueAreInverseLookupsInTheTable) {
  EXPECT_STREQ(enum_name(kShapes, Shape::kSquare), "square");
  EXPECT_EQ(enum_value(kShapes, "oval", "shape must be"), Shape::kOval);
  EXPECT_STREQ(enum_name(kShapes, Shape::kUnlisted), "?");
}

TEST(EnumNames, AnUnknownNameIsAUsageErrorListingTheNamesInOrder) {
  try {
    enum_value(kShapes, "cube", "shape must be");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "shape must be \"round\", \"square\" or \"oval\", got \"cube\"");
  }
}

}  // namespace
}  // namespace locbench
