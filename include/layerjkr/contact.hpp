// layerjkr: the adhesive contact solution of one scene - curves, critical points,
// and inverse lookups.
//
// Data flow: ContactModel (non-adhesive state at a) -> adhesive law (adhesion.hpp: JKR's
// transform, DMT, Maugis-Dugdale) -> AdhesiveSolution.
// Everything is computed on demand: a curve costs one model evaluation per radius;
// critical points cost a log-grid scan plus a bracketed refinement, once per solution (see
// JkrSolution).
//
// Accuracy (measured against the closed-form half-space and Winkler oracles in
// tests/test_contact.cpp): critical points are the roots of a 6th-order finite-difference
// derivative, so radii come to ~1e-12 relative and forces and approaches to ~1e-14;
// roots of P(a) = P* and delta(a) = delta* to ~1e-15 relative in a (TOMS 748).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr {

/// Search settings; the defaults suit every built-in model.
struct JkrOptions {
  /// Points of the log-spaced scan that brackets an extremum (>= 8).
  int scan_points = 48;
  /// Decades one scan window spans (> 0); windows step down up to max_windows times.
  double scan_decades = 6.0;
  int max_windows = 8;
  /// Maximum bracket-expansion steps (factor 2 each) when looking for a root (>= 10).
  int max_bracket_steps = 500;
  /// Throws DomainError naming the first invalid field.
  void validate() const;
};

/// A point of the adhesive curve where an instability occurs.
struct CriticalPoint {
  double a = 0.0;      ///< contact radius [m]
  double P = 0.0;      ///< force [N]
  double delta = 0.0;  ///< approach [m]
};

namespace detail {
struct JkrCriticalPoints;
}

/// The adhesive solution of one adhesive law (a model, its work of adhesion and how adhesion
/// acts; JkrSolution is its name for JKR). The critical points (zero-load
/// radius, pull-off, fixed-grips point) are searched once, on first use, and kept: later
/// calls of zero_load_radius(), pull_off(), fixed_grips_critical() and of the lookups that
/// start from them (contact_radius_at_force, contact_radius_at_delta, force_at_delta,
/// summarize) cost no search. A search that throws keeps nothing, and the next call
/// searches again. Copies share what was found, so copying stays cheap.
///
/// Thread safety: a JkrSolution (and its copies) may be used from several threads at once,
/// if its model's state() may (every model in this library); concurrent first requests for a
/// critical point run its search once, the others wait for it.
class AdhesiveSolution {
 public:
  /// JKR on `model`: w [J/m^2] >= 0. Throws DomainError for invalid w or options.
  AdhesiveSolution(ContactModelPtr model, double w, JkrOptions options = {});
  /// Any adhesive law (adhesion.hpp). Where the law has a state at a = 0 (DMT,
  /// Maugis-Dugdale), load-controlled pull-off may sit there.
  explicit AdhesiveSolution(AdhesiveLawPtr law, JkrOptions options = {});

  /// Adhesive state at contact radius a [m].
  AdhesiveState at(double a) const;
  std::vector<AdhesiveState> curve(const std::vector<double>& radii) const;

  /// Contact radius at P = 0 on the stable branch (for w = 0: 0). nullopt if the
  /// force stays negative over every admissible radius (e.g. a sphere too small).
  std::optional<double> zero_load_radius() const;

  /// Pull-off under load control: the minimum of P(a). nullopt for w = 0 or when
  /// P has no minimum at a > 0.
  std::optional<CriticalPoint> pull_off() const;

  /// Instability under fixed grips: the minimum of delta(a), where one exists
  /// (not for a Winkler foundation, whose delta(a) is monotone).
  std::optional<CriticalPoint> fixed_grips_critical() const;

  /// Contact radius at force P on the branch stable under load control (a beyond
  /// pull-off). Throws DomainError if P is below the pull-off force or above the
  /// largest force the profile admits.
  double contact_radius_at_force(double P) const;

  /// Contact radius at approach delta on the branch stable under fixed grips.
  double contact_radius_at_delta(double delta) const;

  /// Force at approach delta on the branch stable under fixed grips.
  double force_at_delta(double delta) const;

  double w() const { return w_; }
  const ContactModel& model() const { return *model_; }
  const AdhesiveLaw& law() const { return *law_; }

 private:
  double upper_radius() const;
  double seed_radius() const;
  std::optional<double> minimise(bool force, double a_hi) const;
  std::optional<double> first_root(bool force, double target, double a_lo) const;

  std::optional<double> search_zero_load_radius() const;
  std::optional<CriticalPoint> search_pull_off() const;
  std::optional<CriticalPoint> search_fixed_grips_critical() const;

  AdhesiveLawPtr law_;
  ContactModelPtr model_;  // law_->contact()
  double w_;
  JkrOptions options_;
  std::shared_ptr<detail::JkrCriticalPoints> critical_;  // found once, shared by copies
};

/// The name the JKR solution had before other adhesive laws: JkrSolution(model, w) is JKR.
using JkrSolution = AdhesiveSolution;

/// Summary of a scene's adhesive behaviour.
struct ContactSummary {
  std::string model;
  AdhesionModel adhesion = AdhesionModel::jkr;
  double w = 0.0;
  std::optional<double> zero_load_radius;
  std::optional<CriticalPoint> pull_off;
  std::optional<CriticalPoint> fixed_grips;
  /// One line per quantity, SI units.
  std::string brief_report() const;
};

ContactSummary summarize(const AdhesiveSolution& solution);

}  // namespace layerjkr
