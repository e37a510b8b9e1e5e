// Corpus folders with entries that are not episode files: a FIFO, a symlink loop, a dangling
// link, a link to /dev/zero and a folder, each named sc-XXXX-ep-YY.json, are invalid files named
// with their reason (never opened so as to block, never searched as folders), beside the valid
// episode; a FIFO given as a file is read when written to and invalid at once when not.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>

#include <chrono>
#include <filesystem>
#include <map>
#include <thread>

#include "eval/corpus_scorer.hpp"
#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "tests/eval/episode_builder.hpp"

namespace a3::eval {
namespace {

namespace fs = std::filesystem;

// Writes `text` into the FIFO once a reader holds it open to the end (a reader that saw no
// writer and left makes the write fail with EPIPE: then again, for the next reader).
std::thread write_when_read(const fs::path& fifo, std::string text) {
  std::signal(SIGPIPE, SIG_IGN);
  return std::thread([fifo, text = std::move(text)] {
    for (int tries = 0; tries < 200; ++tries) {
      const int fd = ::open(fifo.c_str(), O_WRONLY);
      if (fd < 0) return;
      const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
      ::close(fd);
      if (written) return;
    }
  });
}

class CorpusFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("a3-corpus-faults-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // file name -> the first violation's message ("" when valid), from check_corpus.
  std::map<std::string, std::string> check(const fs::path& root, double& elapsed_s) {
    std::map<std::string, std::string> seen;
    const auto t0 = std::chrono::steady_clock::now();
    check_corpus({root}, validator_, 2, 1u << 20, [&](const EpisodeFile& f, const EpisodeCheck& c) {
      seen[f.path.filename().string()] = c.violations.empty() ? "" : c.violations[0].message;
    });
    elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return seen;
  }

  fs::path dir_;
  const ScoringProfile profile_ = release_profile();
  const JsonSchemaValidator validator_{episode_schema_json(), kEpisodeSchemaName};
  EpisodeReader reader_{validator_, profile_, 1u << 20};
};

TEST_F(CorpusFaults, EntriesThatAreNotFilesAreInvalidWithTheirReason) {
  test::write_json(dir_ / "sc-0001-ep-00.json", test::make_episode());
  ASSERT_EQ(::mkfifo((dir_ / "sc-0001-ep-01.json").c_str(), 0600), 0);
  fs::create_symlink("sc-0001-ep-02.json", dir_ / "sc-0001-ep-02.json");  // a loop onto itself
  fs::create_symlink("nowhere.json", dir_ / "sc-0001-ep-03.json");        // dangling
  fs::create_symlink("/dev/zero", dir_ / "sc-0001-ep-04.json");
  fs::create_directories(dir_ / "sc-0001-ep-05.json");
  test::write_json(dir_ / "sc-0001-ep-05.json" / "sc-0001-ep-06.json", test::make_episode());
  double elapsed_s = 0.0;
  const auto seen = check(dir_, elapsed_s);
  EXPECT_LT(elapsed_s, 5.0) << "nothing blocks";
  ASSERT_EQ(seen.size(), 6u) << "the folder named like an episode is an entry, not searched";
  EXPECT_EQ(seen.at("sc-0001-ep-00.json"), "");
  EXPECT_EQ(seen.at("sc-0001-ep-01.json"), "a FIFO or pipe with nothing written to it (no writer)");
  EXPECT_NE(seen.at("sc-0001-ep-02.json").find("cannot open: Too many levels of symbolic links"), std::string::npos)
      << seen.at("sc-0001-ep-02.json");
  EXPECT_NE(seen.at("sc-0001-ep-03.json").find("cannot open: No such file"), std::string::npos)
      << seen.at("sc-0001-ep-03.json");
  EXPECT_EQ(seen.at("sc-0001-ep-04.json"), "is a device, not a regular file: not read");
  EXPECT_EQ(seen.at("sc-0001-ep-05.json"), "is a folder, not an episode file");
}

TEST_F(CorpusFaults, AFifoWithoutAWriterIsInvalidAtOnce) {
  const fs::path fifo = dir_ / "episode.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto t0 = std::chrono::steady_clock::now();
  const EpisodeCheck c = reader_.check_file(fifo);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  ASSERT_FALSE(c.violations.empty());
  EXPECT_EQ(c.violations[0].rule, "file-read");
}

TEST_F(CorpusFaults, AFifoThatIsWrittenToIsReadLikeAPipe) {
  const fs::path fifo = dir_ / "episode.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer = write_when_read(fifo, test::make_episode().dump());
  EpisodeCheck c;
  for (int i = 0; i < 100; ++i) {
    c = reader_.check_file(fifo);
    if (c.status == EpisodeStatus::kValid) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  writer.join();
  EXPECT_EQ(c.status, EpisodeStatus::kValid) << (c.violations.empty() ? "" : c.violations[0].message);
}

TEST_F(CorpusFaults, ASyntaxErrorInAPipeIsReportedWithoutReadingItAgain) {
  const fs::path fifo = dir_ / "broken.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer = write_when_read(fifo, "{\"dialogue\": [1, 2,");
  EpisodeCheck c;
  for (int i = 0; i < 100; ++i) {
    c = reader_.check_file(fifo);
    if (!c.violations.empty() && c.violations[0].rule == "json-syntax") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  writer.join();
  ASSERT_FALSE(c.violations.empty());
  EXPECT_EQ(c.violations[0].rule, "json-syntax") << c.violations[0].message;
}

}  // namespace
}  // namespace a3::eval
