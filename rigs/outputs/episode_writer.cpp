// Building and writing the episode (the plot: trajectory_plot.cpp).
#include "rigs/outputs/episode_writer.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <set>

#include "common/atomic_file.hpp"
#include "common/json_text.hpp"
#include "rigs/outputs/agent_faults.hpp"
#include "rigs/run/llm_run.hpp"

namespace a3::rigs {
namespace {

double yaw_deg(const a3lcm::vehicle_state_t& s) {
  const double w = s.q_WB[0], x = s.q_WB[1], y = s.q_WB[2], z = s.q_WB[3];
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z)) * 180.0 / M_PI;
}

std::string iso_time(int64_t unix_us) {
  const std::time_t t = static_cast<std::time_t>(unix_us / 1'000'000);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

nlohmann::json link_json(const LinkDirectionStats& d) {
  return {{"messages", d.messages}, {"delivered", d.delivered}, {"lost", d.lost}, {"dropped", d.dropped},
          {"bytes", d.bytes}, {"mean_delay_ms", d.delivered > 0 ? d.delay_sum_ms / d.delivered : 0.0},
          {"max_delay_ms", d.delay_max_ms}};
}

// final_state.uav.landed when the vehicle ended on the ground, disarmed and whole, within the
// return-and-land radius of home (15 m without such an objective); null otherwise. The scorer
// then does not count the ground below the altitude envelope as a violation (eval/README.md).
nlohmann::json landing_marker(const Scenario& s, const RecordedEpisode& rec) {
  const auto& last = rec.last_state;
  if (!rec.have_state || !last.on_ground || last.crashed || rec.last_fc.armed) return nullptr;
  const Eigen::Vector2d home_W_m = s.mission.home_W_m.head<2>();
  const double distance_m = std::hypot(last.p_W_m[0] - home_W_m.x(), last.p_W_m[1] - home_W_m.y());
  nlohmann::json marker = {{"site", "home"}, {"distance_m", distance_m}};
  double radius_m = 15.0;
  for (const auto& o : s.mission.objectives) {
    if (o.type != agent::ObjectiveType::kReturnAndLand) continue;
    radius_m = o.radius_m;
    marker["objective"] = o.id;
    break;
  }
  return distance_m <= radius_m ? marker : nullptr;
}

// The scenario's initial state as the rig started it: on the ground below the pose.
nlohmann::json initial_state_json(const Scenario& s) {
  nlohmann::json initial = s.initial_state;
  initial["uav"]["pose"]["z"] = 0.0;
  initial["uav"]["speed_mps"] = 0.0;
  initial["uav"]["energy"]["battery_pct"] = s.start.battery_pct;
  initial["safety_flags"] = {{"nfz_violation", false}, {"separation_breach", false}};
  return initial;
}

// The safety events as recorded, and the kinds that were entered (a "leave..." detail ends one).
struct SafetyRecord {
  nlohmann::json events = nlohmann::json::array();
  std::set<std::string> kinds;
};

SafetyRecord safety_record(const RecordedEpisode& rec) {
  SafetyRecord out;
  for (const auto& e : rec.safety) {
    if (e.detail.rfind("leave", 0) != 0) out.kinds.insert(e.kind);
    out.events.push_back({{"t_s", e.utime_us * 1e-6}, {"kind", e.kind}, {"source", e.source},
                          {"p_W_m", {e.p_W_m[0], e.p_W_m[1], e.p_W_m[2]}}, {"value", e.value}, {"detail", e.detail}});
  }
  return out;
}

nlohmann::json final_state_json(const Scenario& s, const RecordedEpisode& rec, const nlohmann::json& initial,
                                const std::set<std::string>& kinds, double mission_time_s) {
  const auto& last = rec.last_state;
  nlohmann::json final_state = initial;
  final_state["time_s"] = mission_time_s;
  final_state["uav"]["pose"] = {{"x", last.p_W_m[0]}, {"y", last.p_W_m[1]}, {"z", last.p_W_m[2]}, {"yaw", yaw_deg(last)}};
  final_state["uav"]["speed_mps"] = std::sqrt(last.v_W_mps[0] * last.v_W_mps[0] + last.v_W_mps[1] * last.v_W_mps[1] +
                                              last.v_W_mps[2] * last.v_W_mps[2]);
  final_state["uav"]["energy"]["battery_pct"] = last.battery_pct;
  if (nlohmann::json landed = landing_marker(s, rec); !landed.is_null()) final_state["uav"]["landed"] = landed;
  final_state["safety_flags"] = {{"nfz_violation", kinds.count("nfz_intrusion") > 0},
                                 {"separation_breach", kinds.count("separation_breach") > 0}};
  return final_state;
}

// The recorded turns split into the dialogue (the corpus's fields) and their `_rig` parts, with
// the agent's totals over its turns.
struct DialogueRecord {
  nlohmann::json dialogue = nlohmann::json::array();
  nlohmann::json turns_rig = nlohmann::json::array();
  double gen_time_s = 0.0;
  int attempts = 1;
  int64_t prompt = 0, completion = 0, total = 0;
  double cost_usd = 0.0;
  bool has_cost = false;

  void add_agent_totals(const nlohmann::json& rig) {
    gen_time_s += rig.value("think_time_s", 0.0);
    attempts = std::max(attempts, rig.value("attempts", 1));
    const auto& u = rig.value("usage", nlohmann::json::object());
    prompt += u.value("prompt_tokens", int64_t{0});
    completion += u.value("completion_tokens", int64_t{0});
    total += u.value("total_tokens", int64_t{0});
    if (u.contains("cost") && u["cost"].is_number()) {
      cost_usd += u["cost"].get<double>();
      has_cost = true;
    }
  }
  nlohmann::json usage() const {
    nlohmann::json u = {{"prompt_tokens", prompt}, {"completion_tokens", completion}, {"total_tokens", total}};
    if (has_cost) u["cost"] = cost_usd;  // as OpenRouter reports it, summed over the turns
    return u;
  }
};

DialogueRecord dialogue_record(const RecordedEpisode& rec) {
  DialogueRecord out;
  for (const auto& t : rec.turns) {
    nlohmann::json turn = t;
    nlohmann::json rig = turn.value("_rig", nlohmann::json::object());
    turn.erase("_rig");
    out.dialogue.push_back(turn);
    rig["turn"] = t.value("turn", 0);
    rig["speaker"] = t.value("speaker", "");
    out.turns_rig.push_back(rig);
    if (t.value("speaker", "") == "agent") out.add_agent_totals(rig);
  }
  return out;
}

nlohmann::json meta_json(const RunOptions& o, const RunFacts& f, const DialogueRecord& d) {
  nlohmann::json meta = {{"model", f.agent_name},
                         {"seed", o.seed},
                         {"ts", f.start_unix_us * 1e-6},
                         {"ts_iso", iso_time(f.start_unix_us)},
                         {"gen_time_s", d.gen_time_s},
                         {"attempts_used", d.attempts},
                         {"generation_failed", false},
                         {"usage", d.usage()}};
  // An llm agent is named by its endpoint's model and provider (the corpus's folder layout).
  if (const LlmAgentIdentity llm = llm_agent_identity(o); !llm.model.empty()) {
    meta["model"] = llm.model;
    meta["provider"] = llm.provider;
  }
  return meta;
}

nlohmann::json trajectory_json(const RecordedEpisode& rec, bool crashed) {
  nlohmann::json samples = nlohmann::json::array();
  for (const auto& p : rec.trajectory) samples.push_back({p[0], p[1], p[2], p[3], p[4], p[5]});
  return {{"columns", {"t_s", "x_m", "y_m", "z_m", "battery_pct", "speed_mps"}},
          {"samples_1hz", samples},
          {"distance_m", rec.distance_m},
          {"max_altitude_m", rec.max_altitude_m},
          {"max_speed_mps", rec.max_speed_mps},
          {"crashed", crashed}};
}

// The closest the vehicle came to each no-fly zone it flew beside (at the zone's altitudes).
nlohmann::json zone_clearance_json(const RecordedEpisode& rec) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [zone, c] : rec.zone_clearance) {
    out.push_back({{"zone", zone}, {"closest_m", c.closest_m}, {"t_s", c.t_s}, {"at_m", c.p_W_m}});
  }
  return out;
}

nlohmann::json rig_json(const Scenario& s, const RunOptions& o, const RecordedEpisode& rec, const RunFacts& f,
                        const DialogueRecord& dialogue, nlohmann::json safety_events, bool crashed) {
  nlohmann::json rig = {
      {"status", f.status},
      {"scenario", s.name},
      {"scenario_source", s.source},
      {"agent", o.agent},
      {"think_time", o.think_time},
      {"runtime", o.runtime == Runtime::kVirtual ? "virtual" : "real"},
      {"seed", o.seed},
      {"airframe", s.airframe},
      {"mission_time_s", f.mission_time_s},
      {"wall_time_s", f.wall_time_s},
      {"real_time_factor", {{"requested", o.runtime == Runtime::kVirtual ? 0.0 : o.real_time_factor},
                            {"achieved", f.achieved_real_time_factor}}},
      {"dialogue_end", rec.dialogue_end_reason},
      {"turns", dialogue.turns_rig},
      {"agent_faults", find_agent_faults(dialogue.dialogue)},
      {"link", {{"up", link_json(rec.up)}, {"down", link_json(rec.down)}}},
      {"safety_events", std::move(safety_events)},
      {"no_fly_zone_clearance", zone_clearance_json(rec)},
      {"flight_controller", {{"modes", rec.fc_modes}, {"failsafes", rec.fc_failsafes}}},
      {"objectives", rec.objectives},
      {"trajectory", trajectory_json(rec, crashed)},
      {"counters", f.counters}};
  if (!f.realtime.is_null()) rig["realtime"] = f.realtime;
  if (o.slice) rig["slice"] = linkemu::to_string(*o.slice);
  return rig;
}

}  // namespace

nlohmann::json build_episode(const Scenario& s, const RunOptions& o, const RecordedEpisode& rec, const RunFacts& f) {
  const nlohmann::json initial = initial_state_json(s);
  SafetyRecord safety = safety_record(rec);
  const DialogueRecord dialogue = dialogue_record(rec);
  const bool crashed = rec.last_state.crashed || safety.kinds.count("crash") > 0;
  return {{"initial_state", initial},
          {"final_state", final_state_json(s, rec, initial, safety.kinds, f.mission_time_s)},
          {"dialogue", dialogue.dialogue},
          {"success", rec.objectives_all_done && !crashed},
          {"_meta", meta_json(o, f, dialogue)},
          {"_rig", rig_json(s, o, rec, f, dialogue, std::move(safety.events), crashed)}};
}

void write_episode(const std::filesystem::path& dir, const nlohmann::json& episode) {
  common::write_file_atomically(dir / "episode.json", common::dump_json_text(episode, 2) + "\n");
}

}  // namespace a3::rigs
