// One visitor per options struct gives to_json, from_json, validation and the docs table.
#include "core/option_fields.h"

#include <gtest/gtest.h>

#include "core/json_file.h"
#include "tests/options_error_message.h"

namespace locbench::option_fields_test {

enum class Shape { kRound, kSquare };
const char* to_string(Shape s) { return s == Shape::kRound ? "round" : "square"; }
Shape shape_from_string(const std::string& s) {
  if (s == "round") return Shape::kRound;
  if (s == "square") return Shape::kSquare;
  throw UsageError("expected \"round\" or \"square\", got \"" + s + "\"");
}

struct Inner {
  double gain = 0.5;
};
template <class V>
void visit_fields(V& v, Inner& o) {
  v.field("gain", o.gain, "", closed(0.0, 1.0), "mixing gain");
}
void validate(const Inner& o) { validate_fields(o, "Inner"); }
void to_json(nlohmann::json& j, const Inner& o) { j = fields_to_json(o); }
void from_json(const nlohmann::json& j, Inner& o) {
  fields_from_json(j, o, "Inner");
  validate(o);
}

struct Outer {
  double radius = 0.2;
  int tries = 3;
  std::size_t points = 5;
  bool strict = true;
  Shape shape = Shape::kRound;
  Inner inner;
};
template <class V>
void visit_fields(V& v, Outer& o) {
  v.field("radius", o.radius, "m", positive(), "search radius");
  v.field("tries", o.tries, "", at_least(1), "attempts");
  v.field("points", o.points, "", at_least(2), "points per line");
  v.flag("strict", o.strict, "reject outliers");
  v.choice("shape", o.shape, to_string, shape_from_string, "\"round\" or \"square\"");
  v.nested("inner", o.inner, "the inner options");
}
void validate(const Outer& o) { validate_fields(o, "Outer"); }
void to_json(nlohmann::json& j, const Outer& o) { j = fields_to_json(o); }
void from_json(const nlohmann::json& j, Outer& o) {
  fields_from_json(j, o, "Outer");
  validate(o);
}

std::string error_of(const nlohmann::json& j) { return testing::options_error_message<Outer>(j); }

TEST(OptionFields, ToJsonWritesEveryFieldOnceWithNestedStructsAndEnumNames) {
  nlohmann::json j;
  to_json(j, Outer{});
  EXPECT_EQ(j.dump(), R"({"inner":{"gain":0.5},"points":5,"radius":0.2,"shape":"round","strict":true,"tries":3})");
}

TEST(OptionFields, FromJsonReadsPresentKeysAndKeepsDefaultsForAbsentOnes) {
  Outer o;
  from_json(nlohmann::json::parse(R"({"radius": 0.5, "shape": "square", "inner": {"gain": 1}})"), o);
  EXPECT_EQ(o.radius, 0.5);
  EXPECT_EQ(o.shape, Shape::kSquare);
  EXPECT_EQ(o.inner.gain, 1.0);
  EXPECT_EQ(o.tries, 3);
  EXPECT_EQ(o.points, 5u);
  nlohmann::json back;
  to_json(back, o);
  Outer again;
  from_json(back, again);
  EXPECT_EQ(again.radius, 0.5);
  EXPECT_EQ(again.shape, Shape::kSquare);
}

TEST(OptionFields, AnUnknownKeyIsRejectedByNameWithTheKnownKeys) {
  EXPECT_EQ(error_of({{"radios", 1.0}}),
            "Outer.radios: unknown key (expected one of: radius, tries, points, strict, shape, inner)");
  EXPECT_EQ(error_of({{"inner", {{"gian", 1.0}}}}), "Outer.inner: Inner.gian: unknown key (expected one of: gain)");
}

TEST(OptionFields, AWrongTypeNamesTheKeyAndWhatWasExpected) {
  EXPECT_EQ(error_of({{"radius", "0.2"}}), "Outer.radius: expected a number, found string");
  EXPECT_EQ(error_of({{"tries", 1.5}}), "Outer.tries: expected an integer, found number");
  EXPECT_EQ(error_of({{"points", -1}}), "Outer.points: expected a whole number ≥ 0, found -1");
  EXPECT_EQ(error_of({{"strict", 1}}), "Outer.strict: expected true or false, found number");
  EXPECT_EQ(error_of({{"shape", "oval"}}), "Outer.shape: expected \"round\" or \"square\", got \"oval\"");
}

TEST(OptionFields, AnOutOfRangeValueNamesTheKeyTheRangeAndTheUnit) {
  EXPECT_EQ(error_of({{"radius", 0.0}}), "Outer.radius: expected > 0 m, got 0.0");
  EXPECT_EQ(error_of({{"tries", 0}}), "Outer.tries: expected ≥ 1, got 0");
  EXPECT_EQ(error_of({{"points", 1}}), "Outer.points: expected ≥ 2, got 1");
  EXPECT_EQ(error_of({{"inner", {{"gain", 1.5}}}}), "Outer.inner: Inner.gain: expected a number in [0, 1], got 1.5");
  Outer o;
  o.radius = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate(o), UsageError);
}

TEST(OptionFields, TheDocumentationTableListsEachFieldWithDefaultUnitAndRange) {
  EXPECT_EQ(fields_markdown(describe_fields<Outer>()),
            "| key | default | unit | allowed | meaning |\n"
            "| --- | --- | --- | --- | --- |\n"
            "| `radius` | `0.2` | m | > 0 | search radius |\n"
            "| `tries` | `3` |  | ≥ 1, whole | attempts |\n"
            "| `points` | `5` |  | ≥ 2, whole | points per line |\n"
            "| `strict` | `true` |  | true or false | reject outliers |\n"
            "| `shape` | `\"round\"` |  | see meaning | \"round\" or \"square\" |\n"
            "| `inner` | `{\"gain\":0.5}` |  | object | the inner options |\n");
}

TEST(StrictJsonReader, ErrorsFromAFileAreInputErrorsNamingTheFileAndTheKeyPath) {
  const nlohmann::json j = parse_json_text(R"({"a": {"b": "x"}})", "in.json");
  StrictJsonReader top(j, "", "in.json");
  StrictJsonReader a = top.object("a");
  double b = 0.0;
  try {
    a.read("b", b);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "in.json: a.b: expected a number, found string");
  }
}

TEST(JsonFile, SyntaxErrorsNaNAndOverflowNameTheSourceAndLine) {
  const auto message = [](const std::string& text) {
    try {
      parse_json_text(text, "x.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("{\n\"a\": NaN}").rfind("x.json:2: 'NaN' is not a JSON number", 0), 0u)
      << message("{\n\"a\": NaN}");
  EXPECT_EQ(message("{\n\n\"a\": 1e400}").rfind("x.json:3: '1e400' is not a finite number (number overflow", 0), 0u)
      << message("{\n\n\"a\": 1e400}");
  EXPECT_EQ(message("{\"a\": 1,}").rfind("x.json:1: invalid JSON", 0), 0u) << message("{\"a\": 1,}");
}

}  // namespace locbench::option_fields_test
