// Adhesion on a relaxing half-space (viscoelastic_adhesion.hpp, theory.md s.8a) against independent
// oracles: Maugis' closed form at every step where the law does not relax, and where the history is
// much faster or much slower than the law (the elastic contact at the instantaneous or the relaxed
// modulus); Ting's non-adhesive response (hereditary_response, written differently) as w -> 0;
// convergence under refinement of the grid and of the step; the toughening a relaxing law gives a
// retract, between its bounds; bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/tools/roots.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/maugis_dugdale.hpp"
#include "layerjkr/profile.hpp"
#include "layerjkr/viscoelastic.hpp"
#include "layerjkr/viscoelastic_adhesion.hpp"

using namespace layerjkr;

namespace {

// A 10 um bead on a 10 kPa gel with w = 10 uJ/m^2; sigma0 from Maugis' lambda.
constexpr double kR = 1e-5, kE = 1e4, kW = 1e-5, kPi = 3.14159265358979323846;
constexpr double kScaleP = kPi * kW * kR;  // JKR's pull-off is 1.5 of this
double sigma_for(double lambda, double E = kE) {
  return lambda / (2.0 * std::cbrt(kR / (kPi * kW * std::pow(4.0 * E / 3.0, 2))));
}

// From snap-in at delta = 0 to d_max in time T, then back at the same speed to d_end.
struct Triangle {
  std::vector<double> t, d;
  Triangle(double T, double d_max, double d_end, int per_leg) {
    const double v = d_max / T, T2 = T + (d_max - d_end) / v;
    const int n2 = static_cast<int>(per_leg * (T2 - T) / T);
    for (int i = 0; i <= per_leg; ++i) t.push_back(T * i / per_leg), d.push_back(v * t.back());
    for (int i = 1; i <= n2; ++i) t.push_back(T + (T2 - T) * i / n2), d.push_back(d_max - v * (t.back() - T));
  }
};

// The largest difference, over the samples in contact, between the stepper's (delta, P) and
// Maugis' elastic solution at modulus E and the stepper's own contact radius: in delta over d_max,
// in P over pi w R.
struct Misfit {
  double delta = 0.0, P = 0.0;
};
Misfit against_maugis(const RelaxingDugdaleResponse& r, const Triangle& h, double E, double sigma0, std::size_t from) {
  Misfit m;
  const double d_max = *std::max_element(h.d.begin(), h.d.end());
  for (std::size_t i = from; i < r.separated_at; ++i) {
    const auto md = maugis_dugdale_half_space(kR, E, kW, sigma0, r.a[i]);
    m.delta = std::max(m.delta, std::abs(md.delta - h.d[i]) / d_max);
    m.P = std::max(m.P, std::abs(md.P - r.P[i]) / kScaleP);
  }
  return m;
}

double lowest(const std::vector<double>& P) { return *std::min_element(P.begin(), P.end()); }

}  // namespace

TEST_CASE("A law that does not relax gives Maugis' solution at every step, to the fixed-grips jump",
          "[viscoelastic_adhesion]") {
  const auto p = make_paraboloid(kR);
  for (double lambda : {2.0, 5.0, 20.0}) {
    const double s0 = sigma_for(lambda);
    const Triangle h(1.0, 1e-6, -2e-7, 400);
    const auto r = relaxing_dugdale_response(*p, kE, RelaxationLaw{}, kW, s0, h.t, h.d);
    const Misfit m = against_maugis(r, h, kE, s0, 0);
    std::printf("elastic lambda %g: delta %.2e of d_max, P %.2e pi w R\n", lambda, m.delta, m.P);
    CHECK(m.delta < 1e-5);
    CHECK(m.P < 1e-4);
    // The branch ends at Maugis' fixed-grips point: the contact is lost within one sample of it.
    const auto fg = maugis_dugdale_fixed_grips(kR, kE, kW, s0);
    REQUIRE(fg);
    REQUIRE(r.separated_at < h.t.size());
    const double step = h.d[1] - h.d[0];
    CHECK(h.d[r.separated_at - 1] >= fg->delta - 1e-3 * step);
    CHECK(h.d[r.separated_at] <= fg->delta + 1e-3 * step);
    // The lowest force before the jump is the load-control pull-off, to the sampling's resolution.
    CHECK(lowest(r.P) / kScaleP == Approx(maugis_dugdale_pull_off(kR, kE, kW, s0).P / kScaleP).epsilon(2e-3));
  }
}

TEST_CASE("Under a cantilever a law that does not relax gives Maugis' solution, let go where dP/d delta = -k",
          "[viscoelastic_adhesion]") {
  const auto p = make_paraboloid(kR);
  const double s0 = sigma_for(5.0), k = 0.05;  // N/m: about the contact's own stiffness
  const Triangle base(1.0, 1e-6, -6e-7, 400);
  RelaxingDugdaleOptions o;
  o.cantilever_stiffness = k;
  const auto r = relaxing_dugdale_response(*p, kE, RelaxationLaw{}, kW, s0, base.t, base.d, o);
  REQUIRE(r.separated_at < base.t.size());
  double misfit_delta = 0.0, misfit_P = 0.0, lever = 0.0;
  for (std::size_t i = 0; i < r.separated_at; ++i) {
    const auto md = maugis_dugdale_half_space(kR, kE, kW, s0, r.a[i]);
    misfit_delta = std::max(misfit_delta, std::abs(md.delta - r.tip[i]) / 1e-6);
    misfit_P = std::max(misfit_P, std::abs(md.P - r.P[i]) / kScaleP);
    if (i > 0) lever = std::max(lever, std::abs(r.tip[i] + r.P[i] / k - base.d[i]) / 1e-6);  // snapped in unbent
  }
  std::printf("cantilever: delta %.2e, P %.2e pi w R, lever balance %.2e\n", misfit_delta, misfit_P, lever);
  CHECK(misfit_delta < 1e-5);
  CHECK(misfit_P < 1e-4);
  CHECK(lever < 1e-9);
  // Where Maugis' retract branch reaches dP/d delta = -k (past its lowest force), the base is at
  // z = delta + P/k: the contact is lost within one sample of it.
  double z_jump = 0.0, prev_slope = 0.0;
  for (double a = 2e-6; a > 1e-8; a *= 0.9999) {
    const auto x = maugis_dugdale_half_space(kR, kE, kW, s0, a), y = maugis_dugdale_half_space(kR, kE, kW, s0, a * 0.9999);
    const double slope = (x.P - y.P) / (x.delta - y.delta);
    if (x.P < maugis_dugdale_pull_off(kR, kE, kW, s0).P * 0.5 && slope < 0.0 && prev_slope >= -k && slope < -k) {
      z_jump = x.delta + x.P / k;
      break;
    }
    prev_slope = slope;
  }
  const double step = base.d[1] - base.d[0];
  INFO("lost between z = " << base.d[r.separated_at - 1] << " and " << base.d[r.separated_at] << " m; Maugis: " << z_jump);
  CHECK(base.d[r.separated_at - 1] >= z_jump - 1e-3 * step);
  CHECK(base.d[r.separated_at] <= z_jump + 1e-3 * step);
  // Let go, the tip is where the unbent lever holds it.
  CHECK(r.tip.back() == base.d.back());
}

TEST_CASE("Much faster than the law gives the instantaneous modulus, much slower the relaxed one",
          "[viscoelastic_adhesion]") {
  const auto p = make_paraboloid(kR);
  const double s0 = sigma_for(5.0), relaxed = 0.3;
  const Triangle h(1.0, 1e-6, -4e-7, 400);
  const auto fast = relaxing_dugdale_response(*p, kE, RelaxationLaw::standard_linear_solid(relaxed, 1e7), kW, s0, h.t, h.d);
  const Misfit mf = against_maugis(fast, h, kE, s0, 0);
  // tau 1e7 s against a 2 s history: the modulus moves by 2e-7 of itself.
  std::printf("fast: delta %.2e, P %.2e\n", mf.delta, mf.P);
  CHECK(mf.delta < 1e-5);
  CHECK(mf.P < 1e-4);
  // Much slower: after the snap-in (at the instantaneous modulus) the contact relaxes within a few
  // tau and then follows the relaxed modulus - up to the viscous stress at the crack's tip, first
  // order in tau over the time the crack takes to cross its zone (measured: 1.1e-3 of d_max and
  // 0.08 pi w R at tau = 1e-5 s, 1e-4 times that at 1e-9 s).
  Misfit slow[2];
  for (int k = 0; k < 2; ++k) {
    const double tau = k == 0 ? 1e-9 : 1e-8;
    const auto r = relaxing_dugdale_response(*p, kE, RelaxationLaw::standard_linear_solid(relaxed, tau), kW, s0, h.t, h.d);
    slow[k] = against_maugis(r, h, relaxed * kE, s0, 1);
    std::printf("slow, tau %g s: delta %.2e, P %.2e\n", tau, slow[k].delta, slow[k].P);
  }
  CHECK(slow[0].delta < 3e-7);
  CHECK(slow[0].P < 2e-5);
  CHECK(slow[1].P / slow[0].P == Approx(10.0).epsilon(0.3));
}

TEST_CASE("The step and the grid converge at second order, and the automatic step error estimate holds",
          "[viscoelastic_adhesion]") {
  const auto p = make_paraboloid(kR);
  const double s0 = sigma_for(5.0);
  const Triangle h(1.0, 1e-6, -4e-7, 200);
  const auto law = RelaxationLaw::standard_linear_solid(0.3, 0.01);
  auto run = [&](int grid, int sub) {
    RelaxingDugdaleOptions o;
    o.grid_points = grid, o.substeps = sub;
    return relaxing_dugdale_response(*p, kE, law, kW, s0, h.t, h.d, o);
  };
  auto max_diff = [](const RelaxingDugdaleResponse& x, const RelaxingDugdaleResponse& y) {
    double e = 0.0;
    for (std::size_t i = 0; i < std::min(x.separated_at, y.separated_at); ++i) e = std::max(e, std::abs(x.P[i] - y.P[i]));
    return e;
  };
  const auto g_ref = run(16001, 4);
  const double e_g1 = max_diff(run(2001, 4), g_ref), e_g2 = max_diff(run(4001, 4), g_ref);
  std::printf("grid: %.3e %.3e pi w R, ratio %.2f\n", e_g1 / kScaleP, e_g2 / kScaleP, e_g1 / e_g2);
  CHECK(e_g1 / e_g2 > 3.0);
  const auto t_ref = run(4001, 32);
  const double e_t1 = max_diff(run(4001, 2), t_ref), e_t2 = max_diff(run(4001, 4), t_ref);
  std::printf("step: %.3e %.3e pi w R, ratio %.2f\n", e_t1 / kScaleP, e_t2 / kScaleP, e_t1 / e_t2);
  CHECK(e_t1 / e_t2 > 3.0);
  const auto automatic = relaxing_dugdale_response(*p, kE, law, kW, s0, h.t, h.d);
  const double actual = max_diff(automatic, t_ref);
  std::printf("automatic: %d substeps, estimate %.3e, actual %.3e pi w R\n", automatic.substeps,
              automatic.force_error / kScaleP, actual / kScaleP);
  CHECK(automatic.converged);
  CHECK(automatic.separated_at == t_ref.separated_at);
  CHECK(actual < 2.0 * automatic.force_error);
  CHECK(automatic.force_error <= 1e-3 * std::abs(*std::max_element(automatic.P.begin(), automatic.P.end())));
}

TEST_CASE("A relaxing law toughens the retract and lowers the approach", "[viscoelastic_adhesion]") {
  const auto p = make_paraboloid(kR);
  const double s0 = sigma_for(5.0), relaxed = 0.3;
  const Triangle h(1.0, 1e-6, -4e-7, 200);
  const auto r = relaxing_dugdale_response(*p, kE, RelaxationLaw::standard_linear_solid(relaxed, 0.1), kW, s0, h.t, h.d);
  const double fast_pull = maugis_dugdale_pull_off(kR, kE, kW, s0).P, slow_pull = maugis_dugdale_pull_off(kR, relaxed * kE, kW, s0).P;
  std::printf("pull-off %.3f pi w R; elastic at E %.3f, at E_inf %.3f\n", lowest(r.P) / kScaleP, fast_pull / kScaleP,
              slow_pull / kScaleP);
  // The crack opens against a tip that has not relaxed: the pull-off is deeper than either elastic one.
  CHECK(lowest(r.P) < 2.0 * std::min(fast_pull, slow_pull));
  // Loading: below the instantaneous elastic force, above the relaxed one (at the same indentation).
  for (std::size_t i = 20; i <= 200; i += 20) {
    const double d = h.d[i];
    auto elastic_force = [&](double E) {  // Maugis' force at indentation d: bisection on its radius
      double lo = 1e-8, hi = 1e-5;
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (maugis_dugdale_half_space(kR, E, kW, s0, mid).delta < d ? lo : hi) = mid;
      }
      return maugis_dugdale_half_space(kR, E, kW, s0, lo).P;
    };
    CHECK(r.P[i] < elastic_force(kE));
    CHECK(r.P[i] > elastic_force(relaxed * kE));
  }
}

TEST_CASE("As w -> 0 the response is Ting's non-adhesive one, computed differently", "[viscoelastic_adhesion]") {
  const auto p = make_paraboloid(kR);
  const double w = 1e-10, s0 = 1e3;  // h0 = 1e-13 m
  const auto law = RelaxationLaw::standard_linear_solid(0.3, 0.2);
  const Triangle h(1.0, 1e-6, 0.0, 400);
  std::vector<double> t = h.t, d = h.d;
  const auto r = relaxing_dugdale_response(*p, kE, law, w, s0, t, d);
  std::vector<double> tt{-0.01}, dd{-1e-8};
  tt.insert(tt.end(), t.begin(), t.end()), dd.insert(dd.end(), d.begin(), d.end());
  const auto ting = hereditary_response(tt, dd, [&](double x) { return 4.0 / 3.0 * kE * std::sqrt(kR) * std::pow(x, 1.5); }, law);
  const double P_max = *std::max_element(ting.P.begin(), ting.P.end());
  double e = 0.0;
  for (std::size_t i = 0; i < t.size() && i < r.separated_at; ++i)
    if (ting.P[i + 1] > 0.02 * P_max) e = std::max(e, std::abs(r.P[i] - ting.P[i + 1]) / P_max);
  std::printf("against Ting: %.2e of the largest force\n", e);
  CHECK(e < 2e-4);
}

namespace {

// The small-scale limit (theory.md s.8a): a Dugdale zone of length eps crossed in t_c = eps/v by a
// crack opening at speed v, on a standard linear solid whose normalised creep compliance is J(t) =
// E C(t) (J(0) = 1, J(inf) = E/E_inf). The zone's end opens to h0 when eps Phi(t_c) = eps0 =
// pi w E*/(4 sigma0^2), with
//   Phi(t_c) = int_0^1 (1 - e)^-1/2 int_0^e J(t_c (e - u)) (1/2) (1 - u)^-1/2 du de,
// and the relaxed far field then releases G_inf = w (E/E_inf) / Phi(t_c). Written without the grid,
// the step or the contact: quadrature of the steady inner problem only.
struct TipKinetics {
  double ratio, tau, eps0;  // E_inf/E, the law's relaxation time [s], the instantaneous zone [m]
  double creep(double t) const {  // J(t) for psi = r + (1 - r) exp(-t/tau): retardation time tau/r
    return 1.0 / ratio - (1.0 / ratio - 1.0) * std::exp(-t * ratio / tau);
  }
  double Phi(double t_c) const {
    boost::math::quadrature::tanh_sinh<double> q;
    return q.integrate([&](double e) {
      if (e <= 0.0) return 0.0;
      const double inner = q.integrate([&](double u) { return creep(t_c * (e - u)) * 0.5 / std::sqrt(1.0 - u); }, 0.0, e);
      return inner / std::sqrt(1.0 - e);
    }, 0.0, 1.0);
  }
  // The zone's length at crack speed v [m/s], and G_inf/w.
  double zone(double v) const {
    std::uintmax_t it = 100;
    const auto r = boost::math::tools::toms748_solve([&](double eps) { return eps * Phi(eps / v) - eps0; }, eps0 * ratio * 0.5,
                                                     eps0 * 2.0, boost::math::tools::eps_tolerance<double>(40), it);
    return 0.5 * (r.first + r.second);
  }
  double toughening(double v) const { return 1.0 / (ratio * Phi(zone(v) / v)); }
};

}  // namespace

TEST_CASE("The small-scale limit: the stepped crack follows the kinetics the law and the zone imply",
          "[viscoelastic_adhesion]") {
  // Maugis' lambda = 10: the zone is 0.1-0.2 % of the contact radius (the correction to the
  // small-scale limit is 1.2-2.7 % at lambda = 5, 0.4-0.6 % at 10, 0.1-0.2 % at 20, measured). Two
  // law times put the tip's crossing time t_c = eps/v from 0.3 to 30 tau: G_inf/w from near 1 (a slow
  // tip, relaxed) towards E/E_inf = 3.3 (a fast one, glassy).
  const auto p = make_paraboloid(kR);
  const double s0 = sigma_for(10.0), ratio = 0.3;
  const double eps0 = kPi * kW * kE / (4.0 * s0 * s0);  // the API takes E* = kE directly
  const Triangle h(1.0, 1e-6, -6e-7, 1000);
  double worst = 0.0, lowest_G = 10.0, highest_G = 0.0;
  int compared = 0;
  for (double tau : {3e-5, 3e-3}) {
    const TipKinetics tip{ratio, tau, eps0};
    RelaxingDugdaleOptions o;
    o.grid_points = tau < 1e-4 ? 32001 : 16001;  // the slow tip's zone is 4x shorter: 7 points across it
    o.substeps = tau < 1e-4 ? 64 : 16;             // >= 60 steps while the tip crosses its zone
    const auto r = relaxing_dugdale_response(*p, kE, RelaxationLaw::standard_linear_solid(ratio, tau), kW, s0, h.t, h.d, o);
    const double a_max = *std::max_element(r.a.begin(), r.a.end());
    const auto speed = [&](std::size_t i) { return (r.a[i - 1] - r.a[i + 1]) / (h.t[i + 1] - h.t[i - 1]); };
    for (std::size_t i = 1100; i + 41 < r.separated_at; i += 25) {
      const double v = speed(i);
      // Steady: the crack's speed moves by less than 10 % over the 80 samples around.
      if (!(v > 0.0) || r.a[i] < 0.3 * a_max || std::abs(speed(i + 40) - speed(i - 40)) > 0.1 * v) continue;
      const double eps = r.c[i] - r.a[i];
      const double G = 2.0 * s0 * s0 * (r.c[i] * r.c[i] - r.a[i] * r.a[i]) / (kPi * r.a[i] * ratio * kE) / kW;
      const double eps_p = tip.zone(v), G_p = tip.toughening(v);
      INFO("tau " << tau << " s, sample " << i << ": v " << v << " m/s, t_c/tau " << eps / v / tau << ", eps " << eps
                  << " m (small-scale " << eps_p << "), G_inf/w " << G << " (" << G_p << ")");
      CHECK(std::abs(eps / eps_p - 1.0) < 0.015);
      CHECK(std::abs(G / G_p - 1.0) < 0.015);
      worst = std::max(worst, std::abs(G / G_p - 1.0));
      lowest_G = std::min(lowest_G, G), highest_G = std::max(highest_G, G);
      ++compared;
    }
  }
  std::printf("small-scale kinetics: %d samples, G_inf/w %.2f-%.2f, largest difference %.2e\n", compared, lowest_G,
              highest_G, worst);
  CHECK(compared >= 12);
  CHECK(lowest_G < 1.5);
  CHECK(highest_G > 2.8);
}

TEST_CASE("Bad input is refused by name", "[viscoelastic_adhesion]") {
  const auto p = make_paraboloid(kR);
  const double s0 = sigma_for(5.0);
  const Triangle h(1.0, 1e-6, -4e-7, 50);
  const auto sls = RelaxationLaw::standard_linear_solid(0.3, 0.1);
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, kE, RelaxationLaw::power_law(0.2, 1.0), kW, s0, h.t, h.d), DomainError);
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, -kE, sls, kW, s0, h.t, h.d), DomainError);
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, kE, sls, 0.0, s0, h.t, h.d), DomainError);
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, kE, sls, kW, std::nan(""), h.t, h.d), DomainError);
  std::vector<double> t = h.t;
  t[3] = t[2];
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, kE, sls, kW, s0, t, h.d), InputError);
  std::vector<double> far = h.d;
  for (double& x : far) x -= 1e-6;  // starts a micrometre above the surface: nothing snaps in
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, kE, sls, kW, s0, h.t, far), InputError);
  Triangle twice(1.0, 1e-6, -4e-7, 50);
  for (int i = 0; i < 20; ++i) twice.t.push_back(twice.t.back() + 0.02), twice.d.push_back(twice.d.back() + 1e-7);
  CHECK_THROWS_WITH(relaxing_dugdale_response(*p, kE, sls, kW, s0, twice.t, twice.d),
                    Catch::Contains("forming it again is not modelled"));
  RelaxingDugdaleOptions o;
  o.grid_points = 10;
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, kE, sls, kW, s0, h.t, h.d, o), DomainError);
  o = {};
  o.tolerance = 0.0;
  CHECK_THROWS_AS(relaxing_dugdale_response(*p, kE, sls, kW, s0, h.t, h.d, o), DomainError);
}
