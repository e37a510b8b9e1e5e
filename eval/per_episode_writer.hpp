// `--per-episode FILE`: one row per episode file with its status, every pillar, α³ and the
// inputs each pillar was computed from. CSV, or JSON Lines when FILE ends in .jsonl.
#pragma once

#include <filesystem>
#include <string>

#include "common/atomic_file.hpp"

#include "eval/corpus_scorer.hpp"

namespace a3::eval {

class PerEpisodeWriter {
 public:
  // Creates missing folders; throws common::OutputError ("<file or folder>: <reason>") when it
  // cannot. Nothing appears at `path` until close().
  explicit PerEpisodeWriter(const std::filesystem::path& path);
  void write(const ScoredEpisode& episode);
  // Writes the rest and renames the file into place; a write error (full disk) throws
  // common::OutputError naming the file.
  void close();

 private:
  void flush_when_full();

  common::AtomicFileWriter out_;
  std::string pending_;  // rows not yet handed to out_
  bool json_lines_ = false;
};

}  // namespace a3::eval
