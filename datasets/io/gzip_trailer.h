#pragma once
// zlib's gzread stops silently at bytes after the last gzip member that do not start another
// member ("trailing garbage": a log appended to by mistake, two files concatenated badly). This
// finds them: the fast check compares the file's last 8 bytes with the CRC-32 and length of
// everything decompressed (one member, the usual case); otherwise every member is walked.
#include <cstdint>
#include <filesystem>
#include <optional>

namespace locbench::io {

// The byte offset where trailing garbage starts in the gzip file `path`, or nullopt when the
// file is one or more complete gzip members and nothing else. `crc` and `length` are the CRC-32
// and byte count (mod 2^32 is enough) of the whole decompressed text.
std::optional<std::uint64_t> gzip_trailing_garbage(const std::filesystem::path& path, std::uint32_t crc,
                                                   std::uint64_t length);

}  // namespace locbench::io
