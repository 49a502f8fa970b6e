// The hereditary responses of viscoelastic.hpp on double: Lee-Radok loading and the response to an
// indentation history (the engine is hereditary.hpp, shared with the fit's Jets).
#include "hereditary.hpp"

#include <numeric>
#include <string>

#include "layerjkr/error.hpp"
#include "layerjkr/viscoelastic.hpp"

namespace layerjkr {
namespace detail {

RelaxationKernel<double> kernel_of(const RelaxationLaw& law, double t_lo, double t_hi) {
  switch (law.kind) {
    case RelaxationLaw::Kind::elastic:
      return prony_kernel<double>(1.0, {}, {});
    case RelaxationLaw::Kind::prony:
      return prony_kernel<double>(1.0 - std::accumulate(law.g.begin(), law.g.end(), 0.0), law.g, law.tau);
    case RelaxationLaw::Kind::power_law:
      return power_law_kernel<double>(law.beta, law.t0, t_lo, t_hi, law.plateau);
    case RelaxationLaw::Kind::fractional:
      return fractional_kernel<double>(law.beta, law.tau_f, t_lo, t_hi, law.plateau);
  }
  return prony_kernel<double>(1.0, {}, {});
}

void time_scales(const std::vector<double>& t, double* t_lo, double* t_hi) {
  *t_lo = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < t.size(); ++i) *t_lo = std::min(*t_lo, t[i] - t[i - 1]);
  *t_hi = t.size() > 1 ? t.back() - t.front() : 1.0;
  if (!(*t_lo > 0.0) || !std::isfinite(*t_lo)) *t_lo = *t_hi;
}

}  // namespace detail

namespace {

void check_times(const char* fn, const std::vector<double>& t, const std::vector<double>& v, const char* name) {
  if (t.size() != v.size())
    throw InputError(std::string(fn) + ": t and " + name + " have different lengths (" + std::to_string(t.size()) +
                     " and " + std::to_string(v.size()) + ")");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    if (!std::isfinite(t[i]) || !std::isfinite(v[i]))
      throw InputError(std::string(fn) + ": t" + at + " or " + name + at + " is not finite");
    if (i > 0 && !(t[i] > t[i - 1]))
      throw InputError(std::string(fn) + ": t" + at + " = " + format_double(t[i]) + " s does not increase (t" +
                       "[" + std::to_string(i - 1) + "] = " + format_double(t[i - 1]) + " s)");
  }
}

}  // namespace

std::vector<double> lee_radok_loading(const std::vector<double>& t, const std::vector<double>& P_H,
                                      const RelaxationLaw& law) {
  law.validate();
  const char* fn = "lee_radok_loading";
  check_times(fn, t, P_H, "P_H");
  if (t.empty()) return {};
  if (t[0] < 0.0) throw InputError(std::string(fn) + ": t[0] = " + format_double(t[0]) + " is negative (the contact starts at t = 0)");
  double P_prev = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (P_H[i] < P_prev || (t[i] == 0.0 && P_H[i] != 0.0))
      throw InputError(std::string(fn) + ": P_H[" + std::to_string(i) + "] = " + format_double(P_H[i]) +
                       " N is below the sample before it (or not 0 at t = 0): the contact recedes, which "
                       "Lee-Radok's hereditary integral does not describe (hereditary_response follows it)");
    P_prev = P_H[i];
  }
  // The engine starts from a sample out of contact: one at t = -1 with the indentation t, which
  // crosses 0 at t = 0 and grows, so every given sample is loading.
  std::vector<double> tt{-1.0}, d{-1.0}, PH{0.0};
  std::size_t skip = 1;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] == 0.0) {  // the contact's own start: P = 0 there
      ++skip;
      continue;
    }
    tt.push_back(t[i]);
    d.push_back(t[i]);
    PH.push_back(P_H[i]);
  }
  double t_lo, t_hi;
  detail::time_scales(std::vector<double>(tt.begin() + 1, tt.end()), &t_lo, &t_hi);
  detail::HereditaryResult<double> r;
  detail::hereditary_response(tt, d, PH, detail::kernel_of(law, t_lo, std::max(t_hi, tt.back())), &r);
  std::vector<double> out(skip - 1, 0.0);
  out.insert(out.end(), r.P.begin() + 1, r.P.end());
  return out;
}

HereditaryResponse hereditary_response(const std::vector<double>& t, const std::vector<double>& delta,
                                       const std::function<double(double)>& elastic_force,
                                       const RelaxationLaw& law) {
  law.validate();
  const char* fn = "hereditary_response";
  check_times(fn, t, delta, "delta");
  if (!t.empty() && delta[0] > 0.0)
    throw InputError(std::string(fn) + ": delta[0] = " + format_double(delta[0]) +
                     " m is in contact; the history must start out of contact (delta <= 0), since the loading "
                     "before its first sample is unknown");
  std::vector<double> PH(t.size(), 0.0);
  for (std::size_t i = 0; i < t.size(); ++i)
    if (delta[i] > 0.0) {
      PH[i] = elastic_force(delta[i]);
      if (!std::isfinite(PH[i]))
        throw NumericalError(std::string(fn) + ": the elastic force at delta = " + format_double(delta[i]) +
                             " m is not finite");
    }
  double t_lo, t_hi;
  detail::time_scales(t, &t_lo, &t_hi);
  detail::HereditaryResult<double> r;
  detail::hereditary_response(t, delta, PH, detail::kernel_of(law, t_lo, t_hi), &r, true);
  return {std::move(r.P), std::move(r.d1), std::move(r.t1)};
}

}  // namespace layerjkr
