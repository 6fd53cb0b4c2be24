// The output layer: atomic replacement, checked writes, outputs that would overwrite inputs,
// and the --out folder lock.
#include "core/output_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "core/errors.h"
#include "tests/input_error_message.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

using testing::input_error_message;

TEST(OutputFile, ReplacesTheTargetAndLeavesNoTemporaryFile) {
  testing::ScratchDir dir;
  write_file_atomically(dir.file("a/r.json"), "old");
  write_file_atomically(dir.file("a/r.json"), "new");
  EXPECT_EQ(testing::file_contents(dir.file("a/r.json")), "new");
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("a"))) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
}

// Written through a temporary file, an output still gets a new file's mode: 0666 less the
// process's umask (0644 under the usual 022), not mkstemp's 0600.
TEST(OutputFile, AnOutputHasTheModeOfANewFileNotOfATemporaryOne) {
  testing::ScratchDir dir;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  write_file_atomically(dir.file("r.json"), "{}");
  struct stat st {};
  ASSERT_EQ(::stat(dir.file("r.json").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0666 & ~mask) << "umask " << std::oct << mask;
}

TEST(OutputFile, AnUncommittedOutputLeavesThePreviousFileIntact) {
  testing::ScratchDir dir;
  write_file_atomically(dir.file("r.json"), "previous report");
  {
    AtomicOutput out(dir.file("r.json"));
    std::ofstream(out.temp_path()) << "half a rep";  // killed before commit()
  }
  EXPECT_EQ(testing::file_contents(dir.file("r.json")), "previous report");
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // the temporary file went with its owner
}

TEST(OutputFile, AFullDiskIsAnInputErrorNamingThePath) {
  const std::string e = input_error_message([] { write_file_atomically("/dev/full", "text"); });
  EXPECT_NE(e.find("/dev/full"), std::string::npos) << e;
  EXPECT_NE(e.find("No space left"), std::string::npos) << e;
}

TEST(OutputFile, AFolderIsNotAFileToWrite) {
  testing::ScratchDir dir;
  EXPECT_NE(input_error_message([&] { write_file_atomically(dir.path(), "x"); }).find("is a folder"),
            std::string::npos);
}

TEST(OutputFile, AnOutputThatIsAnInputIsRefused) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("in.clf")) << "x";
  std::filesystem::create_symlink(dir.file("in.clf"), dir.file("link.clf"));
  const std::string in = dir.file("in.clf").string();
  EXPECT_NE(input_error_message([&] {
              check_outputs({in}, {{"--report", in}});
            }).find("would overwrite the input"),
            std::string::npos);
  EXPECT_NE(input_error_message([&] {
              check_outputs({in}, {{"--report", dir.file("link.clf").string()}});
            }).find("would overwrite"),
            std::string::npos);
  EXPECT_NE(input_error_message([&] {
              check_outputs({in}, {{"--report", dir.path().string() + "/./sub/../in.clf"}});
            }).find("would overwrite"),
            std::string::npos);
  EXPECT_NE(input_error_message([&] {
              check_outputs({}, {{"-o", dir.file("a").string()}, {"--truth-tum", dir.file("a").string()}});
            }).find("name the same file"),
            std::string::npos);
  EXPECT_EQ(input_error_message([&] { check_outputs({in}, {{"--report", dir.file("out.json").string()}}); }), "");
}

TEST(OutputFile, AnOutputInsideAnInputFolderIsRefusedOnlyForTheFilesItReads) {
  testing::ScratchDir dir;
  const std::string folder = dir.path().string();
  EXPECT_NE(input_error_message([&] {
              check_outputs({folder}, {{"--json", dir.file("gate.json").string()}}, ".json");
            }).find("lies in the input folder"),
            std::string::npos);
  EXPECT_EQ(input_error_message([&] {
              check_outputs({folder}, {{"-o", dir.file("report.html").string()}}, ".json");
            }),
            "");
}

TEST(OutputFile, ASecondLockOnAnOutputFolderIsRefused) {
  testing::ScratchDir dir;
  const OutputFolderLock first(dir.file("out"));
  EXPECT_NE(input_error_message([&] { OutputFolderLock second(dir.file("out")); }).find("in use"), std::string::npos);
  std::ofstream(dir.file("file")) << "x";
  EXPECT_NE(input_error_message([&] { OutputFolderLock f(dir.file("file")); }).find("not a folder"), std::string::npos);
}

TEST(OutputFile, TheLockIsReleasedWithItsOwner) {
  testing::ScratchDir dir;
  { const OutputFolderLock first(dir.file("out")); }
  EXPECT_EQ(input_error_message([&] { OutputFolderLock again(dir.file("out")); }), "");
}

TEST(OutputFile, ALockFileThatIsASymbolicLinkIsRefusedAndNothingIsCreatedWhereItPoints) {
  testing::ScratchDir dir;
  std::filesystem::create_directories(dir.file("out"));
  std::filesystem::create_symlink(dir.file("elsewhere"), dir.file("out/.locbench.lock"));
  EXPECT_NE(input_error_message([&] { OutputFolderLock lock(dir.file("out")); }).find("is a symbolic link"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.file("elsewhere")));
}

// A temporary file as a killed writer leaves it: unlocked, its modification time `age` ago.
std::filesystem::path killed_writers_temporary(const std::filesystem::path& folder, const std::string& target,
                                               std::chrono::seconds age) {
  const auto p = folder / ("." + target + ".tmp-Ab12Cd");
  std::filesystem::create_directories(folder);
  std::ofstream(p) << "half a report";
  std::filesystem::last_write_time(p, std::filesystem::file_time_type::clock::now() - age);
  return p;
}

TEST(OutputFile, ATemporaryFileOfAKilledWriterIsRemovedByTheNextLockOfItsFolder) {
  testing::ScratchDir dir;
  const auto stale = killed_writers_temporary(dir.file("out/odometry"), "sim_corridor.json", std::chrono::hours(1));
  const auto fresh = killed_writers_temporary(dir.file("out"), "young.json", std::chrono::seconds(0));
  AtomicOutput live(dir.file("out/live.json"));  // a writer at work: its file is locked
  std::filesystem::last_write_time(live.temp_path(),
                                   std::filesystem::file_time_type::clock::now() - std::chrono::hours(1));
  { const OutputFolderLock lock(dir.file("out")); }
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_TRUE(std::filesystem::exists(fresh));  // maybe a writer about to take its lock
  EXPECT_TRUE(std::filesystem::exists(live.temp_path()));
}

TEST(OutputFile, ATemporaryFileOfAKilledWriterIsRemovedByTheNextWriterOfTheSameFile) {
  testing::ScratchDir dir;
  const auto stale = killed_writers_temporary(dir.path(), "big.clf", std::chrono::hours(1));
  const auto other = killed_writers_temporary(dir.path(), "other.clf", std::chrono::hours(1));
  write_file_atomically(dir.file("big.clf"), "log");
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_TRUE(std::filesystem::exists(other));  // another file's: left to its own writer
}

TEST(OutputFile, AnInputInsideTheOutputFolderIsRefused) {
  testing::ScratchDir dir;
  std::filesystem::create_directories(dir.file("o/slip"));
  std::ofstream(dir.file("o/slip/normality_table_3_1.json")) << "{}";
  EXPECT_NE(input_error_message([&] {
              check_inputs_outside({"", dir.file("o/slip/normality_table_3_1.json").string()}, dir.file("o"), "--out");
            }).find("inside the folder --out"),
            std::string::npos);
  EXPECT_NE(
      input_error_message([&] { check_inputs_outside({dir.file("o/../o/x.json").string()}, dir.file("o"), "--out"); }),
      "");
  EXPECT_EQ(input_error_message([&] { check_inputs_outside({dir.file("c.json").string()}, dir.file("o"), "--out"); }),
            "");
}

TEST(OutputFile, AFileWrittenInsideALockedFolderIsRefusedWhileTheFolderIsInUse) {
  testing::ScratchDir dir;
  std::filesystem::create_directories(dir.file("o/odometry"));
  {
    const OutputFolderLock run(dir.file("o"));  // `run --out o` at work
    EXPECT_NE(input_error_message([&] { lock_folders_above(dir.file("o/odometry/sim_corridor.json")); }).find("in use"),
              std::string::npos);
  }
  EXPECT_EQ(lock_folders_above(dir.file("o/odometry/sim_corridor.json")).size(), 1u);
  EXPECT_EQ(lock_folders_above(dir.file("elsewhere/x.json")).size(), 0u);  // no lock file: none taken or made
}

}  // namespace
}  // namespace locbench
