#pragma once
// The message of the UsageError an options struct's strict from_json throws, for tests that
// check what it says.
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.h"

namespace locbench::testing {

// What reading `j` into a default-constructed O throws as a UsageError (its what()); "no error"
// when `j` reads.
template <class O>
std::string options_error_message(const nlohmann::json& j) {
  try {
    O o;
    from_json(j, o);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace locbench::testing
