#pragma once
// Reads text line by line from a file (plain or gzip-compressed, detected from the content) or
// from memory, counting 1-based line numbers for error messages.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

struct gzFile_s;

namespace locbench::io {

class LineReader {
 public:
  // Opens `path` through the input opener (core/input_file.h). Throws InputError when it is
  // missing, not a regular file (a folder, a FIFO, a device), unreadable, or longer than
  // `max_bytes` — compressed or, while reading, decompressed (a gzip bomb stops at the limit).
  explicit LineReader(const std::filesystem::path& path, std::uint64_t max_bytes = kDefaultMaxBytes);
  static const std::uint64_t kDefaultMaxBytes;  // limits::kInputFileBytes
  // Reads `text` (not copied: it must outlive the reader); `source_name` names it in errors.
  LineReader(std::string_view text, std::string source_name);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its line ending ("\n" or "\r\n"); false at the end of the input.
  // The view stays valid until the next call. Throws InputError on a corrupt or truncated gzip
  // stream, on a read error, and at the end of an input that is empty or only whitespace.
  bool next(std::string_view& line);

  // 1-based number of the line last returned by next() (0 before the first).
  std::size_t line_number() const { return line_number_; }
  // The file name (or source name) used in error messages.
  const std::string& source() const { return source_; }

 private:
  bool fill();          // reads more of the file into buffer_; false at its end
  void check_stream();  // throws InputError if zlib reported an error
  void finish();        // end of input: empty-input check, closes the file

  std::string source_;
  gzFile_s* file_ = nullptr;
  std::string buffer_;  // file data not yet returned: buffer_[begin_, buffer_.size())
  std::size_t begin_ = 0;
  std::string_view text_;  // in-memory input still to return
  bool from_file_ = false;
  bool at_end_ = false;
  bool has_content_ = false;  // a non-whitespace character was seen
  std::size_t line_number_ = 0;
  unsigned long crc_ = 0;     // CRC-32 of the decompressed bytes (gzip_trailer.h)
  std::uint64_t length_ = 0;  // decompressed bytes read
  std::uint64_t max_bytes_ = 0;
};

// Reads a file, or text in memory, with `read` (a function of LineReader&): both entry points of
// every line-based format, in one place.
template <class Read>
auto read_lines_of(const std::filesystem::path& path, Read read) {
  LineReader reader(path);
  return read(reader);
}
template <class Read>
auto read_lines_of(std::string_view text, const std::string& source_name, Read read) {
  LineReader reader(text, source_name);
  return read(reader);
}

}  // namespace locbench::io
