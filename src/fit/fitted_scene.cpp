// fitted_scene (layerjkr/fit.hpp): a fit's values written into its scene's JSON, which is then
// parsed again - so the scene reader stays the one place that turns JSON into a Scene and
// checks it, and the fitted scene carries the JSON a user can save and reload.
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"

namespace layerjkr {

namespace {

using json = nlohmann::json;

[[noreturn]] void no_place(FitParameter q, const std::string& why) {
  throw InputError(std::string("fitted scene: ") + to_string(q) + " was fitted but " + why);
}

json& object_at(json& root, const char* key, FitParameter q) {
  if (!root.contains(key) || !root.at(key).is_object())
    no_place(q, std::string("the scene has no \"") + key + "\" object to hold it");
  return root.at(key);
}

// E of a stack is its top layer's; every modulus (and an elastic base's) scales with it.
void set_modulus(json& medium, double E) {
  if (medium.contains("layers")) {
    json& layers = medium.at("layers");
    const double ratio = E / layers.at(0).at("E").get<double>();
    for (json& layer : layers) layer["E"] = layer.at("E").get<double>() * ratio;
    if (medium.contains("base") && medium.at("base").is_object())
      medium["base"]["E"] = medium.at("base").at("E").get<double>() * ratio;
    return;
  }
  if (!medium.contains("E")) no_place(FitParameter::E, "the medium is given by its constants (no \"E\")");
  medium["E"] = E;
}

void set_value(json& root, FitParameter q, double value) {
  switch (q) {
    case FitParameter::delta0:
    case FitParameter::P0:
    case FitParameter::drag: return;  // the data's offsets and the lever's drag, not the scene's
    case FitParameter::w: root["w"] = value; return;
    case FitParameter::E: set_modulus(object_at(root, "medium", q), value); return;
    case FitParameter::K:
    case FitParameter::G: {
      json& medium = object_at(root, "medium", q);
      const char* key = q == FitParameter::K ? "K" : (medium.contains("T") ? "T" : "G");
      if (!medium.contains(key))
        no_place(q, std::string("the medium has no \"") + key + "\" (its constants follow from E, nu and h: free E instead)");
      medium[key] = value;
      return;
    }
    case FitParameter::R: {
      json& indenter = object_at(root, "indenter", q);
      if (!indenter.contains("R")) no_place(q, "the indenter has no radius R (a sphere or paraboloid has)");
      indenter["R"] = value;
      return;
    }
    case FitParameter::sigma0: {
      json& adhesion = object_at(root, "adhesion", q);
      adhesion.erase("z0");  // the fitted stress replaces the one z0 implied
      adhesion["sigma0"] = value;
      return;
    }
    case FitParameter::E_inf:
    case FitParameter::tau:
    case FitParameter::beta:
    case FitParameter::E_2:
    case FitParameter::tau_2: {
      json& law = object_at(object_at(root, "medium", q), "viscoelastic", q);
      const char* key = to_string(q);  // the scene's keys are the parameters' names
      if (!law.contains(key)) no_place(q, std::string("the relaxation law has no \"") + key + "\"");
      law[key] = value;
      return;
    }
    case FitParameter::v_star:
    case FitParameter::n: {
      json& kinetics = object_at(object_at(root, "adhesion", q), "kinetics", q);
      kinetics[q == FitParameter::v_star ? "v_star" : "n"] = value;
      return;
    }
  }
}

}  // namespace

Scene fitted_scene(const Scene& scene, const std::vector<ParameterEstimate>& parameters) {
  if (scene.origin.json.empty())
    throw InputError("fitted scene: the scene was built in code, not from JSON; set the fitted values on it directly");
  json root = json::parse(scene.origin.json);
  for (const ParameterEstimate& p : parameters) {
    if (p.curve >= 0) continue;  // a joint fit's per-curve delta0 and P0
    if (!std::isfinite(p.value))
      throw InputError(std::string("fitted scene: ") + to_string(p.parameter) + " = " + std::to_string(p.value) +
                       " is not finite; the fit did not give a value to put in the scene");
    set_value(root, p.parameter, p.value);
  }
  std::string source = "the fitted scene";
  if (!scene.origin.file.empty()) source += " of " + scene.origin.file;
  return parse_scene(root.dump(), source);
}

}  // namespace layerjkr
