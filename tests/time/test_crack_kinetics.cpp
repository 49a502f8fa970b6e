// Rate-dependent adhesion (Maugis-Barquins kinetics of the JKR edge crack): the energy release
// rate of the paper's transform is w on the JKR curve of every medium; a retract satisfies the
// kinetic energy balance G = w0 (1 + (v/v_star)^n) at every sample, with v measured from the
// computed a(t) by differences; it tends to JKR's pull-off as v_star grows, monotonically in the
// speed; a second integrator written differently (classical Runge-Kutta on Hertz's closed forms,
// tiny fixed steps) gives the same pull-off; cantilever control lies between load and grips; every
// medium; scenes; bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "time/crack_kinetics.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/kinetics.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/scene.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kR = 1e-3, kE = 1e6, kNu = 0.5, kW = 0.05;  // a 1 mm sphere on a soft elastomer
const double kEstar = kE / (1.0 - kNu * kNu);

ContactModelPtr half_space() { return make_half_space(make_paraboloid(kR), kE, kNu); }

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

}  // namespace

TEST_CASE("the energy release rate of the transform is w on the JKR curve of every medium", "[adhesion]") {
  ModelSpec layer;
  layer.kind = ModelKind::exact;
  layer.layer = {kE, 0.45, 2e-4, Base::bonded};
  for (const ContactModelPtr& model : {half_space(), make_winkler(make_paraboloid(kR), 1e9),
                                       make_two_term(make_sphere(kR), 1e9, -50.0),
                                       make_contact_model(make_paraboloid(kR), layer)}) {
    const AdhesiveSolution sol(model, kW);
    for (double a : {5e-5, 1.5e-4, 4e-4}) {
      const AdhesiveState s = sol.at(a);
      for (RetractControl c : {RetractControl::load, RetractControl::fixed_grips, RetractControl::cantilever}) {
        const double value = c == RetractControl::load ? s.P : c == RetractControl::cantilever ? s.delta + s.P / 50.0 : s.delta;
        const detail::CrackPoint p = detail::crack_point(model->state(a), c, 50.0, value);
        INFO(model->name() << " at a = " << a << ", control " << to_string(c));
        CHECK(rel(p.G, kW) < 1e-9);
        CHECK(rel(p.P, s.P) < 1e-9);
      }
    }
  }
}

TEST_CASE("kinetic retract: the energy balance holds at every sample, a(t) measured by differences", "[adhesion]") {
  const CrackKinetics k{2e-6, 0.6};
  const ContactModelPtr model = half_space();
  const AdhesiveSolution sol(model, kW);
  const double a0 = *sol.zero_load_radius(), v = 1e-6;  // withdraw at 1 um/s from zero load
  detail::KineticStepper stepper([&](double a) { return model->state(a); }, kW, k, RetractControl::fixed_grips, 0.0);
  const double d0 = sol.at(a0).delta, dt = 1e-3;
  stepper.start(0.0, a0, d0);
  std::vector<double> t{0.0}, a{a0}, G{kW};
  while (!stepper.separated() && t.size() < 200000) {
    const double t1 = t.back() + dt;
    REQUIRE(stepper.advance(t1, d0 - v * t1));
    if (stepper.separated()) break;
    t.push_back(t1);
    a.push_back(stepper.a());
    G.push_back(stepper.point().G);
  }
  REQUIRE(stepper.separated());
  REQUIRE(t.size() > 50);
  double worst = 0.0;
  std::size_t checked = 0, where = 0;
  for (std::size_t i = 2; i + 2 < t.size(); ++i) {
    const double speed = -(-a[i + 2] + 8.0 * a[i + 1] - 8.0 * a[i - 1] + a[i - 2]) / (12.0 * dt);  // 4th order
    if (speed < 1e-3 * k.v_star) continue;  // where the crack barely moves the balance is w0 to rounding
    if (a[i - 2] - a[i + 2] > 0.01 * a[i]) continue;  // the last collapse outruns the differences
    const double balance = kW * (1.0 + std::pow(speed / k.v_star, k.n));
    if (rel(G[i], balance) > worst) {
      worst = rel(G[i], balance);
      where = i;
    }
    ++checked;
  }
  INFO(checked << " samples, largest relative imbalance " << worst << " at sample " << where << " of " << t.size()
                << ", a = " << a[where] << ", a0 = " << a0);
  CHECK(checked > 20);
  CHECK(worst < 1e-7);  // measured 1.3e-9 over 7 926 samples
}

TEST_CASE("kinetic retract tends to JKR as v_star grows and deepens the pull-off with speed", "[adhesion]") {
  const ContactModelPtr model = half_space();
  KineticRetractOptions o;
  for (RetractControl control : {RetractControl::load, RetractControl::fixed_grips}) {
    o.drive.control = control;
    o.drive.rate = control == RetractControl::load ? 1e-3 : 1e-6;
    double previous = 0.0;
    for (double v_star : {1e-6, 1e-4, 1e-2, 1.0, 100.0}) {
      const KineticRetract r = kinetic_retract(model, kW, {v_star, 0.6}, o);
      const double jkr = -1.5 * kPi * kW * kR;
      CHECK(rel(r.equilibrium_pull_off.P, jkr) < 1e-9);
      const double excess = r.pull_off.P / jkr - 1.0;
      INFO(to_string(control) << ", v_star = " << v_star << ": pull-off " << r.pull_off.P << " N, " << excess
                              << " beyond JKR's, separated at " << r.separation_time << " s");
      CHECK(excess > 0.0);
      // Measured: load 7.4, 1.5, 0.22, 0.028, 0.0034; grips 2.9, 0.29, 0.020, 0.0013, 7.9e-5.
      if (previous > 0.0) CHECK(excess < previous / 4.0);
      previous = excess;
    }
    CHECK(previous < 5e-3);
  }
  // The separation under fixed grips tends to the fixed-grips point, -5/6 pi w R.
  o.drive.control = RetractControl::fixed_grips;
  o.drive.rate = 1e-6;
  const KineticRetract slow = kinetic_retract(model, kW, {1.0, 0.6}, o);
  CHECK(rel(slow.equilibrium_separation.P, -5.0 / 6.0 * kPi * kW * kR) < 1e-9);
  // Faster withdrawal, larger pull-off: monotone in the speed.
  const std::vector<double> forces =
      kinetic_pull_off_forces(model, kW, {1e-6, 0.6}, o, {1e-8, 1e-7, 1e-6, 1e-5, 1e-4});
  for (std::size_t i = 1; i < forces.size(); ++i) CHECK(forces[i] < forces[i - 1]);
}

TEST_CASE("kinetic retract against a second integrator on Hertz's closed forms", "[adhesion]") {
  // Fixed grips at v from zero load: da/dt = -V ((G/w0) - 1)^(1/n), G = E* (a^2/R - d)^2 / (2 pi a)
  // on a half-space (P_H - P = S (delta_H - delta), S = 2 E* a, S' = 2 E*, delta_H = a^2/R), by
  // classical RK4 with 10^6 fixed steps, P = 4 E* a^3/(3R) - 2 E* a (a^2/R - d).
  const CrackKinetics k{5e-6, 0.5};
  const double v = 2e-6;
  const AdhesiveSolution sol(half_space(), kW);
  const double a0 = *sol.zero_load_radius(), d0 = sol.at(a0).delta;
  const auto rate = [&](double t, double a) {
    const double d = d0 - v * t, gap = a * a / kR - d;
    const double G = kEstar * gap * gap / (2.0 * kPi * a);
    return G > kW ? -k.v_star * std::pow(G / kW - 1.0, 1.0 / k.n) : 0.0;
  };
  KineticRetractOptions o;
  o.drive = {RetractControl::fixed_grips, v, 0.0};
  const KineticRetract r = kinetic_retract(half_space(), kW, k, o);
  const double T = r.pull_off_time * 1.2, h = T / 1e6;
  double a = a0, lowest = 0.0;
  for (int i = 0; i < 1000000 && a > 1e-3 * a0; ++i) {
    const double t = i * h;
    const double k1 = rate(t, a), k2 = rate(t + h / 2, a + h / 2 * k1), k3 = rate(t + h / 2, a + h / 2 * k2),
                 k4 = rate(t + h, a + h * k3);
    a += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    const double d = d0 - v * (t + h);
    lowest = std::min(lowest, 4.0 * kEstar * a * a * a / (3.0 * kR) - 2.0 * kEstar * a * (a * a / kR - d));
  }
  INFO("library " << r.pull_off.P << " N at " << r.pull_off_time << " s, RK4 " << lowest << " N");
  CHECK(rel(r.pull_off.P, lowest) < 1e-6);
}

TEST_CASE("kinetic retract: a cantilever lies between load and fixed grips, on every medium", "[adhesion]") {
  ModelSpec layer;
  layer.kind = ModelKind::exact;
  layer.layer = {kE, 0.45, 2e-4, Base::bonded};
  for (const ContactModelPtr& model : {half_space(), make_contact_model(make_paraboloid(kR), layer)}) {
    KineticRetractOptions o;
    o.drive = {RetractControl::cantilever, 1e-6, 20.0};
    const KineticRetract lever = kinetic_retract(model, kW, {1e-6, 0.6}, o);
    o.drive = {RetractControl::fixed_grips, 1e-6, 0.0};
    const KineticRetract grips = kinetic_retract(model, kW, {1e-6, 0.6}, o);
    INFO(model->name() << ": cantilever " << lever.pull_off.P << " N, grips " << grips.pull_off.P << " N");
    CHECK(lever.pull_off.P < lever.equilibrium_pull_off.P);
    CHECK(lever.equilibrium_separation.P > lever.equilibrium_pull_off.P);
    CHECK(lever.equilibrium_separation.P < grips.equilibrium_separation.P);
    CHECK(std::isfinite(grips.pull_off.P));
  }
}

TEST_CASE("kinetics in scenes and bad input", "[adhesion][scene]") {
  const std::string base = R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space", "E": 1e6,
      "nu": 0.5}, "w": 0.05, "adhesion": )";
  const Scene s = parse_scene(base + R"({"model": "jkr", "kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})");
  REQUIRE(s.adhesion.kinetics);
  CHECK(s.adhesion.kinetics->describe() == "maugis_barquins(v_star = 1e-06 m/s, n = 0.6)");
  const auto refused = [&](const std::string& text) {
    try {
      parse_scene(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refused(base + R"({"model": "dmt", "kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})"),
             Catch::Contains("adhesion.kinetics") && Catch::Contains("JKR's edge crack"));
  CHECK_THAT(refused(base + R"({"kinetics": {"law": "gent", "v_star": 1e-6, "n": 0.6}}})"),
             Catch::Contains("adhesion.kinetics.law = \"gent\" is unknown"));
  CHECK_THAT(refused(base + R"({"kinetics": {"law": "maugis_barquins", "v_star": -1, "n": 0.6}}})"),
             Catch::Contains("adhesion.kinetics") && Catch::Contains("v_star = -1"));
  CHECK_THAT(refused(base + R"({"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0}}})"),
             Catch::Contains("n = 0") && Catch::Contains("(0, 10]"));
  CHECK_THAT(refused(base + R"({"kinetics": {"law": "maugis_barquins", "v_star": 1e-6}}})"), Catch::Contains("n"));
  CHECK_THAT(refused(R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space", "E": 1e6,
      "nu": 0.5}, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})"),
             Catch::Contains("need a work of adhesion w > 0"));
  CHECK_THAT(refused(R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space", "E": 1e6,
      "nu": 0.5, "viscoelastic": {"law": "sls", "E_inf": 1e5, "tau": 1}}, "w": 0.05,
      "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})"),
             Catch::Contains("relaxing medium") && Catch::Contains("give one or the other"));

  const ContactModelPtr model = half_space();
  KineticRetractOptions o;
  o.drive = {RetractControl::fixed_grips, 0.0, 0.0};
  CHECK_THROWS_WITH(kinetic_retract(model, kW, {1e-6, 0.6}, o), Catch::Contains("rate = 0"));
  o.drive = {RetractControl::cantilever, 1e-6, 0.0};
  CHECK_THROWS_WITH(kinetic_retract(model, kW, {1e-6, 0.6}, o), Catch::Contains("stiffness = 0"));
  o.drive = {RetractControl::automatic, 1e-6, 0.0};
  CHECK_THROWS_WITH(kinetic_retract(model, kW, {1e-6, 0.6}, o), Catch::Contains("load, fixed_grips or cantilever"));
  o.drive = {RetractControl::fixed_grips, 1e-6, 0.0};
  o.start_force = -1.0;  // far below the pull-off
  CHECK_THROWS_AS(kinetic_retract(model, kW, {1e-6, 0.6}, o), DomainError);
  o.start_force = 0.0;
  CHECK_THROWS_WITH(kinetic_retract(model, 0.0, {1e-6, 0.6}, o), Catch::Contains("w0 = 0"));
}

TEST_CASE("kinetic retract at the extremes: the JKR limit where kinetics vanish, a refusal beyond reach",
          "[adhesion][limits]") {
  // Issue 41: v_star = 1e50 (the JKR limit) failed at once and 1e10 after 24 s; a retract at
  // 1e-300 m/s or under a 1e-300 N/m lever reported a pull-off of +1.08e-19 N (the limit is
  // -2.356e-4 N); n = 10 ran 2 million steps and failed; 1e10 m/s did the same.
  const ContactModelPtr model = half_space();
  const double jkr = -1.5 * kPi * kW * kR;
  KineticRetractOptions o;
  const auto run = [&](RetractControl control, double rate, double v_star, double n, double k = 0.0) {
    o.drive = {control, rate, k};
    return kinetic_retract(model, kW, {v_star, n}, o);
  };
  for (const KineticRetract& r : {run(RetractControl::fixed_grips, 1e-6, 1e50, 0.6), run(RetractControl::fixed_grips, 1e-6, 1e10, 0.6),
                                  run(RetractControl::fixed_grips, 1e-300, 1e-6, 0.6), run(RetractControl::load, 1e-300, 1e-6, 0.6),
                                  run(RetractControl::cantilever, 1e-6, 1e-6, 0.6, 1e-300), run(RetractControl::fixed_grips, 1e-8, 1e-6, 10.0)}) {
    INFO("rate ratio " << r.rate_ratio);
    CHECK(r.at_equilibrium);
    CHECK(rel(r.pull_off.P, jkr) < 1e-9);
    CHECK(r.separation_time >= r.pull_off_time);
    CHECK(r.t.size() == r.P.size());
  }
  // Where the integration takes over, its answer meets the limit: the kinetic correction is of
  // order rate_ratio^n (measured here: 1.0-1.3 x it), so the limit at rate_ratio^n < 1e-6 is
  // within about 1e-6 of the force.
  for (double rate : {1e-13, 1e-12, 1e-11}) {
    const KineticRetract r = run(RetractControl::fixed_grips, rate, 1e-6, 0.6);
    REQUIRE_FALSE(r.at_equilibrium);
    const double correction = std::pow(r.rate_ratio, 0.6);
    INFO("rate " << rate << ": ratio " << r.rate_ratio << ", pull-off " << r.pull_off.P);
    CHECK(rel(r.pull_off.P, jkr) > 0.3 * correction);
    CHECK(rel(r.pull_off.P, jkr) < 3.0 * correction);
  }
  // Beyond reach: refused, naming the rate and the fastest one allowed.
  try {
    run(RetractControl::fixed_grips, 1e10, 1e-6, 0.6);
    FAIL("not refused");
  } catch (const DomainError& e) {
    CHECK(e.parameter() == "rate");
    CHECK_THAT(e.what(), Catch::Contains("times v_star") && Catch::Contains("valid range: (0, "));
  }
  // A sweep keeps its other rates and gives NaN for the one beyond reach.
  o.drive = {RetractControl::fixed_grips, 1e-6, 0.0};
  const std::vector<double> sweep = kinetic_pull_off_forces(model, kW, {1e-6, 0.6}, o, {1e-300, 1e-6, 1e10});
  CHECK(rel(sweep[0], jkr) < 1e-9);
  CHECK(sweep[1] < jkr);
  CHECK(std::isnan(sweep[2]));
}
