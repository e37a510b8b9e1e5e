// common/atomic_file: whole or absent, parent folders created, errors naming the file and why.
#include "common/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/common/common_test_util.hpp"
#include "tests/tiny_tmpfs.hpp"

namespace a3::common {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every entry of `folder`, so that a left-over temporary file is seen.
std::vector<std::string> entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicFile, WritesTheWholeFileAndCreatesMissingFolders) {
  test::TempDir dir;
  const fs::path path = dir.path() / "a" / "b" / "out.txt";
  write_file_atomically(path, "hello\n");
  EXPECT_EQ(read_all(path), "hello\n");
  EXPECT_EQ(entries(path.parent_path()), std::vector<std::string>{"out.txt"});
}

TEST(AtomicFile, ReplacesAnOldFileOnlyOnCommit) {
  test::TempDir dir;
  const fs::path path = dir.path() / "table.csv";
  write_file_atomically(path, "old");
  {
    AtomicFileWriter writer(path);
    writer.write("new ");
    writer.write("rows");
    EXPECT_EQ(writer.bytes_written(), 8u);
    EXPECT_EQ(read_all(path), "old");
    writer.commit();
  }
  EXPECT_EQ(read_all(path), "new rows");
}

TEST(AtomicFile, AWriterDestroyedWithoutCommitLeavesNothing) {
  test::TempDir dir;
  {
    AtomicFileWriter writer(dir.path() / "half.json");
    writer.write("{\"a\":");
  }
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(AtomicFile, AFolderUnderAFileIsRefusedWithTheReason) {
  test::TempDir dir;
  write_file_atomically(dir.path() / "plain", "x");
  try {
    write_file_atomically(dir.path() / "plain" / "sub" / "x.csv", "y");
    FAIL() << "no OutputError";
  } catch (const OutputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find((dir.path() / "plain" / "sub").string()), std::string::npos) << what;
    EXPECT_NE(what.find("Not a directory"), std::string::npos) << what;
  }
}

TEST(AtomicFile, FreeBytesAreReadFromTheNearestExistingFolder) {
  test::TempDir dir;
  const std::uint64_t here = free_bytes_at(dir.path());
  EXPECT_GT(here, 0u);
  const std::uint64_t below = free_bytes_at(dir.path() / "not" / "yet");
  EXPECT_LT(std::max(here, below) - std::min(here, below), std::uint64_t{64} << 20);
}

TEST(AtomicFileFaults, AFullFilesystemThrowsNamingTheFileAndLeavesNothing) {
  test::TinyTmpfs disk(64 * 1024);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  EXPECT_EQ(free_bytes_at(disk.path()), 64u * 1024u);
  const fs::path path = disk.path() / "episode.json";
  try {
    write_file_atomically(path, std::string(100 * 1024, 'x'));
    FAIL() << "no OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": No space left on device");
  }
  EXPECT_TRUE(entries(disk.path()).empty());
  write_file_atomically(path, "{}\n");  // the space was given back
  EXPECT_EQ(read_all(path), "{}\n");
}

TEST(AtomicFileFaults, AFailedPieceKeepsTheOldFileAndRefusesFurtherWrites) {
  test::TinyTmpfs disk(64 * 1024);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  const fs::path path = disk.path() / "results.csv";
  write_file_atomically(path, "old\n");
  AtomicFileWriter writer(path);
  EXPECT_THROW(writer.write(std::string(80 * 1024, 'r')), OutputError);
  EXPECT_THROW(writer.write("more"), OutputError);
  EXPECT_THROW(writer.commit(), OutputError);
  EXPECT_EQ(read_all(path), "old\n");
  EXPECT_EQ(entries(disk.path()), std::vector<std::string>{"results.csv"});
}

}  // namespace
}  // namespace a3::common
