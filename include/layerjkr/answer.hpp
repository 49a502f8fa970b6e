// layerjkr: what a scene answers - its adhesive curve or its summary - computed by the
// library with the estimated error of every number and the warnings it deserves. The CLI and
// the Python module only print these.
//
//   layerjkr::Scene scene = layerjkr::load_scene("sphere_pdms_film_two_term.json");
//   layerjkr::SummaryAnswer s = layerjkr::solve_summary(scene);
//   if (s.contact.pull_off) std::cout << s.contact.pull_off->P << " N +- "
//                                     << 100 * s.error.pull_off_force << " %\n";
//   for (const auto& w : s.warnings) std::cerr << w << "\n";  // "model 'two_term' is estimated 10 % off ..."
//   layerjkr::CurveAnswer c = layerjkr::solve_curve(scene, {2e-4, 4e-4});
//   // c.states[i] (AdhesiveState), c.error_estimate[i] (relative), c.warnings
//
// Cost: one model evaluation per radius or one critical-point search, plus the judge - the
// reference model (for thin-layer laws the exact layer) at up to 24 radii for a curve, or one
// summary of the reference (10-100 ms) for a summary (model_error.hpp). `seconds` says what
// an answer took. Thread-safe: answers share nothing but the library's caches (context.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/adhesion_check.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/kinetics.hpp"
#include "layerjkr/model_error.hpp"
#include "layerjkr/scene.hpp"

namespace layerjkr {

struct AnswerOptions {
  /// An answer whose estimated relative model error exceeds this carries a warning; in (0, 1).
  double warning_threshold = 0.05;
  /// A summary of a scene whose adhesion has kinetics (adhesion.hpp): the retract whose
  /// rate-dependent pull-off it reports (SummaryAnswer::kinetic), from equilibrium at
  /// retract_start_force [N] (default zero load). Without it such a summary reports the
  /// equilibrium (slow-retract) values and a notice says so; with it a scene without kinetics is
  /// an InputError (the rate would change nothing).
  std::optional<RetractDrive> retract;
  double retract_start_force = 0.0;
  /// Throws DomainError naming the first invalid field.
  void validate() const;
};

/// A scene's summary: the critical points, their estimated errors and the medium's constants.
struct SummaryAnswer {
  ContactSummary contact;  ///< model name, w, zero-load radius, pull-off, fixed-grips point
  SummaryError error;      ///< relative errors of the pull-off force and the zero-load radius
  std::string profile;     ///< the indenter, described (Profile::describe)
  std::optional<double> K;       ///< foundation modulus [N/m^3] (ResolvedModel::K)
  std::optional<double> G;       ///< [N/m]: shear modulus, or tension T where g_is_tension
  bool g_is_tension = false;     ///< Filonenko-Borodich: reports name G "T"
  std::optional<double> E_star;  ///< plane-strain modulus [Pa]: layers and the half-space
  std::optional<AutoChoice> choice;   ///< model "auto": what it chose
  /// Whether the scene's adhesion model applies (adhesion_check.hpp); none for w = 0 or
  /// without a JKR pull-off.
  std::optional<AdhesionCheck> adhesion;
  /// With kinetics and AnswerOptions::retract: the rate-dependent pull-off (kinetics.hpp). The
  /// critical points in `contact` are the equilibrium ones, the slow-retract limit.
  std::optional<KineticSummary> kinetic;
  std::vector<std::string> warnings;  ///< validity of constants, model and adhesion error above threshold
  std::vector<std::string> notices;   ///< recorded, not warned about (ResolvedModel::notices)
  double seconds = 0.0;               ///< wall time of the answer [s]
};

/// A scene's adhesive curve at given contact radii.
struct CurveAnswer {
  std::vector<AdhesiveState> states;   ///< one per radius, in the order given
  std::vector<double> error_estimate;  ///< estimated relative model error at each radius
  std::string model;                   ///< the model that answered (ContactModel::name)
  std::string reference;               ///< what it was judged against, or "none"
  std::optional<AutoChoice> choice;    ///< model "auto": what it chose
  std::optional<AdhesionCheck> adhesion;  ///< as SummaryAnswer::adhesion
  std::vector<std::string> warnings;   ///< validity of constants, model and adhesion error above threshold
  std::vector<std::string> notices;    ///< recorded, not warned about (ResolvedModel::notices)
  double seconds = 0.0;                ///< wall time of the answer [s]
};

/// The summary of `scene`. Throws InputError for an invalid scene, DomainError for invalid
/// options, NumericalError where a search fails.
SummaryAnswer solve_summary(const Scene& scene, const AnswerOptions& options = {});

/// The curve of `scene` at `radii` [m] (each finite and > 0, at least one; InputError names
/// the first invalid one).
CurveAnswer solve_curve(const Scene& scene, const std::vector<double>& radii, const AnswerOptions& options = {});

}  // namespace layerjkr
