// The episode report page: the episode, its world and its score as JSON in the page, drawn by
// rigs/report/report.js with d3.
#include "rigs/report/episode_report.hpp"

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/json_file.hpp"
#include "common/json_text.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/outputs/episode_score.hpp"
#include "rigs/report/html_page.hpp"
#include "rigs/report/report_assets.hpp"
#include "rigs/report/report_world.hpp"

namespace a3::rigs {
namespace {

std::string read_d3() {
  const std::filesystem::path path = d3_script_path();
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || text.str().empty()) {
    throw common::InputError(path.string() + ": cannot read d3, which the report inlines (Debian: apt-get install libjs-d3; or set A3_D3_JS to a d3 v3 file)");
  }
  return text.str();
}

// JSON inside <script type="application/json">: no "<" may end the element early.
std::string script_safe_json(const nlohmann::json& data) {
  const std::string text = common::dump_json_text(data);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

// Fills the template's @A3_<NAME>@ placeholders in one pass, so that a value (the episode's
// text, say) is never searched for placeholders itself.
std::string filled(std::string_view page, const std::map<std::string, std::string>& values) {
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = page.find("@A3_", at);
    const std::size_t close = open == std::string_view::npos ? open : page.find('@', open + 1);
    if (close == std::string_view::npos) break;
    const auto value = values.find(std::string(page.substr(open + 1, close - open - 1)));
    if (value == values.end()) {
      out += page.substr(at, close - at);
      at = close;
      continue;
    }
    out += page.substr(at, open - at);
    out += value->second;
    at = close + 1;
  }
  out += page.substr(at);
  return out;
}

std::optional<Scenario> try_load(const std::string& spec, const std::filesystem::path& shared_dir) {
  try {
    return load_scenario_spec(spec, shared_dir);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

std::filesystem::path d3_script_path() {
  if (const char* env = std::getenv("A3_D3_JS"); env != nullptr && *env != '\0') return env;
  return "/usr/share/javascript/d3/d3.min.js";
}

std::optional<Scenario> scenario_of_episode(const episode::Episode& episode, const std::filesystem::path& shared_dir) {
  const episode::Document no_rig = episode::Document::object();
  const episode::Document& rig = episode.rig() != nullptr ? *episode.rig() : no_rig;
  const std::string source = rig.value("scenario_source", "");
  std::error_code ec;
  if (source.rfind("gen:", 0) == 0 || (!source.empty() && std::filesystem::is_regular_file(source, ec))) {
    if (auto s = try_load(source, shared_dir)) return s;
  }
  if (const std::string name = rig.value("scenario", ""); builtin_scenario_json(name)) return try_load(name, shared_dir);
  if (const episode::Document* initial_state = episode.initial_state()) {
    try {
      return scenario_from_initial_state(nlohmann::json(*initial_state), "episode");
    } catch (const std::exception&) {
    }
  }
  return std::nullopt;
}

std::string episode_report_html(const nlohmann::json& episode, const std::optional<Scenario>& scenario,
                                const std::string& title) {
  const nlohmann::json data = {{"title", title},
                               {"episode", episode},
                               {"world", scenario ? report_world_json(*scenario) : nlohmann::json(nullptr)},
                               {"score", episode_score_json(score_episode(episode))}};
  // The rig's own parts first: the policy is computed over this skeleton's inline scripts and
  // style, which hold no episode text; the title and the data go in after.
  const std::string skeleton = filled(report_page_template(), {{"A3_CSS", std::string(report_style())},
                                                               {"A3_D3", read_d3()},
                                                               {"A3_JS", std::string(report_script())}});
  const std::string policy = content_security_policy(inline_elements(skeleton, "script"),
                                                     inline_elements(skeleton, "style"), "");
  return filled(skeleton, {{"A3_CSP", content_security_policy_meta(policy)},
                           {"A3_TITLE", html_escaped(title)},
                           {"A3_DATA", script_safe_json(data)}});
}

void write_episode_report(const std::filesystem::path& out, const nlohmann::json& episode,
                          const std::optional<Scenario>& scenario, const std::string& title) {
  common::write_file_atomically(out, episode_report_html(episode, scenario, title));
}

}  // namespace a3::rigs
