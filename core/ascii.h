#pragma once
// ASCII letters in lower case (file extensions, format names); other bytes unchanged.
#include <cctype>
#include <string>

namespace locbench {

inline std::string ascii_lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace locbench
