// Building and writing the episode.
#include "rigs/core/episode_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <set>

#include "rigs/core/llm_run.hpp"

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

}  // namespace

nlohmann::json build_episode(const Scenario& s, const RunOptions& o, const RecordedEpisode& rec, const RunFacts& f) {
  // Initial state: the scenario's, as the rig started it (on the ground below the pose).
  nlohmann::json initial = s.initial_state;
  initial["uav"]["pose"]["z"] = 0.0;
  initial["uav"]["speed_mps"] = 0.0;
  initial["uav"]["energy"]["battery_pct"] = 100.0;
  initial["safety_flags"] = {{"nfz_violation", false}, {"separation_breach", false}};

  std::set<std::string> kinds;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : rec.safety) {
    if (e.detail.rfind("leave", 0) != 0) kinds.insert(e.kind);
    events.push_back({{"t_s", e.utime_us * 1e-6}, {"kind", e.kind}, {"source", e.source},
                      {"p_W_m", {e.p_W_m[0], e.p_W_m[1], e.p_W_m[2]}}, {"value", e.value}, {"detail", e.detail}});
  }
  const auto& last = rec.last_state;
  nlohmann::json final_state = initial;
  final_state["time_s"] = f.mission_time_s;
  final_state["uav"]["pose"] = {{"x", last.p_W_m[0]}, {"y", last.p_W_m[1]}, {"z", last.p_W_m[2]}, {"yaw", yaw_deg(last)}};
  final_state["uav"]["speed_mps"] = std::sqrt(last.v_W_mps[0] * last.v_W_mps[0] + last.v_W_mps[1] * last.v_W_mps[1] +
                                              last.v_W_mps[2] * last.v_W_mps[2]);
  final_state["uav"]["energy"]["battery_pct"] = last.battery_pct;
  final_state["safety_flags"] = {{"nfz_violation", kinds.count("nfz_intrusion") > 0},
                                 {"separation_breach", kinds.count("separation_breach") > 0}};

  nlohmann::json dialogue = nlohmann::json::array();
  nlohmann::json turns_rig = nlohmann::json::array();
  double gen_time_s = 0.0;
  int64_t prompt = 0, completion = 0, total = 0;
  double cost_usd = 0.0;
  bool has_cost = false;
  int attempts = 1;
  for (const auto& t : rec.turns) {
    nlohmann::json turn = t;
    nlohmann::json rig = turn.value("_rig", nlohmann::json::object());
    turn.erase("_rig");
    dialogue.push_back(turn);
    rig["turn"] = t.value("turn", 0);
    rig["speaker"] = t.value("speaker", "");
    turns_rig.push_back(rig);
    if (t.value("speaker", "") == "agent") {
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
  }
  const bool crashed = last.crashed || kinds.count("crash") > 0;
  const bool success = rec.objectives_all_done && !crashed;

  nlohmann::json trajectory = nlohmann::json::array();
  for (const auto& p : rec.trajectory) trajectory.push_back({p[0], p[1], p[2], p[3], p[4], p[5]});

  nlohmann::json usage = {{"prompt_tokens", prompt}, {"completion_tokens", completion}, {"total_tokens", total}};
  if (has_cost) usage["cost"] = cost_usd;  // as OpenRouter reports it, summed over the turns
  // An llm agent is named by its endpoint's model and provider (the corpus's folder layout).
  const LlmAgentIdentity llm = llm_agent_identity(o);

  nlohmann::json episode = {
      {"initial_state", initial},
      {"dialogue", dialogue},
      {"final_state", final_state},
      {"success", success},
      {"_meta",
       {{"model", f.agent_name},
        {"seed", o.seed},
        {"ts", f.start_unix_us * 1e-6},
        {"ts_iso", iso_time(f.start_unix_us)},
        {"gen_time_s", gen_time_s},
        {"attempts_used", attempts},
        {"generation_failed", false},
        {"usage", usage}}},
      {"_rig",
       {{"status", f.status},
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
        {"turns", turns_rig},
        {"link", {{"up", link_json(rec.up)}, {"down", link_json(rec.down)}}},
        {"safety_events", events},
        {"flight_controller", {{"modes", rec.fc_modes}, {"failsafes", rec.fc_failsafes}}},
        {"objectives", rec.objectives},
        {"trajectory", {{"columns", {"t_s", "x_m", "y_m", "z_m", "battery_pct", "speed_mps"}},
                        {"samples_1hz", trajectory},
                        {"distance_m", rec.distance_m},
                        {"max_altitude_m", rec.max_altitude_m},
                        {"max_speed_mps", rec.max_speed_mps},
                        {"crashed", crashed}}},
        {"counters", f.counters}}}};
  if (!f.realtime.is_null()) episode["_rig"]["realtime"] = f.realtime;
  if (!llm.model.empty()) {
    episode["_meta"]["model"] = llm.model;
    episode["_meta"]["provider"] = llm.provider;
  }
  return episode;
}

void write_episode(const std::filesystem::path& dir, const nlohmann::json& episode) {
  std::filesystem::create_directories(dir);
  const auto path = dir / "episode.json";
  std::ofstream out(path);
  out << episode.dump(2) << "\n";
  if (!out.flush()) throw std::runtime_error(path.string() + ": write failed");
}

std::string write_trajectory_plot(const std::filesystem::path& dir, const Scenario& s, const RecordedEpisode& rec) {
  if (rec.trajectory.empty()) return "no trajectory recorded";
  const auto abs = std::filesystem::absolute(dir);
  {
    std::ofstream d(abs / "trajectory.tsv");
    d << "# t_s\tx_m\ty_m\tz_m\tbattery_pct\tspeed_mps\n";
    for (const auto& p : rec.trajectory) d << p[0] << "\t" << p[1] << "\t" << p[2] << "\t" << p[3] << "\t" << p[4] << "\t" << p[5] << "\n";
  }
  std::ofstream gp(abs / "trajectory.gp");
  // The map frames the track, the objectives and the no-fly zones (not the whole geofence).
  double x0 = 1e18, x1 = -1e18, y0 = 1e18, y1 = -1e18;
  auto extend = [&](double x, double y, double r) {
    x0 = std::min(x0, x - r);
    x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r);
    y1 = std::max(y1, y + r);
  };
  for (const auto& p : rec.trajectory) extend(p[1], p[2], 0.0);
  for (const auto& o : s.mission.objectives) {
    for (const auto& p : o.area) extend(p.x(), p.y(), 0.0);
    if (o.type == agent::ObjectiveType::kImagePoint || o.type == agent::ObjectiveType::kDelivery) extend(o.point.x(), o.point.y(), o.radius_m);
  }
  for (const auto& z : s.airspace.no_fly_zones) {
    if (z.polygon.empty()) extend(z.centre.x(), z.centre.y(), z.radius_m);
    for (const auto& p : z.polygon) extend(p.x(), p.y(), 0.0);
  }
  const double pad = 0.08 * std::max(x1 - x0, y1 - y0) + 10.0;
  gp << "set terminal pngcairo size 1200,550 font ',10' noenhanced\nset output '" << (abs / "trajectory.png").string() << "'\n"
     << "set multiplot layout 1,2 title '" << s.name << "'\n"
     << "set size ratio -1\nset xlabel 'east (m)'\nset ylabel 'north (m)'\nset grid\nset key bottom right\n"
     << "set xrange [" << x0 - pad << ":" << x1 + pad << "]\nset yrange [" << y0 - pad << ":" << y1 + pad << "]\n";
  int obj = 1;
  if (s.airspace.geofence.size() >= 3) {
    gp << "set object " << obj++ << " polygon from ";
    for (std::size_t i = 0; i <= s.airspace.geofence.size(); ++i) {
      const auto& p = s.airspace.geofence[i % s.airspace.geofence.size()];
      gp << (i ? " to " : "") << p.x() << "," << p.y();
    }
    gp << " fs empty border lc rgb '#888888' dt 2\n";
  }
  for (const auto& z : s.airspace.no_fly_zones) {
    if (z.polygon.empty()) {
      gp << "set object " << obj++ << " circle at " << z.centre.x() << "," << z.centre.y() << " size " << z.radius_m
         << " fs transparent solid 0.25 fc rgb '#d62728'\n";
    }
  }
  for (const auto& o : s.mission.objectives) {
    if (o.area.size() >= 3) {
      gp << "set object " << obj++ << " polygon from ";
      for (std::size_t i = 0; i <= o.area.size(); ++i) {
        const auto& p = o.area[i % o.area.size()];
        gp << (i ? " to " : "") << p.x() << "," << p.y();
      }
      gp << " fs transparent solid 0.15 fc rgb '#2ca02c'\n";
    } else if (o.type != agent::ObjectiveType::kReturnAndLand) {
      gp << "set label " << obj++ << " '" << o.id << "' at " << o.point.x() << "," << o.point.y() << " point pt 7 ps 1.5 lc rgb '#2ca02c' offset 1,1\n";
    }
  }
  gp << "plot '" << (abs / "trajectory.tsv").string() << "' using 2:3 with lines lw 2 lc rgb '#1f77b4' title 'ground track'\n"
     << "unset object\nunset label\nset size noratio\nset autoscale\nset xlabel 'mission time (s)'\nset ylabel 'altitude (m)'\n"
     << "set y2label 'battery (%)'\nset y2tics\nset ytics nomirror\n"
     << "plot '" << (abs / "trajectory.tsv").string() << "' using 1:4 with lines lw 2 title 'altitude', '' using 1:5 axes x1y2 with lines lw 2 title 'battery'\n"
     << "unset multiplot\n";
  gp.close();
  const std::string cmd = "gnuplot '" + (abs / "trajectory.gp").string() + "' > '" + (abs / "gnuplot.log").string() + "' 2>&1";
  if (std::system(cmd.c_str()) != 0) return "gnuplot failed (see " + (abs / "gnuplot.log").string() + ")";
  return "";
}

}  // namespace a3::rigs
