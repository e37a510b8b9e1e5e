// Open Dynamics Engine integration of the vehicle model.
#include "dynamics/ode_integrator.hpp"

#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

namespace a3::dynamics {
namespace {

// ODE needs one global initialisation and per-thread data in every thread that calls it.
void ensure_ode_ready() {
  static std::once_flag once;
  std::call_once(once, [] { dInitODE2(0); });
  thread_local bool thread_ready = false;
  if (!thread_ready) {
    dAllocateODEDataForThread(dAllocateMaskAll);
    thread_ready = true;
  }
}

constexpr double kHullSize_m = 0.4;    // landing-gear footprint
constexpr double kHullHeight_m = 0.1;  // the hull's bottom is level with the centre of mass
constexpr int kMaxContacts = 4;

}  // namespace

OdeIntegrator::OdeIntegrator(const QuadrotorModel& model, WindField& wind, double step_s)
    : Integrator(model, wind), step_s_(step_s) {
  if (!(step_s > 0.0 && step_s <= 0.01)) {
    throw std::invalid_argument("ODE step must be in (0, 0.01] s, got " + std::to_string(step_s));
  }
  ensure_ode_ready();
  world_ = dWorldCreate();
  dWorldSetGravity(world_, 0, 0, 0);  // gravity is part of the model's force
  // Soft, non-penetrating contact that settles within a few steps.
  dWorldSetERP(world_, 0.2);
  dWorldSetCFM(world_, 1e-7);
  dWorldSetContactSurfaceLayer(world_, 0.0);
  space_ = dSimpleSpaceCreate(nullptr);
  contacts_ = dJointGroupCreate(0);
  ground_ = dCreatePlane(space_, 0, 0, 1, 0);
  body_ = dBodyCreate(world_);
  dMass mass;
  const VehicleParams& p = model.params();
  dMassSetZero(&mass);
  dMassSetParameters(&mass, model.mass_kg(), 0, 0, 0, p.inertia_xx_kgm2, p.inertia_yy_kgm2,
                     p.inertia_zz_kgm2, 0, 0, 0);
  dBodySetMass(body_, &mass);
  dBodySetGyroscopicMode(body_, 1);
  dBodySetAutoDisableFlag(body_, 0);
  hull_ = dCreateBox(space_, kHullSize_m, kHullSize_m, kHullHeight_m);
  dGeomSetBody(hull_, body_);
  dGeomSetOffsetPosition(hull_, 0, 0, kHullHeight_m / 2);
}

OdeIntegrator::~OdeIntegrator() {
  ensure_ode_ready();
  if (contacts_ != nullptr) dJointGroupDestroy(contacts_);
  if (space_ != nullptr) dSpaceDestroy(space_);  // destroys the geoms
  if (world_ != nullptr) dWorldDestroy(world_);   // destroys the body
}

void OdeIntegrator::on_reset() {
  ensure_ode_ready();
  const VehicleState& s = state_;
  dBodySetPosition(body_, s.p_W_m.x(), s.p_W_m.y(), s.p_W_m.z());
  dBodySetLinearVel(body_, s.v_W_mps.x(), s.v_W_mps.y(), s.v_W_mps.z());
  const dQuaternion q = {s.q_WB.w(), s.q_WB.x(), s.q_WB.y(), s.q_WB.z()};
  dBodySetQuaternion(body_, q);
  const Eigen::Vector3d w_W = s.q_WB * s.w_B_radps;
  dBodySetAngularVel(body_, w_W.x(), w_W.y(), w_W.z());
  in_contact_ = on_ground_;
}

void OdeIntegrator::read_body() {
  const dReal* p = dBodyGetPosition(body_);
  const dReal* v = dBodyGetLinearVel(body_);
  const dReal* q = dBodyGetQuaternion(body_);
  const dReal* w = dBodyGetAngularVel(body_);
  state_.p_W_m = {p[0], p[1], p[2]};
  state_.v_W_mps = {v[0], v[1], v[2]};
  state_.q_WB = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  state_.w_B_radps = state_.q_WB.conjugate() * Eigen::Vector3d(w[0], w[1], w[2]);
}

void OdeIntegrator::near_callback(void* data, dGeomID a, dGeomID b) {
  auto* self = static_cast<OdeIntegrator*>(data);
  dContact contact[kMaxContacts];
  for (auto& c : contact) {
    c.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
    c.surface.mu = 1.0;  // rubber feet on ground: no sliding once landed
    c.surface.soft_erp = 0.2;
    c.surface.soft_cfm = 1e-6;
    c.surface.bounce = 0.0;
  }
  const int n = dCollide(a, b, kMaxContacts, &contact[0].geom, sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    const dJointID j = dJointCreateContact(self->world_, self->contacts_, &contact[i]);
    dJointAttach(j, dGeomGetBody(contact[i].geom.g1), dGeomGetBody(contact[i].geom.g2));
  }
  self->contact_count_ += n;
}

int OdeIntegrator::collide() {
  contact_count_ = 0;
  dSpaceCollide(space_, this, &OdeIntegrator::near_callback);
  return contact_count_;
}

void OdeIntegrator::step(double dt_s, const RotorSpeeds& command) {
  const double t0 = time_s_;
  const Wrench w = model_.wrench(state_, wind_.wind_W_mps(t0));
  dBodyAddForce(body_, w.force_W_N.x(), w.force_W_N.y(), w.force_W_N.z());
  dBodyAddRelTorque(body_, w.torque_B_Nm.x(), w.torque_B_Nm.y(), w.torque_B_Nm.z());
  const double descent_speed = state_.v_W_mps.z();
  const int contacts = collide();
  dWorldStep(world_, dt_s);
  dJointGroupEmpty(contacts_);

  const double power0 = model_.electrical_power_W(state_.rotor_speed_radps);
  for (int i = 0; i < 4; ++i) {
    state_.rotor_speed_radps[i] = model_.rotor_speed_after(state_.rotor_speed_radps[i], command[i], dt_s);
  }
  const double power1 = model_.electrical_power_W(state_.rotor_speed_radps);
  state_.energy_used_J += 0.5 * (power0 + power1) * dt_s;
  read_body();
  time_s_ = t0 + dt_s;

  const bool touching = contacts > 0;
  if (touching && !in_contact_) {
    touchdown(time_s_, state_.p_W_m, descent_speed);
  } else if (!touching && in_contact_ && state_.p_W_m.z() > 1e-3) {
    liftoff(time_s_, state_.p_W_m);
  }
  in_contact_ = touching || (in_contact_ && state_.p_W_m.z() <= 1e-3);
  if (!battery_empty_ && state_.energy_used_J >= model_.battery_energy_J()) empty_battery(time_s_);
}

void OdeIntegrator::integrate(double t_end_s, const RotorSpeeds& command_radps) {
  ensure_ode_ready();
  RotorSpeeds command = command_radps;
  while (time_s_ < t_end_s - 1e-12) {
    const double dt = std::min(step_s_, t_end_s - time_s_);
    step(dt, command);
    command = effective_command(command_radps);  // a crash or an empty battery cuts the motors
  }
  time_s_ = t_end_s;
}

}  // namespace a3::dynamics
