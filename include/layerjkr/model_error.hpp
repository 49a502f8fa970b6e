// layerjkr: the error of a model's answer, estimated a posteriori against the model it
// approximates - every curve point and every summary carries one.
//
// A thin-layer law (winkler, two_term, edge_corrected, full_foundation, incompressible,
// uniform) approximates the exact elastic layer; the asymptotic Pasternak or
// Filonenko-Borodich model approximates the full one. The estimator evaluates that
// reference at the radii that matter and reports the relative difference, plus both
// models' own numerical error (ContactModel::numerical_error: the exact layer's
// two-resolution estimate, 1e-12 for closed forms). A model that solves its medium exactly
// (Winkler, the half-space, the full foundation, the exact layer) has no reference, and its
// estimate is its numerical error alone.
//
// Because the exact layer is fast (docs/exact-layer.md), the check is made on the scene
// itself, for any profile, rather than read from a table measured for one profile. Cost: a
// summary's estimate is one summary of the reference (an exact-layer summary: 10-100 ms); a
// curve's is the reference at no more than 24 radii. Beyond the reference's largest radius
// (exact layer: 1000 h) the error is extrapolated from there as O(h/a), which every
// thin-layer law satisfies or beats; that costs exact solves at 1000 h (~2 s for a summary
// whose points lie beyond 500 h, measured on a paraboloid at a/h ~ 1800).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "layerjkr/contact.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr {

/// Estimated relative errors of a summary's two headline quantities.
struct SummaryError {
  double pull_off_force = 0.0;    ///< |P* - P*_ref| / |P*_ref| (0 without adhesion)
  double zero_load_radius = 0.0;  ///< |a0 - a0_ref| / a0_ref (0 without adhesion)
  std::string reference;          ///< the reference model's name, or "none"
  double worst() const { return pull_off_force > zero_load_radius ? pull_off_force : zero_load_radius; }
};

class ModelErrorEstimator {
 public:
  /// `reference`: the model `model` approximates, for the same profile (null: `model` is
  /// exact for its medium). w [J/m^2] >= 0, the work of adhesion of the answers judged.
  ModelErrorEstimator(ContactModelPtr model, ContactModelPtr reference, double w);

  /// Relative error of the adhesive state at contact radius a [m]: the larger for force and
  /// approach of |x - x_ref| / (|x_H,ref| + |x_ref - x_H,ref|), i.e. relative to the size of
  /// the non-adhesive and the adhesive term (finite where P or delta crosses zero), plus
  /// both models' numerical error.
  double at(double a) const;

  /// at() for every radius: the reference is evaluated at the radii themselves when there
  /// are at most 24, else at 24 log-spaced anchors spanning them, each radius taking the
  /// larger estimate of its two bracketing anchors.
  std::vector<double> along(const std::vector<double>& radii) const;

  /// Errors of `summary` (the summary of `model` with this w) against the reference's own
  /// pull-off and zero-load point. Where the reference cannot reach them (beyond its largest
  /// radius) or finds none, the state estimate at() at the model's radius stands in; where the
  /// model misses a point the reference has, the error is +infinity.
  SummaryError summary(const ContactSummary& summary) const;

  /// The same judge for another model of the scene (same profile, medium and w): shares the
  /// reference's critical points, which are searched for once, on first use.
  ModelErrorEstimator for_model(ContactModelPtr model) const;

  const std::string& reference_name() const { return reference_name_; }

 private:
  struct ReferencePoints;
  double numerical(double a) const;
  const ReferencePoints& reference_points() const;

  ContactModelPtr model_, reference_;
  double w_;
  std::string reference_name_;
  std::shared_ptr<ReferencePoints> points_;  // shared by for_model() copies
};

/// The reference a model of a thin layer is judged by: the exact layer for the same profile
/// (default options). Cheap to build; the exact layer builds its kernel once per (nu, base).
ContactModelPtr layer_reference(ProfilePtr profile, const ElasticLayer& layer);

}  // namespace layerjkr
