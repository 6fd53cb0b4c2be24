#pragma once
// Typed errors thrown by library code. The CLI maps InputError and UsageError to exit code 2.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace locbench {

// Malformed or unreadable input: names the file, the line (0 when not line-based) and what
// was expected, e.g. "log.clf:12: ODOM: expected 9 fields, found 7".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::size_t line, const std::string& what)
      : std::runtime_error(format(file, line, what)), file_(std::move(file)), line_(line) {}
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }

 private:
  static std::string format(const std::string& file, std::size_t line, const std::string& what) {
    return line > 0 ? file + ":" + std::to_string(line) + ": " + what : file + ": " + what;
  }
  std::string file_;
  std::size_t line_;
};

// Bad command-line usage or an invalid option value (not tied to a file).
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace locbench
