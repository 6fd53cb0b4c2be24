#include "core/output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>

#include "core/errors.h"

namespace locbench {
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

// Opens a special target for writing without blocking: a FIFO that nothing reads is refused
// (open would wait for a reader forever), one being read is written as a pipe (`-o /dev/stdout`
// into `| less`). The descriptor is blocking again when returned.
int open_special_for_writing(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0 && errno == ENXIO) {
    throw InputError(path.string(), 0,
                     "is a named pipe (FIFO) that nothing reads: expected a file to write (or a pipe being read)");
  }
  if (fd < 0) fail(path, "cannot open for writing", errno);
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
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

// Temporary files are named ".<target name>.tmp-XXXXXX" (mkstemp), beside their target.
constexpr std::string_view kTempMark = ".tmp-";
bool is_temporary_name(const std::string& n) {
  return n.size() > kTempMark.size() + 7 && n.front() == '.' &&
         n.compare(n.size() - 6 - kTempMark.size(), kTempMark.size(), kTempMark) == 0;
}

// Removes `path` when it is a temporary file no live writer holds: every writer keeps an
// exclusive flock on its temporary file until it is renamed or removed, so a lock we can take
// means its writer was killed. Files younger than 10 s are left alone (a writer takes its lock
// just after creating the file).
void remove_if_stale(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return;
  struct stat st {};
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && now - st.st_mtime > 10 && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {
    ::unlink(path.c_str());
  }
  ::close(fd);  // releases the flock
}

// The stale temporary files of `target` in its folder (`target` empty: every temporary file in
// the folder and below it).
void remove_stale_temporaries(const fs::path& folder, const std::string& target) {
  std::error_code ec;
  const std::string prefix = "." + target + std::string(kTempMark);
  const auto visit = [&](const fs::directory_entry& e) {
    const std::string n = e.path().filename().string();
    if (is_temporary_name(n) && (target.empty() || n.rfind(prefix, 0) == 0)) remove_if_stale(e.path());
  };
  if (target.empty()) {
    // Reports lie at most a few folders down (<out>/<group>/<experiment>.json): 3 levels.
    for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
      if (it.depth() >= 3) it.disable_recursion_pending();
      visit(*it);
    }
  } else {
    for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
      visit(*it);
    }
  }
}

}  // namespace

AtomicOutput::AtomicOutput(const fs::path& target) : target_(target) {
  refuse_folder(target);
  if (is_special(target)) {
    temp_ = target;  // written in place (see is_special)
    committed_ = true;
    // Held open while the writer opens the target again: a pipe's reader sees no end before it.
    lock_fd_ = open_special_for_writing(target);
    return;
  }
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  remove_stale_temporaries(dir, target.filename().string());  // left by a killed writer
  std::string name = (dir / ("." + target.filename().string() + std::string(kTempMark) + "XXXXXX")).string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) fail(target, "cannot open for writing (a temporary file beside it)", errno);
  // Held until the file is renamed or removed: a later writer removes only unlocked ones.
  ::flock(fd, LOCK_EX);
  // mkstemp creates the file 0600; the output gets what any new file gets (0666 less the umask),
  // so that reports are readable by whoever could read the folder.
  const int rc = ::fchmod(fd, 0666 & ~process_umask());
  const int err = errno;
  if (rc != 0) {
    ::unlink(name.c_str());
    ::close(fd);
    fail(target, "cannot set the permissions of the temporary file beside it", err);
  }
  temp_ = name;
  lock_fd_ = fd;
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);
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
  if (lock_fd_ >= 0) ::close(lock_fd_);
  lock_fd_ = -1;
  sync_folder(target_);
}

void write_file_atomically(const fs::path& path, std::string_view text) {
  refuse_folder(path);
  if (is_special(path)) {
    const int fd = open_special_for_writing(path);
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
  // Never followed through a symbolic link (O_NOFOLLOW), never a FIFO or device (O_NONBLOCK, then
  // a regular file required): the lock file is created in the folder and nowhere else.
  fd_ = ::open(lock.c_str(), O_CREAT | O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (fd_ < 0 && errno == ELOOP) {
    throw InputError(lock.string(), 0,
                     "is a symbolic link: the output folder's lock file is never followed (remove the link)");
  }
  if (fd_ < 0) fail(lock, "cannot create the output folder's lock file", errno);
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw InputError(lock.string(), 0, "is not a regular file: expected the output folder's lock file");
  }
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
  remove_stale_temporaries(folder, "");  // left by a killed writer in this folder
}

std::vector<std::unique_ptr<OutputFolderLock>> lock_folders_above(const fs::path& file) {
  std::vector<std::unique_ptr<OutputFolderLock>> locks;
  for (fs::path dir = resolved(file).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    struct stat st {};
    if (::lstat((dir / ".locbench.lock").c_str(), &st) == 0) locks.push_back(std::make_unique<OutputFolderLock>(dir));
    if (dir == dir.root_path()) break;
  }
  return locks;
}

void check_inputs_outside(const std::vector<std::string>& inputs, const fs::path& folder, const std::string& flag) {
  for (const std::string& in : inputs) {
    if (in.empty()) continue;
    const fs::path file = in.substr(0, in.find('#'));
    if (resolved(file) == resolved(folder) || inside(file, folder)) {
      throw InputError(in, 0,
                       "is an input inside the folder " + flag + " " + folder.string() +
                           " writes: its files may be replaced; move the input or choose another " + flag);
    }
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock; the empty lock file stays (harmless)
}

}  // namespace locbench
