// Vehicle parameters from JSON.
#include "dynamics/vehicle_params.hpp"

#include <cmath>
#include <limits>

#include "common/json_file.hpp"
#include "dynamics/airframe_default.hpp"

namespace a3::dynamics {
namespace {

using common::InputError;
using common::number_or;
using common::require_number;
using common::require_object;

double positive(const nlohmann::json& o, const std::string& key, const std::string& where) {
  const double x = require_number(o, key, where);
  if (!(x > 0.0)) throw InputError(where + "/" + key + ": must be > 0, got " + std::to_string(x));
  return x;
}

double non_negative(const nlohmann::json& o, const std::string& key, double fallback,
                    const std::string& where) {
  const double x = number_or(o, key, fallback, where);
  if (x < 0.0) throw InputError(where + "/" + key + ": must be >= 0, got " + std::to_string(x));
  return x;
}

}  // namespace

VehicleParams vehicle_params_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw InputError(where + ": an airframe must be a JSON object");
  VehicleParams p;
  p.name = j.contains("name") && j["name"].is_string() ? j["name"].get<std::string>() : "unnamed";
  p.source = j.contains("source") && j["source"].is_string() ? j["source"].get<std::string>() : "";
  p.mass_kg = positive(j, "mass_kg", where);
  const std::string wi = where + "/inertia_kgm2";
  const auto& inertia = require_object(j, "inertia_kgm2", where);
  p.inertia_xx_kgm2 = positive(inertia, "xx", wi);
  p.inertia_yy_kgm2 = positive(inertia, "yy", wi);
  p.inertia_zz_kgm2 = positive(inertia, "zz", wi);
  p.arm_length_m = positive(j, "arm_length_m", where);

  const std::string wr = where + "/rotor";
  const auto& rotor = require_object(j, "rotor", where);
  p.rotor.thrust_coeff_N_per_radps2 = positive(rotor, "thrust_coeff_N_per_radps2", wr);
  p.rotor.drag_torque_coeff_Nm_per_radps2 = positive(rotor, "drag_torque_coeff_Nm_per_radps2", wr);
  p.rotor.max_speed_radps = positive(rotor, "max_speed_radps", wr);
  p.rotor.time_constant_up_s = positive(rotor, "time_constant_up_s", wr);
  p.rotor.time_constant_down_s = positive(rotor, "time_constant_down_s", wr);
  p.rotor.radius_m = positive(rotor, "radius_m", wr);
  p.rotor.figure_of_merit = positive(rotor, "figure_of_merit", wr);
  if (p.rotor.figure_of_merit > 1.0) throw InputError(wr + "/figure_of_merit: must be <= 1");

  const std::string wa = where + "/aero";
  const auto& aero = require_object(j, "aero", where);
  p.aero.linear_drag_Ns_per_m = non_negative(aero, "linear_drag_Ns_per_m", 0.0, wa);
  p.aero.drag_cdA_m2 = non_negative(aero, "drag_cdA_m2", 0.0, wa);
  p.aero.angular_drag_Nms_per_rad = non_negative(aero, "angular_drag_Nms_per_rad", 0.0, wa);

  const std::string wb = where + "/battery";
  const auto& battery = require_object(j, "battery", where);
  const double cells = positive(battery, "cells", wb);
  if (cells != std::floor(cells) || cells > 24) {
    throw InputError(wb + "/cells: must be a whole number of cells (1..24)");
  }
  p.battery.cells = static_cast<int>(cells);
  p.battery.capacity_Ah = positive(battery, "capacity_Ah", wb);
  p.battery.cell_full_V = positive(battery, "cell_full_V", wb);
  p.battery.cell_nominal_V = positive(battery, "cell_nominal_V", wb);
  p.battery.cell_empty_V = positive(battery, "cell_empty_V", wb);
  if (!(p.battery.cell_empty_V < p.battery.cell_nominal_V &&
        p.battery.cell_nominal_V < p.battery.cell_full_V)) {
    throw InputError(wb + ": cell voltages must satisfy empty < nominal < full");
  }
  p.battery.internal_resistance_ohm = non_negative(battery, "internal_resistance_ohm", 0.0, wb);
  p.battery.powertrain_efficiency = positive(battery, "powertrain_efficiency", wb);
  if (p.battery.powertrain_efficiency > 1.0) {
    throw InputError(wb + "/powertrain_efficiency: must be <= 1");
  }
  p.battery.avionics_power_W = non_negative(battery, "avionics_power_W", 0.0, wb);

  if (j.contains("ground")) {
    p.crash_speed_mps = positive(require_object(j, "ground", where), "crash_speed_mps", where + "/ground");
  }
  return p;
}

VehicleParams load_vehicle_params(const std::filesystem::path& path) {
  return vehicle_params_from_json(common::load_json_file(path), path.string());
}

VehicleParams default_vehicle_params() {
  static const VehicleParams params =
      vehicle_params_from_json(nlohmann::json::parse(default_airframe_json()), "airframes/iris.json");
  return params;
}

VehicleParams airframe_by_name_or_path(const std::string& name_or_path) {
  for (const std::string& name : builtin_airframe_names()) {
    if (name == name_or_path) {
      return vehicle_params_from_json(nlohmann::json::parse(builtin_airframe_json(name)), "airframes/" + name);
    }
  }
  std::error_code ec;
  if (!std::filesystem::exists(name_or_path, ec)) {
    std::string names;
    for (const std::string& name : builtin_airframe_names()) names += (names.empty() ? "" : ", ") + name;
    throw InputError("airframe '" + name_or_path + "' is neither a built-in airframe (" + names +
                     ") nor an existing file");
  }
  return load_vehicle_params(name_or_path);
}

VehicleParams with_payloads(VehicleParams params, const std::vector<Payload>& payloads) {
  constexpr double kPayloadOffset_m = 0.1;
  for (const Payload& p : payloads) {
    params.payload_mass_kg += p.mass_kg;
    params.payload_power_W += p.power_W;
    params.aero.drag_cdA_m2 += p.drag_cdA_m2;
    params.inertia_xx_kgm2 += p.mass_kg * kPayloadOffset_m * kPayloadOffset_m;
    params.inertia_yy_kgm2 += p.mass_kg * kPayloadOffset_m * kPayloadOffset_m;
    params.payloads.push_back(p);
  }
  return params;
}

double airspeed_for_drag_mps(const AeroParams& aero, double force_N) {
  const double a = 0.5 * kAirDensity_kgpm3 * aero.drag_cdA_m2;
  const double b = aero.linear_drag_Ns_per_m;
  if (a <= 0.0) return b > 0.0 ? force_N / b : std::numeric_limits<double>::infinity();
  return (-b + std::sqrt(b * b + 4.0 * a * force_N)) / (2.0 * a);
}

}  // namespace a3::dynamics
