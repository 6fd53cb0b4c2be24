#pragma once
// The message of the InputError a piece of code throws, for tests that check what it says.
#include <string>

#include "core/errors.h"

namespace locbench::testing {

// What f() throws as an InputError (its what()); empty when it throws none.
template <class F>
std::string input_error_message(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace locbench::testing
