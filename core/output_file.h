#pragma once
// The one output layer every verb writes through, so that nothing is lost or half-written:
//   - write_file_atomically: the text goes to a temporary file in the target's folder, is
//     flushed and fsync'ed, and is renamed over the target only when every write and the close
//     succeeded; a kill or a full disk leaves the previous file intact (no 0-byte reports).
//   - check_outputs: an output that is, or resolves to, one of the command's inputs or another
//     of its outputs is refused before any work (exit 2), so no input is ever overwritten.
//   - OutputFolderLock: a folder given to --out is locked (flock on <folder>/.locbench.lock) for
//     the life of the command; a second command on the same folder is refused, not interleaved.
//     The lock file is never followed through a symbolic link.
//   - Temporary files (".<name>.tmp-XXXXXX") stay flock'ed by their writer; one left by a killed
//     writer is removed by the next writer of the same file and by the next lock of its folder.
// Every failure is an InputError naming the path and the system's reason (exit 2).
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace locbench {

// Writes `text` to `path` atomically (creating its folder). InputError on any failure.
// AtomicOutput (below) does not create folders.
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

// A temporary file beside `target`, renamed over it by commit(); removed if never committed.
// For writers that stream (gzip logs): write to temp_path(), then commit().
class AtomicOutput {
 public:
  explicit AtomicOutput(const std::filesystem::path& target);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& target() const { return target_; }
  // fsyncs the finished temporary file and renames it over the target.
  void commit();

 private:
  std::filesystem::path target_, temp_;
  bool committed_ = false;
  int lock_fd_ = -1;  // the temporary file, flock'ed while it may be written
};

// One named output of a command: its flag ("--report") and path; empty paths are ignored.
struct NamedPath {
  std::string flag;
  std::string path;
};

// InputError (exit 2) when an output is the same file as an input (same path after resolving
// symlinks and "..", or the same inode), lies inside a folder input whose files the command
// reads (`folder_inputs_read_by_extension` = ".json" refuses out/x.json under an input folder
// `out`, not out/report.html), is an existing folder where a file is expected, or equals
// another output.
void check_outputs(const std::vector<std::string>& inputs, const std::vector<NamedPath>& outputs,
                   const std::string& folder_inputs_read_by_extension = "");

// InputError (exit 2) when an input lies inside (or is) the output folder a command writes, e.g.
// `run --config out/x.json --out out`: its files may be replaced by the command's reports.
void check_inputs_outside(const std::vector<std::string>& inputs, const std::filesystem::path& folder,
                          const std::string& flag);

// Holds an exclusive lock on `folder` (created if absent) until destroyed, then removes the
// temporary files killed writers left in it. InputError when the folder is in use by another
// locbench command, is an existing file, or its lock file is a symbolic link or not a file.
class OutputFolderLock {
 public:
  explicit OutputFolderLock(const std::filesystem::path& folder);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int fd_ = -1;
};

// The locks a command writing the single file `file` takes: every folder above it that holds a
// .locbench.lock (a `run --out` or `merge -o` folder it lies in). InputError when one is in use.
std::vector<std::unique_ptr<OutputFolderLock>> lock_folders_above(const std::filesystem::path& file);

}  // namespace locbench
