// The strict JSON scene reader (scene.hpp): every key is known, every value checked and named.
#include "layerjkr/scene.hpp"

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <nlohmann/json.hpp>

#include "io/read_file.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/provenance.hpp"
#include "provenance/scene_description.hpp"

namespace layerjkr {
namespace {

using json = nlohmann::json;

// Deeper nesting than any scene needs is refused while parsing, before anything recursive
// (dump, destruction) walks the document: 100 000 '[' used to overflow the stack.
constexpr int kMaxDepth = 32;

// Appends v's JSON text until `out` holds more than `budget` characters: a snippet for an
// error message costs O(budget), not O(document), and recursion is bounded by kMaxDepth.
void put(const json& v, std::string& out, std::size_t budget) {
  if (out.size() > budget) return;
  if (!v.is_structured()) {
    out += v.dump();
    return;
  }
  const bool obj = v.is_object();
  out += obj ? '{' : '[';
  bool first = true;
  for (auto it = v.begin(); it != v.end() && out.size() <= budget; ++it, first = false) {
    if (!first) out += ',';
    if (obj) out += json(it.key()).dump() + ':';
    put(*it, out, budget);
  }
  out += obj ? '}' : ']';
}

std::string show(const json& v) {
  std::string s;
  put(v, s, 80);
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

// The keys seen so far in each open object or array, for the parser callback: a key given
// twice in one object is an error (nlohmann keeps the last silently).
struct OpenValue {
  std::string path;
  bool object;
  std::set<std::string> keys;
  std::string last_key;
};

// Parses with a depth limit and duplicate-key detection, both while parsing.
json parse_strict(const std::string& text, const std::string& source) {
  std::vector<OpenValue> open;
  auto child_path = [&open]() -> std::string {
    if (open.empty()) return "";
    const OpenValue& p = open.back();
    const std::string sep = p.path.empty() ? "" : ".";
    return p.object ? p.path + sep + p.last_key : p.path + "[]";
  };
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if (event == E::object_start || event == E::array_start) {
      if (open.size() >= static_cast<std::size_t>(kMaxDepth))
        throw InputError(source + ": the JSON nests objects and arrays deeper than " +
                         std::to_string(kMaxDepth) + " levels, the limit for scene files");
      open.push_back({child_path(), event == E::object_start, {}, {}});
    } else if (event == E::object_end || event == E::array_end) {
      open.pop_back();
    } else if (event == E::key) {
      OpenValue& o = open.back();
      o.last_key = parsed.get<std::string>();
      if (!o.keys.insert(o.last_key).second) {
        const std::string sep = o.path.empty() ? "" : ".";
        throw InputError(source + ": " + o.path + sep + o.last_key +
                         " is given twice in the same object; give each key once");
      }
    }
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const json::exception& e) {  // syntax errors and number overflow (1e999)
    throw InputError(source + ": not valid JSON (" + e.what() + ")");
  }
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
  if (shape == "pyramid") {
    in.only_keys(ind, "indenter", {"shape", "semi_angle_deg", "sides"});
    const double deg = in.number(ind, "semi_angle_deg", "indenter");
    if (!(deg > 0.0 && deg < 90.0))
      in.fail("indenter.semi_angle_deg", "= " + format_double(deg) + " is invalid; valid range: (0, 90), the "
                                         "angle between a face and the axis");
    const double sides = in.number(ind, "sides", "indenter");
    if (!(sides == 3.0 || sides == 4.0))
      in.fail("indenter.sides", "= " + format_double(sides) + " is invalid; valid: 3 or 4");
    return make_pyramid(deg * boost::math::constants::degree<double>(), static_cast<int>(sides));
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
                                "\" is unknown (known: paraboloid, sphere, cone, pyramid, power_law, table)");
}

// An enum spelled by the registry (types.hpp), or a failure naming the key and the known values.
template <class E>
E read_enum(const Reader& in, const std::string& text, const std::string& key) {
  if (const std::optional<E> e = from_string<E>(text)) return *e;
  in.fail(key, "= \"" + text + "\" is unknown (known: " + known_names<E>() + ")");
}

// E > 0 and nu in (-1, 0.5] of a layer or the substrate at `path`.
void check_elastic(const Reader& in, const std::string& path, double E, double nu) {
  if (!(E > 0.0)) in.fail(path + ".E", "= " + format_double(E) + " is invalid; valid range: > 0 [Pa]");
  if (!(nu > -1.0 && nu <= 0.5)) in.fail(path + ".nu", "= " + format_double(nu) + " is invalid; valid range: (-1, 0.5]");
}

// medium.viscoelastic: {"law": "sls", "E_inf", "tau"} | {"law": "prony", "g", "tau"} |
// {"law": "power_law", "beta", "t0"} | {"law": "power_law_plateau", "beta", "t0", "E_inf"} |
// {"law": "fractional_sls", "beta", "tau", "E_inf"} | {"law": "fractional_maxwell", "beta", "tau"} |
// {"law": "maxwell2", "E_inf", "tau", "E_2", "tau_2"}; E is the medium's instantaneous modulus (a stack's top
// layer's: every layer relaxes by the same ratio).
RelaxationLaw read_relaxation(const Reader& in, const json& med, double E) {
  const std::string path = "medium.viscoelastic";
  const json& v = in.object(med, "viscoelastic", path);
  const std::string law = in.string(v, "law", path);
  if (law == "sls") {
    in.only_keys(v, path, {"law", "E_inf", "tau"});
    const double E_inf = in.number(v, "E_inf", path), tau = in.number(v, "tau", path);
    if (!(E_inf >= 0.0 && E_inf <= E))
      in.fail(path + ".E_inf", "= " + format_double(E_inf) + " is invalid; valid range: [0, E] with E = " + format_double(E) +
                                   " Pa, the instantaneous modulus");
    return in.checked(path, [&] { return RelaxationLaw::standard_linear_solid(E_inf / E, tau); });
  }
  if (law == "prony") {
    in.only_keys(v, path, {"law", "g", "tau"});
    std::vector<double> g = in.numbers(v, "g", path), tau = in.numbers(v, "tau", path);
    try {
      return RelaxationLaw::prony(std::move(g), std::move(tau));
    } catch (const Error& e) {
      in.fail(path, std::string("is invalid: ") + e.what());
    }
  }
  if (law == "power_law") {
    in.only_keys(v, path, {"law", "beta", "t0"});
    const double beta = in.number(v, "beta", path), t0 = in.number(v, "t0", path);
    return in.checked(path, [&] { return RelaxationLaw::power_law(beta, t0); });
  }
  if (law == "power_law_plateau") {
    in.only_keys(v, path, {"law", "beta", "t0", "E_inf"});
    const double beta = in.number(v, "beta", path), t0 = in.number(v, "t0", path), E_inf = in.number(v, "E_inf", path);
    if (!(E_inf >= 0.0 && E_inf < E))
      in.fail(path + ".E_inf", "= " + format_double(E_inf) + " is invalid; valid range: [0, E) with E = " + format_double(E) +
                                   " Pa, the modulus at t0");
    return in.checked(path, [&] { return RelaxationLaw::power_law_plateau(beta, t0, E_inf / E); });
  }
  if (law == "maxwell2") {
    in.only_keys(v, path, {"law", "E_inf", "tau", "E_2", "tau_2"});
    const double E_inf = in.number(v, "E_inf", path), tau = in.number(v, "tau", path);
    const double E_2 = in.number(v, "E_2", path), tau_2 = in.number(v, "tau_2", path);
    if (!(E_inf >= 0.0 && E_2 > 0.0 && E_inf + E_2 < E))
      in.fail(path, "has E_inf = " + format_double(E_inf) + " Pa and E_2 = " + format_double(E_2) +
                        " Pa; valid: E_inf >= 0, E_2 > 0 and E_inf + E_2 < E = " + format_double(E) +
                        " Pa, the instantaneous modulus (the first arm has E - E_inf - E_2)");
    return in.checked(path, [&] { return RelaxationLaw::maxwell2(E_inf / E, tau, E_2 / E, tau_2); });
  }
  if (law == "fractional_sls" || law == "fractional_maxwell") {
    const bool plateau = law == "fractional_sls";
    in.only_keys(v, path, plateau ? std::set<std::string>{"law", "beta", "tau", "E_inf"}
                                  : std::set<std::string>{"law", "beta", "tau"});
    const double beta = in.number(v, "beta", path), tau = in.number(v, "tau", path);
    const double E_inf = plateau ? in.number(v, "E_inf", path) : 0.0;
    if (!(E_inf >= 0.0 && E_inf < E))
      in.fail(path + ".E_inf", "= " + format_double(E_inf) + " is invalid; valid range: [0, E) with E = " + format_double(E) +
                                   " Pa, the instantaneous modulus");
    return in.checked(path, [&] {
      return plateau ? RelaxationLaw::fractional_sls(beta, tau, E_inf / E) : RelaxationLaw::fractional_maxwell(beta, tau);
    });
  }
  in.fail(path + ".law", "= \"" + law + "\" is unknown (known: sls, prony, maxwell2, power_law, power_law_plateau, "
                         "fractional_sls, fractional_maxwell)");
}

// {"type": "layers", "layers": [{"E", "nu", "h"}, ...], "base": "bonded" | "frictionless" | {"E", "nu"}}
void read_stack(const Reader& in, const json& med, MediumSpec& m) {
  in.only_keys(med, "medium", {"type", "layers", "base", "viscoelastic"});
  if (!med.contains("layers")) in.fail("medium.layers", "is missing; give the layers top first, each {E, nu, h}");
  const json& layers = med.at("layers");
  if (!layers.is_array() || layers.empty())
    in.fail("medium.layers", "must be a non-empty array of layers {E, nu, h} (top first), got " + show(layers));
  if (layers.size() > kMaxStackLayers)  // before any is read: the count alone is the cost
    in.fail("medium.layers", "has " + std::to_string(layers.size()) + " layers; at most " +
                                 std::to_string(kMaxStackLayers) +
                                 " (a stack's set-up grows with its layers, 25 ms each; docs/development.md, Limits)");
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const std::string path = "medium.layers[" + std::to_string(i) + "]";
    if (!layers[i].is_object()) in.fail(path, "must be a JSON object {E, nu, h}, got " + show(layers[i]));
    if (layers[i].contains("viscoelastic"))
      in.fail(path + ".viscoelastic", "is not allowed: a stack relaxes by one normalised law for all its layers (the "
                                      "correspondence principle needs every modulus to follow the same psi(t)); give "
                                      "medium.viscoelastic, each layer keeping its own E and nu");
    in.only_keys(layers[i], path, {"E", "nu", "h"});
    StackLayer l{in.number(layers[i], "E", path), in.number(layers[i], "nu", path), in.number(layers[i], "h", path)};
    check_elastic(in, path, l.E, l.nu);
    if (!(l.h > 0.0)) in.fail(path + ".h", "= " + format_double(l.h) + " is invalid; valid range: > 0 [m]");
    m.stack.layers.push_back(l);
  }
  if (med.contains("base")) {
    const json& base = med.at("base");
    if (base.is_object()) {
      in.only_keys(base, "medium.base", {"E", "nu"});
      const Substrate sub{in.number(base, "E", "medium.base"), in.number(base, "nu", "medium.base")};
      check_elastic(in, "medium.base", sub.E, sub.nu);
      m.stack.substrate = sub;
    } else if (base.is_string()) {
      m.stack.base = read_enum<Base>(in, base.get<std::string>(), "medium.base");
    } else {
      in.fail("medium.base", "must be \"bonded\", \"frictionless\" or an elastic half-space {E, nu}, got " + show(base));
    }
  }
  const StackLayer& top = m.stack.layers.front();
  m.E = top.E;
  m.nu = top.nu;
  m.h = top.h;
  m.base = m.stack.substrate ? Base::bonded : m.stack.base;
}

MediumSpec read_medium(const Reader& in, const json& root) {
  const json& med = in.object(root, "medium", "medium");
  MediumSpec m;
  m.type = read_enum<MediumType>(in, in.string(med, "type", "medium"), "medium.type");
  const bool foundation =
      m.type == MediumType::winkler || m.type == MediumType::pasternak || m.type == MediumType::filonenko_borodich;
  if (foundation && med.contains("viscoelastic"))
    in.fail("medium.viscoelastic", "is for media with a Young's modulus (half_space, layer, layers); a foundation's "
                                   "constants do not relax by a modulus law");
  switch (m.type) {
    case MediumType::winkler:
      in.only_keys(med, "medium", {"type", "K"});
      m.K = in.number(med, "K", "medium");
      break;
    case MediumType::pasternak:
      in.only_keys(med, "medium", {"type", "K", "G"});
      m.K = in.number(med, "K", "medium");
      m.G = in.number(med, "G", "medium");
      break;
    case MediumType::filonenko_borodich:
      in.only_keys(med, "medium", {"type", "K", "T"});
      m.K = in.number(med, "K", "medium");
      m.T = in.number(med, "T", "medium");
      break;
    case MediumType::layer:
      in.only_keys(med, "medium", {"type", "E", "nu", "h", "base", "viscoelastic"});
      m.E = in.number(med, "E", "medium");
      m.nu = in.number(med, "nu", "medium");
      m.h = in.number(med, "h", "medium");
      if (med.contains("base")) m.base = read_enum<Base>(in, in.string(med, "base", "medium"), "medium.base");
      break;
    case MediumType::half_space:
      in.only_keys(med, "medium", {"type", "E", "nu", "viscoelastic"});
      m.E = in.number(med, "E", "medium");
      m.nu = in.number(med, "nu", "medium");
      break;
    case MediumType::layers: read_stack(in, med, m); break;
  }
  if (med.contains("viscoelastic")) m.relaxation = read_relaxation(in, med, m.E);
  return m;
}

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
    case MediumType::layers:
      return {{SceneModel::exact, SceneModel::leading, SceneModel::two_term, SceneModel::incompressible,
               SceneModel::automatic},
              false};
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

// {"law": "maugis_barquins", "v_star": V, "n": N}
CrackKinetics read_kinetics(const Reader& in, const json& obj) {
  const std::string path = "adhesion.kinetics";
  const json& k = in.object(obj, "kinetics", path);
  const std::string law = in.string(k, "law", path);
  if (law != "maugis_barquins") in.fail(path + ".law", "= \"" + law + "\" is unknown (known: maugis_barquins)");
  in.only_keys(k, path, {"law", "v_star", "n"});
  CrackKinetics c;
  c.v_star = in.number(k, "v_star", path);
  c.n = in.number(k, "n", path);
  in.checked(path, [&] { c.validate(); });
  return c;
}

// {"model": ..., "sigma0": ... | "z0": ..., "kinetics": {...}}; every value checked here, by key.
AdhesionSpec read_adhesion(const Reader& in, const json& root) {
  const json& obj = in.object(root, "adhesion", "adhesion");
  in.only_keys(obj, "adhesion", {"model", "sigma0", "z0", "kinetics"});
  AdhesionSpec a;
  if (obj.contains("model")) a.model = read_enum<AdhesionModel>(in, in.string(obj, "model", "adhesion"), "adhesion.model");
  for (const char* key : {"sigma0", "z0"}) {
    if (!obj.contains(key)) continue;
    const double v = in.number(obj, key, "adhesion");
    if (!(v > 0.0))
      in.fail(std::string("adhesion.") + key,
              "= " + format_double(v) + " is invalid; valid range: > 0 " + (key[0] == 's' ? "[Pa]" : "[m]"));
    (key[0] == 's' ? a.sigma0 : a.z0) = v;
  }
  if (a.sigma0 && a.z0) in.fail("adhesion", "gives both sigma0 and z0; give one (z0 sets sigma0 = 16 w / (9 sqrt(3) z0))");
  if (a.model == AdhesionModel::maugis_dugdale && !a.sigma0 && !a.z0)
    in.fail("adhesion", "model \"maugis_dugdale\" needs sigma0 [Pa] (the Dugdale stress) or z0 [m]");
  if (obj.contains("kinetics")) {
    if (a.model != AdhesionModel::jkr)
      in.fail("adhesion.kinetics", std::string("act on JKR's edge crack; adhesion.model is \"") + to_string(a.model) +
                                       "\" (use \"jkr\")");
    a.kinetics = read_kinetics(in, obj);
  }
  return a;
}

// The scene's lengths and energies in dimensionless form. Outside these ranges the
// quantities the solvers form (a^3, R^2, ratios of moments) overflow or underflow: the
// answer would be non-finite or silently wrong (w = 1e308 found no pull-off), so the scene
// is refused, naming the key. L is the indenter's length scale (R; f(L) = L for a power
// law); a cone is scale-free and has none.
void check_scales(const Reader& in, const Scene& s) {
  const auto pl = s.profile->power_law_form();
  if (pl && pl->d == 1.0) return;
  const double L = s.profile->length_scale();
  const MediumSpec& m = s.medium;
  const bool elastic = m.type == MediumType::layer || m.type == MediumType::half_space || m.type == MediumType::layers;
  // An elastic modulus: E* for solids, K L for foundations (K [N/m^3]).
  const double E = elastic ? m.E / (1.0 - m.nu * m.nu) : m.K * L;
  if ((m.type == MediumType::layer || m.type == MediumType::layers) && !(L / m.h >= 1e-9 && L / m.h <= 1e9))
    in.fail("indenter", "length scale L = " + format_double(L) + " m against " +
                            (m.type == MediumType::layers ? "medium.layers[0].h = " : "medium.h = ") + format_double(m.h) +
                            " m is out of range: L/h = " + format_double(L / m.h) + "; valid range: [1e-9, 1e9]");
  const double omega = s.w / (E * L);
  if (s.w > 0.0 && !(omega >= 1e-30 && omega <= 1e6))
    in.fail("w", "= " + format_double(s.w) + " J/m^2 is out of range for this indenter and medium: w/(E L) = " +
                     format_double(omega) + " with " + (elastic ? "E* = " : "E = K L = ") + format_double(E) +
                     " Pa, L = " + format_double(L) + " m (the indenter's length scale); valid range: [1e-30, 1e6]");
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
  Reader in(source);
  const json root = parse_strict(text, source);
  if (!root.is_object()) in.fail("the scene", "must be a JSON object, got " + show(root));
  in.only_keys(root, "scene", {"indenter", "medium", "model", "solver", "w", "tolerance", "adhesion"});
  Scene s;
  s.profile = read_indenter(in, root);
  s.medium = read_medium(in, root);

  s.model = read_model(in, root, s.medium.type);

  if (root.contains("solver")) {
    s.solver = read_enum<Solver>(in, in.string(root, "solver", "scene"), "solver");
    if (s.solver == Solver::ode && (s.medium.type == MediumType::half_space || s.medium.type == MediumType::layers))
      in.fail("solver", "= \"ode\" is available for foundation models only, not " +
                            std::string(to_string(s.medium.type)));
  }
  if (root.contains("w")) {
    s.w = in.as_number(root.at("w"), "w");
    if (s.w < 0.0) in.fail("w", "= " + format_double(s.w) + " is invalid; valid range: >= 0");
  }
  if (root.contains("adhesion")) s.adhesion = read_adhesion(in, root);
  if (s.adhesion.kinetics && !(s.w > 0.0))
    in.fail("adhesion.kinetics", "need a work of adhesion w > 0 (w0 in G = w0 (1 + (v/v_star)^n)); w is " + format_double(s.w));
  if (s.adhesion.kinetics && s.medium.relaxation.kind != RelaxationLaw::Kind::elastic)
    in.fail("adhesion.kinetics", "on a relaxing medium (medium.viscoelastic) are not modelled: Maugis-Barquins kinetics "
                                 "are the edge crack's dissipation on an elastic body; give one or the other");
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
  in.checked("medium", [&] { validate(resolve_model(s).spec); });
  check_scales(in, s);
  s.origin.json = root.dump();
  s.origin.description = detail::describe_scene(s);
  return s;
}

Scene load_scene(const std::string& path) {
  // A scene, even with a table indenter of 10^6 points, is far below 64 MiB.
  const std::string text = detail::read_file(path, "the scene file", std::uint64_t{64} << 20);
  Scene s = parse_scene(text, path);
  s.origin.file = path;
  s.origin.file_sha256 = sha256_hex(text.data(), text.size());
  return s;
}

}  // namespace layerjkr
