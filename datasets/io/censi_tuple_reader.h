#pragma once
// Reader of Censi et al.'s calibration "tuple" files (IEEE T-RO 2013, censi_khepera/*.tuple):
// one JSON object per line, {"T": s, "phi_l": rad/s, "phi_r": rad/s, "sm": [x, y, θ]}.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/calibration_records.h"

namespace locbench::io {

// Reads a tuple file (plain or gzip). The upstream solver reads a stream of JSON values, and the
// published full sets (lstraight, l90) are concatenations of the subset files, three of which
// lack their final newline — so a line may hold several objects. Each must be a JSON object with
// the numbers T (> 0), phi_l, phi_r and the array sm of three numbers, all finite; other keys
// are ignored (the upstream solver ignores them too); an object may not span lines. Throws
// InputError naming the file, the line and what was expected for anything else, and for a file
// without tuples.
std::vector<WheelSpeedTuple> read_censi_tuples(const std::filesystem::path& path);

// The same for text in memory; `source_name` stands for the file name in errors.
std::vector<WheelSpeedTuple> parse_censi_tuples(std::string_view text, const std::string& source_name);

}  // namespace locbench::io
