// Loading the scenarios of `a3rig generate`.
#include "rigs/generate/generate_scenarios.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "common/json_text.hpp"
#include "eval/corpus.hpp"
#include "rigs/scenario/builtin_scenarios.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

constexpr std::uintmax_t kMaxScenarioBytes = 16u << 20;

ordered_json read_json(const fs::path& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) throw std::invalid_argument(path.string() + ": cannot read (" + ec.message() + ")");
  if (size > kMaxScenarioBytes) throw std::invalid_argument(path.string() + ": larger than 16 MiB");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw std::invalid_argument(path.string() + ": cannot read");
  ordered_json doc;
  try {
    doc = common::parse_ordered_json_text(text.str(), path.string());
  } catch (const common::InputError& e) {
    throw std::invalid_argument(e.what());
  }
  if (!doc.is_object()) throw std::invalid_argument(path.string() + ": not a JSON object");
  return doc;
}

// A scenario from a parsed episode or scenario document; number is filled by the caller.
GenerateScenario scenario_from_document(const ordered_json& doc, const std::string& source) {
  const auto state = doc.find("initial_state");
  if (state == doc.end() || !state->is_object()) throw std::invalid_argument(source + ": no initial_state object");
  GenerateScenario s;
  s.source = source;
  s.initial_state = *state;
  if (const auto mission = doc.find("mission"); mission != doc.end() && mission->is_object()) {
    if (const auto d = mission->find("description"); d != mission->end() && d->is_string()) {
      s.mission = d->get<std::string>();
    }
  }
  return s;
}

struct Pending {
  std::optional<int> number;
  GenerateScenario scenario;
};

void add_folder(const fs::path& folder, const std::string& spec, std::vector<Pending>& out) {
  std::map<int, std::pair<int, fs::path>> first;  // scenario → (episode, file) of the lowest episode
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (!entry.is_regular_file()) continue;
    const auto name = eval::parse_episode_name(entry.path().filename().string());
    if (!name) continue;
    const auto it = first.find(name->scenario);
    if (it == first.end() || name->episode < it->second.first) first[name->scenario] = {name->episode, entry.path()};
  }
  if (ec) throw std::invalid_argument("--scenarios " + spec + ": cannot list the folder (" + ec.message() + ")");
  if (first.empty()) {
    throw std::invalid_argument("--scenarios " + spec +
                                ": no sc-XXXX-ep-YY.json file in this folder (give a model's domain folder such "
                                "as alphabench/eval_runs/openai/chatgpt-4o-latest/uav)");
  }
  for (const auto& [number, file] : first) {
    out.push_back({number, scenario_from_document(read_json(file.second), file.second.string())});
  }
}

}  // namespace

std::vector<GenerateScenario> load_generate_scenarios(const std::vector<std::string>& specs) {
  if (specs.empty()) throw std::invalid_argument("no scenario: give --scenarios DIR|FILE|NAME");
  std::vector<Pending> pending;
  for (const std::string& spec : specs) {
    const auto builtin = std::find_if(builtin_scenarios().begin(), builtin_scenarios().end(),
                                      [&](const auto& entry) { return entry.first == spec; });
    std::error_code ec;
    if (fs::is_directory(spec, ec)) {
      add_folder(spec, spec, pending);
    } else if (fs::is_regular_file(spec, ec)) {
      const auto name = eval::parse_episode_name(fs::path(spec).filename().string());
      pending.push_back({name ? std::optional<int>(name->scenario) : std::nullopt,
                         scenario_from_document(read_json(spec), spec)});
    } else if (builtin != builtin_scenarios().end()) {
      const ordered_json doc = common::parse_ordered_json_text(builtin->second, "built-in scenario " + spec);
      if (!doc.is_object()) throw std::logic_error("built-in scenario " + spec + " is not a JSON object");
      pending.push_back({std::nullopt, scenario_from_document(doc, "built-in " + spec)});
    } else {
      std::string names;
      for (const auto& n : builtin_scenario_names()) names += (names.empty() ? "" : ", ") + n;
      throw std::invalid_argument("--scenarios " + spec + ": not a folder, a file, nor a built-in scenario (" +
                                  names + ")");
    }
  }
  std::map<int, GenerateScenario> by_number;
  for (auto& p : pending) {
    if (!p.number) continue;
    if (const auto it = by_number.find(*p.number); it != by_number.end()) {
      throw std::invalid_argument("scenario " + scenario_id(*p.number) + " given twice: " + it->second.source +
                                  " and " + p.scenario.source);
    }
    p.scenario.number = *p.number;
    by_number.emplace(*p.number, std::move(p.scenario));
  }
  int next = 0;
  for (auto& p : pending) {
    if (p.number) continue;
    while (by_number.count(next) != 0) ++next;
    if (next > 9999) throw std::invalid_argument("more than 10000 scenarios");
    p.scenario.number = next;
    by_number.emplace(next, std::move(p.scenario));
  }
  std::vector<GenerateScenario> out;
  for (auto& [number, scenario] : by_number) out.push_back(std::move(scenario));
  return out;
}

}  // namespace a3::rigs
