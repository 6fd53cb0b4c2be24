#include "datasets/io/dataset_name.h"

#include <array>
#include <string_view>

namespace locbench::io {
namespace {

bool strip_suffix(std::string& s, std::string_view suffix) {
  if (s.size() <= suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i) {
    char c = s[s.size() - suffix.size() + i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != suffix[i]) return false;
  }
  s.resize(s.size() - suffix.size());
  return true;
}

}  // namespace

std::string dataset_name_from_file(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  strip_suffix(name, ".gz");
  constexpr std::array<std::string_view, 9> kExtensions = {".clf", ".log", ".carmen", ".relations", ".dat",
                                                           ".txt", ".tum", ".bag",    ".db3"};
  for (const auto ext : kExtensions) {
    if (strip_suffix(name, ext)) break;
  }
  return name;
}

}  // namespace locbench::io
