// A scenario's network section → ScenarioNetwork.
#include "linkemu/scenario_network.hpp"

#include <stdexcept>
#include <utility>

#include "common/json_file.hpp"

namespace a3::linkemu {
namespace {

using common::InputError;

std::string initial_slice(const nlohmann::json& n, const std::string& wn) {
  const std::string slice = n.contains("initial_slice") ? common::require_string(n, "initial_slice", wn) : "eMBB";
  if (slice_by_name().count(slice) == 0) {
    throw InputError(wn + "/initial_slice: '" + slice + "' is not URLLC, eMBB or mMTC");
  }
  return slice;
}

std::vector<ScenarioNetwork::Window> degradations(const nlohmann::json& n, const std::string& wn) {
  std::vector<ScenarioNetwork::Window> out;
  if (!n.contains("degradations")) return out;
  const auto& d = common::require_array(n, "degradations", wn);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const std::string wd = wn + "/degradations/" + std::to_string(i);
    const ScenarioNetwork::Window w{common::require_number(d[i], "start_s", wd),
                                    common::require_number(d[i], "duration_s", wd)};
    if (w.start_s < 0.0 || !(w.duration_s > 0.0)) throw InputError(wd + ": start_s >= 0 and duration_s > 0");
    out.push_back(w);
  }
  return out;
}

std::string trace(const nlohmann::json& n, const std::string& wn, const std::filesystem::path& base_dir) {
  if (!n.contains("trace")) return "";
  std::string t = common::require_string(n, "trace", wn);
  if (t.rfind("alphabench:", 0) != 0 && std::filesystem::path(t).is_relative()) t = (base_dir / t).string();
  return t;
}

// network.link: the link emulator's settings, less what the scenario sets in its own fields.
LinkEmulatorConfig link_settings(const nlohmann::json& link, const std::string& wl,
                                 const std::filesystem::path& base_dir) {
  const std::pair<const char*, const char*> owned[] = {
      {"seed", "the run's --seed"}, {"slice", "network/initial_slice"},
      {"trace", "network/trace and trace_period_s"}, {"degradations", "network/degradations"}};
  for (const auto& [key, owner] : owned) {
    if (link.is_object() && link.contains(key)) throw InputError(wl + "/" + key + ": set by " + std::string(owner) + ", not here");
  }
  LinkEmulatorConfig c = parse_link_emulator_config(link, wl, base_dir);
  try {
    validate(c);
  } catch (const std::invalid_argument& e) {
    throw InputError(wl + ": " + e.what());
  }
  return c;
}

}  // namespace

ScenarioNetwork parse_scenario_network(const nlohmann::json& network, const std::string& json_path,
                                       const std::filesystem::path& base_dir) {
  if (!network.is_object()) {
    throw InputError(json_path + ": expected an object, got " + std::string(network.type_name()));
  }
  ScenarioNetwork out;
  out.initial_slice = initial_slice(network, json_path);
  out.degradations = degradations(network, json_path);
  out.trace = trace(network, json_path, base_dir);
  out.trace_period_s = common::number_or(network, "trace_period_s", out.trace_period_s, json_path);
  if (!(out.trace_period_s > 0.0)) throw InputError(json_path + "/trace_period_s: must be > 0");
  if (network.contains("link")) {
    out.link = link_settings(common::require_object(network, "link", json_path), json_path + "/link", base_dir);
  }
  return out;
}

}  // namespace a3::linkemu
