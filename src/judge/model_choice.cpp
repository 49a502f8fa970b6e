// Model choice by a posteriori error against the exact layer (model_choice.hpp).
#include "layerjkr/model_choice.hpp"

#include <algorithm>
#include <functional>

#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/model_error.hpp"

namespace layerjkr {
namespace {

void require_tolerance(const char* fn, double tolerance) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw DomainError(fn, "tolerance", tolerance, "(0, 1)");
}

// The first candidate whose error (from `judge`) is within tolerance, else the exact layer.
ModelChoice first_within(const ProfilePtr& profile, const ElasticLayer& layer, double tolerance,
                         const ContactModelPtr& exact,
                         const std::function<double(const ContactModelPtr&)>& judge) {
  ModelChoice choice;
  for (ModelKind kind : layer_model_candidates(layer)) {
    ContactModelPtr candidate;
    try {
      candidate = make_contact_model(profile, layer_model_spec(kind, layer));
    } catch (const DomainError&) {
      continue;  // e.g. edge_corrected where a + beta h < 0 for the radii asked
    }
    double error = 0.0;
    try {
      error = judge(candidate);
    } catch (const DomainError&) {
      continue;  // the candidate cannot reach a radius asked for
    }
    if (error <= tolerance) {
      choice.model = kind;
      choice.estimated_error = error;
      choice.contact_model = std::move(candidate);
      choice.reference = exact;
      return choice;
    }
  }
  choice.model = ModelKind::exact;
  choice.contact_model = exact;
  choice.estimated_error = judge(exact);
  return choice;
}

}  // namespace

std::vector<ModelKind> layer_model_candidates(const ElasticLayer& layer) {
  (void)effective_modulus(layer.E, layer.nu);  // validates E and nu
  detail::require_positive("layer_model_candidates", "h", layer.h);
  std::vector<ModelKind> out;
  const bool bonded = layer.base == Base::bonded;
  if (layer.nu < 0.5) {
    const ThinLayerConstants c = thin_layer_constants(layer);
    out.push_back(ModelKind::winkler);
    if (c.G != 0.0) out.push_back(ModelKind::two_term);
    out.push_back(ModelKind::edge_corrected);
    if (c.G > 0.0) out.push_back(ModelKind::full_foundation);
  } else if (bonded) {
    out.push_back(ModelKind::incompressible);
  }
  if (bonded) out.push_back(ModelKind::uniform);
  return out;
}

ModelSpec layer_model_spec(ModelKind kind, const ElasticLayer& layer) {
  ModelSpec spec;
  spec.kind = kind;
  spec.layer = layer;
  if (kind == ModelKind::winkler || kind == ModelKind::two_term || kind == ModelKind::full_foundation) {
    const ThinLayerConstants c = thin_layer_constants(layer);
    spec.K = c.K;
    spec.G = kind == ModelKind::winkler ? 0.0 : c.G;
  }
  return spec;
}

ModelChoice choose_layer_model(const ProfilePtr& profile, const ElasticLayer& layer, double w, double tolerance,
                               const std::vector<double>& radii) {
  const char* fn = "choose_layer_model";
  require_tolerance(fn, tolerance);
  detail::require_non_negative(fn, "w", w);
  if (radii.empty()) throw DomainError(fn, "radii (empty)", 0.0, "at least one contact radius");
  for (double a : radii) detail::require_positive(fn, "contact radius", a);
  const ContactModelPtr exact = layer_reference(profile, layer);
  return first_within(profile, layer, tolerance, exact, [&](const ContactModelPtr& m) {
    const ModelErrorEstimator estimator(m, m == exact ? nullptr : exact, w);
    const std::vector<double> e = estimator.along(radii);
    return *std::max_element(e.begin(), e.end());
  });
}

ModelChoice choose_layer_model_for_summary(const ProfilePtr& profile, const ElasticLayer& layer, double w,
                                           double tolerance) {
  const char* fn = "choose_layer_model_for_summary";
  require_tolerance(fn, tolerance);
  detail::require_non_negative(fn, "w", w);
  const ContactModelPtr exact = layer_reference(profile, layer);
  const ModelErrorEstimator judge(exact, exact, w);  // one search for the exact critical points
  return first_within(profile, layer, tolerance, exact, [&](const ContactModelPtr& m) {
    const ModelErrorEstimator estimator = m == exact ? ModelErrorEstimator(exact, nullptr, w) : judge.for_model(m);
    return estimator.summary(summarize(JkrSolution(m, w))).worst();
  });
}

}  // namespace layerjkr
