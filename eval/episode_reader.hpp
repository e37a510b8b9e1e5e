// Reads one episode file and decides what it is: a valid episode (with the facts the pillars
// need), a failure stub, or an invalid file (with every reason). One reader per thread: it
// keeps its read buffer and parse memory between files.
#pragma once

#include "eval/rapidjson.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "eval/episode_facts.hpp"
#include "eval/exact_numbers.hpp"
#include "eval/json_schema_validator.hpp"
#include "eval/json_shape.hpp"
#include "eval/scoring_profile.hpp"
#include "eval/simdjson_parser.hpp"
#include "eval/violation.hpp"

namespace a3::eval {

enum class EpisodeStatus { kValid, kFailureStub, kInvalid };
const char* to_string(EpisodeStatus status);

struct EpisodeCheck {
  EpisodeStatus status = EpisodeStatus::kInvalid;
  Violations violations;      // why the file is invalid (empty otherwise)
  EpisodeFacts facts;         // filled for valid episodes
  int64_t attempts_used = 1;  // `_meta.attempts_used`, 1 when absent or unreadable
};

inline constexpr std::uintmax_t kDefaultMaxEpisodeFileBytes = 16u << 20;

class EpisodeReader {
 public:
  // validator and profile must outlive the reader.
  EpisodeReader(const JsonSchemaValidator& validator, const ScoringProfile& profile,
                std::uintmax_t max_file_bytes = kDefaultMaxEpisodeFileBytes);

  // A regular file, or a pipe such as /dev/stdin (read to its end).
  EpisodeCheck check_file(const std::filesystem::path& path);
  // Checks JSON text already in memory (the text is copied).
  EpisodeCheck check_text(std::string_view text);

 private:
  // buffer_ holds `size` bytes of text and room for a NUL; original_text() gives the text
  // back when a syntax error has to be located (the parser rewrites the buffer).
  EpisodeCheck check_buffer(std::size_t size, const std::function<std::string()>& original_text);
  // The reference parse (RapidJSON) of buffer_'s text into `document`; nothing when it parsed,
  // else why the file is invalid (not UTF-8, a NUL byte, a syntax error).
  std::optional<EpisodeCheck> parse_reference(std::size_t size,
                                              const std::function<std::string()>& original_text,
                                              rapidjson::Document& document);
  EpisodeCheck too_big(std::uintmax_t size) const;
  // Room for text_bytes, the NUL the parser needs and the bytes its SIMD scan may read beyond.
  void resize_buffer(std::size_t text_bytes);

  const JsonSchemaValidator& validator_;
  const ScoringProfile& profile_;
  std::uintmax_t max_file_bytes_;
  static constexpr std::size_t kPoolChunkBytes = 256u << 10;
  JsonShapeChecker shape_;
  SimdjsonParser fast_parser_;  // first; ExactNumberParser where it does not accept the text
  ExactNumberParser parser_;
  std::string buffer_;  // the file's bytes, parsed in place
  std::vector<char> pool_chunk_;
  rapidjson::MemoryPoolAllocator<> pool_;  // the parsed document's memory
};

}  // namespace a3::eval
