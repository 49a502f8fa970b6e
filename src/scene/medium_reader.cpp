// The medium of a scene: half-space, layer, stack, and its relaxation law (scene_reader.cpp reads the
// rest of the scene; medium_reader.hpp).
#include "medium_reader.hpp"

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "layerjkr/viscoelastic.hpp"

namespace layerjkr::detail {
namespace {

// E > 0 and nu in (-1, 0.5] of a layer or the substrate at `path`.
void check_elastic(const JsonReader& in, const std::string& path, double E, double nu) {
  if (!(E > 0.0)) in.fail(path + ".E", "= " + format_double(E) + " is invalid; valid range: > 0 [Pa]");
  if (!(nu > -1.0 && nu <= 0.5)) in.fail(path + ".nu", "= " + format_double(nu) + " is invalid; valid range: (-1, 0.5]");
}

// medium.viscoelastic: {"law": "sls", "E_inf", "tau"} | {"law": "prony", "g", "tau"} |
// {"law": "power_law", "beta", "t0"} | {"law": "power_law_plateau", "beta", "t0", "E_inf"} |
// {"law": "fractional_sls", "beta", "tau", "E_inf"} | {"law": "fractional_maxwell", "beta", "tau"} |
// {"law": "maxwell2", "E_inf", "tau", "E_2", "tau_2"}; E is the medium's instantaneous modulus (a stack's top
// layer's: every layer relaxes by the same ratio).
RelaxationLaw read_relaxation(const JsonReader& in, const json& med, double E) {
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
void read_stack(const JsonReader& in, const json& med, MediumSpec& m) {
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

}  // namespace

MediumSpec read_medium(const JsonReader& in, const json& root) {
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

}  // namespace layerjkr::detail
