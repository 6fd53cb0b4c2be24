#pragma once
// Shared by the libFuzzer targets: a reader may reject its input only with InputError or
// UsageError (exit 2 in the CLI). Any other exception escapes and libFuzzer reports it as a
// crash, like a sanitizer finding, a hang (-timeout) or a memory blowup (-rss_limit_mb).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.h"

namespace locbench::fuzz {

template <typename F>
int accept_or_reject(F f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const UsageError&) {
  }
  return 0;
}

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace locbench::fuzz
