// Vehicle parameters: airframe, rotors, aerodynamics, battery, ground contact. Read from a JSON
// airframe file (dynamics' own format: dynamics/airframes/*.json, the 3DR Iris, the default,
// and a heavy-lift class for heavy payloads, both compiled in), then typed payloads add mass,
// drag area and electrical load (the scenario's uav.payloads are parsed outside dynamics/, by
// rigs/scenario/uav_payloads.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace a3::dynamics {

struct RotorParams {
  double thrust_coeff_N_per_radps2 = 0.0;       // T = k_f ω²
  double drag_torque_coeff_Nm_per_radps2 = 0.0;  // Q = k_m ω²
  double max_speed_radps = 0.0;
  double time_constant_up_s = 0.0;    // first-order motor lag, spinning up
  double time_constant_down_s = 0.0;  // and down
  double radius_m = 0.0;              // for the induced-power model
  double figure_of_merit = 0.6;       // ideal induced power / actual rotor power
};

struct AeroParams {
  double linear_drag_Ns_per_m = 0.0;       // F = -c v_air (rotor/induced drag, at low speed)
  double drag_cdA_m2 = 0.0;                // F = -½ ρ CdA |v_air| v_air (body; payloads add)
  double angular_drag_Nms_per_rad = 0.0;   // τ = -c ω_body
};

struct BatteryParams {
  int cells = 3;
  double capacity_Ah = 0.0;
  double cell_full_V = 4.2;
  double cell_nominal_V = 3.7;
  double cell_empty_V = 3.3;
  double internal_resistance_ohm = 0.0;
  double powertrain_efficiency = 0.8;  // electrical → rotor shaft power (ESC and motor)
  double avionics_power_W = 0.0;
};

struct Payload {
  std::string id;
  double mass_kg = 0.0;
  double drag_cdA_m2 = 0.0;
  double power_W = 0.0;
};

struct VehicleParams {
  std::string name;
  std::string source;
  double mass_kg = 0.0;  // airframe with battery
  double inertia_xx_kgm2 = 0.0, inertia_yy_kgm2 = 0.0, inertia_zz_kgm2 = 0.0;
  double arm_length_m = 0.0;  // rotor centre to vehicle centre
  RotorParams rotor;
  AeroParams aero;
  BatteryParams battery;
  double crash_speed_mps = 3.0;  // vertical touchdown speed above which the impact is a crash
  // Added by payloads (with_payloads()).
  double payload_mass_kg = 0.0;
  double payload_power_W = 0.0;
  std::vector<Payload> payloads;

  double total_mass_kg() const { return mass_kg + payload_mass_kg; }
};

// Physical constants of the environment.
inline constexpr double kGravity_mps2 = 9.80665;
inline constexpr double kAirDensity_kgpm3 = 1.225;  // ISA sea level

// The steady airspeed at which the airframe's drag (linear plus quadratic, sea-level air)
// equals `force_N`: ½ ρ CdA v² + c v = F solved for v >= 0 (infinite without any drag).
double airspeed_for_drag_mps(const AeroParams& aero, double force_N);

// Parses an airframe object; `where` names the source in errors. Throws common::InputError
// naming the file and JSON path of a missing, mistyped or out-of-range field.
VehicleParams vehicle_params_from_json(const nlohmann::json& j, const std::string& where);
VehicleParams load_vehicle_params(const std::filesystem::path& path);
// The default airframe (dynamics/airframes/iris.json, compiled in).
VehicleParams default_vehicle_params();
// A built-in airframe by name ("iris", "heavy-lift") or an airframe JSON file by path.
VehicleParams airframe_by_name_or_path(const std::string& name_or_path);

// The params with the payloads' mass, drag area and power added. A payload is carried at the
// centre of mass; its inertia is that of a point mass 0.1 m below it (roll and pitch).
VehicleParams with_payloads(VehicleParams params, const std::vector<Payload>& payloads);

}  // namespace a3::dynamics
