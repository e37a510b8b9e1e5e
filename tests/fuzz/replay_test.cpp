// Replays every stored input of every fuzz target (fuzz/corpus/<target>/ seeds and the
// regression inputs tests/data/fuzz/<target>/, one per finding) through the target's body, in
// the normal build: an input that once crashed a target must now run cleanly.
#include <gtest/gtest.h>

#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/fuzz_target.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> stored_inputs(const std::string& target) {
  std::vector<fs::path> files;
  for (const char* folder : {"fuzz/corpus/", "tests/data/fuzz/"}) {
    const fs::path dir = fs::path(A3_SOURCE_DIR) / folder / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (entry.is_regular_file()) files.push_back(entry.path());
    }
  }
  return files;
}

std::vector<std::uint8_t> bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzReplay : public testing::TestWithParam<std::string> {};

TEST_P(FuzzReplay, EveryStoredInputRunsWithoutAnEscapedException) {
  const auto body = a3::fuzz::registered_targets().at(GetParam());
  const auto files = stored_inputs(GetParam());
  ASSERT_FALSE(files.empty()) << "no seed inputs in fuzz/corpus/" << GetParam();
  for (const auto& file : files) {
    const std::vector<std::uint8_t> input = bytes_of(file);
    try {
      body(a3::fuzz::Input(input.data(), input.size()));
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": " << e.what();
    }
  }
}

std::vector<std::string> target_names() {
  std::vector<std::string> names;
  for (const auto& [name, body] : a3::fuzz::registered_targets()) names.push_back(name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, testing::ValuesIn(target_names()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(FuzzStoredInputs, EveryFolderBelongsToARegisteredTarget) {
  for (const char* folder : {"fuzz/corpus", "tests/data/fuzz"}) {
    const fs::path dir = fs::path(A3_SOURCE_DIR) / folder;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (!entry.is_directory()) continue;
      EXPECT_TRUE(a3::fuzz::registered_targets().contains(entry.path().filename().string()))
          << entry.path() << " names no fuzz target";
    }
  }
}

}  // namespace
