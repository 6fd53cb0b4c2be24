#pragma once
// Writes a text file, gzip-compressed when the path ends in ".gz", plain otherwise. Atomic: the
// file appears (replacing any previous one) only when close() succeeds; a writer destroyed
// without close() (an exception, a kill) leaves the previous file untouched.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

struct gzFile_s;

namespace locbench {
class AtomicOutput;
}

namespace locbench::io {

class TextWriter {
 public:
  // Creates (or truncates) `path`. Throws InputError if it cannot be opened for writing.
  explicit TextWriter(const std::filesystem::path& path);
  ~TextWriter();  // discards the text unless close() succeeded
  TextWriter(const TextWriter&) = delete;
  TextWriter& operator=(const TextWriter&) = delete;

  void write(std::string_view text);  // throws InputError on a write error
  void close();                       // flushes and closes; throws InputError on failure

 private:
  std::string path_;
  std::unique_ptr<AtomicOutput> output_;
  gzFile_s* file_ = nullptr;
};

// Writes `text` to `path` through a TextWriter (atomic; gzip for ".gz").
void write_text_file(const std::filesystem::path& path, std::string_view text);

// True if the file name ends in ".gz" (case-insensitive).
bool has_gz_suffix(const std::filesystem::path& path);

}  // namespace locbench::io
