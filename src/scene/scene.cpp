// Strict JSON scene reader: every key is known, every value checked and named.
#include "layerjkr/scene.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <set>

#include <boost/math/constants/constants.hpp>
#include <nlohmann/json.hpp>

#include "io/read_file.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model_choice.hpp"

namespace layerjkr {
namespace {

using json = nlohmann::json;

std::string show(const json& v) {
  std::string s = v.dump();
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(source_ + ": " + key + " " + what);
  }

  const json& object(const json& parent, const std::string& key, const std::string& path) const {
    if (!parent.contains(key)) fail(path, "is missing");
    const json& v = parent.at(key);
    if (!v.is_object()) fail(path, "must be a JSON object, got " + show(v));
    return v;
  }

  void only_keys(const json& obj, const std::string& path, const std::set<std::string>& allowed) const {
    for (const auto& item : obj.items())
      if (!allowed.count(item.key())) {
        std::string list;
        for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
        fail(path + "." + item.key(), "is not a known key here (known: " + list + ")");
      }
  }

  double number(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.contains(key)) fail(path + "." + key, "is missing");
    return as_number(obj.at(key), path + "." + key);
  }

  double as_number(const json& v, const std::string& path) const {
    if (!v.is_number()) fail(path, "must be a number, got " + show(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(path, "must be finite, got " + show(v));
    return d;
  }

  std::string string(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.contains(key)) fail(path + "." + key, "is missing");
    const json& v = obj.at(key);
    if (!v.is_string()) fail(path + "." + key, "must be a string, got " + show(v));
    return v.get<std::string>();
  }

  std::vector<double> numbers(const json& obj, const std::string& key,
                              const std::string& path) const {
    if (!obj.contains(key)) fail(path + "." + key, "is missing");
    const json& v = obj.at(key);
    if (!v.is_array()) fail(path + "." + key, "must be an array of numbers, got " + show(v));
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out.push_back(as_number(v[i], path + "." + key + "[" + std::to_string(i) + "]"));
    return out;
  }

  // Runs a library factory; its DomainError is re-thrown naming the scene key.
  template <class F>
  auto checked(const std::string& path, F make) const {
    try {
      return make();
    } catch (const DomainError& e) {
      throw InputError(source_ + ": " + path + ": " + e.what());
    }
  }

 private:
  std::string source_;
};

ProfilePtr read_indenter(const Reader& in, const json& root) {
  const json& ind = in.object(root, "indenter", "indenter");
  const std::string shape = in.string(ind, "shape", "indenter");
  if (shape == "paraboloid" || shape == "sphere") {
    in.only_keys(ind, "indenter", {"shape", "R"});
    const double R = in.number(ind, "R", "indenter");
    return in.checked("indenter.R", [&] {
      return shape == "sphere" ? make_sphere(R) : make_paraboloid(R);
    });
  }
  if (shape == "cone") {
    in.only_keys(ind, "indenter", {"shape", "semi_angle_deg"});
    const double deg = in.number(ind, "semi_angle_deg", "indenter");
    if (!(deg > 0.0 && deg < 90.0))
      in.fail("indenter.semi_angle_deg", "= " + format_double(deg) + " is invalid; valid range: (0, 90)");
    return make_cone(deg * boost::math::constants::degree<double>());
  }
  if (shape == "power_law") {
    in.only_keys(ind, "indenter", {"shape", "B", "d"});
    const double B = in.number(ind, "B", "indenter"), d = in.number(ind, "d", "indenter");
    return in.checked("indenter", [&] { return make_power_law(B, d); });
  }
  if (shape == "table") {
    in.only_keys(ind, "indenter", {"shape", "r", "z"});
    auto r = in.numbers(ind, "r", "indenter");
    auto z = in.numbers(ind, "z", "indenter");
    return in.checked("indenter", [&] { return make_table_profile(std::move(r), std::move(z)); });
  }
  in.fail("indenter.shape", "= \"" + shape +
                                "\" is unknown (known: paraboloid, sphere, cone, power_law, table)");
}

MediumSpec read_medium(const Reader& in, const json& root) {
  const json& med = in.object(root, "medium", "medium");
  const std::string type = in.string(med, "type", "medium");
  MediumSpec m;
  if (type == "winkler") {
    in.only_keys(med, "medium", {"type", "K"});
    m.type = MediumType::winkler;
    m.K = in.number(med, "K", "medium");
  } else if (type == "pasternak") {
    in.only_keys(med, "medium", {"type", "K", "G"});
    m.type = MediumType::pasternak;
    m.K = in.number(med, "K", "medium");
    m.G = in.number(med, "G", "medium");
  } else if (type == "filonenko_borodich") {
    in.only_keys(med, "medium", {"type", "K", "T"});
    m.type = MediumType::filonenko_borodich;
    m.K = in.number(med, "K", "medium");
    m.T = in.number(med, "T", "medium");
  } else if (type == "layer") {
    in.only_keys(med, "medium", {"type", "E", "nu", "h", "base"});
    m.type = MediumType::layer;
    m.E = in.number(med, "E", "medium");
    m.nu = in.number(med, "nu", "medium");
    m.h = in.number(med, "h", "medium");
    const std::string base = med.contains("base") ? in.string(med, "base", "medium") : "bonded";
    if (base == "bonded")
      m.base = Base::bonded;
    else if (base == "frictionless")
      m.base = Base::frictionless;
    else
      in.fail("medium.base", "= \"" + base + "\" is unknown (known: bonded, frictionless)");
  } else if (type == "half_space") {
    in.only_keys(med, "medium", {"type", "E", "nu"});
    m.type = MediumType::half_space;
    m.E = in.number(med, "E", "medium");
    m.nu = in.number(med, "nu", "medium");
  } else {
    in.fail("medium.type", "= \"" + type +
                               "\" is unknown (known: winkler, pasternak, filonenko_borodich, "
                               "layer, half_space)");
  }
  return m;
}

constexpr std::pair<SceneModel, const char*> kSceneModelNames[] = {
    {SceneModel::winkler, "winkler"},   {SceneModel::half_space, "half_space"},
    {SceneModel::leading, "leading"},   {SceneModel::two_term, "two_term"},
    {SceneModel::edge_corrected, "edge_corrected"}, {SceneModel::exact, "exact"},
    {SceneModel::automatic, "auto"},    {SceneModel::asymptotic, "asymptotic"},
    {SceneModel::full, "full"},         {SceneModel::incompressible, "incompressible"},
    {SceneModel::uniform, "uniform"}};

// The models a medium accepts, and its default (none: the scene must name one).
struct MediumModels {
  std::vector<SceneModel> allowed;
  bool has_default;  // then allowed.front() is the default
};

MediumModels models_for(MediumType t) {
  switch (t) {
    case MediumType::winkler: return {{SceneModel::winkler}, true};
    case MediumType::half_space: return {{SceneModel::half_space}, true};
    case MediumType::layer:
      return {{SceneModel::leading, SceneModel::two_term, SceneModel::edge_corrected,
               SceneModel::exact, SceneModel::incompressible, SceneModel::uniform, SceneModel::automatic},
              false};
    case MediumType::pasternak:
    case MediumType::filonenko_borodich: return {{SceneModel::asymptotic, SceneModel::full}, false};
  }
  return {{}, false};
}

// Models that take a layer solve or a beta fit to build (0.2 s and up): parse_scene
// validates their parameters without building them.
bool expensive(SceneModel m) {
  return m == SceneModel::automatic || m == SceneModel::exact || m == SceneModel::edge_corrected;
}

SceneModel read_model(const Reader& in, const json& root, MediumType medium) {
  const MediumModels models = models_for(medium);
  std::string list;
  for (SceneModel m : models.allowed) list += (list.empty() ? "" : ", ") + std::string(to_string(m));
  const std::string medium_name = root.at("medium").at("type").get<std::string>();
  if (!root.contains("model")) {
    if (!models.has_default) in.fail("model", "is missing; medium '" + medium_name + "' needs one of: " + list);
    return models.allowed.front();
  }
  const std::string name = in.string(root, "model", "scene");
  for (SceneModel m : models.allowed)
    if (name == to_string(m)) return m;
  in.fail("model", "= \"" + name + "\" is not available for medium '" + medium_name +
                       "' (available: " + list + ")");
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
  Reader in(source);
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors and number overflow (1e999)
    throw InputError(source + ": not valid JSON (" + e.what() + ")");
  }
  if (!root.is_object()) in.fail("the scene", "must be a JSON object, got " + show(root));
  in.only_keys(root, "scene", {"indenter", "medium", "model", "solver", "w", "tolerance"});
  Scene s;
  s.profile = read_indenter(in, root);
  s.medium = read_medium(in, root);

  s.model = read_model(in, root, s.medium.type);

  if (root.contains("solver")) {
    const std::string solver = in.string(root, "solver", "scene");
    if (solver != "closed_form" && solver != "ode")
      in.fail("solver", "= \"" + solver + "\" is unknown (known: closed_form, ode)");
    s.solver = solver == "ode" ? Solver::ode : Solver::closed_form;
    if (s.solver == Solver::ode && s.medium.type == MediumType::half_space)
      in.fail("solver", "= \"ode\" is available for foundation models only, not half_space");
  }
  if (root.contains("w")) {
    s.w = in.as_number(root.at("w"), "w");
    if (s.w < 0.0) in.fail("w", "= " + format_double(s.w) + " is invalid; valid range: >= 0");
  }
  if (s.model == SceneModel::automatic) {
    if (!root.contains("tolerance"))
      in.fail("tolerance", "is missing; model \"auto\" needs a relative error target in (0, 1)");
    s.tolerance = in.as_number(root.at("tolerance"), "tolerance");
    if (!(s.tolerance > 0.0 && s.tolerance < 1.0))
      in.fail("tolerance", "= " + format_double(s.tolerance) + " is invalid; valid range: (0, 1)");
  } else if (root.contains("tolerance")) {
    in.fail("tolerance", "is only used with model \"auto\" (model is \"" + std::string(to_string(s.model)) + "\")");
  }
  if (expensive(s.model) && s.solver != Solver::closed_form)
    in.fail("solver", "must be closed_form with model \"" + std::string(to_string(s.model)) + "\"");
  // Every invalid value is reported at parse time, without building anything.
  in.checked("medium", [&] {
    if (s.model == SceneModel::automatic) {  // resolves only for a radius: check the layer
      detail::require_positive("layer", "h", s.medium.h);
      (void)effective_modulus(s.medium.E, s.medium.nu);
    } else {
      validate(resolve_model(s).spec);
    }
  });
  return s;
}

const char* to_string(SceneModel model) {
  for (const auto& [m, name] : kSceneModelNames)
    if (m == model) return name;
  return "unknown";
}

ResolvedModel resolve_model(const Scene& s) {
  const MediumSpec& m = s.medium;
  ResolvedModel r;
  ModelSpec& spec = r.spec;
  spec.ode = s.solver == Solver::ode;
  switch (m.type) {
    case MediumType::half_space:
      spec.kind = ModelKind::half_space;
      spec.layer = {m.E, m.nu, 0.0, Base::bonded};
      return r;
    case MediumType::winkler:
      spec.kind = ModelKind::winkler;
      spec.K = r.K = m.K;
      r.has_foundation_constants = true;
      return r;
    case MediumType::pasternak:
    case MediumType::filonenko_borodich:
      spec.kind = s.model == SceneModel::full ? ModelKind::full_foundation : ModelKind::two_term;
      spec.K = r.K = m.K;
      spec.G = r.G = m.type == MediumType::pasternak ? m.G : m.T;
      r.has_foundation_constants = true;
      return r;
    case MediumType::layer:
      break;
  }
  spec.layer = {m.E, m.nu, m.h, m.base};
  if (s.model == SceneModel::automatic)
    throw Error("resolve_model: model \"auto\" resolves only for a contact radius (build_scene)");
  if (s.model == SceneModel::exact) {  // needs no thin-layer constants (allows nu = 0.5)
    spec.kind = ModelKind::exact;
    return r;
  }
  if (s.model == SceneModel::incompressible) {  // nu = 0.5 only: no compressible constants
    spec.kind = ModelKind::incompressible;
    return r;
  }
  if (s.model == SceneModel::uniform) {  // finite up to nu = 0.5: no compressible constants
    spec.kind = ModelKind::uniform;
    return r;
  }
  const ThinLayerConstants c = thin_layer_constants(spec.layer);
  r.has_foundation_constants = true;
  r.K = c.K;
  r.G = c.G;
  r.warnings = c.warnings;
  if (s.model == SceneModel::edge_corrected) {
    spec.kind = ModelKind::edge_corrected;
    return r;
  }
  spec.kind = s.model == SceneModel::leading || c.G == 0.0 ? ModelKind::winkler : ModelKind::two_term;
  spec.K = c.K;
  spec.G = s.model == SceneModel::leading ? 0.0 : c.G;
  return r;
}

Scene load_scene(const std::string& path) {
  return parse_scene(detail::read_file(path, "the scene file"), path);
}

namespace {

using Choose = std::function<ModelChoice(const ElasticLayer&)>;

// What a resolved model approximates (BuiltScene::reference).
ContactModelPtr reference_model(const Scene& s, const ModelSpec& spec) {
  const MediumSpec& m = s.medium;
  switch (spec.kind) {
    case ModelKind::winkler:
    case ModelKind::two_term:
    case ModelKind::edge_corrected:
    case ModelKind::incompressible:
    case ModelKind::uniform:
      if (m.type == MediumType::layer) return layer_reference(s.profile, {m.E, m.nu, m.h, m.base});
      if (spec.kind == ModelKind::two_term && spec.G > 0.0) {  // asymptotic Pasternak / F-B
        ModelSpec full = spec;
        full.kind = ModelKind::full_foundation;
        return make_contact_model(s.profile, full);
      }
      return nullptr;
    case ModelKind::full_foundation:
      if (m.type == MediumType::layer) return layer_reference(s.profile, {m.E, m.nu, m.h, m.base});
      return nullptr;
    case ModelKind::half_space:
    case ModelKind::exact:
      return nullptr;
  }
  return nullptr;
}

BuiltScene build(const Scene& s, const Choose& choose) {
  Reader in("scene");
  BuiltScene b;
  const MediumSpec& m = s.medium;
  if (m.type == MediumType::layer || m.type == MediumType::half_space) {
    b.has_effective_modulus = true;
    b.E_star = in.checked("medium", [&] { return effective_modulus(m.E, m.nu); });
  }
  if (s.model == SceneModel::automatic) {
    const ElasticLayer layer{m.E, m.nu, m.h, m.base};
    if (m.nu < 0.5) {  // the thin-layer constants are reported where they exist
      const ThinLayerConstants c = in.checked("medium", [&] { return thin_layer_constants(layer); });
      b.has_foundation_constants = true;
      b.K = c.K;
      b.G = c.G;
    }
    const ModelChoice choice = in.checked("medium", [&] { return choose(layer); });
    b.model = choice.contact_model;
    b.reference = choice.reference;
    b.automatic = true;
    b.chosen_model = choice.model;
    b.estimated_error = choice.estimated_error;
    return b;
  }
  const ResolvedModel r = in.checked("medium", [&] { return resolve_model(s); });
  b.warnings = r.warnings;
  b.has_foundation_constants = r.has_foundation_constants;
  b.K = r.K;
  b.G = r.G;
  b.model = in.checked("medium", [&] { return make_contact_model(s.profile, r.spec); });
  b.reference = in.checked("medium", [&] { return reference_model(s, r.spec); });
  return b;
}

}  // namespace

BuiltScene build_scene(const Scene& s, double a_min) {
  if (s.model != SceneModel::automatic) return build(s, nullptr);
  if (!(a_min > 0.0) || !std::isfinite(a_min))
    throw DomainError("build_scene", "a_min (smallest contact radius of interest)", a_min,
                      "finite and > 0 for model auto");
  std::vector<double> radii;
  for (int k = 0; k <= 4; ++k) radii.push_back(a_min * std::ldexp(1.0, k));
  return build_scene_for_radii(s, radii);
}

BuiltScene build_scene_for_radii(const Scene& s, const std::vector<double>& radii) {
  return build(s, [&](const ElasticLayer& layer) {
    return choose_layer_model(s.profile, layer, s.w, s.tolerance, radii);
  });
}

BuiltScene build_scene_for_summary(const Scene& s) {
  return build(s, [&](const ElasticLayer& layer) {
    return choose_layer_model_for_summary(s.profile, layer, s.w, s.tolerance);
  });
}

ModelErrorEstimator error_estimator(const Scene& s, const BuiltScene& b) {
  return ModelErrorEstimator(b.model, b.reference, s.w);
}

}  // namespace layerjkr
