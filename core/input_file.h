#pragma once
// The one way an input file is opened. Every reader (JSON, line-based logs plain or gzip, the
// checksums of provenance) goes through it, so every input is held to the same rules:
//  * it must be a regular file: a folder, a FIFO (named pipe), a socket or a device such as
//    /dev/zero is an InputError naming the file and what it is — opening never blocks (a FIFO
//    is opened with O_NONBLOCK, then refused), and nothing is read without end;
//  * it is at most `max_bytes` long (the limits of core/input_limits.h, printed by `--help`),
//    checked from its size before reading and again while reading (a file that grows).
// Readers of compressed data count the decompressed bytes against the same limit themselves
// (datasets/io/line_reader.h).
#include <cstdint>
#include <filesystem>
#include <string>

namespace locbench {

class InputFile {
 public:
  // `what` names the file's role in messages ("rules file (JSON)", "log", …).
  InputFile(const std::filesystem::path& path, const std::string& what, std::uint64_t max_bytes);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& name() const { return name_; }
  std::uint64_t size() const { return size_; }
  std::uint64_t max_bytes() const { return max_bytes_; }
  // The open descriptor (still owned by this object).
  int fd() const { return fd_; }
  // Hands the descriptor over (to gzdopen, which closes it); this object no longer closes it.
  int release();
  // The whole file. Throws InputError on a read error or when it holds more than max_bytes.
  std::string read_all();
  // Reads up to `n` bytes into `buf`; 0 at the end. Throws InputError on a read error or past
  // max_bytes in total.
  std::size_t read(char* buf, std::size_t n);

 private:
  std::string name_;
  std::string what_;
  std::uint64_t max_bytes_;
  std::uint64_t size_ = 0;
  std::uint64_t read_ = 0;
  int fd_ = -1;
};

// "is (decompresses to) more than N bytes: expected at most that …": the message for an input
// beyond `max_bytes`, shared with the readers that decompress.
std::string too_large_message(std::uint64_t max_bytes, bool decompressed);

}  // namespace locbench
