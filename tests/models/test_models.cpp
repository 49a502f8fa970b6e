// Non-adhesive models against independent oracles.
#include <catch2/catch.hpp>

#include <cmath>

#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/bessel.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/model.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

// A bonded PDMS-like film: nu = 0.3 gives G < 0, nu = 0.2 gives G > 0.
const ThinLayerConstants kNegG = thin_layer_constants({3e6, 0.3, 1e-4, Base::bonded});
const ThinLayerConstants kPosG = thin_layer_constants({3e6, 0.2, 1e-4, Base::bonded});

struct NamedModel {
  std::string name;
  ContactModelPtr closed;
  ContactModelPtr ode;  // the same foundation by the ODE route (null if none)
};

std::vector<NamedModel> foundation_models(const ProfilePtr& p) {
  return {
      {"winkler", make_winkler(p, kNegG.K), make_ode_foundation(p, kNegG.K, 0.0, FoundationKind::asymptotic)},
      {"two_term G<0", make_two_term(p, kNegG.K, kNegG.G),
       make_ode_foundation(p, kNegG.K, kNegG.G, FoundationKind::asymptotic)},
      {"two_term G>0", make_two_term(p, kPosG.K, kPosG.G),
       make_ode_foundation(p, kPosG.K, kPosG.G, FoundationKind::asymptotic)},
      {"full lam*a~40", make_full_foundation(p, kPosG.K, kPosG.G),
       make_ode_foundation(p, kPosG.K, kPosG.G, FoundationKind::full)},
      {"full lam*a~1", make_full_foundation(p, 1e10, 1e10 * 1e-6),
       make_ode_foundation(p, 1e10, 1e10 * 1e-6, FoundationKind::full)},
  };
}

// d/da by 6th-order differences in ln a (Boost's step is absolute, so never difference
// in a itself at sub-millimetre radii).
template <class F>
double derivative(F f, double a) {
  auto g = [&](double x) { return f(std::exp(x)); };
  return boost::math::differentiation::finite_difference_derivative<decltype(g), double, 6>(
             g, std::log(a)) / a;
}

}  // namespace

TEST_CASE("S = dP_H/d delta_H and S' = dS/da for every model and profile", "[models]") {
  for (const auto& np : test::profile_zoo()) {
    std::vector<NamedModel> models = foundation_models(np.profile);
    models.push_back({"half_space", make_half_space(np.profile, 3e6, 0.3), nullptr});
    for (const auto& m : models) {
      for (double a : np.radii) {
        INFO(np.name << " / " << m.name << " a=" << a);
        const NonAdhesiveState s = m.closed->state(a);
        const double dP = derivative([&](double x) { return m.closed->state(x).P_H; }, a);
        const double dd = derivative([&](double x) { return m.closed->state(x).delta_H; }, a);
        const double dS = derivative([&](double x) { return m.closed->state(x).S; }, a);
        CHECK(rel_err(dP / dd, s.S) < 1e-7);
        CHECK(rel_err(dS, s.dS_da) < 1e-8);
        CHECK(s.S > 0.0);
        CHECK(s.dS_da > 0.0);
      }
    }
  }
}

TEST_CASE("ODE route agrees with the closed forms to 1e-9", "[models][ode]") {
  for (const auto& np : test::profile_zoo()) {
    for (const auto& m : foundation_models(np.profile)) {
      for (double a : np.radii) {
        INFO(np.name << " / " << m.name << " a=" << a);
        const NonAdhesiveState c = m.closed->state(a), o = m.ode->state(a);
        CHECK(rel_err(o.P_H, c.P_H) < 1e-9);
        CHECK(rel_err(o.delta_H, c.delta_H) < 1e-12);
        CHECK(rel_err(o.S, c.S) < 1e-13);
        CHECK(rel_err(o.dS_da, c.dS_da) < 1e-13);
      }
    }
  }
}

TEST_CASE("two-term force integrates the pressure (44): the corrected (47)", "[models][erratum]") {
  // P_H = 2 pi int_0^a [K (delta_H - f) + G (f'' + f'/r)] r dr, evaluated by quadrature.
  for (const auto& np : test::profile_zoo()) {
    const double K = kNegG.K, G = kNegG.G;
    const auto model = make_two_term(np.profile, K, G);
    for (double a : np.radii) {
      const double delta = model->state(a).delta_H;
      auto pressure_r = [&](double r) {
        const ProfileDerivatives d = np.profile->derivatives(r);
        return (K * (delta - d.f) + G * d.d2f) * r + G * d.df;
      };
      // Quadrature in t = r/a, split at table knots (the third derivative jumps there).
      boost::math::quadrature::tanh_sinh<double> ts;
      std::vector<double> cuts{0.0};
      for (double b : np.profile->breakpoints(a)) cuts.push_back(b / a);
      cuts.push_back(1.0);
      double integral = 0.0;
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
        integral += a * ts.integrate([&](double t) { return pressure_r(a * t); }, cuts[i],
                                     cuts[i + 1], 1e-14);
      INFO(np.name << " a=" << a);
      CHECK(rel_err(model->state(a).P_H, 2 * M_PI * integral) < 1e-11);
      // The printed (47) has pi G a [2 f' - a f''] and is off by pi G a f'(a).
      const double printed = model->state(a).P_H + M_PI * G * a * np.profile->derivatives(a).df;
      CHECK(rel_err(printed, 2 * M_PI * integral) > 1e-6);
    }
  }
}

TEST_CASE("paraboloid two-term force is independent of G", "[models][erratum]") {
  const auto p = make_paraboloid(1e-2);
  const double K = 4e10, R = 1e-2;
  for (double a : {1e-5, 3e-4, 2e-3}) {
    const double winkler = make_winkler(p, K)->state(a).P_H;
    CHECK(rel_err(winkler, M_PI * K * std::pow(a, 4) / (4 * R)) < 1e-14);
    for (double G : {-50.0, -1e-3, 1e-3, 50.0}) {
      const NonAdhesiveState s = make_two_term(p, K, G)->state(a);
      CHECK(rel_err(s.P_H, winkler) < 1e-14);
      CHECK(rel_err(s.delta_H, a * a / (2 * R) - 2 * G / (K * R)) < 1e-13);
    }
  }
}

TEST_CASE("G -> 0 is continuous between Winkler, two-term and the full foundation", "[models]") {
  for (const auto& np : test::profile_zoo()) {
    const double K = 4e10;
    const auto winkler = make_winkler(np.profile, K);
    for (double a : np.radii) {
      const NonAdhesiveState w = winkler->state(a);
      double previous_two = 1.0, previous_full = 1.0;
      for (double G : {1e-2, 1e-4, 1e-6}) {
        const NonAdhesiveState tp = make_two_term(np.profile, K, G)->state(a);
        const NonAdhesiveState tn = make_two_term(np.profile, K, -G)->state(a);
        const NonAdhesiveState fu = make_full_foundation(np.profile, K, G)->state(a);
        const double e_two = std::max(rel_err(tp.P_H, w.P_H), rel_err(tn.delta_H, w.delta_H));
        const double e_full = std::max(rel_err(fu.P_H, w.P_H), rel_err(fu.delta_H, w.delta_H));
        INFO(np.name << " a=" << a << " G=" << G << " two=" << e_two << " full=" << e_full);
        CHECK(e_two <= previous_two);
        CHECK(e_full < previous_full);
        // S_full - S_winkler = 2 pi G lam a K1/K0 ~ S_winkler * 2 sqrt(G/K)/a (1 + 1/(2 lam a))
        CHECK(rel_err(fu.S, w.S) < 2.2 * std::sqrt(G / K) / a);
        previous_two = e_two + 1e-15;
        previous_full = e_full;
      }
      CHECK(previous_full < 1e-3);
    }
  }
}

TEST_CASE("full foundation force equals the spring reaction over the whole plane", "[models]") {
  const double K = 1e10, G = 1e4;  // lam = 1000 1/m
  const double lam = std::sqrt(K / G);
  for (const auto& np : test::profile_zoo()) {
    const auto model = make_full_foundation(np.profile, K, G);
    for (double a : np.radii) {
      const NonAdhesiveState s = model->state(a);
      // Dimensionless variables: t = r/a inside, u = lam (r - a) outside.
      boost::math::quadrature::tanh_sinh<double> ts;
      const double inner = a * a * ts.integrate(
          [&](double t) { return K * (s.delta_H - np.profile->f(a * t)) * t; }, 0.0, 1.0, 1e-14);
      const double c = s.delta_H - np.profile->f(a);
      const double k0a = boost::math::cyl_bessel_k(0, lam * a);
      boost::math::quadrature::exp_sinh<double> tail;
      const double outer = tail.integrate([&](double u) {
        return K * c * boost::math::cyl_bessel_k(0, lam * a + u) / k0a * (a + u / lam) / lam;
      });
      INFO(np.name << " a=" << a);
      CHECK(rel_err(s.P_H, 2 * M_PI * (inner + outer)) < 1e-10);
      // Slope continuity: -w'(a+) = f'(a).
      const double w_slope = c * lam * boost::math::cyl_bessel_k(1, lam * a) / k0a;
      CHECK(rel_err(w_slope, np.profile->derivatives(a).df) < 1e-12);
    }
  }
}

TEST_CASE("full foundation stays finite for huge lambda*a (scaled Bessel ratio)", "[models]") {
  const auto p = make_paraboloid(1e-2);
  const double K = 1e20, G = 1e-6;  // lam a ~ 1e10: unscaled K0 underflows
  const NonAdhesiveState s = make_full_foundation(p, K, G)->state(1e-3);
  const NonAdhesiveState w = make_winkler(p, K)->state(1e-3);
  CHECK(std::isfinite(s.P_H));
  CHECK(rel_err(s.P_H, w.P_H) < 1e-8);
}

TEST_CASE("half-space: Sneddon form equals Galin's eq. (21) and the closed forms", "[models]") {
  const double E = 3e6, nu = 0.3, Es = E / (1 - nu * nu);
  boost::math::quadrature::tanh_sinh<double> ts;
  for (const auto& np : test::profile_zoo()) {
    const auto model = make_half_space(np.profile, E, nu);
    for (double a : np.radii) {
      auto lap_r = [&](double r) {  // r * (f'' + f'/r)
        const ProfileDerivatives d = np.profile->derivatives(r);
        return r * d.d2f + d.df;
      };
      std::vector<double> cuts = np.profile->breakpoints(a);  // f'' has kinks at knots
      cuts.insert(cuts.begin(), 0.0);
      cuts.push_back(a);
      double P = 0.0, delta = 0.0;
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        P += 2 * Es * ts.integrate([&](double r) { return lap_r(r) * std::sqrt(a * a - r * r); },
                                   cuts[i], cuts[i + 1], 1e-13);
        delta += ts.integrate([&](double r) { return lap_r(r) * std::acosh(a / r); }, cuts[i],
                              cuts[i + 1], 1e-13);
      }
      const NonAdhesiveState s = model->state(a);
      INFO(np.name << " a=" << a);
      CHECK(rel_err(s.P_H, P) < 1e-9);
      CHECK(rel_err(s.delta_H, delta) < 1e-9);
    }
  }
  const double R = 1e-2, a = 7e-4, cot = 1 / std::tan(1.2);
  const NonAdhesiveState hertz = make_half_space(make_paraboloid(R), E, nu)->state(a);
  CHECK(rel_err(hertz.P_H, 4 * Es * a * a * a / (3 * R)) < 1e-15);
  CHECK(rel_err(hertz.delta_H, a * a / R) < 1e-15);
  const NonAdhesiveState cone = make_half_space(make_cone(1.2), E, nu)->state(a);
  CHECK(rel_err(cone.P_H, M_PI / 2 * Es * a * a * cot) < 1e-15);
  CHECK(rel_err(cone.delta_H, M_PI / 2 * a * cot) < 1e-15);
}

TEST_CASE("thin-layer constants are the small-u expansion of the exact layer kernel", "[models][layer]") {
  // p_hat / w_hat = (E*/2h) u / L(u) = K + G xi^2 to second order in u = xi h.
  for (double nu : {-0.5, 0.0, 0.2, 0.25, 0.3, 0.4, 0.45}) {
    const double E = 2e6, h = 3e-5, kappa = 3 - 4 * nu, Es = E / (1 - nu * nu);
    auto c = [&](double u) {
      const double L = (2 * kappa * std::sinh(2 * u) - 4 * u) /
                       (2 * kappa * std::cosh(2 * u) + 4 * u * u + 1 + kappa * kappa);
      return u / L;
    };
    // c(u) = c0 + c2 u^2 + c4 u^4: three samples, eliminate c4.
    const double u1 = 0.01, u2 = 0.02, u3 = 0.03;
    const double d12 = (c(u2) - c(u1)) / (u2 * u2 - u1 * u1);
    const double d13 = (c(u3) - c(u1)) / (u3 * u3 - u1 * u1);
    const double c4 = (d13 - d12) / (u3 * u3 - u2 * u2);
    const double c2 = d12 - c4 * (u1 * u1 + u2 * u2);
    const double c0 = c(u1) - c2 * u1 * u1 - c4 * u1 * u1 * u1 * u1;
    const ThinLayerConstants k = thin_layer_constants({E, nu, h, Base::bonded});
    INFO("nu=" << nu);
    CHECK(rel_err(k.K, Es * c0 / (2 * h)) < 1e-8);
    if (nu == 0.0 || nu == 0.25)
      CHECK(std::abs(k.G) < 1e-20);
    else
      CHECK(rel_err(k.G, Es * c2 * h / 2) < 1e-5);
  }
  // Frictionless base: L = u/2 + O(u^5), so K = E*/h and no h^2 term.
  const ThinLayerConstants f = thin_layer_constants({2e6, 0.49, 1e-4, Base::frictionless});
  CHECK(rel_err(f.K, 2e6 / (1 - 0.49 * 0.49) / 1e-4) < 1e-15);
  CHECK(f.G == 0.0);
  CHECK(f.warnings.empty());
}

TEST_CASE("near-incompressible bonded layers warn - invalid layers throw", "[models][layer][errors]") {
  CHECK(thin_layer_constants({1e6, 0.45, 1e-4, Base::bonded}).warnings.empty());
  const auto w = thin_layer_constants({1e6, 0.49, 1e-4, Base::bonded}).warnings;
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Catch::Contains("non-uniform") && Catch::Contains("3.9"));
  CHECK_THROWS_WITH(thin_layer_constants({1e6, 0.5, 1e-4, Base::bonded}), Catch::Contains("nu = 0.5"));
  CHECK_THROWS_AS(thin_layer_constants({1e6, 0.5, 1e-4, Base::frictionless}), DomainError);
  CHECK_THROWS_WITH(thin_layer_constants({1e6, -1.0, 1e-4, Base::bonded}), Catch::Contains("nu = -1"));
  CHECK_THROWS_WITH(thin_layer_constants({1e6, 0.3, 0.0, Base::bonded}), Catch::Contains("h = 0"));
  CHECK_THROWS_WITH(thin_layer_constants({-1e6, 0.3, 1e-4, Base::bonded}), Catch::Contains("E = -1000000"));
  CHECK_THROWS_AS(thin_layer_constants({NAN, 0.3, 1e-4, Base::bonded}), DomainError);
  const auto p = make_paraboloid(1e-2);
  CHECK_THROWS_WITH(make_full_foundation(p, 1e10, -3.0), Catch::Contains("G (or tension T) = -3") && Catch::Contains("asymptotic"));
  CHECK_THROWS_AS(make_full_foundation(p, 1e10, 0.0), DomainError);
  CHECK_THROWS_AS(make_winkler(p, 0.0), DomainError);
  CHECK_THROWS_AS(make_two_term(p, 1e10, NAN), DomainError);
  CHECK_THROWS_AS(make_half_space(p, 1e6, 0.6), DomainError);
  CHECK_THROWS_AS(make_ode_foundation(p, 1e10, -1.0, FoundationKind::full), DomainError);
  CHECK_THROWS_AS(make_ode_foundation(p, 1e10, 1.0, FoundationKind::full, 0.0), DomainError);
  CHECK_THROWS_WITH(make_winkler(make_sphere(1e-3), 1e10)->state(1e-3), Catch::Contains("contact radius a = 0.001"));
  CHECK_THROWS_AS(make_winkler(p, 1e10)->state(0.0), DomainError);
  CHECK_THROWS_AS(make_winkler(nullptr, 1e10), Error);
}
