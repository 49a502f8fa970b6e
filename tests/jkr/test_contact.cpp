// Critical points and lookups of JkrSolution against closed-form oracles.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

TEST_CASE("half-space JKR: pull-off, fixed grips and zero-load radius, nm to m", "[contact]") {
  struct Case { double R, E, nu, w; };
  for (const Case c : {Case{20e-9, 1e9, 0.3, 0.1}, Case{1e-2, 3e6, 0.3, 0.05},
                       Case{1.0, 1e5, 0.49, 1e-3}}) {
    const double Es = c.E / (1 - c.nu * c.nu);
    const double a0 = std::cbrt(9 * M_PI * c.w * c.R * c.R / (2 * Es));
    const JkrSolution jkr(make_half_space(make_paraboloid(c.R), c.E, c.nu), c.w);
    INFO("R=" << c.R);
    REQUIRE(jkr.zero_load_radius());
    CHECK(rel_err(*jkr.zero_load_radius(), a0) < 1e-12);
    const auto po = jkr.pull_off();
    REQUIRE(po);
    CHECK(rel_err(po->P, -1.5 * M_PI * c.w * c.R) < 1e-10);
    CHECK(rel_err(po->a, a0 / std::cbrt(4.0)) < 1e-10);
    const auto fg = jkr.fixed_grips_critical();
    REQUIRE(fg);
    CHECK(rel_err(fg->P, -5.0 / 6.0 * M_PI * c.w * c.R) < 1e-10);
    CHECK(rel_err(fg->a, a0 / std::cbrt(36.0)) < 1e-10);
  }
}

TEST_CASE("Winkler paraboloid: pull-off -2 pi w R for any K, no fixed-grips instability",
          "[contact]") {
  const double R = 1e-2, w = 0.05;
  for (double K : {1e6, 4e10, 1e16}) {
    for (const auto& model : {make_winkler(make_paraboloid(R), K),
                              make_two_term(make_paraboloid(R), K, -30.0),
                              make_two_term(make_paraboloid(R), K, 30.0)}) {
      const JkrSolution jkr(model, w);
      const auto po = jkr.pull_off();
      INFO(model->name() << " K=" << K);
      REQUIRE(po);
      CHECK(rel_err(po->P, -2 * M_PI * w * R) < 1e-10);
      CHECK(rel_err(po->a * po->a, 2 * R * std::sqrt(2 * w / K)) < 1e-10);
      CHECK_FALSE(jkr.fixed_grips_critical());
      // Zero load: pi K a^4/(4R) = pi a^2 sqrt(2wK)  =>  a^2 = 4 R sqrt(2w/K).
      CHECK(rel_err(std::pow(*jkr.zero_load_radius(), 2), 4 * R * std::sqrt(2 * w / K)) < 1e-12);
    }
  }
}

TEST_CASE("lookups invert the curve on the stable branches", "[contact]") {
  const auto p = make_sphere(5e-3);
  for (const auto& model : {make_half_space(p, 2e6, 0.4), make_two_term(p, 4e10, -28.0),
                            make_full_foundation(p, 4e10, 35.0)}) {
    const JkrSolution jkr(model, 0.03);
    const auto po = jkr.pull_off();
    REQUIRE(po);
    for (double factor : {1.05, 1.5, 3.0, 10.0}) {
      const double a = po->a * factor;
      if (!p->contains(a)) continue;
      const AdhesiveState s = jkr.at(a);
      INFO(model->name() << " a=" << a);
      CHECK(rel_err(jkr.contact_radius_at_force(s.P), a) < 1e-12);
      CHECK(rel_err(jkr.contact_radius_at_delta(s.delta), a) < 1e-12);
      CHECK(rel_err(jkr.force_at_delta(s.delta), s.P) < 1e-10);
    }
    CHECK_THROWS_WITH(jkr.contact_radius_at_force(po->P * 1.01), Catch::Contains("pull-off"));
    CHECK_THROWS_AS(jkr.contact_radius_at_force(NAN), DomainError);
    CHECK_THROWS_AS(jkr.contact_radius_at_force(1e30), DomainError);  // beyond the sphere
  }
  const JkrSolution dry(make_half_space(make_paraboloid(1e-2), 1e6, 0.3), 0.0);
  CHECK(dry.contact_radius_at_force(0.0) == 0.0);
  CHECK_THROWS_AS(dry.contact_radius_at_force(-1e-3), DomainError);
  CHECK_FALSE(dry.pull_off());
  CHECK(rel_err(dry.contact_radius_at_force(dry.at(3e-4).P), 3e-4) < 1e-12);
}

TEST_CASE("Appendix A: slope, approach and force against the paper's FEM", "[contact][paper]") {
  // Top layer h = 0.1 mm, E = 3 MPa, nu = 0.3 (the 300 MPa sublayer is ~rigid), R = 10 mm.
  const ThinLayerConstants c = thin_layer_constants({3e6, 0.3, 1e-4, Base::bonded});
  const auto sphere = make_sphere(1e-2);
  const double a = 4e-4, S_fem = 20276.406, delta_fem = 8.770e-6, P_fem = 0.090009;
  const NonAdhesiveState winkler = make_winkler(sphere, c.K)->state(a);
  const NonAdhesiveState two = make_two_term(sphere, c.K, c.G)->state(a);
  CHECK(winkler.S == Approx(20299.5).epsilon(5e-6));
  CHECK(rel_err(winkler.S, S_fem) < 1.2e-3);
  CHECK(two.S == winkler.S);
  // The O(h/a) edge effect: delta is 8.7 % (Winkler) and 7.2 % (two-term) low, P 9.8 %
  // low for both (theory.md s.7 quotes "7 % and 10 %", i.e. the two-term delta).
  CHECK(rel_err(winkler.delta_H, delta_fem) == Approx(0.087).margin(0.002));
  CHECK(rel_err(two.delta_H, delta_fem) == Approx(0.072).margin(0.002));
  CHECK(rel_err(winkler.P_H, P_fem) == Approx(0.098).margin(0.002));
  CHECK(rel_err(two.P_H, P_fem) == Approx(0.098).margin(0.002));
  CHECK(winkler.delta_H < two.delta_H);
  CHECK(two.delta_H < delta_fem);
}

TEST_CASE("JkrSolution validates its arguments", "[contact][errors]") {
  const auto model = make_winkler(make_paraboloid(1e-2), 1e10);
  CHECK_THROWS_WITH(JkrSolution(model, -1.0), Catch::Contains("w = -1"));
  CHECK_THROWS_AS(JkrSolution(nullptr, 0.1), Error);
  JkrOptions bad;
  bad.scan_points = 3;
  CHECK_THROWS_WITH(JkrSolution(model, 0.1, bad), Catch::Contains("scan_points = 3"));
  bad = JkrOptions{};
  bad.scan_decades = NAN;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("scan_decades"));
}

namespace {

// Forwards to a model and counts its state evaluations (states() falls back to state()).
class CountingModel final : public ContactModel {
 public:
  explicit CountingModel(ContactModelPtr inner) : ContactModel(inner->profile_ptr()), inner_(std::move(inner)) {}
  NonAdhesiveState state(double a) const override {
    ++evaluations;
    return inner_->state(a);
  }
  std::string name() const override { return inner_->name(); }
  double min_radius() const override { return inner_->min_radius(); }
  double max_radius() const override { return inner_->max_radius(); }
  double typical_radius() const override { return inner_->typical_radius(); }
  mutable std::atomic<long> evaluations{0};

 private:
  ContactModelPtr inner_;
};

bool identical(const std::optional<CriticalPoint>& x, const std::optional<CriticalPoint>& y) {
  if (!x || !y) return !x && !y;
  return x->a == y->a && x->P == y->P && x->delta == y->delta;
}

}  // namespace

TEST_CASE("critical points are searched once per solution and shared by its copies", "[contact]") {
  const double w = 0.03;
  const auto model = [] { return make_half_space(make_sphere(5e-3), 2e6, 0.4); };
  const auto counting = std::make_shared<CountingModel>(model());
  const JkrSolution jkr(counting, w);

  const auto po = jkr.pull_off();
  const long after_pull_off = counting->evaluations;
  CHECK(after_pull_off > 0);
  CHECK(identical(jkr.pull_off(), po));
  const auto a0 = jkr.zero_load_radius();  // found on the way to the pull-off
  CHECK(jkr.zero_load_radius() == a0);
  CHECK(counting->evaluations == after_pull_off);

  const auto fg = jkr.fixed_grips_critical();
  const long after_fixed_grips = counting->evaluations;
  CHECK(after_fixed_grips > after_pull_off);
  CHECK(identical(jkr.fixed_grips_critical(), fg));
  CHECK(counting->evaluations == after_fixed_grips);

  // A lookup costs its root search only, the same every time: no critical point again.
  const double a1 = jkr.contact_radius_at_force(0.5 * po->P);
  const long first_lookup = counting->evaluations - after_fixed_grips;
  CHECK(jkr.contact_radius_at_force(0.5 * po->P) == a1);
  CHECK(counting->evaluations - after_fixed_grips == 2 * first_lookup);

  const JkrSolution copy = jkr;  // NOLINT(performance-unnecessary-copy-initialization): shares the points
  const long before_copy = counting->evaluations;
  CHECK(identical(copy.pull_off(), po));
  CHECK(identical(copy.fixed_grips_critical(), fg));
  CHECK(counting->evaluations == before_copy);

  // Bit for bit what a fresh solution finds, in any order of first calls.
  const JkrSolution fresh(model(), w);
  CHECK(identical(fresh.fixed_grips_critical(), fg));
  CHECK(fresh.zero_load_radius() == a0);
  CHECK(identical(fresh.pull_off(), po));
  const JkrSolution uncounted(model(), w);
  CHECK(uncounted.contact_radius_at_force(0.5 * po->P) == a1);
}

TEST_CASE("critical points: concurrent first requests search once", "[contact]") {
  const auto counting = std::make_shared<CountingModel>(make_two_term(make_sphere(5e-3), 4e10, -28.0));
  const JkrSolution jkr(counting, 0.03);
  std::vector<std::optional<CriticalPoint>> got(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i) threads.emplace_back([&, i] { got[i] = jkr.pull_off(); });
  for (std::thread& t : threads) t.join();
  const auto serial = std::make_shared<CountingModel>(make_two_term(make_sphere(5e-3), 4e10, -28.0));
  const auto once = JkrSolution(serial, 0.03).pull_off();
  CHECK(counting->evaluations == serial->evaluations);
  for (const auto& p : got) CHECK(identical(p, once));
}
