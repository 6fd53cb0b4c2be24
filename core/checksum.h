#pragma once
#include <filesystem>
#include <string>
#include <string_view>

namespace locbench {

// "crc32:xxxxxxxx" of a file's bytes as stored (the .gz itself for compressed logs); for a
// folder, of its regular files' names and bytes in name order. Throws InputError if unreadable.
std::string file_checksum(const std::filesystem::path& path);
// "crc32:xxxxxxxx" of a text (e.g. a simulated scenario's JSON and seed).
std::string text_checksum(std::string_view text);

}  // namespace locbench
