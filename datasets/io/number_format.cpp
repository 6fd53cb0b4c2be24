#include "datasets/io/number_format.h"

#include <charconv>

namespace locbench::io {

void append_number(std::string& out, double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  out.append(buf, res.ptr);
}

void append_number(std::string& out, std::int64_t v) {
  char buf[24];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

void append_row(std::string& out, std::initializer_list<double> values) {
  const char* separator = "";
  for (const double v : values) {
    out += separator;
    append_number(out, v);
    separator = " ";
  }
  out.push_back('\n');
}

std::string number_text(double v) {
  std::string out;
  append_number(out, v);
  return out;
}

}  // namespace locbench::io
