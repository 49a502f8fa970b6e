// The closed-form paraboloid specialisation the fit uses must be the general two-term
// formula for f = r^2/(2R), on double and on Jets (values and derivatives).
#include <catch2/catch.hpp>

#include <ceres/jet.h>

#include "models/state_formulas.hpp"
#include "support/test_support.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using layerjkr::detail::ProfileAt;
using layerjkr::detail::StateOf;
using test::rel_err;

namespace {
template <class T>
ProfileAt<T> paraboloid_at(const T& a, const T& R) {
  return {a * a / (2.0 * R), a / R, T(1.0) / R, a * a * a * a / (8.0 * R)};
}
}  // namespace

TEST_CASE("two_term_paraboloid_state is two_term_state for a paraboloid", "[models][formulas]") {
  for (double G : {-30.0, 0.0, 12.0}) {
    const double a = 3e-4, R = 1e-2, K = 4e10;
    const StateOf<double> g = layerjkr::detail::two_term_state(a, paraboloid_at(a, R), K, G);
    const StateOf<double> c = layerjkr::detail::two_term_paraboloid_state(a, R, K, G);
    INFO("G=" << G);
    CHECK(rel_err(c.P_H, g.P_H) < 1e-14);
    CHECK(rel_err(c.delta_H, g.delta_H) < 1e-14);
    CHECK(rel_err(c.S, g.S) < 1e-15);
    CHECK(rel_err(c.dS_da, g.dS_da) < 1e-15);
  }
  using J = ceres::Jet<double, 4>;  // slots: a, R, K, G
  const J a(3e-4, 0), R(1e-2, 1), K(4e10, 2), G(-30.0, 3);
  const StateOf<J> g = layerjkr::detail::two_term_state(a, paraboloid_at(a, R), K, G);
  const StateOf<J> c = layerjkr::detail::two_term_paraboloid_state(a, R, K, G);
  for (int k = 0; k < 4; ++k) {
    INFO("slot " << k);
    CHECK(c.P_H.v[k] == Approx(g.P_H.v[k]).epsilon(1e-12).margin(1e-30));
    CHECK(c.delta_H.v[k] == Approx(g.delta_H.v[k]).epsilon(1e-12).margin(1e-30));
  }
}
