// Relaxation laws: validation, psi(t) and their description (viscoelastic.hpp).
#include "layerjkr/viscoelastic.hpp"

#include <cmath>
#include <numeric>

#include "layerjkr/error.hpp"
#include "relaxation_kernel.hpp"

namespace layerjkr {
namespace {

std::string list(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format_double(v[i]);
  return out + "]";
}

}  // namespace

RelaxationLaw RelaxationLaw::standard_linear_solid(double E_inf_ratio, double tau) {
  if (!(E_inf_ratio >= 0.0 && E_inf_ratio <= 1.0))
    throw DomainError("RelaxationLaw::standard_linear_solid", "E_inf/E", E_inf_ratio, "[0, 1]");
  RelaxationLaw law = prony({1.0 - E_inf_ratio}, {tau});
  law.standard_linear_solid_form = true;
  return law;
}

RelaxationLaw RelaxationLaw::maxwell2(double E_inf_ratio, double tau, double E2_ratio, double tau_2) {
  if (!(E_inf_ratio >= 0.0 && E2_ratio > 0.0 && E_inf_ratio + E2_ratio < 1.0))
    throw DomainError("RelaxationLaw::maxwell2", "(E_inf + E_2)/E", E_inf_ratio + E2_ratio,
                      "[0, 1) with E_inf >= 0 and E_2 > 0 (the first arm's modulus E - E_inf - E_2 must be > 0)");
  RelaxationLaw law = prony({1.0 - E_inf_ratio - E2_ratio, E2_ratio}, {tau, tau_2});
  law.two_term_form = true;
  return law;
}

RelaxationLaw RelaxationLaw::prony(std::vector<double> g, std::vector<double> tau) {
  RelaxationLaw law;
  law.kind = Kind::prony;
  law.g = std::move(g);
  law.tau = std::move(tau);
  law.validate();
  return law;
}

RelaxationLaw RelaxationLaw::power_law(double beta, double t0) {
  RelaxationLaw law;
  law.kind = Kind::power_law;
  law.beta = beta;
  law.t0 = t0;
  law.validate();
  return law;
}

RelaxationLaw RelaxationLaw::power_law_plateau(double beta, double t0, double E_inf_ratio) {
  RelaxationLaw law;
  law.kind = Kind::power_law;
  law.beta = beta;
  law.t0 = t0;
  law.plateau = E_inf_ratio;
  law.plateau_form = true;
  law.validate();
  return law;
}

RelaxationLaw RelaxationLaw::fractional_sls(double beta, double tau, double E_inf_ratio) {
  RelaxationLaw law;
  law.kind = Kind::fractional;
  law.beta = beta;
  law.tau_f = tau;
  law.plateau = E_inf_ratio;
  law.plateau_form = true;
  law.validate();
  return law;
}

RelaxationLaw RelaxationLaw::fractional_maxwell(double beta, double tau) {
  RelaxationLaw law = fractional_sls(beta, tau, 0.0);
  law.plateau_form = false;
  return law;
}

void RelaxationLaw::validate() const {
  const char* fn = "RelaxationLaw";
  switch (kind) {
    case Kind::elastic:
      return;
    case Kind::prony: {
      if (g.empty() || g.size() != tau.size())
        throw InputError(std::string(fn) + ": a Prony law needs as many weights g as times tau, at least one (g has " +
                         std::to_string(g.size()) + ", tau " + std::to_string(tau.size()) + ")");
      double sum = 0.0;
      for (std::size_t i = 0; i < g.size(); ++i) {
        const std::string at = "[" + std::to_string(i) + "]";
        if (!(g[i] > 0.0 && g[i] <= 1.0)) throw DomainError(fn, "g" + at, g[i], "(0, 1]");
        if (!(tau[i] > 0.0 && std::isfinite(tau[i]))) throw DomainError(fn, "tau" + at, tau[i], "finite and > 0 [s]");
        sum += g[i];
      }
      if (sum > 1.0 + 1e-12)
        throw DomainError(fn, "sum of g", sum, "<= 1 (g_inf = 1 - sum g is the relaxed modulus over E)");
      return;
    }
    case Kind::power_law:
      if (!(beta >= 0.0 && beta < 1.0)) throw DomainError(fn, "beta", beta, "[0, 1)");
      if (!(t0 > 0.0 && std::isfinite(t0))) throw DomainError(fn, "t0", t0, "finite and > 0 [s]");
      if (!(plateau >= 0.0 && plateau < 1.0)) throw DomainError(fn, "E_inf/E", plateau, "[0, 1)");
      return;
    case Kind::fractional:
      if (!(beta >= detail::fractional::kBetaMin && beta <= detail::fractional::kBetaMax))
        throw DomainError(fn, "beta", beta,
                          "[0.01, 0.95] (beta -> 1 is the standard linear solid, \"sls\"; the spectrum's quadrature "
                          "costs 1/(1 - beta))");
      if (!(tau_f > 0.0 && std::isfinite(tau_f))) throw DomainError(fn, "tau", tau_f, "finite and > 0 [s]");
      if (!(plateau >= 0.0 && plateau < 1.0)) throw DomainError(fn, "E_inf/E", plateau, "[0, 1)");
      return;
  }
}

double RelaxationLaw::relative_modulus(double t) const {
  switch (kind) {
    case Kind::elastic:
      return 1.0;
    case Kind::prony: {
      double psi = 1.0 - std::accumulate(g.begin(), g.end(), 0.0);
      for (std::size_t i = 0; i < g.size(); ++i) psi += g[i] * std::exp(-t / tau[i]);
      return psi;
    }
    case Kind::power_law:
      return plateau + (1.0 - plateau) * std::pow(t / t0, -beta);
    case Kind::fractional:
      return detail::fractional_kernel<double>(beta, tau_f, t, t, plateau).value(t);
  }
  return 1.0;
}

std::string RelaxationLaw::describe() const {
  switch (kind) {
    case Kind::elastic:
      return "elastic";
    case Kind::prony:
      if (two_term_form && g.size() == 2)
        return "maxwell2(E_inf/E = " + format_double(1.0 - g[0] - g[1]) + ", tau = " + format_double(tau[0]) +
               " s, E_2/E = " + format_double(g[1]) + ", tau_2 = " + format_double(tau[1]) + " s)";
      if (standard_linear_solid_form && g.size() == 1)
        return "sls(E_inf/E = " + format_double(1.0 - g[0]) + ", tau = " + format_double(tau[0]) + " s)";
      return "prony(g = " + list(g) + ", tau = " + list(tau) + " s)";
    case Kind::power_law:
      if (plateau_form)
        return "power_law_plateau(beta = " + format_double(beta) + ", t0 = " + format_double(t0) +
               " s, E_inf/E = " + format_double(plateau) + ")";
      return "power_law(beta = " + format_double(beta) + ", t0 = " + format_double(t0) + " s)";
    case Kind::fractional:
      if (plateau_form)
        return "fractional_sls(beta = " + format_double(beta) + ", tau = " + format_double(tau_f) +
               " s, E_inf/E = " + format_double(plateau) + ")";
      return "fractional_maxwell(beta = " + format_double(beta) + ", tau = " + format_double(tau_f) + " s)";
  }
  return "";
}

}  // namespace layerjkr
