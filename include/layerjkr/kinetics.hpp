// layerjkr: rate-dependent adhesion - the retract of a JKR contact whose edge crack obeys
// Maugis-Barquins kinetics (adhesion.hpp, CrackKinetics), on any medium, under load control,
// fixed grips or a cantilever.
//
// The paper's transform gives every medium's energy release rate at contact radius a and force P,
//   G(a, P) = (P_H(a) - P)^2 S'(a) / (4 pi a S(a)^2),
// (the flat punch of radius a unloaded from the non-adhesive state: P - P_H = S (delta - delta_H);
// G = w is the JKR curve, eq. 19), and the crack recedes at v = -da/dt = v_star (G/w0 - 1)^(1/n)
// where G > w0. With the control moving at a constant rate from an equilibrium contact this is an
// ODE for a(t), integrated implicitly (GSL) to a relative 1e-10; the contact is lost when a falls
// below 1e-6 of its start. docs/theory.md s.9; tests/adhesion/test_crack_kinetics.cpp.
//
//   layerjkr::KineticRetractOptions o;
//   o.drive = {layerjkr::RetractControl::fixed_grips, 1e-6};   // 1 um/s
//   auto r = layerjkr::kinetic_retract(model, 0.05, {1e-7, 0.6}, o);
//   r.pull_off.P;            // the lowest force [N], below JKR's -3/2 pi w R on a sphere
#pragma once

#include <string>
#include <vector>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

/// How a retract is driven: what the instrument holds and how fast it moves it.
struct RetractDrive {
  /// load (the force falls at `rate` [N/s]), fixed_grips (the indenter withdraws at `rate` [m/s]),
  /// or cantilever (its base withdraws at `rate` [m/s]; the tip is at delta = z - P/k).
  RetractControl control = RetractControl::fixed_grips;
  double rate = 0.0;       ///< > 0, finite: [N/s] for load, [m/s] otherwise
  double stiffness = 0.0;  ///< the cantilever's [N/m] (> 0; cantilever only)
  /// Throws DomainError naming the first invalid field (automatic control is invalid here).
  void validate() const;
  /// e.g. "fixed grips at 1e-06 m/s", "a cantilever of 0.1 N/m at 2e-06 m/s", "load at 1e-09 N/s".
  std::string describe() const;
};

struct KineticRetractOptions {
  RetractDrive drive;
  /// The retract starts from the equilibrium (JKR) contact at this force [N] (default: zero load);
  /// it must lie above JKR's pull-off force.
  double start_force = 0.0;
  /// The integrator's steps are at most this fraction of the time the retract takes at
  /// equilibrium (v_star -> infinity), so the lowest force is resolved; in (0, 0.1].
  double max_step_fraction = 1e-3;
  /// Steps before the retract is refused as not separating (>= 100).
  std::size_t max_steps = 2'000'000;
  void validate() const;
};

/// A retract followed to the loss of contact.
struct KineticRetract {
  /// The integrator's steps from the start (t = 0) to the last one in contact: time [s], contact
  /// radius [m], force [N], approach [m], energy release rate G [J/m^2], crack speed -da/dt [m/s].
  std::vector<double> t, a, P, delta, G, speed;
  /// The lowest force (the pull-off force an AFM measures) [N], where and when: the vertex of the
  /// parabola through the lowest step and its neighbours.
  CriticalPoint pull_off;
  double pull_off_time = 0.0;
  double separation_time = 0.0;  ///< when the contact was lost [s]
  /// v_star -> infinity: the JKR curve. Its lowest force is JKR's pull-off whatever the control;
  /// the contact is lost there under load control, at the fixed-grips point under fixed grips,
  /// where dP/d delta = -k under a cantilever.
  CriticalPoint equilibrium_pull_off;
  CriticalPoint equilibrium_separation;
  /// The drive's demand on the crack: the equilibrium retract's mean crack speed over v_star.
  /// Where rate_ratio^n < 1e-6 (the kinetic correction's order) the retract is the equilibrium one
  /// (at_equilibrium: the JKR curve, G = w0, sampled at 401 radii), not integrated; beyond 1e12 a
  /// drive is refused (the pull-off grows without bound).
  double rate_ratio = 0.0;
  bool at_equilibrium = false;
};

/// The retract of the JKR contact of `model` with work of adhesion w0 [J/m^2] > 0 and `kinetics`,
/// driven by options.drive from equilibrium at options.start_force. Throws DomainError for invalid
/// options, kinetics or w0, a start below the pull-off, or a drive more than 1e12 times v_star
/// (rate_ratio); NumericalError if the integrator fails or the contact is not lost within
/// options.max_steps.
KineticRetract kinetic_retract(const ContactModelPtr& model, double w0, const CrackKinetics& kinetics,
                               const KineticRetractOptions& options);

/// A summary's rate-dependent pull-off (answer.hpp): the retract at one drive and how its lowest
/// force moves with the rate.
struct KineticSummary {
  RetractDrive drive;
  double start_force = 0.0;          ///< [N], the equilibrium contact the retract starts from
  CriticalPoint pull_off;            ///< the lowest force at drive.rate
  double pull_off_time = 0.0, separation_time = 0.0;  ///< [s] from the start
  CriticalPoint equilibrium_pull_off, equilibrium_separation;  ///< v_star -> infinity (JKR)
  /// The lowest force [N] at drive.rate times 0.01, 0.1, 1, 10 and 100 [N/s or m/s].
  std::vector<double> rates, pull_off_forces;
  double rate_ratio = 0.0;      ///< KineticRetract::rate_ratio at drive.rate
  bool at_equilibrium = false;  ///< KineticRetract::at_equilibrium at drive.rate
  /// "kinetic", or why the answer is the equilibrium one (reports print it).
  std::string regime() const;
};

/// The lowest retract force at several rates: one kinetic_retract each (the sweep a summary
/// reports), with options.drive's control; rates [N/s or m/s], each > 0. NaN for a rate beyond
/// the crack's reach (more than 1e12 times v_star), which kinetic_retract refuses.
std::vector<double> kinetic_pull_off_forces(const ContactModelPtr& model, double w0, const CrackKinetics& kinetics,
                                            const KineticRetractOptions& options, const std::vector<double>& rates);

}  // namespace layerjkr
