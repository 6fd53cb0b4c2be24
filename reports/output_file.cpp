#include "reports/output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>

#include "core/errors.h"

namespace locbench::reports {
namespace fs = std::filesystem;
namespace {

// The process's umask, read once (umask can only be read by setting it; the function-local
// static makes that happen on one thread only).
mode_t process_umask() {
  static const mode_t mask = [] {
    const mode_t m = ::umask(0);
    ::umask(m);
    return m;
  }();
  return mask;
}

[[noreturn]] void fail(const fs::path& path, const std::string& what, int err) {
  throw InputError(path.string(), 0, what + ": " + std::strerror(err));
}

void write_all(int fd, std::string_view text, const fs::path& shown) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(shown, "cannot write", errno);
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

// write_all, closing `fd` before the error goes on when it fails.
void write_all_or_close(int fd, std::string_view text, const fs::path& shown) {
  try {
    write_all(fd, text, shown);
  } catch (...) {
    ::close(fd);
    throw;
  }
}

// An existing target that is not a regular file (/dev/stdout, /dev/full, a FIFO) cannot be
// replaced by a rename: it is written in place, every write checked.
bool is_special(const fs::path& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

void refuse_folder(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw InputError(path.string(), 0, "is a folder: expected the path of a file to write");
  }
}

void make_parent(const fs::path& path) {
  if (!path.has_parent_path()) return;
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) throw InputError(path.parent_path().string(), 0, "cannot create the folder: " + ec.message());
}

void sync_folder(const fs::path& file) {
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    ::fsync(fd);  // best effort: the rename is already visible to readers
    ::close(fd);
  }
}

fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

bool same_file(const fs::path& a, const fs::path& b) {
  if (resolved(a) == resolved(b)) return true;
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

bool inside(const fs::path& file, const fs::path& folder) {
  const std::string f = resolved(file).string(), d = resolved(folder).string();
  return f.size() > d.size() && f.compare(0, d.size(), d) == 0 && (d.back() == '/' || f[d.size()] == '/');
}

}  // namespace

AtomicOutput::AtomicOutput(const fs::path& target) : target_(target) {
  refuse_folder(target);
  if (is_special(target)) {
    temp_ = target;  // written in place (see is_special)
    committed_ = true;
    return;
  }
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string name = (dir / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) fail(target, "cannot open for writing (a temporary file beside it)", errno);
  // mkstemp creates the file 0600; the output gets what any new file gets (0666 less the umask),
  // so that reports are readable by whoever could read the folder.
  const int rc = ::fchmod(fd, 0666 & ~process_umask());
  const int err = errno;
  ::close(fd);
  if (rc != 0) fail(target, "cannot set the permissions of the temporary file beside it", err);
  temp_ = name;
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicOutput::commit() {
  if (committed_) return;
  const int fd = ::open(temp_.c_str(), O_RDONLY);
  if (fd < 0) fail(target_, "cannot reopen the temporary file " + temp_.string(), errno);
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) fail(target_, "cannot flush to disk", err);
  if (::rename(temp_.c_str(), target_.c_str()) != 0) fail(target_, "cannot replace", errno);
  committed_ = true;
  sync_folder(target_);
}

void write_file_atomically(const fs::path& path, std::string_view text) {
  refuse_folder(path);
  if (is_special(path)) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC);
    if (fd < 0) fail(path, "cannot open for writing", errno);
    write_all_or_close(fd, text, path);
    if (::close(fd) != 0) fail(path, "cannot write (on close)", errno);
    return;
  }
  make_parent(path);
  AtomicOutput out(path);
  const int fd = ::open(out.temp_path().c_str(), O_WRONLY | O_TRUNC);
  if (fd < 0) fail(path, "cannot open the temporary file for writing", errno);
  write_all_or_close(fd, text, path);
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    fail(path, "cannot write (flush)", err);
  }
  if (::close(fd) != 0) fail(path, "cannot write (on close)", errno);
  out.commit();
}

void check_outputs(const std::vector<std::string>& inputs, const std::vector<NamedPath>& outputs,
                   const std::string& folder_ext) {
  std::vector<const NamedPath*> seen;
  for (const NamedPath& o : outputs) {
    if (o.path.empty()) continue;
    for (const std::string& in : inputs) {
      if (in.empty()) continue;
      // A catalog name or "folder#robot1" input: compare the file part.
      const std::string file = in.substr(0, in.find('#'));
      std::error_code ec;
      if (same_file(o.path, file)) {
        throw InputError(o.path, 0, o.flag + " would overwrite the input " + in + ": choose another output path");
      }
      if (!folder_ext.empty() && fs::is_directory(file, ec) && inside(o.path, file) &&
          fs::path(o.path).extension() == folder_ext) {
        throw InputError(o.path, 0,
                         o.flag + " lies in the input folder " + in + ", whose " + folder_ext +
                             " files are read as inputs: choose a path outside it");
      }
    }
    for (const NamedPath* p : seen) {
      if (same_file(o.path, p->path)) {
        throw InputError(o.path, 0, o.flag + " and " + p->flag + " name the same file: give each output its own path");
      }
    }
    refuse_folder(o.path);
    seen.push_back(&o);
  }
}

OutputFolderLock::OutputFolderLock(const fs::path& folder) {
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec)) {
    throw InputError(folder.string(), 0, "exists and is not a folder: --out expects a folder for the reports");
  }
  fs::create_directories(folder, ec);
  if (ec) throw InputError(folder.string(), 0, "cannot create the output folder: " + ec.message());
  const fs::path lock = folder / ".locbench.lock";
  fd_ = ::open(lock.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (fd_ < 0) fail(lock, "cannot create the output folder's lock file", errno);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK) {
      throw InputError(folder.string(), 0,
                       "output folder in use by another locbench command (it holds " + lock.filename().string() +
                           "): wait for it to finish or choose another folder");
    }
    fail(lock, "cannot lock the output folder", err);
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock; the empty lock file stays (harmless)
}

}  // namespace locbench::reports
