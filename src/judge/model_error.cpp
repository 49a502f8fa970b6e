// A posteriori model error against the reference model (model_error.hpp).
#include "layerjkr/model_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/profile.hpp"
#include "judge/reference_profile.hpp"

namespace layerjkr {
namespace {

constexpr std::size_t kMaxAnchors = 24;

double scaled_difference(double x, double x_ref, double x_hertz_ref) {
  const double scale = std::abs(x_hertz_ref) + std::abs(x_ref - x_hertz_ref);
  return scale > 0.0 ? std::abs(x - x_ref) / scale : std::abs(x - x_ref);
}

double relative(double x, double x_ref) {
  return x_ref != 0.0 ? std::abs(x - x_ref) / std::abs(x_ref) : std::abs(x - x_ref);
}

}  // namespace

struct ModelErrorEstimator::ReferencePoints {
  std::once_flag once;
  std::optional<CriticalPoint> pull_off;
  std::optional<double> zero_load_radius;
};

ModelErrorEstimator::ModelErrorEstimator(ContactModelPtr model, ContactModelPtr reference, double w)
    : model_(std::move(model)), reference_(std::move(reference)), w_(w),
      reference_name_(reference_ ? reference_->name() : "none"), points_(std::make_shared<ReferencePoints>()) {
  if (!model_) throw DomainError("ModelErrorEstimator", "model (null)", 0.0, "a contact model");
  detail::require_non_negative("ModelErrorEstimator", "w", w);
}

ModelErrorEstimator ModelErrorEstimator::for_model(ContactModelPtr model) const {
  ModelErrorEstimator copy = *this;
  if (!model) throw DomainError("ModelErrorEstimator::for_model", "model (null)", 0.0, "a contact model");
  copy.model_ = std::move(model);
  return copy;
}

const ModelErrorEstimator::ReferencePoints& ModelErrorEstimator::reference_points() const {
  std::call_once(points_->once, [&] {
    // A reference that cannot find its points (a search leaving its range) has none: the
    // summary then falls back to the state estimate at the model's own points.
    try {
      const JkrSolution reference(reference_, w_);
      points_->pull_off = reference.pull_off();
      points_->zero_load_radius = reference.zero_load_radius();
    } catch (const Error&) {
      points_->pull_off.reset();
      points_->zero_load_radius.reset();
    }
  });
  return *points_;
}

double ModelErrorEstimator::numerical(double a) const {
  return model_->numerical_error(a) + (reference_ ? reference_->numerical_error(a) : 0.0);
}

double ModelErrorEstimator::at(double a) const {
  if (!reference_) return model_->numerical_error(a);
  const double limit = reference_->max_radius();
  const double judged = std::min(a, limit);  // beyond it: O(h/a) from the edge of the range
  const AdhesiveState m = jkr_transform(model_->state(judged), w_);
  const AdhesiveState r = jkr_transform(reference_->state(judged), w_);
  const double difference = std::max(scaled_difference(m.P, r.P, r.hertz.P_H),
                                     scaled_difference(m.delta, r.delta, r.hertz.delta_H));
  return difference * (judged / a) + numerical(judged);
}

std::vector<double> ModelErrorEstimator::along(const std::vector<double>& radii) const {
  std::vector<double> out(radii.size());
  if (radii.empty()) return out;
  if (radii.size() <= kMaxAnchors) {
    for (std::size_t i = 0; i < radii.size(); ++i) out[i] = at(radii[i]);
    return out;
  }
  const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
  std::vector<double> anchors(kMaxAnchors), errors(kMaxAnchors);
  for (std::size_t k = 0; k < kMaxAnchors; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(kMaxAnchors - 1);
    anchors[k] = k + 1 == kMaxAnchors ? *hi : *lo * std::pow(*hi / *lo, t);
    errors[k] = at(anchors[k]);
  }
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const auto above = std::lower_bound(anchors.begin(), anchors.end(), radii[i]);
    const std::size_t j = static_cast<std::size_t>(above - anchors.begin());
    out[i] = j == 0 ? errors[0] : std::max(errors[j - 1], errors[std::min(j, kMaxAnchors - 1)]);
  }
  return out;
}

SummaryError ModelErrorEstimator::summary(const ContactSummary& s) const {
  SummaryError e;
  e.reference = reference_name_;
  if (!reference_) {
    if (s.pull_off) e.pull_off_force = model_->numerical_error(s.pull_off->a);
    if (s.zero_load_radius && *s.zero_load_radius > 0.0) e.zero_load_radius = model_->numerical_error(*s.zero_load_radius);
    return e;
  }
  // The reference's critical points are trusted only well inside its range; a model whose
  // own points lie beyond it is judged state by state (at() extrapolates as O(h/a)).
  const double trusted = 0.5 * reference_->max_radius();
  const bool reachable = (!s.pull_off || s.pull_off->a < trusted) &&
                         (!s.zero_load_radius || *s.zero_load_radius < trusted);
  const ReferencePoints* r = reachable ? &reference_points() : nullptr;
  if (s.pull_off) {
    const bool found = r && r->pull_off && r->pull_off->a < trusted;
    e.pull_off_force = found ? relative(s.pull_off->P, r->pull_off->P) + numerical(r->pull_off->a) : at(s.pull_off->a);
  }
  if (s.zero_load_radius && *s.zero_load_radius > 0.0) {
    const double a0 = *s.zero_load_radius;
    const bool found = r && r->zero_load_radius && *r->zero_load_radius > 0.0 && *r->zero_load_radius < trusted;
    e.zero_load_radius = found ? relative(a0, *r->zero_load_radius) + numerical(*r->zero_load_radius) : at(a0);
  }
  // A point the reference has and the model misses (an edge-shifted law cannot reach
  // a << h, where a small pull-off lies) is an unbounded error.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (r && !s.pull_off && r->pull_off) e.pull_off_force = kInf;
  if (r && !(s.zero_load_radius && *s.zero_load_radius > 0.0) && r->zero_load_radius && *r->zero_load_radius > 0.0)
    e.zero_load_radius = kInf;
  return e;
}

namespace detail {

// The exact layer integrates the profile between its knots at every grid node, so a
// measured table's knots set the reference's cost: 10 000 points took minutes. The
// reference sees the table resampled at this many equal steps (a C2 spline through a
// smooth tip: its values differ from the full table's far below the model errors judged).
namespace {
constexpr int kReferenceKnots = 64;
}  // namespace

ProfilePtr reference_profile(ProfilePtr profile) {
  const double r_max = profile->max_radius();
  if (!std::isfinite(r_max) || profile->breakpoints(r_max).size() <= static_cast<std::size_t>(kReferenceKnots))
    return profile;
  std::vector<double> r(kReferenceKnots + 1), z(kReferenceKnots + 1);
  for (int i = 0; i <= kReferenceKnots; ++i) {
    r[i] = i == kReferenceKnots ? r_max : r_max * i / kReferenceKnots;
    z[i] = profile->f(r[i]);
  }
  try {
    return make_table_profile(std::move(r), std::move(z));
  } catch (const DomainError&) {  // a resampling the spline refuses: the full table, slowly
    return profile;
  }
}

}  // namespace detail

ContactModelPtr layer_reference(ProfilePtr profile, const ElasticLayer& layer) {
  return make_exact_layer(detail::reference_profile(std::move(profile)), layer);
}

}  // namespace layerjkr
