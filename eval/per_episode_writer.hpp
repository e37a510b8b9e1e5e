// `--per-episode FILE`: one row per episode file with its status, every pillar, α³ and the
// inputs each pillar was computed from. CSV, or JSON Lines when FILE ends in .jsonl.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "eval/corpus_scorer.hpp"

namespace a3::eval {

class PerEpisodeWriter {
 public:
  // Throws std::runtime_error when the file cannot be created.
  explicit PerEpisodeWriter(const std::filesystem::path& path);
  void write(const ScoredEpisode& episode);
  // Flushes and reports a write error (full disk) as std::runtime_error.
  void close();

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  bool json_lines_ = false;
};

}  // namespace a3::eval
