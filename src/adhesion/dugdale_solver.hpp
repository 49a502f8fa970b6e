// Internal: Maugis-Dugdale and DMT adhesion (a Dugdale law: tension sigma0 up to a separation
// h0 = w / sigma0) for any profile on the half-space, the exact layer or a stack
// (docs/theory.md s.4b).
//
// Copson's representation on [0, c] (c: the adhesive zone's outer radius, a: the contact
// radius). With p = -sigma0 on [a, c], g = g_D = -(2 sigma0/pi) sqrt(c^2 - t^2) there exactly;
// on [0, a] the exact layer's Fredholm equation gains a third right-hand side, the kernel's
// action on g_D, and g = (E*/pi)(delta phi0 - phi_f) + phi_D. A bounded stress at a (g
// continuous at a) fixes delta; the gap
//   gap(r) = (2/E*) int_a^r [G(t) - (E*/pi) D(t)] / sqrt(r^2 - t^2) dt
// (G: the cosine transform of the surface pressure times L) closing to h0 at c fixes c,
// found by a bracketed toms748 search. DMT: the non-adhesive state at a, with sigma0 acting
// without deforming the surfaces where its gap is below h0.
//
// Numerics: the exact layer's Nystrom grid on [0, a] (one Cholesky factor per radius, reused
// for every trial c); integrals over [a, c] in t = c cos(theta), which makes the square root
// of g_D at c and of the Abel kernel smooth, by composite Gauss-Legendre panels in theta no
// longer than the inner panels. Lengths inside are in units of h (the top layer's
// thickness), pressures in units of E*; the half-space has no kernel and no linear system.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "layerjkr/exact_layer.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/profile.hpp"

namespace layerjkr::detail {

class DugdaleTable;
class ExactPowerLawTable;
struct ExactMoments;

/// A state with the two-grid error estimate: |fine - coarse| of the same state computed with
/// p and 3p/4 nodes a panel (inner grid and [a, c] quadrature alike). Absolute, since P
/// crosses zero: [N], [m], [m].
struct DugdaleEstimate {
  AdhesiveState state;
  double P_error = 0.0;
  double delta_error = 0.0;
  double c_error = 0.0;
};

/// The parts of a Dugdale state at contact radius a and zone radius c, linear in the tension
/// sigma0 and in the profile (docs/theory.md s.4b): with s0 = sigma0/E*,
///   delta = delta_H + s0 D,   P = P_H + sigma0 P,   gap(c) = s0 G + F.
/// They depend on (a/h, c/h), the medium and the profile only: Maugis-Dugdale is gap(c) = w/sigma0,
/// DMT is F = w/sigma0 with delta = delta_H (DugdaleTable tabulates them).
struct DugdaleParts {
  double delta_H = 0.0;  ///< the non-adhesive approach endf/end0 [m]
  double int0 = 0.0;     ///< int_0^a phi0 dt/h (the flat punch's; S = 2 E* h int0)
  double intf = 0.0;     ///< int_0^a phi_f dt/h [m]
  double D = 0.0;        ///< delta's tension part per unit s0 [m]
  double P = 0.0;        ///< P's tension part per unit sigma0 [m^2]
  double G = 0.0;        ///< the gap at c per unit s0 [m]
  double F = 0.0;        ///< the non-adhesive state's gap at c [m]
};

class DugdaleSolver {
 public:
  /// The exact layer or stack of `kernel` (E* and h of its top layer; its options set the
  /// grid: points_per_panel, panel_width, min_panels, max_a_over_h, which also bounds c/h).
  /// Always dense Cholesky, whatever dense_max_unknowns says. With `tabulate` (the library's
  /// make_dugdale_solver; the tests of the direct solve leave it off) and the
  /// options' tabulate_power_laws) a power-law profile's states come from the per-(medium, d)
  /// DugdaleTable wherever the zone's c/h is within its range (microseconds a state; its
  /// measured error in every estimate), the rest from direct solves.
  DugdaleSolver(ProfilePtr profile, std::shared_ptr<const ExactLayerKernel> kernel, bool tabulate = false);
  /// The half-space of plane-strain modulus E_star [Pa] (> 0): Sneddon's closed forms on
  /// [0, a], quadrature only for the gap.
  DugdaleSolver(ProfilePtr profile, double E_star);

  /// Maugis-Dugdale state at contact radius a [m] (>= 0; 0 is the adhesive disc alone, the
  /// surfaces touching at r = 0) for work of adhesion w [J/m^2] (>= 0) and cohesive stress
  /// sigma0 [Pa] (> 0). hertz carries a and NaN otherwise; w = 0 gives the non-adhesive
  /// state (c = a, hertz filled), as dmt() does. Throws DomainError for bad
  /// inputs and when the zone would pass the profile's max_radius or max_a_over_h.
  AdhesiveState maugis_dugdale(double a, double w, double sigma0) const;
  DugdaleEstimate maugis_dugdale_estimate(double a, double w, double sigma0) const;

  /// DMT with the Dugdale law at a [m] (>= 0): P = P_H - sigma0 pi (c^2 - a^2),
  /// delta = delta_H, where the non-adhesive gap reaches h0 at c. hertz = the
  /// non-adhesive state (S, S' included).
  AdhesiveState dmt(double a, double w, double sigma0) const;
  DugdaleEstimate dmt_estimate(double a, double w, double sigma0) const;

  /// The linear parts of the states with contact radius a [m] (>= 0) and zone radius c > a
  /// [m], solved with `nodes` Gauss-Legendre nodes a panel (options' points_per_panel: the
  /// states' own).
  DugdaleParts parts(double a, double c, int nodes) const;

  /// Gap [m] between indenter and surface at r >= a [m] in the non-adhesive state at a.
  double non_adhesive_gap(double a, double r) const;

  /// Gap [m] at radii r >= a [m] in the Maugis-Dugdale state (a, w, sigma0): 0 at a, h0 at c.
  std::vector<double> maugis_dugdale_gap(double a, double w, double sigma0,
                                         const std::vector<double>& radii) const;

  /// Contact pressure [Pa] (positive = compressive) at radii r >= 0 [m] in the
  /// Maugis-Dugdale state: -sigma0 on [a, c), 0 beyond; on [0, a) Copson's
  /// -int_r^a g'(t)/sqrt(t^2 - r^2) dt with g' from the Nystrom interpolant, plus g_D's part
  /// in closed form, -(sigma0/pi) acos((2a^2 - c^2 - r^2)/(c^2 - r^2)). Continuous at a.
  std::vector<double> maugis_dugdale_pressure(double a, double w, double sigma0,
                                              const std::vector<double>& radii) const;

  double effective_modulus() const { return E_star_; }
  /// True when power-law states come from a DugdaleTable.
  bool tabulated() const { return table_ != nullptr; }
  /// The table's largest measured error so far, relative to each part's half-space size (0 if
  /// untabulated or nothing built yet).
  double table_error() const;
  /// True for the half-space (microseconds a state), false for a layer or a stack (milliseconds).
  bool on_half_space() const { return kernel_ == nullptr; }

 private:
  struct Inner;
  struct Zone;
  Inner inner(double a, int nodes) const;
  Zone zone(const Inner& in, double c, double sigma0) const;
  double gap_at(const Inner& in, const Zone* zp, double r) const;  // zp null: non-adhesive
  AdhesiveState solve_md(double a, double w, double sigma0, int nodes) const;
  AdhesiveState solve_dmt(double a, double w, double sigma0, int nodes) const;
  double find_c(double a, double h0, const char* function, double sigma0,
                const std::function<double(double)>& gap) const;
  void check(const char* function, double a, double w, double sigma0) const;
  // The table's path: false when the zone passes the table's range (then a direct solve).
  struct TableState;
  bool from_table(double a, double w, double sigma0, bool md, TableState& out) const;
  ExactMoments moments(double a) const;  // the non-adhesive moments (power-law table or a solve)

  ProfilePtr profile_;
  std::shared_ptr<const ExactLayerKernel> kernel_;  // null: the half-space
  double E_star_ = 0.0;
  double h_ = 1.0;  // length unit [m]: the top layer's h, 1 for the half-space
  ExactLayerOptions options_;
  std::shared_ptr<const DugdaleTable> table_;               // null: every state solved
  std::shared_ptr<const ExactPowerLawTable> moments_table_;  // the non-adhesive moments of r^d
  PowerLawForm form_;
};

/// The solver of `model`'s medium as `spec` describes it: the half-space (E*), or the exact layer
/// or stack (its kernel). Throws InputError beginning with `what` for any other model kind (the
/// thin-layer and foundation laws give no gap outside the contact) or a model without a profile.
std::shared_ptr<const DugdaleSolver> make_dugdale_solver(const ContactModel& model, const ModelSpec& spec,
                                                         const char* what);

}  // namespace layerjkr::detail
