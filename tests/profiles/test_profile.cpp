// Profiles: closed forms against independent quadratures and hand derivatives.
#include <catch2/catch.hpp>

#include <cmath>


#include "layerjkr/callable_profile.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/profile.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {
// Wraps a profile so the base-class (quadrature) moment and Sneddon integrals are used.
class QuadratureOnly final : public Profile {
 public:
  explicit QuadratureOnly(ProfilePtr p) : p_(std::move(p)) {}
  ProfileDerivatives derivatives(double r) const override { return p_->derivatives(r); }
  double max_radius() const override { return p_->max_radius(); }
  bool contains(double r) const override { return p_->contains(r); }
  double length_scale() const override { return p_->length_scale(); }
  std::vector<double> breakpoints(double a) const override { return p_->breakpoints(a); }
  std::string describe() const override { return "quadrature(" + p_->describe() + ")"; }

 private:
  ProfilePtr p_;
};
}  // namespace

TEST_CASE("closed-form moments and Sneddon integrals match adaptive quadrature", "[profile]") {
  for (const auto& np : test::profile_zoo()) {
    const QuadratureOnly q(np.profile);
    for (double a : np.radii) {
      INFO(np.name << " a=" << a);
      CHECK(rel_err(np.profile->moment(a), q.moment(a)) < 1e-12);
      const SneddonIntegrals c = np.profile->sneddon(a), n = q.sneddon(a);
      CHECK(rel_err(c.I0, n.I0) < 1e-12);
      CHECK(rel_err(c.I2, n.I2) < 1e-12);
    }
  }
}

TEST_CASE("closed-form derivatives match autodiff of the same function", "[profile]") {
  const double R = 2e-3;
  const auto sphere = make_sphere(R);
  const auto sphere_ad = make_callable_profile(
      [R](auto r) {
        using std::sqrt;
        return R - sqrt(R * R - r * r);
      },
      R, R);
  const auto power = make_power_law(5.0, 2.5);
  const auto power_ad = make_callable_profile(
      [](auto r) {
        using std::pow;
        return 5.0 * pow(r, 2.5);
      },
      1e-3);
  for (double r : {1e-5, 3e-4, 1e-3, 1.9e-3}) {
    for (const auto& pair : {std::make_pair(sphere, sphere_ad), std::make_pair(power, power_ad)}) {
      const ProfileDerivatives c = pair.first->derivatives(r), d = pair.second->derivatives(r);
      INFO(pair.first->describe() << " r=" << r);
      CHECK(rel_err(c.f, d.f) < 1e-8);  // autodiff's f subtracts f(0) = 0 exactly here
      CHECK(rel_err(c.df, d.df) < 1e-13);
      CHECK(rel_err(c.d2f, d.d2f) < 1e-13);
      CHECK(rel_err(c.d3f, d.d3f) < 1e-12);
    }
  }
}

TEST_CASE("sphere formulas keep full precision at tiny contact radii", "[profile]") {
  // a/R = 1e-7: naive R - sqrt(R^2 - a^2) and R^3 - s^3 would lose every digit.
  const double R = 1e-2, a = 1e-9;
  const auto s = make_sphere(R);
  CHECK(rel_err(s->f(a), a * a / (2 * R)) < 1e-13);
  CHECK(rel_err(s->moment(a), a * a * a * a / (8 * R)) < 1e-13);
  const SneddonIntegrals I = s->sneddon(a);
  CHECK(rel_err(I.I0, a / R) < 1e-13);
  CHECK(rel_err(I.I2, 2 * a / (3 * R)) < 1e-13);
  // Near the rim the exact sphere departs from the paraboloid.
  CHECK(s->f(0.9 * R) > make_paraboloid(R)->f(0.9 * R));
}

TEST_CASE("callable and table profiles subtract f(0)", "[profile]") {
  const auto shifted = make_callable_profile([](auto r) { return 7.0 + r * r / 2e-2; }, 1e-2);
  CHECK(shifted->f(0.0) == 0.0);
  CHECK(rel_err(shifted->derivatives(1e-3).df, 1e-3 / 1e-2) < 1e-14);
  const auto table = make_table_profile({0.0, 1e-3, 2e-3, 3e-3}, {4.0, 4.0 + 1e-6, 4.0 + 4e-6, 4.0 + 9e-6});
  CHECK(table->f(0.0) == 0.0);
  CHECK(table->f(2e-3) == Approx(4e-6).epsilon(1e-9));
}

TEST_CASE("table profile converges to the sampled sphere under refinement", "[profile]") {
  const double R = 1e-2;
  const auto exact = make_sphere(R);
  double previous = 1.0;
  for (int n : {11, 21, 41, 81, 161}) {
    const auto t = test::sampled_sphere_table(R, 5e-3, n);
    double worst = 0.0;
    for (double a : {5.3e-4, 1.37e-3, 2.9e-3, 4.1e-3}) {
      worst = std::max(worst, rel_err(t->f(a), exact->f(a)));
      worst = std::max(worst, rel_err(t->moment(a), exact->moment(a)));
    }
    INFO("n=" << n << " worst=" << worst);
    CHECK(worst < previous / 6.0);  // the cubic spline converges at least at second order
    previous = worst;
  }
  CHECK(previous < 1e-4);
}

TEST_CASE("table profile is C2, monotone, even, and splits quadratures at knots", "[profile]") {
  const auto t = make_table_profile({0, 1, 2, 3, 4}, {0, 0.1, 0.5, 1.2, 2.1});
  for (double knot : {1.0, 2.0, 3.0}) {  // f'' continuous across knots
    CHECK(t->derivatives(knot - 1e-9).d2f == Approx(t->derivatives(knot + 1e-9).d2f).margin(1e-6));
  }
  CHECK(std::abs(t->derivatives(0.0).df) < 1e-15);  // mirrored apex is smooth (to rounding)
  double last = -1.0;
  for (int i = 0; i <= 400; ++i) {
    const double v = t->f(4.0 * i / 400);
    CHECK(v >= last);
    last = v;
  }
  CHECK(t->breakpoints(2.5) == std::vector<double>{1.0, 2.0});
  CHECK(t->contains(4.0));
  // A step the C2 spline can only follow by overshooting is rejected, not clipped.
  CHECK_THROWS_WITH(make_table_profile({0, 1, 2, 3, 4}, {0, 0.1, 0.5, 2.0, 2.01}),
                    Catch::Contains("decreases between r[3] and r[4]"));
  CHECK_FALSE(t->contains(4.0 + 1e-12));
}

TEST_CASE("profile factories reject invalid parameters with named errors", "[profile][errors]") {
  CHECK_THROWS_WITH(make_paraboloid(-1.0), Catch::Contains("R = -1") && Catch::Contains("> 0"));
  CHECK_THROWS_AS(make_paraboloid(0.0), DomainError);
  CHECK_THROWS_AS(make_paraboloid(NAN), DomainError);
  CHECK_THROWS_AS(make_sphere(INFINITY), DomainError);
  CHECK_THROWS_WITH(make_cone(M_PI / 2), Catch::Contains("semi_angle_rad"));
  CHECK_THROWS_AS(make_cone(0.0), DomainError);
  CHECK_THROWS_WITH(make_power_law(1.0, 0.5), Catch::Contains("d = 0.5") && Catch::Contains("[1, 50]"));
  CHECK_THROWS_WITH(make_power_law(1.0, 1000.0), Catch::Contains("d = 1000") && Catch::Contains("[1, 50]"));
  CHECK_THROWS_AS(make_power_law(-1.0, 2.0), DomainError);
  CHECK_THROWS_WITH(make_table_profile({0, 2, 1}, {0, 1, 2}), Catch::Contains("r[2] = 1"));
  CHECK_THROWS_WITH(make_table_profile({0, 1, 2}, {0, 2, 1}), Catch::Contains("z[2] = 1"));
  CHECK_THROWS_WITH(make_table_profile({0.1, 1, 2}, {0, 1, 2}), Catch::Contains("r[0]"));
  CHECK_THROWS_WITH(make_table_profile({0, 1, NAN}, {0, 1, 2}), Catch::Contains("r[2]"));
  CHECK_THROWS_WITH(make_table_profile({0, 1, 2}, {0, INFINITY, 2}), Catch::Contains("z[1]"));
  CHECK_THROWS_WITH(make_table_profile({0, 1}, {0, 1}), Catch::Contains("number of points"));
  CHECK_THROWS_WITH(make_table_profile({0, 1, 2}, {0, 1}), Catch::Contains("size of z"));
  // Found by fuzz_table_profile (fuzz/corpus/table/regression_overflowing_slope.bin): a
  // 3e231 step over a subnormal spacing overflowed the spline into NaN, and the Sneddon
  // quadrature then threw Boost's domain_error instead of a layerjkr::Error.
  CHECK_THROWS_WITH(make_table_profile({0.0, 3.1e-322, 1.0, 2.0, 3.0}, {-3.1e231, 3.16e-322, 1.0, 2.0, 3.0}),
                    Catch::Contains("slope") && Catch::Contains("finite"));
  // Also found by fuzzing: r up to 1.3e294 m overflowed the moment to inf.
  CHECK_THROWS_WITH(make_table_profile({0.0, 1e-4, 1.2774145430680292e294}, {0.0, 1.0250921726772629e-149, 4.843750502931348e-07}),
                    Catch::Contains("moment") && Catch::Contains("overflows"));
  CHECK_THROWS_WITH(make_sphere(1.0)->derivatives(1.0), Catch::Contains("r = 1"));
  CHECK_THROWS_AS(make_paraboloid(1.0)->moment(-1e-3), DomainError);
  CHECK(make_paraboloid(1.0)->moment(0.0) == 0.0);
  const auto bad = make_callable_profile([](auto r) { using std::log; return log(r + 1.0) * 0.0 + 1.0 / (r - 1e-3); }, 1e-3);
  CHECK_THROWS_AS(bad->derivatives(1e-3), DomainError);
}

TEST_CASE("default quadratures keep full accuracy from nm to m (scaled variables)", "[profile]") {
  // Regression: on [0, 2e-7 m] tanh-sinh stalled at a 4e-9 error estimate and threw.
  for (double R : {1e-8, 2e-7, 1e-3, 1.0}) {
    const auto callable = make_callable_profile([R](auto r) { return r * r / (2.0 * R); }, R);
    const auto exact = make_paraboloid(R);
    for (double a : {1e-3 * R, 0.1 * R, 3.0 * R}) {
      INFO("R=" << R << " a=" << a);
      CHECK(rel_err(callable->moment(a), exact->moment(a)) < 1e-14);
      CHECK(rel_err(callable->sneddon(a).I2, exact->sneddon(a).I2) < 1e-14);
    }
  }
}
