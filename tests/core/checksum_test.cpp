#include "core/checksum.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

TEST(Checksum, IsTheCrc32OfTheBytes) {
  // CRC-32 of "123456789" is the standard check value 0xcbf43926.
  EXPECT_EQ(text_checksum("123456789"), "crc32:cbf43926");
  testing::ScratchDir dir;
  std::ofstream(dir.file("a.txt")) << "123456789";
  EXPECT_EQ(file_checksum(dir.file("a.txt")), "crc32:cbf43926");
}

TEST(Checksum, OfAFolderChangesWhenAFileChanges) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("a.txt")) << "one";
  std::ofstream(dir.file("b.txt")) << "two";
  const std::string before = file_checksum(dir.path());
  std::ofstream(dir.file("b.txt")) << "twO";
  EXPECT_NE(file_checksum(dir.path()), before);
}

TEST(Checksum, OfAMissingFileIsAnInputError) { EXPECT_THROW(file_checksum("/nonexistent/file"), InputError); }

}  // namespace
}  // namespace locbench
