#include "core/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <string>

#include "core/errors.h"
#include "core/json_file.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

using testing::ScratchDir;

// The message of the InputError `f` throws ("" when it throws none).
template <class F>
std::string input_error(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

TEST(InputFile, ReadsARegularFileWhole) {
  ScratchDir dir;
  write(dir.file("a.txt"), "hello\n");
  InputFile in(dir.file("a.txt"), "text file", 100);
  EXPECT_EQ(in.size(), 6u);
  EXPECT_EQ(in.read_all(), "hello\n");
}

TEST(InputFile, RefusesAMissingFileAFolderAFifoAndADevice) {
  ScratchDir dir;
  EXPECT_NE(input_error([&] { InputFile(dir.file("none"), "log", 100); }).find("cannot open the log: no such file"),
            std::string::npos);
  EXPECT_NE(input_error([&] {
              InputFile(dir.path(), "log", 100);
            }).find("is a folder: expected the log to be a regular file"),
            std::string::npos);
  ASSERT_EQ(::mkfifo(dir.file("p").c_str(), 0600), 0);
  // Returns at once (no writer is waited for) with what the file is.
  EXPECT_NE(input_error([&] { InputFile(dir.file("p"), "log", 100); }).find("p: is a named pipe (FIFO)"),
            std::string::npos);
  EXPECT_NE(input_error([&] { InputFile("/dev/zero", "log", 100); }).find("/dev/zero: is a character device"),
            std::string::npos);
}

TEST(InputFile, AcceptsAFileAtTheByteLimitAndRefusesOneByteMore) {
  ScratchDir dir;
  write(dir.file("at"), std::string(100, 'x'));
  write(dir.file("past"), std::string(101, 'x'));
  EXPECT_EQ(InputFile(dir.file("at"), "file", 100).read_all().size(), 100u);
  EXPECT_NE(input_error([&] { InputFile(dir.file("past"), "file", 100); }).find("is more than 100 bytes"),
            std::string::npos);
}

TEST(JsonFile, ParsesNestingAtTheLimitAndRefusesOneLevelMore) {
  const auto nested = [](int depth) {
    return std::string(static_cast<std::size_t>(depth), '[') + std::string(static_cast<std::size_t>(depth), ']');
  };
  EXPECT_NO_THROW(parse_json_text(nested(512), "a.json"));
  EXPECT_NE(input_error([&] {
              parse_json_text("\n" + nested(513), "a.json");
            }).find("a.json:2: arrays and objects nest more than 512 levels deep"),
            std::string::npos);
}

TEST(JsonFile, BracketsInsideStringsAreNotNesting) {
  const std::string text = R"({"a": ")" + std::string(1000, '[') + R"(\"{{{", "b": 1})";
  EXPECT_EQ(parse_json_text(text, "a.json").at("b"), 1);
}

TEST(JsonFile, RefusesAFifoAsAJsonInput) {
  ScratchDir dir;
  ASSERT_EQ(::mkfifo(dir.file("c.json").c_str(), 0600), 0);
  EXPECT_NE(input_error([&] {
              read_json_file(dir.file("c.json"), "--config file (JSON)");
            }).find("is a named pipe (FIFO): expected the --config file (JSON) to be a regular file"),
            std::string::npos);
}

}  // namespace
}  // namespace locbench
