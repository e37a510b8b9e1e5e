// Difficulty presets, knob parsing and the gen: spec.
#include "rigs/generator/scenario_generator_knobs.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>

#include "common/json_file.hpp"
#include "linkemu/network_state.hpp"

namespace a3::rigs {
namespace {

using common::InputError;

int parse_count(const std::string& name, const std::string& value) {
  int out = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), out);
  if (ec != std::errc() || end != value.data() + value.size() || out < 0) {
    throw InputError("gen knob " + name + "='" + value + "': expected a non-negative integer");
  }
  return out;
}

double parse_amount(const std::string& name, const std::string& value) {
  double out = 0.0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), out);
  if (ec != std::errc() || end != value.data() + value.size() || !std::isfinite(out) || out < 0.0) {
    throw InputError("gen knob " + name + "='" + value + "': expected a non-negative number");
  }
  return out;
}

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

struct Knob {
  std::function<void(MissionKnobs&, const std::string&, const std::string&)> set;
  std::function<std::string(const MissionKnobs&)> text;
};

template <typename Member>
Knob count_knob(Member member) {
  return {[member](MissionKnobs& k, const std::string& n, const std::string& v) { k.*member = parse_count(n, v); },
          [member](const MissionKnobs& k) { return std::to_string(k.*member); }};
}

template <typename Member>
Knob amount_knob(Member member) {
  return {[member](MissionKnobs& k, const std::string& n, const std::string& v) { k.*member = parse_amount(n, v); },
          [member](const MissionKnobs& k) { return number_text(k.*member); }};
}

// "any" first, then the names.
std::vector<std::string> any_or(std::vector<std::string> names) {
  names.insert(names.begin(), "any");
  return names;
}

Knob word_knob(std::string MissionKnobs::*member, std::vector<std::string> allowed) {
  return {[member, allowed](MissionKnobs& k, const std::string& n, const std::string& v) {
            std::string list;
            for (const auto& a : allowed) {
              if (a == v) {
                k.*member = v;
                return;
              }
              list += (list.empty() ? "" : ", ") + a;
            }
            throw InputError("gen knob " + n + "='" + v + "': expected one of " + list);
          },
          [member](const MissionKnobs& k) { return k.*member; }};
}

// In the order knobs_text writes them.
const std::vector<std::pair<std::string, Knob>>& knob_table() {
  static const std::vector<std::pair<std::string, Knob>> table = {
      {"objectives", count_knob(&MissionKnobs::objectives)},
      {"survey", count_knob(&MissionKnobs::surveys)},
      {"image_point", count_knob(&MissionKnobs::image_points)},
      {"delivery", count_knob(&MissionKnobs::deliveries)},
      {"thermal_search", count_knob(&MissionKnobs::thermal_searches)},
      {"nfz", count_knob(&MissionKnobs::no_fly_zones)},
      {"traffic", count_knob(&MissionKnobs::traffic)},
      {"wind", amount_knob(&MissionKnobs::wind_mps)},
      {"gust", amount_knob(&MissionKnobs::gust_mps)},
      {"payload", amount_knob(&MissionKnobs::payload_kg)},
      {"airframe", word_knob(&MissionKnobs::airframe, {"auto", "iris", "heavy-lift"})},
      {"degradations", count_knob(&MissionKnobs::degradations)},
      {"degrade_at", word_knob(&MissionKnobs::degrade_at, [] {
         std::vector<std::string> names = any_or(degradation_phases());
         names.insert(names.begin() + 1, "phases");
         return names;
       }())},
      {"turns", count_knob(&MissionKnobs::turns)},
      {"slice", word_knob(&MissionKnobs::slice, any_or(linkemu::slice_names()))},
  };
  return table;
}

void require_at_most(const std::string& what, double value, double max) {
  if (value > max) throw InputError("gen knob " + what + "=" + number_text(value) + ": at most " + number_text(max));
}

uint64_t parse_seed(const std::string& text, const std::string& spec) {
  uint64_t seed = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    throw InputError("scenario '" + spec + "': expected gen:SEED[:knob=value+...] with SEED a non-negative integer");
  }
  return seed;
}

}  // namespace

std::vector<std::string> difficulty_names() { return {"easy", "medium", "hard"}; }

const std::vector<std::string>& degradation_phases() {
  static const std::vector<std::string> kPhases = {"takeoff", "transit", "objective", "home"};
  return kPhases;
}

MissionKnobs difficulty_preset(const std::string& name) {
  MissionKnobs k;
  k.difficulty = name;
  if (name == "easy") {
    k.objectives = 1;
    k.no_fly_zones = 0;
    k.traffic = 0;
    k.wind_mps = 2.0;
    k.gust_mps = 3.0;
    k.payload_kg = 0.2;
    k.degradations = 0;
  } else if (name == "medium") {
    // The defaults of MissionKnobs.
  } else if (name == "hard") {
    // One objective: the peer's alert and the degradation each take a turn of the budget.
    k.objectives = 1;
    k.no_fly_zones = 2;
    k.traffic = 1;
    k.wind_mps = 7.0;
    k.gust_mps = 9.5;
    k.payload_kg = 1.5;
    k.degradations = 1;
  } else {
    throw InputError("gen difficulty '" + name + "': expected easy, medium or hard");
  }
  return k;
}

std::string knob_names() {
  std::string names;
  for (const auto& [name, knob] : knob_table()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

void set_knob(MissionKnobs& knobs, const std::string& name, const std::string& value) {
  if (name == "difficulty") {
    knobs = difficulty_preset(value);
    return;
  }
  std::string names = "difficulty";
  for (const auto& [knob_name, knob] : knob_table()) {
    if (knob_name == name) return knob.set(knobs, name, value);
    names += ", " + knob_name;
  }
  throw InputError("gen knob '" + name + "' is not a knob (" + names + ")");
}

void check_knobs(const MissionKnobs& k) {
  if (k.turns < 8 || k.turns > 12) {
    throw InputError("gen knob turns=" + std::to_string(k.turns) + ": expected 8..12 (a valid α³-Bench episode)");
  }
  int given = 0;
  for (int count : {k.surveys, k.image_points, k.deliveries, k.thermal_searches}) given += std::max(count, 0);
  if (given > k.objectives) {
    throw InputError("gen knobs: the per-kind counts (" + std::to_string(given) + ") exceed objectives=" +
                     std::to_string(k.objectives));
  }
  if (k.objectives < 1) throw InputError("gen knob objectives=0: a mission needs at least one objective");
  require_at_most("objectives", k.objectives, 4);
  require_at_most("nfz", k.no_fly_zones, 4);
  require_at_most("traffic", k.traffic, 3);
  require_at_most("degradations", k.degradations, 4);
  require_at_most("wind", k.wind_mps, 20.0);
  require_at_most("payload", k.payload_kg, 5.0);
  if (k.gust_mps < k.wind_mps) {
    throw InputError("gen knobs: gust=" + number_text(k.gust_mps) + " is below wind=" + number_text(k.wind_mps));
  }
}

std::string knobs_text(const MissionKnobs& knobs) {
  std::string out = "difficulty=" + knobs.difficulty;
  for (const auto& [name, knob] : knob_table()) {
    const std::string value = knob.text(knobs);
    if (value != "-1") out += "+" + name + "=" + value;
  }
  return out;
}

bool is_generator_spec(const std::string& spec) { return spec.rfind("gen:", 0) == 0; }

GeneratorSpec parse_generator_spec(const std::string& spec) {
  if (!is_generator_spec(spec)) throw InputError("scenario '" + spec + "' is not a gen:SEED[:knobs] spec");
  const std::string rest = spec.substr(4);
  const auto colon = rest.find(':');
  GeneratorSpec out;
  out.seed = parse_seed(rest.substr(0, colon), spec);
  if (colon == std::string::npos) return out;
  std::size_t start = colon + 1;
  while (start <= rest.size()) {
    const auto plus = rest.find('+', start);
    const std::string item = rest.substr(start, plus == std::string::npos ? std::string::npos : plus - start);
    const auto eq = item.find('=');
    if (item.empty()) throw InputError("scenario '" + spec + "': empty knob (expected knob=value+knob=value)");
    if (eq == std::string::npos) {
      out.knobs = difficulty_preset(item);
    } else {
      set_knob(out.knobs, item.substr(0, eq), item.substr(eq + 1));
    }
    if (plus == std::string::npos) break;
    start = plus + 1;
  }
  check_knobs(out.knobs);
  return out;
}

std::string generator_spec_text(const GeneratorSpec& spec) {
  return "gen:" + std::to_string(spec.seed) + ":" + knobs_text(spec.knobs);
}

}  // namespace a3::rigs
