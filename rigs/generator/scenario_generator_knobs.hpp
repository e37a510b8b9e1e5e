// The knobs of a procedurally generated mission and the `gen:` scenario spec that carries them.
//
// Spec: gen:SEED[:ITEM+ITEM...], ITEM = knob=value or a difficulty name (easy, medium, hard);
// '+' separates items so that a spec survives a comma-separated --scenarios list. The
// difficulty (default medium) sets every knob; knobs given after it override its values, e.g.
// gen:7, gen:7:hard, gen:7:hard+wind=3+nfz=0. Knobs (see MissionKnobs):
//   objectives=N  survey=N image_point=N delivery=N thermal_search=N  nfz=N  traffic=N
//   wind=M/S  gust=M/S  payload=KG  airframe=auto|iris|heavy-lift  degradations=N  turns=T
//   degrade_at=any|phases|takeoff|transit|objective|home
//   slice=URLLC|eMBB|mMTC|any
// Bad specs throw common::InputError naming the item.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace a3::rigs {

struct MissionKnobs {
  std::string difficulty = "medium";
  // Objectives besides the final return_and_land. The kinds are drawn from the seed unless a
  // per-kind count is given (>= 0); given counts are exact, the rest of `objectives` is drawn.
  int objectives = 2;
  int surveys = -1;
  int image_points = -1;
  int deliveries = -1;
  int thermal_searches = -1;
  int no_fly_zones = 1;      // placed across the route (first leg, then the way home)
  int traffic = 0;           // peers patrolling across the route at cruise altitude
  double wind_mps = 4.0;     // mean wind; its direction is drawn
  double gust_mps = 6.0;     // the weather service's gust figure (initial_state.env.gust_mps)
  double payload_kg = 0.3;   // the parcel of a delivery; without a delivery, a sensor pod (0: none)
  std::string airframe = "auto";  // auto: iris unless the payload needs the heavy-lift
  int degradations = 1;      // windows of forced link degradation
  // Where they fall: "any" (drawn over the first minutes), "phases" (window i in the mission
  // phase after window i-1's, the first phase drawn), or a phase — takeoff, transit, objective,
  // home — for the first window (the next ones in the phases after it).
  std::string degrade_at = "phases";
  int turns = 12;            // dialogue turn budget the mission is sized for (8..12)
  std::string slice = "any"; // initial 6G slice; any: drawn
};

struct GeneratorSpec {
  uint64_t seed = 0;
  MissionKnobs knobs;
};

std::vector<std::string> difficulty_names();
// The mission phases a degradation window can be placed in, in flight order.
const std::vector<std::string>& degradation_phases();
// Throws common::InputError for an unknown name.
MissionKnobs difficulty_preset(const std::string& name);
// Every knob's name, ", "-separated (for help texts).
std::string knob_names();
// Sets one knob from text; throws common::InputError naming the knob and the value.
void set_knob(MissionKnobs& knobs, const std::string& name, const std::string& value);
// Checks ranges and consistency (counts within objectives, turns 8..12, ...).
void check_knobs(const MissionKnobs& knobs);
// Every knob, in the spec's syntax ("difficulty=medium+objectives=2+..."): what the mission was made from.
std::string knobs_text(const MissionKnobs& knobs);

bool is_generator_spec(const std::string& spec);
GeneratorSpec parse_generator_spec(const std::string& spec);
// "gen:SEED:" + knobs: the same mission as `spec`, spelled out.
std::string generator_spec_text(const GeneratorSpec& spec);

}  // namespace a3::rigs
