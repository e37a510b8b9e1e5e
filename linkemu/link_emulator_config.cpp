// Link-emulator configuration: JSON reading, range checks, profile overrides.
#include "linkemu/link_emulator_config.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/json_file.hpp"

namespace a3::linkemu {
namespace {

using common::InputError;
using nlohmann::json;

bool require_bool(const json& object, const std::string& key, const std::string& where) {
  const json& value = object.at(key);
  if (!value.is_boolean()) {
    throw InputError(where + "/" + key + ": expected true or false, got " +
                     std::string(value.type_name()));
  }
  return value.get<bool>();
}

int64_t require_count(const json& object, const std::string& key, const std::string& where) {
  const json& value = object.at(key);
  if (!value.is_number_integer() || value.get<int64_t>() < 0) {
    throw InputError(where + "/" + key + ": expected a whole number >= 0");
  }
  return value.get<int64_t>();
}

void reject_unknown(const json& object, const std::set<std::string>& known,
                    const std::string& where) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (known.count(it.key()) == 0) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError(where + "/" + it.key() + ": unknown setting (known: " + list + ")");
    }
  }
}

template <typename Fn>
void checked(const std::string& where, Fn fn) {
  try {
    fn();
  } catch (const std::invalid_argument& e) {
    throw InputError(where + ": " + e.what());
  }
}

}  // namespace

LinkChannels LinkChannels::of_vehicle(common::VehicleId v) {
  namespace ch = common::channels;
  return {ch::kLinkUpTx.of(v).name,     ch::kLinkUpRx.of(v).name,      ch::kLinkDownTx.of(v).name,
          ch::kLinkDownRx.of(v).name,   ch::kNet.of(v).name,           ch::kLinkRecord.of(v).name,
          ch::kEdgeRequest.of(v).name,  ch::kEdgeReply.of(v).name,     ch::kSliceRequest.of(v).name,
          ch::kSliceReply.of(v).name};
}

LinkChannels LinkChannels::with_suffix(const std::string& suffix) const {
  LinkChannels c = *this;
  for (std::string* name : {&c.up_tx, &c.up_rx, &c.down_tx, &c.down_rx, &c.net, &c.record,
                            &c.edge_request, &c.edge_reply, &c.slice_request, &c.slice_reply}) {
    *name += suffix;
  }
  return c;
}

StartRegime parse_start_regime(const std::string& text) {
  if (text == "stationary") return StartRegime::kStationary;
  if (text == "normal") return StartRegime::kNormal;
  if (text == "degraded") return StartRegime::kDegraded;
  throw std::invalid_argument("unknown start regime '" + text +
                              "' (expected stationary, normal or degraded)");
}

const char* to_string(StartRegime start) {
  switch (start) {
    case StartRegime::kStationary: return "stationary";
    case StartRegime::kNormal: return "normal";
    case StartRegime::kDegraded: return "degraded";
  }
  return "?";
}

LinkEmulatorConfig parse_link_emulator_config(const json& object, const std::string& where,
                                              const std::filesystem::path& base_dir) {
  if (!object.is_object()) {
    throw InputError(where + "expected an object, got " + std::string(object.type_name()));
  }
  reject_unknown(object,
                 {"seed", "slice", "start_regime", "redraw_mean_s", "degraded_dwell_mean_s",
                  "min_dwell_s", "degraded_share", "handover_delay_ms", "net_rate_hz",
                  "reordering", "gilbert_elliott", "edge_max_load", "max_message_bytes",
                  "max_pending_messages", "max_pending_bytes", "max_backlog_s",
                  "publish_records", "trace", "degradations"},
                 where);
  LinkEmulatorConfig c;
  const auto has = [&](const char* key) { return object.contains(key); };
  const auto number = [&](const char* key) { return common::require_number(object, key, where); };
  if (has("seed")) {
    const json& seed = object.at("seed");
    if (!seed.is_number_unsigned()) {
      throw InputError(where + "/seed: expected a whole number >= 0");
    }
    c.seed = seed.get<uint64_t>();
  }
  if (has("slice")) {
    checked(where + "/slice",
            [&] { c.initial_slice = parse_slice(common::require_string(object, "slice", where)); });
  }
  if (has("start_regime")) {
    checked(where + "/start_regime", [&] {
      c.start_regime = parse_start_regime(common::require_string(object, "start_regime", where));
    });
  }
  if (has("redraw_mean_s")) c.redraw_mean_s = number("redraw_mean_s");
  if (has("degraded_dwell_mean_s")) c.degraded_dwell_mean_s = number("degraded_dwell_mean_s");
  if (has("min_dwell_s")) c.min_dwell_s = number("min_dwell_s");
  if (has("degraded_share")) c.degraded_share = number("degraded_share");
  if (has("handover_delay_ms")) c.handover_delay_ms = number("handover_delay_ms");
  if (has("net_rate_hz")) c.net_rate_hz = number("net_rate_hz");
  if (has("reordering")) c.link.reordering = require_bool(object, "reordering", where);
  if (has("gilbert_elliott")) {
    const std::string ge_where = where + "/gilbert_elliott";
    const json& ge = common::require_object(object, "gilbert_elliott", where);
    reject_unknown(ge, {"enabled", "mean_burst_messages", "loss_in_bad"}, ge_where);
    c.link.gilbert_elliott.enabled = ge.contains("enabled") ? require_bool(ge, "enabled", ge_where) : true;
    c.link.gilbert_elliott.mean_burst_messages =
        common::number_or(ge, "mean_burst_messages", c.link.gilbert_elliott.mean_burst_messages, ge_where);
    c.link.gilbert_elliott.loss_in_bad =
        common::number_or(ge, "loss_in_bad", c.link.gilbert_elliott.loss_in_bad, ge_where);
  }
  if (has("edge_max_load")) c.edge.max_load = number("edge_max_load");
  if (has("degradations")) {
    const json& windows = common::require_array(object, "degradations", where);
    for (std::size_t i = 0; i < windows.size(); ++i) {
      const std::string w = where + "/degradations/" + std::to_string(i);
      const double start_s = common::require_number(windows[i], "start_s", w);
      const double duration_s = common::require_number(windows[i], "duration_s", w);
      if (start_s < 0.0 || !(duration_s > 0.0)) throw InputError(w + ": start_s >= 0 and duration_s > 0");
      c.forced_degradations.push_back(
          {std::llround(start_s * 1e6), std::llround((start_s + duration_s) * 1e6)});
    }
  }
  if (has("max_message_bytes")) c.max_message_bytes = require_count(object, "max_message_bytes", where);
  if (has("max_pending_messages")) {
    c.max_pending_messages = require_count(object, "max_pending_messages", where);
  }
  if (has("max_pending_bytes")) c.max_pending_bytes = require_count(object, "max_pending_bytes", where);
  if (has("max_backlog_s")) c.max_backlog_s = number("max_backlog_s");
  if (has("publish_records")) c.publish_records = require_bool(object, "publish_records", where);
  if (has("trace")) {
    const std::string trace_where = where + "/trace";
    const json& trace = common::require_object(object, "trace", where);
    reject_unknown(trace, {"path", "period_s", "loop"}, trace_where);
    std::filesystem::path path = common::require_string(trace, "path", trace_where);
    if (path.is_relative()) path = base_dir / path;
    const double period_s = common::number_or(trace, "period_s", kDefaultTracePeriodS, trace_where);
    c.trace = load_network_trace(path, period_s);
    if (trace.contains("loop")) c.trace_loop = require_bool(trace, "loop", trace_where);
  }
  try {
    validate(c);
  } catch (const std::invalid_argument& e) {
    throw InputError(where + "/" + e.what());  // "file.json: /field: value rule"
  }
  return c;
}

LinkEmulatorConfig load_link_emulator_config(const std::filesystem::path& path) {
  return parse_link_emulator_config(common::load_json_file(path, 1u << 20), path.string() + ": ",
                                    path.parent_path());
}

void validate(const LinkEmulatorConfig& c) {
  const auto fail = [](const std::string& field, double value, const std::string& rule) {
    std::ostringstream message;
    message << field << ": " << value << " " << rule;
    throw std::invalid_argument(message.str());
  };
  const auto positive_if_set = [&](const std::optional<double>& v, const char* field) {
    if (v && !(*v > 0.0 && std::isfinite(*v))) fail(field, *v, "must be a positive number");
  };
  positive_if_set(c.redraw_mean_s, "redraw_mean_s");
  positive_if_set(c.degraded_dwell_mean_s, "degraded_dwell_mean_s");
  if (c.min_dwell_s && !(*c.min_dwell_s >= 0.0)) fail("min_dwell_s", *c.min_dwell_s, "must be >= 0");
  if (c.degraded_share && !(*c.degraded_share >= 0.0 && *c.degraded_share < 1.0)) {
    fail("degraded_share", *c.degraded_share, "must be in [0, 1)");
  }
  if (!(c.handover_delay_ms >= 0.0 && std::isfinite(c.handover_delay_ms))) {
    fail("handover_delay_ms", c.handover_delay_ms, "must be a number >= 0");
  }
  if (!(c.net_rate_hz >= 0.0 && c.net_rate_hz <= 10000.0)) {
    fail("net_rate_hz", c.net_rate_hz, "must be in [0, 10000]");
  }
  const auto& ge = c.link.gilbert_elliott;
  if (ge.enabled && !(ge.mean_burst_messages >= 1.0)) {
    fail("gilbert_elliott/mean_burst_messages", ge.mean_burst_messages, "must be >= 1");
  }
  if (ge.enabled && !(ge.loss_in_bad > 0.0 && ge.loss_in_bad <= 1.0)) {
    fail("gilbert_elliott/loss_in_bad", ge.loss_in_bad, "must be in (0, 1]");
  }
  if (!(c.edge.max_load >= 0.0 && c.edge.max_load < 1.0)) {
    fail("edge_max_load", c.edge.max_load, "must be in [0, 1)");
  }
  if (c.max_message_bytes <= 0) fail("max_message_bytes", static_cast<double>(c.max_message_bytes), "must be > 0");
  if (c.max_pending_messages <= 0) {
    fail("max_pending_messages", static_cast<double>(c.max_pending_messages), "must be > 0");
  }
  if (c.max_pending_bytes <= 0) fail("max_pending_bytes", static_cast<double>(c.max_pending_bytes), "must be > 0");
  if (!(c.max_backlog_s > 0.0)) fail("max_backlog_s", c.max_backlog_s, "must be > 0");
}

SliceProfiles effective_profiles(const SliceProfiles& profiles, const LinkEmulatorConfig& c) {
  SliceProfiles p = profiles;
  if (c.redraw_mean_s) p.timing.redraw_mean_s = *c.redraw_mean_s;
  if (c.degraded_dwell_mean_s) p.timing.degraded_dwell_mean_s = *c.degraded_dwell_mean_s;
  if (c.min_dwell_s) p.timing.min_dwell_s = *c.min_dwell_s;
  if (c.degraded_share) {
    for (SliceProfile& s : p.slices) s.degraded_share = *c.degraded_share;
  }
  return p;
}

}  // namespace a3::linkemu
