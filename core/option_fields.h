#pragma once
// Options structs state their fields once — name, unit, allowed range, one line of meaning —
// in a visitor, and get from it both JSON directions, the range validation and their
// documentation table:
//
//   template <class V>                     // in the struct's namespace (found by ADL)
//   void visit_fields(V& v, EapOptions& o) {
//     v.field("d_limit", o.d_limit, "m", positive(), "half-width of ω2 (5.5)");
//     v.flag("remove_claimed", o.remove_claimed, "§5.3: delete matched points");
//     v.choice("region", o.region, to_string, region_rule_from_string, "ω1 rule");
//     v.nested("weighting", o.weighting, "g of 5.8/5.10/5.11");
//   }
//   LOCBENCH_OPTIONS_JSON(EapOptions)      // to_json and from_json (strict, then validate())
//   void validate(const EapOptions& o) { validate_fields(o, "EapOptions"); /* cross-field rules */ }
//
// Absent keys keep their defaults; unknown keys, wrong types and out-of-range values throw
// UsageError naming "Struct.key" and what was expected (the CLI adds the file). Values are in
// SI units like the structs themselves; `unit` is what the docs print.
#include <cmath>
#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.h"
#include "core/json_options.h"

namespace locbench {

// The values a number may take: finite and within [lo, hi] with either end open.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  bool contains(double x) const {
    return std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  // "any finite number", "> 0", "≥ 1", "in [0, 1)".
  std::string text() const;
};

inline Range any_finite() { return {}; }
inline Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
inline Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
inline Range at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
inline Range closed(double lo, double hi) { return {lo, hi, false, false}; }
inline Range open(double lo, double hi) { return {lo, hi, true, true}; }
inline Range closed_open(double lo, double hi) { return {lo, hi, false, true}; }
inline Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }

// One row of an options struct's documentation.
struct FieldDoc {
  std::string name;
  std::string unit;          // "m", "rad", "" for a pure number
  std::string default_json;  // the default as JSON text
  std::string allowed;       // Range::text(), "true or false", "\"a\" or \"b\"", "object"
  std::string meaning;
};

// A Markdown table (| key | default | unit | allowed | meaning |) of the rows.
std::string fields_markdown(const std::vector<FieldDoc>& rows);

namespace option_fields {

// Fixed-size vectors of numbers (Vector3d, …), written as JSON arrays.
template <class T>
struct IsVector : std::false_type {};
template <int N>
struct IsVector<Eigen::Matrix<double, N, 1>> : std::true_type {};

template <class T>
nlohmann::json json_of(const T& value) {
  if constexpr (IsVector<T>::value) {
    return vector_json(value);
  } else {
    return nlohmann::json(value);
  }
}

// An enum's names: to_string and its inverse (which throws UsageError for an unknown name).
template <class E>
using ToText = const char* (*)(E);
template <class E>
using FromText = E (*)(const std::string&);

// Writes every field (nested structs through their own to_json).
class ToJson {
 public:
  template <class T>
  void field(const char* name, const T& value, const char*, Range, const char*) {
    j_[name] = json_of(value);
  }
  template <class B>
  void flag(const char* name, B& value, const char* meaning) {
    field(name, value, "", Range{}, meaning);
  }
  template <class E>
  void choice(const char* name, const E& value, ToText<E> to_s, FromText<E>, const char*) {
    j_[name] = to_s(value);
  }
  template <class T>
  void nested(const char* name, const T& value, const char*) {
    nlohmann::json n;
    to_json(n, value);
    j_[name] = std::move(n);
  }
  nlohmann::json take() { return std::move(j_); }

 private:
  nlohmann::json j_ = nlohmann::json::object();
};

// Reads the present keys with the strict reader; the reader's finish() rejects the others.
class FromJson {
 public:
  explicit FromJson(StrictJsonReader& r) : r_(r) {}
  template <class T>
  void field(const char* name, T& value, const char*, Range, const char*) {
    r_.read(name, value);
  }
  template <class B>
  void flag(const char* name, B& value, const char* meaning) {
    field(name, value, "", Range{}, meaning);
  }
  template <class E>
  void choice(const char* name, E& value, ToText<E> to_s, FromText<E> from_s, const char*) {
    std::string text = to_s(value);
    r_.read(name, text);
    try {
      value = from_s(text);
    } catch (const UsageError& e) {
      r_.fail(name, e.what());
    }
  }
  template <class T>
  void nested(const char* name, T& value, const char*) {
    r_.read_object(name, value);
  }

 private:
  StrictJsonReader& r_;
};

// Checks each number against its range; nested structs through their own validate().
class Validate {
 public:
  explicit Validate(std::string what) : what_(std::move(what)) {}
  template <class T>
  void field(const char* name, const T& value, const char* unit, Range range, const char*) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      if (!range.contains(static_cast<double>(value))) out_of_range(name, unit, range, nlohmann::json(value));
    } else if constexpr (IsVector<T>::value) {
      for (Eigen::Index i = 0; i < value.size(); ++i) {
        if (!range.contains(value(i))) out_of_range(name, unit, range, json_of(value), "each ");
      }
    }
  }
  template <class B>
  void flag(const char* name, B& value, const char* meaning) {
    field(name, value, "", Range{}, meaning);
  }
  template <class E>
  void choice(const char*, const E&, ToText<E>, FromText<E>, const char*) {}
  template <class T>
  void nested(const char* name, const T& value, const char*) {
    try {
      validate(value);
    } catch (const UsageError& e) {
      throw UsageError(what_ + "." + name + ": " + e.what());
    }
  }

 private:
  [[noreturn]] void out_of_range(const char* name, const char* unit, Range range, const nlohmann::json& value,
                                 const char* each = "") const {
    throw UsageError(what_ + "." + name + ": expected " + each + range.text() +
                     (*unit ? std::string(" ") + unit : std::string()) + ", got " + value.dump());
  }

  std::string what_;
};

// One documentation row per field.
class Describe {
 public:
  template <class T>
  void field(const char* name, const T& value, const char* unit, Range range, const char* meaning) {
    std::string allowed;
    if constexpr (std::is_same_v<T, bool>) {
      allowed = "true or false";
    } else if constexpr (std::is_arithmetic_v<T>) {
      allowed = range.text() + (std::is_integral_v<T> ? ", whole" : "");
    } else if constexpr (IsVector<T>::value) {
      allowed = std::to_string(value.size()) + " numbers, each " + range.text();
    } else {
      allowed = "text";
    }
    rows_.push_back({name, unit, json_of(value).dump(), allowed, meaning});
  }
  template <class B>
  void flag(const char* name, B& value, const char* meaning) {
    field(name, value, "", Range{}, meaning);
  }
  template <class E>
  void choice(const char* name, const E& value, ToText<E> to_s, FromText<E>, const char* meaning) {
    rows_.push_back({name, "", nlohmann::json(to_s(value)).dump(), "see meaning", meaning});
  }
  template <class T>
  void nested(const char* name, const T& value, const char* meaning) {
    nlohmann::json n;
    to_json(n, value);
    rows_.push_back({name, "", n.dump(), "object", meaning});
  }
  std::vector<FieldDoc> take() { return std::move(rows_); }

 private:
  std::vector<FieldDoc> rows_;
};

}  // namespace option_fields

// Visits the fields of `o` with `v` and returns it. For the writing visitors (ToJson, Validate,
// Describe), which only read the fields: one visit_fields per struct serves both directions, so
// the const object is visited through a non-const reference.
template <class V, class O>
V visit_const(V v, const O& o) {
  visit_fields(v, const_cast<O&>(o));
  return v;
}

template <class O>
nlohmann::json fields_to_json(const O& o) {
  return visit_const(option_fields::ToJson{}, o).take();
}

// Reads the keys present in `j` into `o` (absent keys keep o's values); `what` names the
// struct in errors. Does not validate: call validate(o) after, which knows the cross-field rules.
template <class O>
void fields_from_json(const nlohmann::json& j, O& o, const char* what) {
  StrictJsonReader r(j, what);
  read_fields(r, o);
  r.finish();
}

// Reads the struct's keys from an open reader (an input file's object, errors naming the file
// and key path); the caller calls r.finish() once every key of the object is read.
template <class O>
void read_fields(StrictJsonReader& r, O& o) {
  option_fields::FromJson v(r);
  visit_fields(v, o);
}

// Reads `j` into `o` and, when the struct has a validate(o) (its ranges and cross-field rules),
// validates the result.
template <class O>
void options_from_json(const nlohmann::json& j, O& o, const char* what) {
  fields_from_json(j, o, what);
  if constexpr (requires { validate(o); }) validate(o);
}

template <class O>
void validate_fields(const O& o, const char* what) {
  visit_const(option_fields::Validate(what), o);
}

template <class O>
std::vector<FieldDoc> describe_fields(const O& defaults = O{}) {
  return visit_const(option_fields::Describe{}, defaults).take();
}

}  // namespace locbench

// Defines to_json and from_json (strict, then validate()) of an options struct from its
// visit_fields; use inside the struct's namespace, in one .cpp.
#define LOCBENCH_OPTIONS_JSON(Options)                                                     \
  void to_json(nlohmann::json& j, const Options& o) { j = ::locbench::fields_to_json(o); } \
  void from_json(const nlohmann::json& j, Options& o) { ::locbench::options_from_json(j, o, #Options); }
