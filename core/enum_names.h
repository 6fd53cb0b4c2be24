#pragma once
// An enum's names stated once, as a table {value, "name"}: its to_string and its inverse are
// lookups in that table.
#include <array>
#include <cstddef>
#include <string>
#include <utility>

#include "core/errors.h"

namespace locbench {

template <class E, std::size_t N>
using EnumNames = std::array<std::pair<E, const char*>, N>;

// The name of `value`; "?" for a value the table lacks.
template <class E, std::size_t N>
const char* enum_name(const EnumNames<E, N>& names, E value) {
  for (const auto& [v, name] : names) {
    if (v == value) return name;
  }
  return "?";
}

// The value named `text`; otherwise throws UsageError `<what> "a", "b" or "c", got "text"`.
template <class E, std::size_t N>
E enum_value(const EnumNames<E, N>& names, const std::string& text, const std::string& what) {
  std::string allowed;
  for (std::size_t i = 0; i < N; ++i) {
    if (text == names[i].second) return names[i].first;
    allowed += std::string(i == 0 ? "" : i + 1 == N ? " or " : ", ") + '"' + names[i].second + '"';
  }
  throw UsageError(what + " " + allowed + ", got \"" + text + "\"");
}

}  // namespace locbench
