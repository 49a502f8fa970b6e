// Relaxation laws and the Lee-Radok loading response (viscoelastic.hpp).
#include "layerjkr/viscoelastic.hpp"

#include <cmath>
#include <numeric>
#include <sstream>

#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

std::string list(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format_double(v[i]);
  return out + "]";
}

// (1 - exp(-x)) / x without cancellation for small x.
double one_minus_exp_over(double x) { return x < 1e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x; }

// Prony: the pieces' integrals by recursion. For term i, h_i(n) = sum over pieces k <= n of
// slope_k int_{t_{k-1}}^{t_k} exp(-(t_n - s)/tau_i) ds obeys
// h_i(n) = exp(-dt_n/tau_i) h_i(n-1) + slope_n dt_n (1 - exp(-dt_n/tau_i)) / (dt_n/tau_i).
std::vector<double> prony_loading(const std::vector<double>& t, const std::vector<double>& P, const RelaxationLaw& law) {
  const double g_inf = 1.0 - std::accumulate(law.g.begin(), law.g.end(), 0.0);
  std::vector<double> h(law.g.size(), 0.0), out(t.size());
  double t_prev = 0.0, P_prev = 0.0;
  for (std::size_t n = 0; n < t.size(); ++n) {
    const double dt = t[n] - t_prev, dP = P[n] - P_prev;
    double sum = g_inf * P[n];  // the relaxed part: the elastic force itself
    for (std::size_t i = 0; i < law.g.size(); ++i) {
      const double x = dt / law.tau[i];
      h[i] = std::exp(-x) * h[i] + dP * one_minus_exp_over(x);
      sum += law.g[i] * h[i];
    }
    out[n] = sum;
    t_prev = t[n];
    P_prev = P[n];
  }
  return out;
}

// Power law: slope_k int_{t_{k-1}}^{t_k} ((t_n - s)/t0)^-beta ds
//          = slope_k t0^beta ((t_n - t_{k-1})^(1-beta) - (t_n - t_k)^(1-beta)) / (1 - beta).
std::vector<double> power_law_loading(const std::vector<double>& t, const std::vector<double>& P, const RelaxationLaw& law) {
  const double e = 1.0 - law.beta;
  std::vector<double> out(t.size());
  for (std::size_t n = 0; n < t.size(); ++n) {
    double sum = 0.0, t_prev = 0.0, P_prev = 0.0;
    for (std::size_t k = 0; k <= n; ++k) {
      const double dt = t[k] - t_prev;
      if (dt > 0.0) {
        const double slope = (P[k] - P_prev) / dt;
        // (t_n - t_{k-1})^e - (t_n - t_k)^e, each in units of t0.
        const double a = (t[n] - t_prev) / law.t0, b = (t[n] - t[k]) / law.t0;
        sum += slope * law.t0 * (std::pow(a, e) - std::pow(b, e)) / e;
      }
      t_prev = t[k];
      P_prev = P[k];
    }
    out[n] = sum;
  }
  return out;
}

}  // namespace

RelaxationLaw RelaxationLaw::standard_linear_solid(double E_inf_ratio, double tau) {
  if (!(E_inf_ratio >= 0.0 && E_inf_ratio <= 1.0))
    throw DomainError("RelaxationLaw::standard_linear_solid", "E_inf/E", E_inf_ratio, "[0, 1]");
  return prony({1.0 - E_inf_ratio}, {tau});
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
      return std::pow(t / t0, -beta);
  }
  return 1.0;
}

std::string RelaxationLaw::describe() const {
  switch (kind) {
    case Kind::elastic:
      return "elastic";
    case Kind::prony:
      return "prony(g = " + list(g) + ", tau = " + list(tau) + " s)";
    case Kind::power_law:
      return "power_law(beta = " + format_double(beta) + ", t0 = " + format_double(t0) + " s)";
  }
  return "";
}

std::vector<double> lee_radok_loading(const std::vector<double>& t, const std::vector<double>& P_H,
                                      const RelaxationLaw& law) {
  law.validate();
  if (t.size() != P_H.size())
    throw InputError("lee_radok_loading: t and P_H have different lengths (" + std::to_string(t.size()) + " and " +
                     std::to_string(P_H.size()) + ")");
  double t_prev = 0.0, P_prev = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    if (!std::isfinite(t[i]) || !std::isfinite(P_H[i]))
      throw InputError("lee_radok_loading: t" + at + " or P_H" + at + " is not finite");
    if (i == 0 ? t[0] < 0.0 : !(t[i] > t_prev))
      throw InputError("lee_radok_loading: t" + at + " = " + format_double(t[i]) +
                       (i == 0 ? " is negative (the contact starts at t = 0)" : " does not increase"));
    if (P_H[i] < P_prev || (t[i] == 0.0 && P_H[i] != 0.0))
      throw InputError("lee_radok_loading: P_H" + at + " = " + format_double(P_H[i]) +
                       " N is below the sample before it (or not 0 at t = 0): the contact recedes, which "
                       "Lee-Radok's hereditary integral does not describe (Ting's rule does)");
    t_prev = t[i];
    P_prev = P_H[i];
  }
  switch (law.kind) {
    case RelaxationLaw::Kind::elastic:
      return P_H;
    case RelaxationLaw::Kind::prony:
      return prony_loading(t, P_H, law);
    case RelaxationLaw::Kind::power_law:
      return power_law_loading(t, P_H, law);
  }
  return P_H;
}

}  // namespace layerjkr
