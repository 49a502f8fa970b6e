// Internal: the JKR edge crack with Maugis-Barquins kinetics, stepped in time under the
// instrument's control - the ODE da/dt = -v_star (G/w0 - 1)^(1/n) (G > w0, else 0) with the energy
// release rate of the paper's transform, G = (P_H - P)^2 S' / (4 pi a S^2) (docs/theory.md s.9).
// Shared by kinetic_retract (kinetics.hpp), simulate_curve and the fit.
#pragma once

#include <functional>
#include <memory>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr::detail {

/// The non-adhesive state at a contact radius [m] (P_H, delta_H, S and S' are used).
using StateAt = std::function<NonAdhesiveState(double)>;

/// Force [N], approach [m] and energy release rate [J/m^2] of the contact of radius a under a
/// control value c: the approach (fixed grips), the base's position z = delta + P/k (a cantilever
/// of stiffness k) or the force (load). The flat punch of radius a unloads linearly from the
/// non-adhesive state: P - P_H = S (delta - delta_H).
struct CrackPoint {
  double P = 0.0, delta = 0.0, G = 0.0;
};
CrackPoint crack_point(const NonAdhesiveState& s, RetractControl control, double stiffness, double c);

/// Steps a(t) from a start under a control value that moves linearly in time between the points
/// given to advance(). Implicit (GSL's bsimp, with the Jacobian by differences): near v_star ->
/// infinity the crack follows its equilibrium closely and the equation is stiff (GSL's implicit
/// Gaussian Runge-Kutta failed to start at equilibrium, where the speed leaves 0 as (G/w0 - 1)^(1/n)). The contact is
/// lost (separated()) once a falls below 1e-6 of its start: from there the crack runs to a = 0 in a
/// time far below any step (G grows like 1/a^3 on a half-space).
class KineticStepper {
 public:
  /// `state` must outlive the stepper. control: load, fixed_grips or cantilever (stiffness > 0).
  KineticStepper(StateAt state, double w0, const CrackKinetics& kinetics, RetractControl control, double stiffness);
  ~KineticStepper();
  KineticStepper(const KineticStepper&) = delete;
  KineticStepper& operator=(const KineticStepper&) = delete;

  /// At radius a [m] > 0 and control value c at time t [s].
  void start(double t, double a, double c);
  /// To time t1 > t() with the control moving linearly to c1; false if the integrator failed. A
  /// contact lost on the way stays lost (a() = 0).
  bool advance(double t1, double c1);
  /// One of the integrator's own steps towards t1 (the control moving linearly to c1 there), no
  /// longer than h_max [s]; false if it failed.
  bool step(double t1, double c1, double h_max);

  double t() const { return t_; }
  double a() const { return separated_ ? 0.0 : a_; }
  double control() const { return c_; }
  bool separated() const { return separated_; }
  /// P, delta and G now (zero force and G once separated).
  CrackPoint point() const;
  /// -da/dt now [m/s].
  double speed() const;

 private:
  friend struct KineticSystem;
  double rate(double t, double a) const;  // da/dt at (t, a)
  double control_at(double t) const { return c_ + slope_ * (t - t_); }
  void begin_segment(double t1, double c1);

  StateAt state_;
  double w0_;
  CrackKinetics kinetics_;
  RetractControl control_;
  double stiffness_;
  double t_ = 0.0, a_ = 0.0, c_ = 0.0, slope_ = 0.0, a_floor_ = 0.0, a_scale_ = 0.0;
  bool separated_ = false;
  struct Gsl;
  std::unique_ptr<Gsl> gsl_;
};

}  // namespace layerjkr::detail
