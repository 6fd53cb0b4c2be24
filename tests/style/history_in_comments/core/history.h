#pragma once
// A fixture: comments that carry history (flagged) beside strings and literals that may (not).
#include <string>

namespace fixture {

// Measured on 2026-11-25: flagged.
inline const std::string kStamp = "2026-11-25T12:00:00Z";  // a string may hold a date
inline const std::string kColour = R"css(
body{color:#222} /* not a comment: inside a raw string, issue 12 */
)css";
inline constexpr int kMany = 10'000;  // digit separators are not quotes
inline constexpr char kQuote = '"';   // as before commit 84a7e1e: flagged
/* A block comment
   that names issue 17 on its second line: flagged. */
inline const std::string kIssue = "see issue 4 and #5";  // the version 1.0 is not history
inline int twice(int x) { return 2 * x; }                /* #9: flagged */

}  // namespace fixture
