// Maugis-Dugdale and DMT for any profile on the half-space, layers and stacks
// (adhesion/dugdale_solver): against Maugis' published half-space equations and against the
// three limits - a thick layer is a half-space, lambda -> infinity is the JKR transform of the
// exact layer, lambda -> 0 is DMT.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/minima.hpp>

#include "adhesion/dugdale_solver.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/maugis_dugdale.hpp"
#include "support/stack_media.hpp"
#include "support/test_support.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;
using detail::DugdaleSolver;
using test::rel_err;

namespace {

constexpr double kPi = boost::math::constants::pi<double>();

// A sphere of R = 10 um, E* = 1 MPa, w = 50 mJ/m^2 and the Maugis units.
struct Case {
  double R = 1e-5, E_star = 1e6, w = 0.05;
  double K() const { return 4.0 * E_star / 3.0; }
  double length() const { return std::cbrt(kPi * w * R * R / K()); }
  double approach() const { return std::cbrt(kPi * kPi * w * w * R / (K() * K())); }
  double sigma0(double lambda) const { return lambda / 2.0 * std::cbrt(kPi * w * K() * K() / R); }
};

std::shared_ptr<const ExactLayerKernel> layer_kernel(double E, double nu, double h, Base base = Base::bonded) {
  ElasticLayer layer{E, nu, h, base};
  return std::make_shared<const ExactLayerKernel>(layer);
}

}  // namespace

// The general-profile path (Sneddon's integrals, the gap by quadrature in theta) against the
// closed form of maugis_dugdale.hpp (Maugis 1992's equations, checked there against a 50-digit
// mpmath solution): two different routes to the same state.
TEST_CASE("half-space Maugis-Dugdale reproduces Maugis 1992 for a paraboloid", "[dugdale]") {
  const Case k;
  const DugdaleSolver solver(make_paraboloid(k.R), k.E_star);
  for (double lambda : {0.1, 1.0, 10.0})
    for (double A : {0.0, 0.3, 1.0, 2.0}) {
      const MaugisPoint ref = maugis_point(lambda, A);
      const AdhesiveState s = solver.maugis_dugdale(A * k.length(), k.w, k.sigma0(lambda));
      CHECK(rel_err(maugis_lambda(k.R, k.E_star, k.w, k.sigma0(lambda)), lambda) < 1e-14);
      const double P_bar = s.P / (kPi * k.w * k.R), Delta = s.delta / k.approach();
      INFO("lambda = " << lambda << ", A = " << A << ": P " << P_bar << " vs " << ref.P << ", Delta " << Delta
                       << " vs " << ref.Delta << ", c " << s.c / k.length() << " vs " << ref.C);
      CHECK(std::abs(P_bar - ref.P) < 1e-10 * (1.0 + std::abs(ref.P)));
      CHECK(std::abs(Delta - ref.Delta) < 1e-10 * (1.0 + std::abs(ref.Delta)));
      CHECK(rel_err(s.c / k.length(), ref.C) < 1e-10);
    }
}

TEST_CASE("half-space Maugis-Dugdale pull-off by the general path matches maugis_pull_off", "[dugdale]") {
  const Case k;
  const DugdaleSolver solver(make_paraboloid(k.R), k.E_star);
  for (double lambda : {0.1, 1.0, 10.0}) {
    const MaugisPoint ref = maugis_pull_off(lambda);
    auto load = [&](double A) { return solver.maugis_dugdale(A * k.length(), k.w, k.sigma0(lambda)).P; };
    std::uintmax_t it = 200;
    const auto min = boost::math::tools::brent_find_minima(load, 0.5 * ref.A, 2.0 * ref.A, 40, it);
    INFO("lambda = " << lambda << ": A " << min.first << " vs " << ref.A << ", Pbar "
                     << min.second / (kPi * k.w * k.R) << " vs " << ref.P);
    CHECK(rel_err(min.second / (kPi * k.w * k.R), ref.P) < 1e-10);
    CHECK(rel_err(min.first, ref.A) < 1e-5);  // a minimum: A to sqrt of P's precision
  }
}

TEST_CASE("a thick layer's Maugis-Dugdale state tends to the half-space's", "[dugdale]") {
  // At fixed a the layer differs from the half-space, to first order in a/h, only by the
  // rigid shift of the approach that the kernel's constant part Ft(0) brings:
  // delta_layer = delta_half - Ft(0) P / (pi E* h). P agrees to O((a/h)^3) (measured: 1.7e-8 at
  // a/h = 2.3e-3, 1.7e-5 at 2.3e-2); the shifted delta to O((a/h)^2).
  const Case k;
  const DugdaleSolver half(make_paraboloid(k.R), k.E_star);
  for (double h : {1e-3, 1e-4}) {
    const auto kernel = layer_kernel(k.E_star * (1 - 0.09), 0.3, h);
    const DugdaleSolver layer(make_paraboloid(k.R), kernel);
    const double a = 1.0 * k.length(), eps = a / h;  // 2.3e-3, 2.3e-2
    for (double lambda : {0.3, 3.0}) {
      const AdhesiveState s = layer.maugis_dugdale(a, k.w, k.sigma0(lambda));
      const AdhesiveState r = half.maugis_dugdale(a, k.w, k.sigma0(lambda));
      const double shifted = r.delta - kernel->kernel(0.0) * r.P / (kPi * k.E_star * h);
      INFO("a/h = " << eps << ", lambda = " << lambda << ": P " << rel_err(s.P, r.P) << ", delta "
                    << rel_err(s.delta, r.delta) << ", shifted delta " << rel_err(s.delta, shifted));
      CHECK(rel_err(s.P, r.P) < 2.0 * eps * eps * eps);
      CHECK(rel_err(s.c, r.c) < 2.0 * eps * eps * eps);
      CHECK(rel_err(s.delta, r.delta) < 6.0 * eps);
      CHECK(rel_err(s.delta, shifted) < 2.0 * eps * eps);
    }
  }
}

namespace {

// sigma0 for Maugis' lambda (the half-space definition with the top layer's E*), R = 100 um.
struct LayerCase {
  double R = 1e-4, E_star = 1e6, w = 0.05, h = 1e-6;
  double sigma0(double lambda) const {
    const double K = 4.0 * E_star / 3.0;
    return lambda / 2.0 * std::cbrt(kPi * w * K * K / R);
  }
};

// lambda -> infinity at fixed a: the process zone c - a shrinks like lambda^-2 and so does the
// distance to JKR. Errors are relative to JKR's adhesive parts, P_H - P and delta_H - delta
// (P itself may cross zero). Measured at lambda = 1000 (Maugis' lambda with R = 100 um and the
// top layer's E*): P 1.5e-6 .. 1.9e-5, delta 4.6e-7 .. 8.1e-6 over the ten cases below.
void check_jkr_limit(const DugdaleSolver& md, const ContactModel& model, double a, const LayerCase& k) {
  const AdhesiveState jkr = jkr_transform(model.state(a), k.w);
  const double P_adh = jkr.hertz.P_H - jkr.P, delta_adh = jkr.hertz.delta_H - jkr.delta;
  const AdhesiveState s100 = md.maugis_dugdale(a, k.w, k.sigma0(100.0));
  const AdhesiveState s1000 = md.maugis_dugdale(a, k.w, k.sigma0(1000.0));
  const double e100 = std::abs(s100.P - jkr.P) / P_adh, e1000 = std::abs(s1000.P - jkr.P) / P_adh;
  const double d1000 = std::abs(s1000.delta - jkr.delta) / delta_adh;
  INFO("a = " << a << ": P error " << e100 << " at lambda 100, " << e1000 << " at 1000; delta error " << d1000);
  CHECK(e1000 < 4e-5);
  CHECK(d1000 < 2e-5);
  CHECK(e100 / e1000 > 60.0);  // lambda^-2: 100
  CHECK(e100 / e1000 < 160.0);
  CHECK(s1000.c > a);
}

}  // namespace

TEST_CASE("lambda to infinity on a layer gives the exact layer's JKR transform", "[dugdale]") {
  const LayerCase k;
  for (double nu : {0.45, 0.5})
    for (double a_over_h : {0.5, 2.0, 10.0}) {
      ElasticLayer layer{k.E_star * (1 - nu * nu), nu, k.h, Base::bonded};
      const auto profile = make_paraboloid(k.R);
      const DugdaleSolver md(profile, std::make_shared<const ExactLayerKernel>(layer));
      check_jkr_limit(md, *make_exact_layer(profile, layer), a_over_h * k.h, k);
    }
}

TEST_CASE("lambda to infinity on a layer gives JKR for a sphere and a cone too", "[dugdale]") {
  const LayerCase k;
  ElasticLayer layer{k.E_star * (1 - 0.45 * 0.45), 0.45, k.h, Base::bonded};
  const auto kernel = std::make_shared<const ExactLayerKernel>(layer);
  for (const ProfilePtr& profile : {make_sphere(20 * k.h), make_cone(70.0 * kPi / 180.0)}) {
    INFO(profile->describe());
    check_jkr_limit(DugdaleSolver(profile, kernel), *make_exact_layer(profile, layer), 2.0 * k.h, k);
  }
}

TEST_CASE("lambda to infinity on a stack gives the stack's JKR transform", "[dugdale]") {
  const LayerCase k;
  // A soft film on a stiffer one, bonded to a half-space: two layers and a substrate.
  const LayeredMedium medium = test::on_half_space({{k.E_star * 0.75, 0.5, k.h}, {20e6, 0.3, 2 * k.h}}, 5e6, 0.4);
  const auto profile = make_paraboloid(k.R);
  const DugdaleSolver md(profile, std::make_shared<const ExactLayerKernel>(medium));
  const auto model = make_exact_layer(profile, medium);
  for (double a_over_h : {0.5, 2.0}) check_jkr_limit(md, *model, a_over_h * k.h, k);
}

TEST_CASE("lambda to zero on a layer gives DMT on the same layer", "[dugdale]") {
  // The tension's own deformation, the one thing DMT leaves out, falls linearly with lambda
  // (measured: |P_MD - P_DMT| / |P_DMT - P_H| = 7.0e-3 at a/h = 10, 2.8e-4 at a/h = 2 and 1.8e-5 at
  // a/h = 0.5, lambda 0.01, ten times more at lambda 0.1).
  const LayerCase k;
  for (double nu : {0.45, 0.5})
    for (double a_over_h : {0.5, 2.0, 10.0}) {
      ElasticLayer layer{k.E_star * (1 - nu * nu), nu, k.h, Base::bonded};
      const DugdaleSolver md(make_paraboloid(k.R), std::make_shared<const ExactLayerKernel>(layer));
      const double a = a_over_h * k.h;
      double P_gap[2], delta_gap[2], adhesion = 0.0;
      int i = 0;
      for (double lambda : {0.1, 0.01}) {
        const AdhesiveState s = md.maugis_dugdale(a, k.w, k.sigma0(lambda));
        const AdhesiveState d = md.dmt(a, k.w, k.sigma0(lambda));
        CHECK(d.delta == d.hertz.delta_H);
        CHECK(d.c > a);
        P_gap[i] = std::abs(s.P - d.P);
        delta_gap[i] = std::abs(s.delta - d.delta);
        adhesion = std::abs(d.P - d.hertz.P_H);
        ++i;
      }
      INFO("nu " << nu << ", a/h " << a_over_h << ": |dP| " << P_gap[0] << " -> " << P_gap[1] << " of "
                 << adhesion << ", |d delta| " << delta_gap[0] << " -> " << delta_gap[1]);
      CHECK(P_gap[1] < 0.01 * adhesion);
      // (nu = 0.45, a/h = 0.5: the linear term nearly vanishes; 1.6e-5 of the adhesion remains.)
      CHECK((P_gap[1] < 3e-5 * adhesion || P_gap[0] / P_gap[1] > 7.0));
      CHECK((delta_gap[1] < 1e-9 * k.h || delta_gap[0] / delta_gap[1] > 7.0));
    }
}

TEST_CASE("half-space DMT with a Dugdale law tends to P_H - 2 pi w R, and its gap is Johnson's", "[dugdale]") {
  const double R = 1e-5, E_star = 1e6, w = 0.05, a = 1e-6;
  const DugdaleSolver solver(make_paraboloid(R), E_star);
  // The Hertz gap outside the contact (Johnson, Contact Mechanics, eq. 3.42 rearranged):
  //   gap(r) = [a sqrt(r^2 - a^2) + (r^2 - 2 a^2) acos(a/r)] / (pi R).
  for (double r : {1.0001 * a, 1.5 * a, 3.0 * a, 30.0 * a}) {
    const double ref = (a * std::sqrt(r * r - a * a) + (r * r - 2 * a * a) * std::acos(a / r)) / (kPi * R);
    CHECK(std::abs(solver.non_adhesive_gap(a, r) - ref) < 1e-13 * r * r / R);
  }
  // sigma0 pi (c^2 - a^2) -> 2 pi w R with an error sigma0 pi a^2 (c^2 = 2R(h0 + delta_H) + O(a^3/c)).
  for (double sigma0 : {1e2, 1e1, 1e0}) {
    const AdhesiveState d = solver.dmt(a, w, sigma0);
    const double ref = d.hertz.P_H - 2 * kPi * w * R;
    INFO("sigma0 = " << sigma0 << ": " << d.P << " vs " << ref);
    CHECK(std::abs(d.P - ref) < 1.5 * sigma0 * kPi * a * a);
    CHECK(rel_err(d.hertz.P_H, 4 * E_star * a * a * a / (3 * R)) < 1e-13);
  }
  // a = 0: the undeformed profile's gap, f(c) = h0 exactly.
  const AdhesiveState d0 = solver.dmt(0.0, w, 1e3);
  CHECK(rel_err(d0.c * d0.c / (2 * R), w / 1e3) < 1e-10);
  CHECK(rel_err(d0.P, -kPi * 1e3 * d0.c * d0.c) < 1e-14);
}

TEST_CASE("layer Maugis-Dugdale: the gap closes at c, grows from zero at a, and the grid converges", "[dugdale]") {
  const LayerCase k;
  ElasticLayer layer{0.75e6, 0.5, k.h, Base::bonded};
  const auto profile = make_paraboloid(k.R);
  const double a = 2.0 * k.h, sigma0 = k.sigma0(1.0), h0 = k.w / sigma0;
  std::vector<AdhesiveState> by_nodes;
  for (int p : {8, 12, 16, 24}) {
    ExactLayerOptions o;
    o.points_per_panel = p;
    const DugdaleSolver md(profile, std::make_shared<const ExactLayerKernel>(layer, o));
    by_nodes.push_back(md.maugis_dugdale(a, k.w, sigma0));
  }
  const AdhesiveState& best = by_nodes.back();
  const double d8 = rel_err(by_nodes[0].P, best.P), d12 = rel_err(by_nodes[1].P, best.P),
               d16 = rel_err(by_nodes[2].P, best.P);
  INFO("P against 24 nodes: " << d8 << " (8), " << d12 << " (12), " << d16 << " (16)");
  CHECK(d16 < 1e-9);
  CHECK(d12 <= d8);
  CHECK(rel_err(by_nodes[2].delta, best.delta) < 1e-9);

  const DugdaleSolver md(profile, std::make_shared<const ExactLayerKernel>(layer));
  const detail::DugdaleEstimate e = md.maugis_dugdale_estimate(a, k.w, sigma0);
  CHECK(e.P_error < 1e-7 * std::abs(e.state.P));
  CHECK(std::abs(e.state.P - by_nodes[2].P) <= e.P_error + 1e-15 * std::abs(best.P));
  const double c = e.state.c;
  std::vector<double> radii{a};
  for (int j = 1; j <= 12; ++j) radii.push_back(a + (3.0 * c - a) * j / 12.0);
  radii.push_back(c);
  const std::vector<double> gap = md.maugis_dugdale_gap(a, k.w, sigma0, radii);
  CHECK(gap.front() == 0.0);
  CHECK(rel_err(gap.back(), h0) < 1e-9);
  for (std::size_t j = 1; j + 1 < gap.size(); ++j) CHECK(gap[j] > gap[j - 1]);
}

TEST_CASE("Dugdale solver: the adhesive disc alone (a = 0) on a layer", "[dugdale]") {
  const LayerCase k;
  ElasticLayer layer{0.75e6, 0.5, k.h, Base::bonded};
  const auto profile = make_paraboloid(k.R);
  const DugdaleSolver md(profile, std::make_shared<const ExactLayerKernel>(layer));
  const double sigma0 = k.sigma0(1.0);
  const AdhesiveState s0 = md.maugis_dugdale(0.0, k.w, sigma0);
  CHECK(s0.P < 0.0);
  CHECK(rel_err(s0.P, -kPi * sigma0 * s0.c * s0.c) < 1e-14);
  // The a -> 0 limit of the contact states.
  const AdhesiveState s1 = md.maugis_dugdale(1e-6 * k.h, k.w, sigma0);
  CHECK(rel_err(s1.P, s0.P) < 1e-5);
  CHECK(rel_err(s1.delta, s0.delta) < 1e-5);
}

TEST_CASE("Dugdale solver: w = 0 is the non-adhesive state", "[dugdale]") {
  const LayerCase k;
  const ElasticLayer layer{0.75e6, 0.45, k.h, Base::bonded};
  const auto kernel = std::make_shared<const ExactLayerKernel>(layer);
  const auto profile = make_paraboloid(k.R);
  const DugdaleSolver md(profile, kernel);
  for (double a : {0.0, 0.5 * k.h, 3.0 * k.h}) {
    const NonAdhesiveState ref = a > 0 ? kernel->state(*profile, a) : NonAdhesiveState{};
    for (const AdhesiveState& s : {md.maugis_dugdale(a, 0.0, 1e3), md.dmt(a, 0.0, 1e3)}) {
      CHECK(s.c == a);
      CHECK(std::abs(s.P - ref.P_H) <= 1e-13 * std::abs(ref.P_H));
      CHECK(std::abs(s.delta - ref.delta_H) <= 1e-13 * std::abs(ref.delta_H));
    }
  }
}

TEST_CASE("Dugdale solver: bad inputs name the parameter", "[dugdale]") {
  const DugdaleSolver half(make_sphere(1e-6), 1e9);
  CHECK_THROWS_AS(half.maugis_dugdale(-1e-9, 0.05, 1e8), DomainError);
  CHECK_THROWS_AS(half.maugis_dugdale(1e-7, -0.05, 1e8), DomainError);
  CHECK_THROWS_AS(half.maugis_dugdale(1e-7, 0.05, std::nan("")), DomainError);
  CHECK_THROWS_AS(half.dmt(2e-6, 0.05, 1e8), DomainError);  // a beyond the sphere
  CHECK_THROWS_AS(half.non_adhesive_gap(1e-7, 0.5e-7), DomainError);
  CHECK_THROWS_AS(DugdaleSolver(make_paraboloid(1.0), -1.0), DomainError);
  // h0 = w / sigma0 = 1 mm: the zone would leave the 1 um sphere.
  try {
    half.maugis_dugdale(1e-7, 0.05, 50.0);
    FAIL("no DomainError");
  } catch (const DomainError& e) {
    CHECK(e.parameter() == "sigma0");
  }
}

namespace {

// 2 pi int_0^c r p(r) dr from the pressure: r = a sin(phi) on [0, a] smooths p's square-root
// approach to -sigma0 at a; the zone adds -sigma0 pi (c^2 - a^2).
double integrated_load(const DugdaleSolver& md, double a, double w, double sigma0, double c) {
  using rule = boost::math::quadrature::gauss<double, 40>;
  std::vector<double> radii, weights;
  for (std::size_t i = 0; i < rule::abscissa().size(); ++i)
    for (double sign : {-1.0, 1.0}) {
      if (rule::abscissa()[i] == 0.0 && sign < 0) continue;  // a centre node once
      const double phi = kPi / 4 * (1.0 + sign * rule::abscissa()[i]);
      radii.push_back(a * std::sin(phi));
      weights.push_back(kPi / 4 * rule::weights()[i] * a * std::cos(phi));
    }
  const std::vector<double> p = md.maugis_dugdale_pressure(a, w, sigma0, radii);
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += 2 * kPi * radii[i] * p[i] * weights[i];
  return sum - sigma0 * kPi * (c - a) * (c + a);
}

}  // namespace

TEST_CASE("Dugdale solver: the pressure integrates to P and is continuous at a", "[dugdale]") {
  const LayerCase k;
  const auto profile = make_paraboloid(k.R);
  const Case hk;
  ElasticLayer layer{0.75e6, 0.5, k.h, Base::bonded};
  const DugdaleSolver on_layer(profile, std::make_shared<const ExactLayerKernel>(layer));
  const DugdaleSolver half(make_paraboloid(hk.R), hk.E_star);
  struct Run {
    const DugdaleSolver* md;
    double a, w, sigma0;
  };
  for (const Run& run : {Run{&on_layer, 2.0 * k.h, k.w, k.sigma0(1.0)}, Run{&on_layer, 0.5 * k.h, k.w, k.sigma0(0.3)},
                         Run{&half, hk.length(), hk.w, hk.sigma0(1.0)}}) {
    const AdhesiveState s = run.md->maugis_dugdale(run.a, run.w, run.sigma0);
    const double load = integrated_load(*run.md, run.a, run.w, run.sigma0, s.c);
    INFO("a = " << run.a << ": P " << s.P << ", integrated " << load);
    CHECK(std::abs(load - s.P) < 1e-10 * run.sigma0 * kPi * s.c * s.c);
    const std::vector<double> edge = run.md->maugis_dugdale_pressure(run.a, run.w, run.sigma0,
                                                                     {run.a * (1 - 1e-8), run.a, 2 * s.c});
    CHECK(std::abs(edge[0] + run.sigma0) < 1e-3 * run.sigma0);
    CHECK(edge[1] == -run.sigma0);
    CHECK(edge[2] == 0.0);
  }
}
