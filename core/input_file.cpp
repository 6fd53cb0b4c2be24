#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/errors.h"
#include "core/input_limits.h"

namespace locbench {
namespace {

// What a non-regular file is, for "is a named pipe (FIFO): expected …".
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string too_large_message(std::uint64_t max_bytes, bool decompressed) {
  return std::string(decompressed ? "decompresses to" : "is") + " more than " +
         limits::limit_text(static_cast<double>(max_bytes)) +
         " bytes: expected at most that for one input file (see `locbench --help`, \"Input limits\")";
}

InputFile::InputFile(const std::filesystem::path& path, const std::string& what, std::uint64_t max_bytes)
    : name_(path.string()), what_(what), max_bytes_(max_bytes) {
  // O_NONBLOCK: opening a FIFO without a writer returns at once instead of waiting for one.
  fd_ = ::open(name_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int err = errno;
    throw InputError(name_, 0,
                     "cannot open the " + what + ": " + (err == ENOENT ? "no such file" : std::strerror(err)));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int err = errno;
    ::close(fd_);
    throw InputError(name_, 0, "cannot open the " + what + ": " + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw InputError(name_, 0, "is " + kind_of(st.st_mode) + ": expected the " + what + " to be a regular file");
  }
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
  size_ = static_cast<std::uint64_t>(st.st_size);
  if (size_ > max_bytes_) {
    ::close(fd_);
    throw InputError(name_, 0, too_large_message(max_bytes_, false));
  }
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

int InputFile::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

std::size_t InputFile::read(char* buf, std::size_t n) {
  for (;;) {
    const ssize_t got = ::read(fd_, buf, n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw InputError(name_, 0, "cannot read the " + what_ + ": " + std::strerror(errno));
    read_ += static_cast<std::uint64_t>(got);
    if (read_ > max_bytes_) throw InputError(name_, 0, too_large_message(max_bytes_, false));
    return static_cast<std::size_t>(got);
  }
}

std::string InputFile::read_all() {
  std::string text;
  text.reserve(static_cast<std::size_t>(size_));
  char buf[1 << 16];
  while (const std::size_t got = read(buf, sizeof buf)) text.append(buf, got);
  return text;
}

}  // namespace locbench
