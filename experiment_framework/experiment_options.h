#pragma once
// An experiment's configuration is an options struct that states its fields once, with the
// project's one options mechanism (core/option_fields.h: visit_fields giving to_json, the strict
// reader with key paths, the range checks and the documentation table):
//
//   struct Options {
//     int runs = 10;
//     std::vector<std::string> datasets = {"aces", "intel"};
//     laser::EapOptions eap;
//   };
//   template <class V>
//   void visit_fields(V& v, Options& o) {
//     v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs");
//     v.field("datasets", o.datasets, "", any_finite(), "catalog names or user files");
//     v.nested("eap", o.eap, "EAP matcher (eap_matcher.h)");
//   }
//   LOCBENCH_EXPERIMENT_OPTIONS(Options)
//
// default_config() is options_json(Options{}); the merged user configuration is read back with
// read_options, which rejects unknown keys, wrong types and values out of range with a
// UsageError naming "<experiment>.key". The experiments' visitors add what their
// configurations hold beyond core's scalars: lists (std::vector of numbers or text), raw JSON
// passed on to a reader of its own (dataset specs, method options), and `coded` values written
// and read by a pair of functions (a simulator scenario).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "core/option_fields.h"

namespace locbench::experiments {
namespace options_detail {

template <class T>
std::string list_item_expected() {
  if constexpr (option_fields::IsVector<T>::value) {
    return "an array of " + std::to_string(T::RowsAtCompileTime) + " numbers";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return "text";
  } else if constexpr (std::is_class_v<T>) {
    return "an object";
  } else if constexpr (std::is_integral_v<T>) {
    return "a whole number";
  } else {
    return "a number";
  }
}

template <class T>
bool list_item_fits(const nlohmann::json& v) {
  if constexpr (option_fields::IsVector<T>::value) {
    if (!v.is_array() || v.size() != static_cast<std::size_t>(T::RowsAtCompileTime)) return false;
    for (const auto& x : v) {
      if (!x.is_number()) return false;
    }
    return true;
  } else if constexpr (std::is_same_v<T, std::string>) {
    return v.is_string();
  } else if constexpr (std::is_class_v<T>) {
    return v.is_object();
  } else if constexpr (std::is_unsigned_v<T>) {
    return v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0);
  } else if constexpr (std::is_integral_v<T>) {
    return v.is_number_integer();
  } else {
    return v.is_number();
  }
}

template <class T>
T list_item(const nlohmann::json& v) {
  if constexpr (option_fields::IsVector<T>::value) {
    T out;
    for (Eigen::Index i = 0; i < out.size(); ++i) out(i) = v[static_cast<std::size_t>(i)].get<double>();
    return out;
  } else {
    return v.get<T>();
  }
}

template <class T>
nlohmann::json list_json(const std::vector<T>& value) {
  nlohmann::json a = nlohmann::json::array();
  for (const T& x : value) a.push_back(option_fields::json_of(x));
  return a;
}

class ToJson : public option_fields::ToJson {
 public:
  using option_fields::ToJson::field;
  template <class T>
  void field(const char* name, const std::vector<T>& value, const char* unit, Range r, const char* m) {
    option_fields::ToJson::field(name, list_json(value), unit, r, m);
  }
  void field(const char* name, const nlohmann::json& value, const char* unit, Range r, const char* m) {
    option_fields::ToJson::field(name, value, unit, r, m);
  }
  template <class T, class Enc, class Dec>
  void coded(const char* name, const T& value, Enc encode, Dec, const char* meaning) {
    field(name, nlohmann::json(encode(value)), "", Range{}, meaning);
  }
};

class FromJson : public option_fields::FromJson {
 public:
  explicit FromJson(StrictJsonReader& r) : option_fields::FromJson(r), r_(r) {}
  using option_fields::FromJson::field;
  template <class T>
  void field(const char* name, std::vector<T>& value, const char*, Range, const char*) {
    const nlohmann::json* v = r_.raw(name);
    if (!v) return;
    if (!v->is_array()) r_.fail(name, "expected an array, found " + json_type_name(*v));
    std::vector<T> out;
    for (std::size_t i = 0; i < v->size(); ++i) {
      const nlohmann::json& item = (*v)[i];
      if (!list_item_fits<T>(item)) {
        r_.fail(std::string(name) + "[" + std::to_string(i) + "]",
                "expected " + list_item_expected<T>() + ", found " + json_type_name(item));
      }
      if constexpr (std::is_class_v<T> && !std::is_same_v<T, std::string> && !option_fields::IsVector<T>::value) {
        T x;
        try {
          from_json(item, x);  // the item's own options (LOCBENCH_EXPERIMENT_OPTIONS)
        } catch (const UsageError& e) {
          r_.fail(std::string(name) + "[" + std::to_string(i) + "]", e.what());
        }
        out.push_back(std::move(x));
      } else {
        out.push_back(list_item<T>(item));
      }
    }
    value = std::move(out);
  }
  void field(const char* name, nlohmann::json& value, const char*, Range, const char*) {
    if (const nlohmann::json* v = r_.raw(name)) value = *v;
  }
  template <class T, class Enc, class Dec>
  void coded(const char* name, T& value, Enc, Dec decode, const char*) {
    if (const nlohmann::json* v = r_.raw(name)) {
      try {
        value = decode(*v);
      } catch (const UsageError& e) {
        r_.fail(name, e.what());
      }
    }
  }

 private:
  StrictJsonReader& r_;
};

class Validate : public option_fields::Validate {
 public:
  explicit Validate(std::string what) : option_fields::Validate(what), what_(std::move(what)) {}
  using option_fields::Validate::field;
  template <class T>
  void field(const char* name, const std::vector<T>& value, const char* unit, Range range, const char*) {
    if constexpr (std::is_arithmetic_v<T>) {
      for (const T x : value) {
        if (!range.contains(static_cast<double>(x))) {
          throw UsageError(what_ + "." + name + ": expected each " + range.text() +
                           (*unit ? std::string(" ") + unit : std::string()) + ", got " + nlohmann::json(value).dump());
        }
      }
    }
  }
  void field(const char*, const nlohmann::json&, const char*, Range, const char*) {}
  template <class T, class Enc, class Dec>
  void coded(const char*, const T&, Enc, Dec, const char*) {}

 private:
  std::string what_;
};

class Describe : public option_fields::Describe {
 public:
  using option_fields::Describe::field;
  template <class T>
  void field(const char* name, const std::vector<T>& value, const char* unit, Range range, const char* meaning) {
    std::string allowed = "list; each item " + list_item_expected<T>();
    if constexpr (std::is_arithmetic_v<T>) allowed += ", " + range.text();
    rows_.push_back({name, unit, list_json(value).dump(), allowed, meaning});
  }
  void field(const char* name, const nlohmann::json& value, const char* unit, Range, const char* meaning) {
    rows_.push_back({name, unit, value.dump(), "JSON (see meaning)", meaning});
  }
  template <class T, class Enc, class Dec>
  void coded(const char* name, const T& value, Enc encode, Dec, const char* meaning) {
    rows_.push_back({name, "", nlohmann::json(encode(value)).dump(), "object", meaning});
  }
  std::vector<FieldDoc> take() {
    std::vector<FieldDoc> rows = option_fields::Describe::take();
    rows.insert(rows.end(), rows_.begin(), rows_.end());
    return rows;
  }

 private:
  std::vector<FieldDoc> rows_;
};

}  // namespace options_detail

// A struct with its own to_json/from_json (found by ADL) as a `coded` option, for option
// structs of other modules that have no validate() for `nested`:
//   v.coded("split_and_merge", o.split_and_merge, adl_json<T>, adl_from_json<T>, "…");
template <class T>
nlohmann::json adl_json(const T& x) {
  nlohmann::json j;
  to_json(j, x);
  return j;
}
template <class T>
T adl_from_json(const nlohmann::json& j) {
  T x;
  from_json(j, x);
  return x;
}

// The options as JSON: every field, nested ones through their own to_json.
template <class O>
nlohmann::json options_json(const O& o) {
  return visit_const(options_detail::ToJson{}, o).take();
}

// Checks the fields' ranges; `what` names the options in errors ("<experiment>.key: …").
template <class O>
void validate_options(const O& o, const std::string& what) {
  visit_const(options_detail::Validate(what), o);
}

// Reads the keys of `j` into `o` (absent keys keep o's values; others are a UsageError naming
// "<what>.key"), then checks the ranges.
template <class O>
void read_options_into(const nlohmann::json& j, O& o, const std::string& what) {
  StrictJsonReader r(j, what);
  options_detail::FromJson v(r);
  visit_fields(v, o);
  r.finish();
  validate_options(o, what);
}

// `config` read over the defaults `o`.
template <class O>
O read_options(const nlohmann::json& config, const std::string& what, O o = O{}) {
  read_options_into(config, o, what);
  return o;
}

// The options' documentation rows (fields_markdown formats them).
template <class O>
std::vector<FieldDoc> describe_options(const O& defaults = O{}) {
  return visit_const(options_detail::Describe{}, defaults).take();
}

}  // namespace locbench::experiments

// to_json, from_json (strict, then the range checks) and validate of an options struct of an
// experiment from its visit_fields; use in the struct's namespace, after visit_fields (nested
// options of an experiment's configuration reach them by ADL). Inline: a header may hold them.
#define LOCBENCH_EXPERIMENT_OPTIONS(Options)                                    \
  [[maybe_unused]] inline void to_json(nlohmann::json& j, const Options& o) {   \
    j = ::locbench::experiments::options_json(o);                               \
  }                                                                             \
  [[maybe_unused]] inline void from_json(const nlohmann::json& j, Options& o) { \
    ::locbench::experiments::read_options_into(j, o, #Options);                 \
  }                                                                             \
  [[maybe_unused]] inline void validate(const Options& o) { ::locbench::experiments::validate_options(o, #Options); }
