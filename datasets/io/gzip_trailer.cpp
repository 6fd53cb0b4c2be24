#include "datasets/io/gzip_trailer.h"

#include <unistd.h>
#include <zlib.h>

#include <string>
#include <vector>

#include "core/input_file.h"
#include "core/input_limits.h"

namespace locbench::io {
namespace {

std::uint32_t le32(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// Walks the members with inflate; returns where the bytes after the last complete member start
// when they do not begin another member, nullopt when the file ends exactly after a member.
std::optional<std::uint64_t> walk_members(InputFile& in) {
  const std::string text = in.read_all();
  const std::vector<unsigned char> data(text.begin(), text.end());
  std::size_t at = 0;
  std::vector<unsigned char> sink(1 << 16);
  while (at < data.size()) {
    if (data.size() - at < 2 || data[at] != 0x1f || data[at + 1] != 0x8b) return at;
    z_stream z{};
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) return at;
    z.next_in = const_cast<unsigned char*>(data.data() + at);
    z.avail_in = static_cast<uInt>(data.size() - at);
    int rc = Z_OK;
    while (rc == Z_OK) {
      z.next_out = sink.data();
      z.avail_out = static_cast<uInt>(sink.size());
      rc = inflate(&z, Z_NO_FLUSH);
    }
    const std::size_t used = data.size() - at - z.avail_in;
    inflateEnd(&z);
    if (rc != Z_STREAM_END) return at;  // a broken member: gzread reports those itself
    at += used;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::uint64_t> gzip_trailing_garbage(const std::filesystem::path& path, std::uint32_t crc,
                                                   std::uint64_t length) {
  InputFile in(path, "gzip file", static_cast<std::uint64_t>(limits::kInputFileBytes.max));
  const std::uint64_t size = in.size();
  if (size >= 18) {
    unsigned char tail[8];
    if (::pread(in.fd(), tail, 8, static_cast<off_t>(size - 8)) == 8 && le32(tail) == crc &&
        le32(tail + 4) == static_cast<std::uint32_t>(length)) {
      return std::nullopt;  // one member ending exactly at the end of the file
    }
  }
  return walk_members(in);
}

}  // namespace locbench::io
