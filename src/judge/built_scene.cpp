// A scene's model built with its judge (built_scene.hpp).
#include "layerjkr/built_scene.hpp"

#include <cmath>
#include <functional>

#include "judge/reference_profile.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/model_choice.hpp"

namespace layerjkr {
namespace {

using Choose = std::function<ModelChoice(const ModelSpec&)>;  // the resolved exact spec

// Runs a library factory; its DomainError becomes an InputError naming the scene's medium.
template <class F>
auto checked(F make) {
  try {
    return make();
  } catch (const DomainError& e) {
    throw InputError(std::string("scene: medium: ") + e.what());
  }
}

BuiltScene build(const Scene& s, const Choose& choose, bool with_reference) {
  BuiltScene b;
  b.resolved = checked([&] { return resolve_model(s); });
  if (b.resolved.automatic) {
    const ModelChoice choice = checked([&] { return choose(b.resolved.spec); });
    b.model = choice.contact_model;
    b.reference = choice.reference;
    b.choice = AutoChoice{choice.model, choice.estimated_error, s.tolerance, ""};
    return b;
  }
  b.model = checked([&] { return make_contact_model(s.profile, b.resolved.spec); });
  if (with_reference && b.resolved.reference)
    b.reference = checked([&] { return make_contact_model(detail::reference_profile(s.profile), *b.resolved.reference); });
  return b;
}

}  // namespace

std::string AutoChoice::brief_report() const {
  return "auto chose model '" + std::string(to_string(model)) + "' (estimated error " + format_double(estimated_error) +
         " " + judged_at + ")";
}

BuiltScene build_scene(const Scene& s, double a_min, bool with_reference) {
  if (s.model != SceneModel::automatic) return build(s, nullptr, with_reference);
  if (!(a_min > 0.0) || !std::isfinite(a_min))
    throw DomainError("build_scene", "a_min (smallest contact radius of interest)", a_min,
                      "finite and > 0 for model auto");
  std::vector<double> radii;
  for (int k = 0; k <= 4; ++k) radii.push_back(a_min * std::ldexp(1.0, k));
  return build_scene_for_radii(s, radii);
}

BuiltScene build_scene_for_radii(const Scene& s, const std::vector<double>& radii) {
  BuiltScene b = build(
      s,
      [&](const ModelSpec& spec) {
        return spec.stack ? choose_stack_model(s.profile, *spec.stack, s.w, s.tolerance, radii)
                          : choose_layer_model(s.profile, spec.layer, s.w, s.tolerance, radii);
      },
      true);
  if (b.choice) b.choice->judged_at = "over the curve's radii";
  return b;
}

BuiltScene build_scene_for_summary(const Scene& s) {
  BuiltScene b = build(
      s,
      [&](const ModelSpec& spec) {
        return spec.stack ? choose_stack_model_for_summary(s.profile, *spec.stack, s.w, s.tolerance)
                          : choose_layer_model_for_summary(s.profile, spec.layer, s.w, s.tolerance);
      },
      true);
  if (b.choice) b.choice->judged_at = "at the pull-off and zero-load point";
  return b;
}

ModelErrorEstimator error_estimator(const Scene& s, const BuiltScene& b) {
  return ModelErrorEstimator(b.model, b.reference, s.w);
}

}  // namespace layerjkr
