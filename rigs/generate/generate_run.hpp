// A whole `a3rig generate` run: every scenario × episode seed, written to
// <out>/<provider>/<model>/<domain>/sc-XXXX-ep-YY.json (the layout `a3rig score` reads), where
// YY is the seed's position in the seed list (default 42, 77, 101, 2025, 1337 → ep-00..ep-04; the
// public corpus's files are all seed 42, ep-00). Resumable: a file that is already a valid
// episode (of the same seed) or a failure stub is kept; an invalid or missing one is generated.
// Files are written whole (temporary file, then rename), so an interrupted run never leaves a
// half-written episode. Up to `jobs` episodes are generated at once, one chat client per worker.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rigs/generate/generate_episode.hpp"
#include "rigs/generate/generate_prompt.hpp"

namespace a3::rigs {

struct GenerateRunOptions {
  std::vector<GenerateScenario> scenarios;
  std::vector<int64_t> seeds = {42, 77, 101, 2025, 1337};
  std::filesystem::path output_dir;  // the domain folder: <out>/<provider>/<model>/<domain>
  std::string model_label;           // "provider/model", a failure stub's _meta.model
  int jobs = 1;                      // episodes generated at once
  bool retry_failed = false;         // generate again where a failure stub was written
};

// One episode's outcome, reported as it ends (from the worker's thread, one call at a time).
struct GenerateProgress {
  enum class Outcome { kValid, kFailureStub };
  std::string file;       // the file written
  Outcome outcome = Outcome::kValid;
  int attempts_used = 0;
  double gen_time_s = 0.0;
  int64_t total_tokens = 0;
  std::vector<std::string> attempt_errors;
  std::size_t done = 0;   // episodes of this run finished so far (this one included)
  std::size_t to_do = 0;  // episodes this run generates (the plan minus the kept files)
  double elapsed_s = 0.0;
  double eta_s = 0.0;     // at the run's pace so far
};

struct GenerateRunSummary {
  std::size_t planned = 0;          // scenarios × seeds
  std::size_t kept_valid = 0;       // valid episodes already there
  std::size_t kept_stubs = 0;       // failure stubs already there (not --retry-failed)
  std::size_t replaced_invalid = 0; // invalid files found and generated again
  std::size_t generated_valid = 0;
  std::size_t generated_stubs = 0;
  std::size_t not_generated = 0;    // left for a later run (stopped, or the endpoint failed)
  double wall_s = 0.0;
  int64_t total_tokens = 0;         // of this run's episodes
  bool stopped = false;             // stop_requested said so
  std::string stop_error;           // why the run stopped early: the endpoint failed, or a file could not be written
};

// A chat function for one worker thread (each gets its own client).
using GenerateChatFactory = std::function<GenerateChat()>;

// The file name of scenario `number`'s episode `index`: sc-XXXX-ep-YY.json.
std::string episode_file_name(int number, std::size_t index);

// Throws std::invalid_argument before generating anything when the options are unusable (no
// scenario, no or repeated seeds, jobs < 1, an output folder that cannot be made) or an
// existing file is a valid episode of another seed (another seed list wrote this folder).
GenerateRunSummary run_generate(const GenerateRunOptions& options, const GenerateChatFactory& make_chat,
                                const std::function<void(const GenerateProgress&)>& on_episode,
                                const std::function<bool()>& stop_requested);

}  // namespace a3::rigs
