#include "core/checksum.h"

#include <zlib.h>

#include <algorithm>
#include <vector>

#include "core/input_file.h"
#include "core/input_limits.h"

namespace locbench {
namespace {

std::string hex(uLong crc) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08lx", crc & 0xffffffffUL);
  return std::string("crc32:") + buf;
}

uLong update_with_file(uLong crc, const std::filesystem::path& path) {
  InputFile in(path, "input file", static_cast<std::uint64_t>(limits::kInputFileBytes.max));
  std::vector<char> buf(1 << 16);
  while (const std::size_t got = in.read(buf.data(), buf.size())) {
    crc = crc32(crc, reinterpret_cast<const Bytef*>(buf.data()), static_cast<uInt>(got));
  }
  return crc;
}

}  // namespace

std::string file_checksum(const std::filesystem::path& path) {
  uLong crc = crc32(0L, Z_NULL, 0);
  if (std::filesystem::is_directory(path)) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(path)) {
      if (e.is_regular_file()) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      const std::string name = f.filename().string();
      crc = crc32(crc, reinterpret_cast<const Bytef*>(name.data()), static_cast<uInt>(name.size()));
      crc = update_with_file(crc, f);
    }
    return hex(crc);
  }
  return hex(update_with_file(crc, path));
}

std::string text_checksum(std::string_view text) {
  const uLong crc =
      crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(text.data()), static_cast<uInt>(text.size()));
  return hex(crc);
}

}  // namespace locbench
