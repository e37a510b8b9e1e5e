// The grid of an `a3rig sweep`: scenarios (gen:N expanded) × agents × think times × slices × seeds, parsed from
// comma lists, expanded in a fixed order (seed innermost) so that cell indices — and therefore
// shards (`--shard i/N`: the cells whose index % N == i) — are the same on every machine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace a3::rigs::sweep {

struct SweepAxes {
  std::vector<std::string> scenarios;
  std::vector<std::string> agents;
  std::vector<std::string> think_times;  // think-time specs (agent/conversation/think_time.hpp)
  std::vector<std::string> slices;       // eMBB, URLLC, mMTC
  std::vector<uint64_t> seeds;
};

struct SweepCell {
  std::size_t index = 0;  // position in the full grid
  std::string scenario;
  std::string agent;
  std::string think_time;
  double think_time_mean_s = 0.0;  // the spec's mean per agent turn: the x axis of the plots
  std::string slice;
  uint64_t seed = 0;
};

struct Shard {
  int index = 0;
  int count = 1;
};

// Comma list of non-empty, distinct items (spaces around items dropped). `flag` names the
// option in errors (std::invalid_argument).
std::vector<std::string> split_list(const std::string& text, const std::string& flag);
// Like split_list, but a two-parameter spec (uniform:A,B, normal:M,SD, lognormal:MEDIAN,SIGMA)
// takes the item after it as its second parameter: "0,uniform:1,4,60" is 0, uniform:1,4 and 60.
// Every spec is checked with ThinkTime::parse.
std::vector<std::string> split_think_times(const std::string& text, const std::string& flag);
// "1,2,3", "1-5" or a mix ("1-3,10"); non-negative integers, distinct.
std::vector<uint64_t> parse_seeds(const std::string& text, const std::string& flag);
// Generated missions (rigs/generator/scenario_generator_knobs.hpp) in a sweep: gen:N[:knobs] stands
// for the N missions gen:1[:knobs] .. gen:N[:knobs], gen:A-B[:knobs] for seeds A..B; other
// items pass unchanged. Expanded before the grid, so cell indices and shards stay fixed.
std::vector<std::string> expand_generated_missions(const std::vector<std::string>& scenarios, const std::string& flag);
// Checks the slices (eMBB, URLLC, mMTC) and the agents (scripted, llm, replay:<file>), and
// that no two items of an axis map to the same folder name.
SweepAxes make_axes(const std::string& scenarios, const std::string& agents, const std::string& think_times,
                    const std::string& slices, const std::string& seeds);

std::vector<SweepCell> expand_grid(const SweepAxes& axes);

// "i/N" with 0 <= i < N.
Shard parse_shard(const std::string& text);
bool in_shard(const SweepCell& cell, const Shard& shard);
std::vector<SweepCell> cells_of_shard(const std::vector<SweepCell>& grid, const Shard& shard);

// A grid item as a folder name: letters, digits and . , + - = kept, anything else '_'.
std::string folder_name(const std::string& item);
// out/cells/<scenario>/<agent>/think-<t>/<slice>/seed-<s>
std::filesystem::path cell_dir(const std::filesystem::path& out_dir, const SweepCell& cell);

}  // namespace a3::rigs::sweep
