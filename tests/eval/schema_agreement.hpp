// What the differential tests of the compiled schema share (test_compiled_schema*.cpp): the two
// engines on the episode schema, parsing as the episode reader does, and a tally of verdicts that
// fails the test on each disagreement.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "eval/compiled_schema.hpp"
#include "eval/episode_schema.hpp"
#include "eval/exact_numbers.hpp"
#include "eval/json_schema_validator.hpp"

namespace a3::eval::testing {

namespace fs = std::filesystem;

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline const JsonSchemaValidator& valijson_validator() {
  static const JsonSchemaValidator v(episode_schema_json(), kEpisodeSchemaName, SchemaEngine::kValijson);
  return v;
}

inline const CompiledSchema& compiled_schema() {
  static const CompiledSchema c(episode_schema_json(), kEpisodeSchemaName);
  return c;
}

// Parses as the episode reader does (in place, numbers converted exactly); false when it is not
// JSON or holds a NUL byte. The text is kept in the document's own memory pool, where the strings
// parsed in place stay.
inline bool parse_like_the_reader(const std::string& text, rapidjson::Document& document) {
  if (text.find('\0') != std::string::npos) return false;
  char* buffer = static_cast<char*>(document.GetAllocator().Malloc(text.size() + 1));
  std::memcpy(buffer, text.data(), text.size());
  buffer[text.size()] = '\0';
  static ExactNumberParser parser;
  return !parser.parse_insitu(document, buffer).IsError();
}

struct Agreement {
  int compared = 0, valid = 0, invalid = 0, disagreements = 0;

  void compare(const rapidjson::Value& document, const std::string& what) {
    const bool expected = valijson_validator().is_valid(document);
    const bool got = compiled_schema().is_valid(document);
    ++compared;
    ++(expected ? valid : invalid);
    if (got == expected) return;
    if (++disagreements <= 20) {
      ADD_FAILURE() << what << ": valijson says " << (expected ? "valid" : "invalid")
                    << ", the compiled schema " << (got ? "valid" : "invalid");
    }
  }
};

inline std::vector<fs::path> json_files_under(const fs::path& root) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace a3::eval::testing
