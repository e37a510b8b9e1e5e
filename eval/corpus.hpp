// Finding episode files: `<provider>/<model>/<domain>/sc-XXXX-ep-YY.json` trees (the α³-Bench
// layout), flat folders, and a3rig's own run and sweep folders (every `episode.json`, attributed
// from its `_meta` and `_rig`: rig_episode_label.hpp). Walks lazily in sorted order (deterministic output) and holds one
// folder listing at a time, never the whole corpus.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace a3::eval {

// Scenario and episode numbers of a file named sc-XXXX-ep-YY.json.
struct EpisodeName {
  int scenario = -1;
  int episode = -1;
};
std::optional<EpisodeName> parse_episode_name(const std::string& file_name);

struct EpisodeFile {
  std::filesystem::path path;
  std::string model;   // "provider/model", or the --model override
  std::string domain;  // the domain folder, or the --domain override
  std::optional<EpisodeName> name;
};

struct CorpusOptions {
  std::string model_override;             // flat folders: every file belongs to this model
  std::string domain_override = "uav";    // with model_override
};

// model and domain of a file from its path: the last three folders are provider/model/domain.
void attribute_model(EpisodeFile& file, const CorpusOptions& options);

class CorpusWalker {
 public:
  // roots: folders (searched recursively for sc-XXXX-ep-YY.json) or files (taken as they are).
  // Every entry named sc-XXXX-ep-YY.json is returned whatever its type (a folder so named is
  // not searched): a FIFO, device, folder or broken link is an invalid episode file, counted.
  // Throws std::invalid_argument for a root that does not exist.
  CorpusWalker(std::vector<std::filesystem::path> roots, CorpusOptions options);

  // The next episode file, or nothing at the end.
  std::optional<EpisodeFile> next();

  // Problems met while walking (unreadable folders), for the caller to report.
  const std::vector<std::string>& warnings() const { return warnings_; }
  // .json files in the folders that are not named sc-XXXX-ep-YY.json (not scored).
  uint64_t ignored_json_files() const { return ignored_json_; }

 private:
  struct Frame {
    std::vector<std::filesystem::directory_entry> entries;  // sorted by path
    std::size_t next = 0;
    std::string model, domain;  // attribution shared by the folder's files
    uint64_t device = 0, inode = 0;  // identity, to refuse a symlink back to an ancestor
  };
  void push_directory(const std::filesystem::path& dir);
  // An a3rig episode.json: model from the file (or the override), scenario and seed as its name.
  EpisodeFile rig_episode(const std::filesystem::path& path);

  std::vector<std::filesystem::path> roots_;
  std::size_t next_root_ = 0;
  CorpusOptions options_;
  std::vector<Frame> stack_;
  std::vector<std::string> warnings_;
  uint64_t ignored_json_ = 0;
  std::map<std::string, int> rig_scenario_numbers_;  // a3rig scenario names, numbered as met
};

}  // namespace a3::eval
