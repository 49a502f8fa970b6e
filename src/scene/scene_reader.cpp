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
#include "json_reader.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/provenance.hpp"
#include "medium_reader.hpp"
#include "provenance/scene_description.hpp"

namespace layerjkr {
namespace {

using detail::json;
using detail::parse_strict;
using detail::read_enum;
using detail::read_medium;
using detail::JsonReader;
using detail::show;

ProfilePtr read_indenter(const JsonReader& in, const json& root) {
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

SceneModel read_model(const JsonReader& in, const json& root, MediumType medium) {
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
CrackKinetics read_kinetics(const JsonReader& in, const json& obj) {
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
AdhesionSpec read_adhesion(const JsonReader& in, const json& root) {
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
void check_scales(const JsonReader& in, const Scene& s) {
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
  JsonReader in(source);
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
