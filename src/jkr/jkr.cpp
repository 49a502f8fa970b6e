#include "layerjkr/jkr.hpp"

#include <cmath>

#include <boost/math/constants/constants.hpp>

#include "jkr/jkr_transform.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {
constexpr double kPi = boost::math::constants::pi<double>();

void require_w(const char* fn, double w) { detail::require_non_negative(fn, "w", w); }
}  // namespace

AdhesiveState jkr_transform(const NonAdhesiveState& h, double w) {
  require_w("jkr_transform", w);
  AdhesiveState s{h.a, h.a, h.P_H, h.delta_H, h};
  if (w == 0.0) return s;
  if (!(h.S > 0.0) || !std::isfinite(h.S)) throw DomainError("jkr_transform", "S", h.S, "> 0");
  if (!(h.dS_da > 0.0) || !std::isfinite(h.dS_da))
    throw DomainError("jkr_transform", "dS/da", h.dS_da,
                      "> 0 (the transform needs a stiffness that grows with a)");
  detail::jkr_from_state(h.a, h.P_H, h.delta_H, h.S, h.dS_da, w, &s.delta, &s.P);
  return s;
}

namespace {
AdhesiveState explicit_two_term(const char* fn, const Profile& p, double K, double G, double w,
                                double a) {
  detail::require_positive(fn, "K", K);
  detail::require_finite(fn, "G", G);
  require_w(fn, w);
  p.require_contact_radius(fn, a);
  const ProfileDerivatives d = p.derivatives(a);
  const double root = std::sqrt(2.0 * w / K);
  const double bracket = a * a * d.f - 2.0 * p.moment(a);
  const double g_delta = G == 0.0 ? 0.0 : (G / K) * (d.d2f + d.df / a);
  const double g_force = G == 0.0 ? 0.0 : (G * a / K) * (d.df - a * d.d2f);
  AdhesiveState s;
  s.a = a;
  s.c = a;
  s.hertz = {a, kPi * K * (bracket + g_force), d.f - g_delta, kPi * K * a * a, 2.0 * kPi * K * a};
  s.delta = d.f - g_delta - root;
  s.P = kPi * K * (bracket + g_force - a * a * root);
  return s;
}
}  // namespace

AdhesiveState jkr_leading_order(const Profile& p, double K, double w, double a) {
  return explicit_two_term("jkr_leading_order", p, K, 0.0, w, a);
}

AdhesiveState jkr_two_term(const Profile& p, double K, double G, double w, double a) {
  return explicit_two_term("jkr_two_term", p, K, G, w, a);
}

}  // namespace layerjkr
