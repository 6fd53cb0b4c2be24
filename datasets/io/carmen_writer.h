#pragma once
// Writer of CARMEN text logs; reading the output back gives the same Log (see
// datasets/FORMAT.md for what is and is not stored).
#include <filesystem>
#include <string>

#include "core/log.h"

namespace locbench::io {

// Writes PARAM records first, then ENCODER, ODOM, COMPASS, TRUEPOS and FLASER records merged in
// time order (ties in that order), numbers in shortest round-trip form, host "locbench".
// Gzip-compressed when the path ends in ".gz". Relations and landmarks are not written (use
// write_relations for relations). PARAM records for the FLASER maximum range and laser mounting
// are set from the scans when they disagree with log.params.
// Throws std::invalid_argument for a Log the format cannot hold (times going backwards within a
// record type, non-finite numbers, negative ranges, bearings other than the FLASER convention,
// scans with different max ranges or mountings, PARAM names or values empty or with
// whitespace) and InputError when the file cannot be written.
void write_carmen_log(const Log& log, const std::filesystem::path& path);

// The same text in memory.
std::string format_carmen_log(const Log& log);

}  // namespace locbench::io
