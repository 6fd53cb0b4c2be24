#include "datasets/io/line_reader.h"

#include <zlib.h>

#include <cerrno>
#include <cstring>

#include "core/errors.h"
#include "core/input_file.h"
#include "core/input_limits.h"
#include "datasets/io/gzip_trailer.h"

namespace locbench::io {
namespace {

constexpr std::size_t kChunk = std::size_t{1} << 18;  // bytes read from zlib at a time

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

}  // namespace

const std::uint64_t LineReader::kDefaultMaxBytes = static_cast<std::uint64_t>(limits::kInputFileBytes.max);

LineReader::LineReader(const std::filesystem::path& path, std::uint64_t max_bytes)
    : source_(path.string()), from_file_(true), max_bytes_(max_bytes) {
  InputFile in(path, "input file", max_bytes);
  file_ = gzdopen(in.fd(), "rb");
  if (file_ == nullptr) throw InputError(source_, 0, "cannot open: out of memory");
  in.release();  // gzclose_r closes it now
  gzbuffer(file_, static_cast<unsigned>(kChunk));
}

LineReader::LineReader(std::string_view text, std::string source_name) : source_(std::move(source_name)), text_(text) {}

LineReader::~LineReader() {
  if (file_ != nullptr) gzclose_r(file_);
}

void LineReader::check_stream() {
  int errnum = Z_OK;
  const char* msg = gzerror(file_, &errnum);
  if (errnum == Z_OK) return;
  std::string what;
  if (errnum == Z_BUF_ERROR) {
    what = "truncated gzip stream: the file ends in the middle of compressed data";
  } else if (errnum == Z_ERRNO) {
    what = std::string("read error: ") + std::strerror(errno);
  } else {
    what = std::string("corrupt gzip stream: ") + (msg != nullptr ? msg : "unknown zlib error");
  }
  throw InputError(source_, line_number_ + 1, what);
}

bool LineReader::fill() {
  if (file_ == nullptr) return false;
  if (begin_ > 0) {  // drop what was already returned
    buffer_.erase(0, begin_);
    begin_ = 0;
  }
  const std::size_t old = buffer_.size();
  buffer_.resize(old + kChunk);
  const int n = gzread(file_, buffer_.data() + old, static_cast<unsigned>(kChunk));
  if (n < 0) {
    buffer_.resize(old);
    check_stream();
    throw InputError(source_, line_number_ + 1, "read error");
  }
  buffer_.resize(old + static_cast<std::size_t>(n));
  if (n > 0) {
    crc_ = crc32(crc_, reinterpret_cast<const Bytef*>(buffer_.data() + old), static_cast<uInt>(n));
    length_ += static_cast<std::uint64_t>(n);
    if (length_ > max_bytes_) {
      throw InputError(source_, 0, too_large_message(max_bytes_, gzdirect(file_) == 0));
    }
  }
  if (n == 0) {
    check_stream();
    if (gzdirect(file_) == 0) {
      if (const auto at = gzip_trailing_garbage(source_, static_cast<std::uint32_t>(crc_), length_)) {
        throw InputError(source_, 0,
                         "trailing garbage after the gzip data (from byte " + std::to_string(*at) +
                             "): expected the file to end with its last gzip member");
      }
    }
    const int rc = gzclose_r(file_);
    file_ = nullptr;
    if (rc == Z_BUF_ERROR) {
      throw InputError(source_, line_number_ + 1,
                       "truncated gzip stream: the file ends in the middle of compressed data");
    }
    if (rc != Z_OK) throw InputError(source_, line_number_ + 1, "error closing the file");
    return false;
  }
  return true;
}

void LineReader::finish() {
  at_end_ = true;
  if (!has_content_) {
    throw InputError(source_, 0, "empty file: expected at least one line of data");
  }
}

bool LineReader::next(std::string_view& line) {
  if (at_end_) return false;
  std::size_t eol = std::string_view::npos;
  if (from_file_) {
    std::size_t searched = begin_;
    for (;;) {
      const auto pos = buffer_.find('\n', searched);
      if (pos != std::string::npos) {
        eol = pos;
        break;
      }
      const std::size_t pending = buffer_.size() - begin_;
      if (!fill()) break;
      searched = pending;  // fill() moved the pending bytes to the front
    }
    const std::size_t end = eol == std::string_view::npos ? buffer_.size() : eol;
    if (end == begin_ && eol == std::string_view::npos) {
      finish();
      return false;
    }
    line = std::string_view(buffer_).substr(begin_, end - begin_);
    begin_ = eol == std::string_view::npos ? buffer_.size() : eol + 1;
  } else {
    if (text_.empty()) {
      finish();
      return false;
    }
    eol = text_.find('\n');
    line = text_.substr(0, eol);
    text_.remove_prefix(eol == std::string_view::npos ? text_.size() : eol + 1);
  }
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (!has_content_) {
    for (char c : line) {
      if (!is_blank(c)) {
        has_content_ = true;
        break;
      }
    }
  }
  ++line_number_;
  return true;
}

}  // namespace locbench::io
