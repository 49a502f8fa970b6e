// layerjkr: the check on every adhesive answer - does its adhesion model apply?
//
// JKR assumes adhesion acts at the contact edge only, DMT that it acts outside the contact
// without deforming it; Maugis-Dugdale (maugis_dugdale.hpp) spans both, and its parameter
// lambda says where a contact sits: lambda >> 1 is JKR, lambda << 1 DMT. The check reports
// lambda and the estimated error of the answer's pull-off force against Maugis-Dugdale; the
// answers (answer.hpp) warn above AnswerOptions::warning_threshold, the same contract as the
// model error estimate (model_error.hpp).
//
// lambda of any contact, from its own compliance: at the JKR pull-off radius a_c the adhesive
// part of the approach is delta_a = sqrt(4 pi w a_c / S'(a_c)) (jkr.hpp), the opening JKR's
// neck must reach, and h0 = w / sigma0 is the Dugdale zone's range; lambda is their ratio,
//     lambda = kappa delta_a / h0,   kappa = 2 (9/(16 pi))^(1/3) / sqrt(2 pi (9 pi/8)^(1/3)) = 0.36432,
// normalised so that a paraboloid on a half-space gives Maugis' lambda exactly (docs/models.md).
#pragma once

#include <string>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/contact.hpp"

namespace layerjkr {

/// Whether an answer's adhesion model applies (see the header comment).
struct AdhesionCheck {
  AdhesionModel model = AdhesionModel::jkr;  ///< the answer's adhesion model
  double lambda = 0.0;           ///< Maugis' lambda of the contact (from its compliance)
  double sigma0 = 0.0;           ///< the Dugdale stress it was judged with [Pa]
  bool sigma0_assumed = false;   ///< sigma0 from AdhesionSpec::kAssumedSpacing (none was given)
  /// Estimated |P_model / P_MD - 1| of the load-controlled pull-off force against
  /// Maugis-Dugdale with the same w and sigma0; 0 for a Maugis-Dugdale answer.
  double pull_off_error = 0.0;
  /// How the error was found: "closed form" (a paraboloid on a half-space: Maugis 1992),
  /// "solved on the medium" (Maugis-Dugdale's pull-off by the Dugdale solver), or "half-space
  /// estimate" (Maugis' pull-off at the contact's lambda: exact on a half-space, an upper
  /// bound on the layers measured in docs/models.md, "Adhesion map").
  std::string basis;
  /// One line, e.g. "lambda = 0.856 (sigma0 = 1.71e+08 Pa, from z0 = 0.3 nm assumed; set
  /// adhesion.sigma0 or adhesion.z0), pull-off force estimated 7.59 % off Maugis-Dugdale
  /// (half-space estimate)".
  std::string brief_report() const;
};

/// lambda of a contact from its JKR pull-off state (the non-adhesive state at the JKR pull-off
/// radius: a, S'), w [J/m^2] > 0 and sigma0 [Pa] > 0. Equals maugis_lambda(R, E*, w, sigma0) for
/// a paraboloid R on a half-space to rounding.
double contact_lambda(const NonAdhesiveState& at_jkr_pull_off, double w, double sigma0);

/// The pull-off error above which check_adhesion solves Maugis-Dugdale on the medium instead
/// of trusting the half-space estimate: 1 %. Below it the estimate stands, because it is an
/// upper bound wherever it was measured on layers (docs/models.md, "Adhesion map").
inline constexpr double kAdhesionSolveAbove = 0.01;

/// The check of `answer`'s adhesion model on its contact, from the contact's JKR solution
/// `jkr` (its law must be JKR: lambda comes from its pull-off; `answer` may be `jkr` itself),
/// with the Dugdale stress of `adhesion` (AdhesionSpec::dugdale_stress).
///
/// The error: for a paraboloid on a half-space, Maugis' closed form. Otherwise the half-space
/// estimate at the contact's lambda, and where that exceeds kAdhesionSolveAbove and `medium`
/// is given (the spec `jkr`'s model was built from, when that model solves its medium
/// exactly: model_spec.hpp kinds half_space and exact), Maugis-Dugdale's pull-off solved on
/// the medium (a Dugdale solve per radius of a pull-off search: ~0.5 s on a layer,
/// docs/benchmarks.md). nullopt for w = 0 or without a JKR pull-off.
std::optional<AdhesionCheck> check_adhesion(const AdhesiveSolution& jkr, const AdhesiveSolution& answer,
                                            const AdhesionSpec& adhesion, const ModelSpec* medium = nullptr);

}  // namespace layerjkr
