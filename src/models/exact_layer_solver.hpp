// Internal: what the exact layer's Nystrom solve yields, shared by the solver
// (exact_layer.cpp) and the per-(nu, base, d) power-law tables (exact_power_law_table.cpp).
#pragma once

#include "layerjkr/contact.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/profile.hpp"

namespace layerjkr::detail {

// The flat-punch solution phi0 and the profile's phi_f: their integrals over [0, a/h] (in
// units of h) and their values at the edge. A state is a closed form in these.
struct ExactMoments {
  double int0 = 0.0, intf = 0.0, end0 = 0.0, endf = 0.0;
};

// delta_H = phi_f(a)/phi0(a), S = 2E* h int phi0, P_H = 2E* h (delta_H int phi0 - int phi_f),
// S' = 2E* phi0(a)^2 (docs/theory.md s.4): no differentiation anywhere.
inline HertzState exact_state_from(const ExactMoments& mo, double a, double h, double E_star) {
  HertzState s;
  s.a = a;
  s.delta_H = mo.endf / mo.end0;
  s.S = 2.0 * E_star * h * mo.int0;
  s.P_H = 2.0 * E_star * h * (s.delta_H * mo.int0 - mo.intf);
  s.dS_da = 2.0 * E_star * mo.end0 * mo.end0;
  return s;
}

// One Nystrom solve at a/h = rho with the kernel's options (no range checks).
ExactMoments exact_moments(const ExactLayerKernel& kernel, const Profile& profile, double rho);

}  // namespace layerjkr::detail
