// `a3rig report`: one self-contained HTML file for an episode (a rig run's or the public
// corpus's): a top-down map of the world and the flown track coloured by agent turn, timelines
// over mission time (altitude with its bounds, speed, battery, the link per turn, each turn's
// think time and link delay), the score with what it came from, and the dialogue; a time slider
// moves a marker on the map and a cursor on every timeline. The page's script uses d3 from
// Debian's libjs-d3, inlined, so the file opens anywhere without network access.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

#include "episode/episode.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

// Where d3 is read from: $A3_D3_JS, else Debian's /usr/share/javascript/d3/d3.min.js.
std::filesystem::path d3_script_path();

// The scenario an episode was flown in, when it can be found: the `gen:` spec or scenario file
// it names (_rig.scenario_source), its built-in scenario (_rig.scenario), or a corpus episode's
// initial_state (geofence and envelope only). Nothing when none of these works.
std::optional<Scenario> scenario_of_episode(const episode::Episode& episode, const std::filesystem::path& shared_dir);

// The page. Throws common::InputError when d3 cannot be read (naming the file and the package).
std::string episode_report_html(const nlohmann::json& episode, const std::optional<Scenario>& scenario,
                                const std::string& title);

// Writes the page to `out` atomically; throws common::OutputError naming the file.
void write_episode_report(const std::filesystem::path& out, const nlohmann::json& episode,
                          const std::optional<Scenario>& scenario, const std::string& title);

}  // namespace a3::rigs
