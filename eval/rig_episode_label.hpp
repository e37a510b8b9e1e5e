// a3rig's own episode files (`a3rig run`'s RUN/episode.json, a sweep's
// cells/<scenario>/<agent>/think-<t>/<slice>/seed-<n>/episode.json) say who flew them inside the
// file, not in their path: `_meta.model`, and in `_rig` the scenario, seed, think time and slice.
// This reads just those fields (simdjson DOM: validated whole, then looked up by key), so a
// run or sweep folder scores as one leaderboard row per agent configuration.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace a3::eval {

// The name a3rig gives every episode it writes.
inline constexpr const char* kRigEpisodeFileName = "episode.json";

struct RigEpisodeLabel {
  std::string model;     // `_meta.model`, then ", think <t>" and ", <slice>" when set
  std::string scenario;  // `_rig.scenario`
  int64_t seed = 0;      // `_rig.seed`
};

// nullopt when the file cannot be read or lacks `_meta.model` or `_rig.scenario` (not a3rig's);
// the scorer still checks the file and reports what is wrong with it.
std::optional<RigEpisodeLabel> read_rig_episode_label(const std::filesystem::path& path);
// The same from an episode's text (fuzz/episode.cpp runs it on every input).
std::optional<RigEpisodeLabel> rig_episode_label_from_text(std::string_view text);

}  // namespace a3::eval
