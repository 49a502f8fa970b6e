// Fits a rescaling cannot fool: relative weights of any uniform scale change nothing, a robust
// loss's scale is refused outside its usable range, no solve that saw a non-finite cost is
// reported, and correlations are correlations (in [-1, 1], or NaN when unknown - never inf).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "fit/run/fit_run.hpp"
#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

const std::string kSource = LAYERJKR_SOURCE_DIR;

CurveData sample() { return read_curve_csv(kSource + "/data/curves/hydrogel_film_two_term.csv", CsvOptions{}); }
Scene sample_scene() { return load_scene(kSource + "/data/scenes/hydrogel_film_two_term.json"); }

FitOptions sample_options() {
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0};
  o.branch = Branch::all;
  return o;
}

void check_correlations(const FitSummary& s) {
  for (const auto& row : s.correlation)
    for (double r : row) {
      INFO(r);
      CHECK((std::isnan(r) || (r >= -1.0 && r <= 1.0)));
    }
}

}  // namespace

TEST_CASE("weights: a uniform scale from 1e-200 to 1e200 changes nothing, bit for bit", "[fit][weights]") {
  const Scene scene = sample_scene();
  const FitSummary plain = fit(sample(), scene, sample_options());
  REQUIRE(plain.converged);
  for (double scale : {1e-200, 1e-20, 1e-3, 1.0, 7.0, 1e20, 1e200}) {
    CurveData c = sample();
    c.weight.assign(c.P.size(), scale);
    const FitSummary s = fit(c, scene, sample_options());
    INFO("scale " << scale << "\n" << s.brief_report());
    CHECK(s.converged);
    CHECK(s.identifiable);
    CHECK(s.iterations == plain.iterations);
    for (std::size_t j = 0; j < s.parameters.size(); ++j) {
      CHECK(s.parameters[j].value == plain.parameters[j].value);
      CHECK(s.parameters[j].standard_error == plain.parameters[j].standard_error);
    }
    check_correlations(s);
  }
}

TEST_CASE("weights: uneven weights give the same fit at any overall scale", "[fit][weights]") {
  const Scene scene = sample_scene();
  CurveData base = sample();
  base.weight.resize(base.P.size());
  for (std::size_t i = 0; i < base.P.size(); ++i) base.weight[i] = 1.0 + 0.5 * std::sin(0.37 * static_cast<double>(i));
  const FitSummary one = fit(base, scene, sample_options());
  REQUIRE(one.converged);
  for (double scale : {1e-150, 1e150}) {
    CurveData c = base;
    for (double& w : c.weight) w *= scale;
    const FitSummary s = fit(c, scene, sample_options());
    INFO("scale " << scale << "\n" << s.brief_report());
    CHECK(s.converged);
    for (std::size_t j = 0; j < s.parameters.size(); ++j) {
      CHECK(std::abs(s.parameters[j].value - one.parameters[j].value) <= 1e-9 * std::abs(one.parameters[j].value));
      CHECK(std::abs(s.parameters[j].standard_error / one.parameters[j].standard_error - 1.0) < 1e-6);
    }
    check_correlations(s);
  }
}

TEST_CASE("a robust loss's scale outside 1e-6..1e6 of the force span is refused, naming the range", "[fit][loss]") {
  const Scene scene = sample_scene();
  for (const LossType loss : {LossType::huber, LossType::cauchy})
    for (double scale : {1e-300, 1e-18, 1e300, 1e3}) {
      FitOptions o = sample_options();
      o.loss = loss;
      o.loss_scale = scale;
      INFO(to_string(loss) << " " << scale);
      try {
        fit(sample(), scene, o);
        FAIL("accepted");
      } catch (const InputError& e) {
        const std::string m = e.what();
        CHECK(m.find("loss scale") != std::string::npos);
        CHECK(m.find("outside its usable range") != std::string::npos);
        CHECK(m.find("force span") != std::string::npos);
      }
    }
  FitOptions o = sample_options();  // a scale near the noise (2e-10 N) is what the loss is for
  o.loss = LossType::cauchy;
  o.loss_scale = 5e-10;
  const FitSummary s = fit(sample(), scene, o);
  CHECK(s.converged);
  CHECK(std::abs(s[FitParameter::E].value / 5e4 - 1.0) < 0.01);
}

TEST_CASE("a solve that saw a non-finite cost or gradient is never a result", "[fit][nan]") {
  ceres::Solver::Summary s;
  s.initial_cost = 1.0;
  s.final_cost = 0.5;
  ceres::IterationSummary it;
  it.cost = 1.0;
  it.gradient_max_norm = 1e-3;
  s.iterations = {it, it};
  CHECK(detail::finite_solve(s));
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    ceres::Solver::Summary t = s;
    t.final_cost = bad;
    CHECK_FALSE(detail::finite_solve(t));
    t = s;
    t.initial_cost = bad;
    CHECK_FALSE(detail::finite_solve(t));
    t = s;
    t.iterations[1].gradient_max_norm = bad;  // "|cost_change|/cost: nan" stopped such a solve as converged
    CHECK_FALSE(detail::finite_solve(t));
    t = s;
    t.iterations[0].cost = bad;
    CHECK_FALSE(detail::finite_solve(t));
  }
}
