#pragma once
// Reader of the UMBmark input a person fills in after driving the square (§2.1):
//
//   { "side_length_m": 1.6,
//     "nominal": { "wheel_diameter_m": 0.0885, "wheelbase_m": 0.198,
//                  "gear_ratio": 1, "counts_per_rev": 22 },
//     "tape_measure_scale": 1.0,
//     "leg_ticks": { "left": 127, "right": 127 },
//     "runs": [ { "direction": "cw", "x_error_m": 0.31, "y_error_m": -0.12 }, ... ] }
//
// Metres throughout. `nominal` may give per-wheel diameters (`wheel_diameter_left_m` and
// `wheel_diameter_right_m`) instead of `wheel_diameter_m`. `tape_measure_scale` (E_s = D_a/D_n,
// eq. 2.15) is optional, default 1. `leg_ticks` are the encoder counts logged on one straight leg
// (N_L, N_R of eq. 2.22–2.23). `runs`: normally 5 per direction; at least one each.
//
// Strict: unknown keys, missing fields, wrong types, NaN/Infinity (as literals or strings),
// non-positive lengths and values that look like millimetres (a wheel diameter over 2 m, a
// wheelbase over 5 m, a side over 100 m, a return error longer than the side) throw InputError
// naming the file and the JSON path (`runs[3].x_error_m`). Syntax errors carry their line;
// semantic errors have line 0.
#include <nlohmann/json.hpp>
#include <string>

#include "core/umbmark_measurements.h"

namespace locbench::io {

// Reads and checks the file at `path`; unreadable files throw InputError.
UmbmarkInput read_umbmark_input(const std::string& path);

// The same for JSON text; `source` names it in errors.
UmbmarkInput parse_umbmark_input(const std::string& text, const std::string& source);
// The same from already parsed JSON; `source` names it in errors.
UmbmarkInput umbmark_input_from_json(const nlohmann::json& j, const std::string& source);

}  // namespace locbench::io
