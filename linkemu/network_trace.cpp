// Reading network traces (plain lists, {"trace": ...} objects, α³-Bench episodes).
#include "linkemu/network_trace.hpp"

#include <cmath>
#include <optional>
#include <sstream>

#include "common/json_file.hpp"

namespace a3::linkemu {
namespace {

using common::InputError;
using nlohmann::json;

double checked(const json& object, const std::string& key, const std::string& where, double lo,
               double hi, bool lo_open) {
  const double x = common::require_number(object, key, where);
  if ((lo_open ? !(x > lo) : !(x >= lo)) || !(x <= hi)) {
    std::ostringstream message;
    message << where << "/" << key << ": " << x << " is outside " << (lo_open ? "(" : "[") << lo
            << ", " << hi << "]";
    throw InputError(message.str());
  }
  return x;
}

NetworkState parse_vector(const json& object, const std::string& where) {
  if (!object.is_object()) {
    throw InputError(where + ": expected an n_t object, got " + std::string(object.type_name()));
  }
  NetworkState s;
  const std::string slice = common::require_string(object, "slice", where);
  try {
    s.slice = parse_slice(slice);
  } catch (const std::invalid_argument& e) {
    throw InputError(where + "/slice: " + e.what());
  }
  s.lat_ms = checked(object, "lat_ms", where, 0.0, HUGE_VAL, false);
  s.jitter_ms = checked(object, "jitter_ms", where, 0.0, HUGE_VAL, false);
  s.loss_pct = checked(object, "loss_pct", where, 0.0, 100.0, false);
  s.throughput_mbps = checked(object, "throughput_mbps", where, 0.0, HUGE_VAL, true);
  s.edge_load = checked(object, "edge_load", where, 0.0, 1.0, false);
  if (auto it = object.find("degraded"); it != object.end()) {
    if (!it->is_boolean()) throw InputError(where + "/degraded: expected true or false");
    s.degraded = it->get<bool>();
  } else {
    s.degraded = is_hard(s);
  }
  return s;
}

int64_t to_us(double seconds) { return std::llround(seconds * 1e6); }

// A `where` at the top level of a file ends in ": " ("file.json: "); below it, in a path.
bool is_top_level(const std::string& where) {
  return where.size() >= 2 && where.compare(where.size() - 2, 2, ": ") == 0;
}

// "file.json: " + text at the top level, "file.json: /trace: " + text below it.
std::string problem(const std::string& where, const std::string& text) {
  return where + (is_top_level(where) ? "" : ": ") + text;
}

void check_period(double period_s, const std::string& where) {
  if (!(period_s > 0.0) || !std::isfinite(period_s)) {
    throw InputError(problem(where, "the trace period must be a positive number of seconds"));
  }
}

}  // namespace

NetworkTrace episode_network_trace(const episode::Episode& episode, double period_s) {
  check_period(period_s, episode.where() + ": ");
  if (episode.turn_count() == 0) throw InputError(episode.where() + ": /dialogue: the trace has no points");
  NetworkTrace trace;
  trace.last_hold_us = to_us(period_s);
  for (std::size_t i = 0; i < episode.turn_count(); ++i) {
    TracePoint point;
    point.state = parse_vector(json(episode.net(i)), episode.turn_where(i) + "/net");
    point.t_us = to_us(static_cast<double>(i) * period_s);
    trace.points.push_back(point);
  }
  return trace;
}

NetworkTrace parse_network_trace(const json& document, const std::string& where, double period_s) {
  const json* points = &document;
  std::string points_where = where;
  if (document.is_object()) {
    if (document.contains("period_s")) period_s = common::require_number(document, "period_s", where);
    if (document.contains("dialogue")) {
      const std::string file = is_top_level(where) ? where.substr(0, where.size() - 2) : where;
      return episode_network_trace(episode::Episode(episode::Document(document), file), period_s);
    }
    points = &common::require_array(document, "trace", where);
    points_where = where + "/trace";
  } else if (!document.is_array()) {
    throw InputError(problem(where, "expected a list of n_t points, an object with \"trace\", or an "
                                    "α³-Bench episode; got " + std::string(document.type_name())));
  }
  check_period(period_s, where);
  if (points->empty()) throw InputError(problem(points_where, "the trace has no points"));

  NetworkTrace trace;
  trace.last_hold_us = to_us(period_s);
  std::optional<bool> timed;
  for (std::size_t i = 0; i < points->size(); ++i) {
    const std::string at = points_where + "/" + std::to_string(i);
    const json& item = (*points)[i];
    TracePoint point;
    point.state = parse_vector(item, at);
    const bool has_time = item.contains("t_s");
    if (timed && *timed != has_time) throw InputError(at + ": \"t_s\" must be on every point or on none");
    timed = has_time;
    point.t_us = has_time ? to_us(checked(item, "t_s", at, 0.0, HUGE_VAL, false)) : to_us(static_cast<double>(i) * period_s);
    if (!trace.points.empty() && point.t_us <= trace.points.back().t_us) {
      throw InputError(at + "/t_s: times must increase (previous point at " +
                       std::to_string(trace.points.back().t_us * 1e-6) + " s)");
    }
    trace.points.push_back(point);
  }
  return trace;
}

NetworkTrace load_network_trace(const std::filesystem::path& path, double period_s) {
  NetworkTrace trace = parse_network_trace(common::load_json_file(path), path.string() + ": ", period_s);
  trace.source = path.string();
  return trace;
}

json to_json(const NetworkTrace& trace) {
  json points = json::array();
  for (const TracePoint& p : trace.points) {
    points.push_back({{"t_s", static_cast<double>(p.t_us) * 1e-6},
                      {"slice", to_string(p.state.slice)},
                      {"lat_ms", p.state.lat_ms},
                      {"jitter_ms", p.state.jitter_ms},
                      {"loss_pct", p.state.loss_pct},
                      {"throughput_mbps", p.state.throughput_mbps},
                      {"edge_load", p.state.edge_load},
                      {"degraded", p.state.degraded}});
  }
  return {{"period_s", static_cast<double>(trace.last_hold_us) * 1e-6}, {"trace", points}};
}

}  // namespace a3::linkemu
