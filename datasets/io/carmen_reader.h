#pragma once
// Reader of CARMEN text logs (plain or gzip) with the locbench ENCODER and COMPASS records;
// see datasets/FORMAT.md.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "core/log.h"

namespace locbench::io {

// Records of unknown types (ROBOTLASER1, RAWLASER1, SONAR, …) are skipped; their count per
// type is stored in Log::params under this prefix, e.g. "locbench_skipped_records.SONAR" → "12".
inline constexpr std::string_view kSkippedRecordsParamPrefix = "locbench_skipped_records.";

// Reads a CARMEN log file. Log::name is the file name without extensions, Log::source the
// path. Throws InputError (file, line, expectation) on any malformed or unreadable input.
Log read_carmen_log(const std::filesystem::path& path);

// The same for log text in memory; `source_name` stands for the file name in errors.
Log parse_carmen_log(std::string_view text, const std::string& source_name);

// The skipped-record counts stored by the reader: type → count.
std::map<std::string, std::size_t> skipped_record_counts(const Log& log);

}  // namespace locbench::io
