#pragma once
// Numbers printed for the text formats: the shortest text that reads back to the same value.
#include <cstdint>
#include <initializer_list>
#include <string>

namespace locbench::io {

// Appends the shortest decimal form of `v` that parses back to exactly `v` (e.g. "0.1", "1e+20").
void append_number(std::string& out, double v);
void append_number(std::string& out, std::int64_t v);
// The same as a string, for messages ("time: 1248444189.599 before …").
std::string number_text(double v);

// Appends one line of a whitespace-separated numeric format: the values, each as above,
// separated by single spaces, then '\n'.
void append_row(std::string& out, std::initializer_list<double> values);

}  // namespace locbench::io
