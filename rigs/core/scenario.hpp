// A scenario: an α³-Bench initial_state (the corpus format), a mission (the objectives that
// decide success), airspace extras the corpus lacks (no-fly zones, other traffic), the
// airframe, and the network script. Loaded from JSON (rigs/scenarios/*.json are built in) and
// validated with errors that name the file and field; or derived from any initial_state of the
// public corpus (`alphabench:<path>`).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "agent/airspace.hpp"
#include "agent/mission/mission.hpp"

namespace a3::rigs {

struct NetworkScript {
  std::string initial_slice = "eMBB";
  // Windows of forced degradation (the SPEC §2 hard regime), mission seconds.
  struct Window {
    double start_s = 0.0;
    double duration_s = 0.0;
  };
  std::vector<Window> degradations;
  std::string trace;       // a recorded trace to replay instead (file, or alphabench:<path>)
  double trace_period_s = 20.0;
  nlohmann::json link_overrides = nlohmann::json::object();  // extra link emulator settings
};

struct Scenario {
  std::string name;
  std::string description;
  std::string source;  // where it was loaded from
  std::string airframe = "iris";
  nlohmann::json initial_state;
  agent::Mission mission;
  agent::Airspace airspace;
  NetworkScript network;

  // What agents are told about the airspace: geofence, altitude envelope, no-fly zones, and
  // the other aircraft (ids and declared intent, not their future).
  nlohmann::json airspace_brief() const;
};

// Throws common::InputError naming `where` and the field.
Scenario scenario_from_json(const nlohmann::json& j, const std::string& where,
                            const std::filesystem::path& base_dir);
// A name of a built-in scenario, a JSON file, or alphabench:<path> (relative to the shared
// folder's alphabench/eval_runs, or absolute).
Scenario load_scenario(const std::string& spec, const std::filesystem::path& shared_dir);
std::vector<std::string> builtin_scenario_names();

// A default mission for a corpus initial_state: take off from below its pose, image a point
// 250 m away inside the geofence (away from the nearest edge), and return and land.
Scenario scenario_from_initial_state(const nlohmann::json& initial_state, const std::string& where);

}  // namespace a3::rigs
