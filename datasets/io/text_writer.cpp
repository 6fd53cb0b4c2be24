#include "datasets/io/text_writer.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

#include "core/errors.h"
#include "core/output_file.h"

namespace locbench::io {

bool has_gz_suffix(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  return ext.size() == 3 && ext[0] == '.' && (ext[1] == 'g' || ext[1] == 'G') && (ext[2] == 'z' || ext[2] == 'Z');
}

TextWriter::TextWriter(const std::filesystem::path& path)
    : path_(path.string()), output_(std::make_unique<AtomicOutput>(path)) {
  errno = 0;
  // "T": transparent (uncompressed) writing through the same zlib interface. The text goes to a
  // temporary file beside `path`, renamed over it by close() (core/output_file.h).
  file_ = gzopen(output_->temp_path().c_str(), has_gz_suffix(path) ? "wb6" : "wbT");
  if (file_ == nullptr) {
    const int err = errno;
    throw InputError(path_, 0,
                     std::string("cannot open for writing: ") + (err != 0 ? std::strerror(err) : "out of memory"));
  }
  gzbuffer(file_, 1u << 18);
}

TextWriter::~TextWriter() {
  if (file_ != nullptr) gzclose_w(file_);
}

void TextWriter::write(std::string_view text) {
  while (!text.empty()) {
    const std::size_t n = std::min<std::size_t>(text.size(), std::numeric_limits<int>::max() / 2);
    if (gzwrite(file_, text.data(), static_cast<unsigned>(n)) != static_cast<int>(n)) {
      int errnum = Z_OK;
      const char* msg = gzerror(file_, &errnum);
      throw InputError(path_, 0, std::string("write error: ") + (errnum == Z_ERRNO ? std::strerror(errno) : msg));
    }
    text.remove_prefix(n);
  }
}

void TextWriter::close() {
  if (file_ == nullptr) return;
  const int rc = gzclose_w(file_);
  file_ = nullptr;
  if (rc != Z_OK) {
    throw InputError(
        path_, 0,
        rc == Z_ERRNO ? std::string("write error: ") + std::strerror(errno) : std::string("write error on close"));
  }
  output_->commit();
}

void write_text_file(const std::filesystem::path& path, std::string_view text) {
  TextWriter writer(path);
  writer.write(text);
  writer.close();
}

}  // namespace locbench::io
