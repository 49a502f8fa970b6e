// The explicit JKR transform (19) against closed forms and the explicit (42), (50)-(51).
#include <catch2/catch.hpp>

#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/model.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

TEST_CASE("classical JKR on a half-space: P(a) and delta(a) in closed form", "[jkr]") {
  const double E = 1.5e6, nu = 0.45, R = 5e-3, w = 0.04, Es = E / (1 - nu * nu);
  const auto model = make_half_space(make_paraboloid(R), E, nu);
  for (double a : {1e-6, 3e-5, 1e-4, 4e-4, 2e-3}) {
    const AdhesiveState s = jkr_transform(model->state(a), w);
    const double P = 4 * Es * a * a * a / (3 * R) - std::sqrt(8 * M_PI * w * Es * a * a * a);
    const double delta = a * a / R - std::sqrt(2 * M_PI * w * a / Es);
    INFO("a=" << a);
    CHECK(rel_err(s.P, P) < 1e-12);
    CHECK(rel_err(s.delta, delta) < 1e-12);
  }
}

TEST_CASE("explicit leading-order (42) and two-term (50)-(51) equal the generic transform",
          "[jkr]") {
  const double K = 4e10, w = 0.07;
  for (const auto& np : test::profile_zoo()) {
    for (double G : {0.0, -28.8, 35.0}) {
      const auto model = G == 0.0 ? make_winkler(np.profile, K) : make_two_term(np.profile, K, G);
      for (double a : np.radii) {
        const AdhesiveState generic = jkr_transform(model->state(a), w);
        const AdhesiveState expl = G == 0.0 ? jkr_leading_order(*np.profile, K, w, a)
                                            : jkr_two_term(*np.profile, K, G, w, a);
        INFO(np.name << " G=" << G << " a=" << a);
        CHECK(rel_err(expl.P, generic.P) < 1e-12);
        CHECK(rel_err(expl.delta, generic.delta) < 1e-12);
        // (42): the adhesive shift of delta is sqrt(2w/K) for every profile and order.
        CHECK(rel_err(generic.hertz.delta_H - generic.delta, std::sqrt(2 * w / K)) < 1e-13);
      }
    }
  }
}

TEST_CASE("w = 0 reproduces the non-adhesive state exactly", "[jkr]") {
  for (const auto& np : test::profile_zoo()) {
    const auto model = make_full_foundation(np.profile, 4e10, 35.0);
    for (double a : np.radii) {
      const NonAdhesiveState h = model->state(a);
      const AdhesiveState s = jkr_transform(h, 0.0);
      CHECK(s.P == h.P_H);
      CHECK(s.delta == h.delta_H);
      // The explicit form groups the terms differently, so it agrees to rounding only.
      CHECK(rel_err(jkr_two_term(*np.profile, 4e10, -3.0, 0.0, a).P,
                    make_two_term(np.profile, 4e10, -3.0)->state(a).P_H) < 1e-14);
    }
  }
}

TEST_CASE("the adhesive correction vanishes like sqrt(w) as w -> 0", "[jkr]") {
  const auto model = make_half_space(make_sphere(1e-3), 1e6, 0.3);
  const NonAdhesiveState h = model->state(2e-4);
  double previous = 0.0;
  for (double w : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    const AdhesiveState s = jkr_transform(h, w);
    // P_H - P cancels ~6 digits at w = 1e-12 (the shift is 1e-6 of P_H here).
    const double shift = h.P_H - s.P;
    if (previous > 0.0) CHECK(rel_err(previous / shift, 10.0) < 1e-8);
    previous = shift;
  }
}

TEST_CASE("jkr_transform and the explicit forms reject invalid input", "[jkr][errors]") {
  const NonAdhesiveState ok{1e-4, 1.0, 1e-6, 10.0, 1e5};
  CHECK_THROWS_WITH(jkr_transform(ok, -0.1), Catch::Contains("w = -0.1"));
  CHECK_THROWS_AS(jkr_transform(ok, NAN), DomainError);
  CHECK_THROWS_AS(jkr_transform(ok, INFINITY), DomainError);
  NonAdhesiveState flat = ok;
  flat.dS_da = 0.0;
  CHECK_THROWS_WITH(jkr_transform(flat, 0.1), Catch::Contains("dS/da = 0"));
  CHECK_NOTHROW(jkr_transform(flat, 0.0));  // no adhesion: S' is not needed
  NonAdhesiveState soft = ok;
  soft.S = -1.0;
  CHECK_THROWS_WITH(jkr_transform(soft, 0.1), Catch::Contains("S = -1"));
  const auto p = make_paraboloid(1e-2);
  CHECK_THROWS_WITH(jkr_leading_order(*p, 0.0, 0.1, 1e-4), Catch::Contains("jkr_leading_order") && Catch::Contains("K = 0"));
  CHECK_THROWS_WITH(jkr_two_term(*p, 1e10, NAN, 0.1, 1e-4), Catch::Contains("jkr_two_term") && Catch::Contains("G = nan"));
  CHECK_THROWS_WITH(jkr_two_term(*p, 1e10, 1.0, 0.1, -1e-4), Catch::Contains("contact radius a = -0.0001"));
}
