// Errors in both variables (FitOptions::errors_in_displacement): a JKR rig whose displacement
// sensor has noise of its own. The data are the classical JKR sphere on a half-space in closed
// form (E = 1 MPa, nu = 0.49, w = 0.05 J/m^2, R = 5 mm), loaded and unloaded in contact, each
// sample at an exact radius with Gaussian noise added to delta and to P. Oracles:
//  - a second method written differently: every radius a_i a Ceres parameter of its own, both
//    residuals per sample, eliminated by Schur complement (the textbook orthogonal-distance
//    problem), must reach the fit's minimum;
//  - the limit of an exact displacement: the fit is least squares in the force;
//  - many noise draws: the estimates centre on the truth and the error bars cover them.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <ceres/ceres.h>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "support/catch_after_glog.hpp"

using namespace layerjkr;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kE = 1e6, kNu = 0.49, kW = 0.05, kR = 5e-3, kDelta0 = 1e-6;
const double kEs = kE / (1.0 - kNu * kNu);

template <class T>
T jkr_delta(const T& a, const T& Es, const T& s) {
  return a * a / kR - s * sqrt(2.0 * kPi * a / Es);
}
template <class T>
T jkr_force(const T& a, const T& Es, const T& s) {
  return 4.0 * Es * a * a * a / (3.0 * kR) - s * sqrt(8.0 * kPi * Es * a * a * a);
}

Scene half_space(double E) {
  return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-3},
      "medium": {"type": "half_space", "E": )" + format_double(E) + R"(, "nu": 0.49}, "w": 0.05})",
                     "rig");
}

struct Rig {
  CurveData curve;
  double sP = 0.0, sd = 0.0;  // the noises put in [N], [m]
};

// Loading from 1.2 x (loading_from) the zero-load radius to 4 x the pull-off radius, unloading to 1.6 x (unloading_to) the
// pull-off radius (above the grips point: delta still grows with a), 150 samples each even in a.
Rig rig(unsigned seed, double d_noise_of_span = 0.01, double loading_from = 1.2, double P_noise_of_pull_off = 0.002,
        double unloading_to = 1.6) {
  const double s = std::sqrt(kW);
  const double a_po = std::cbrt(9.0 * kPi * kW * kR * kR / (8.0 * kEs)), a_zero = std::cbrt(4.0) * a_po;
  const double a_top = 4.0 * a_po, a_end = unloading_to * a_po;
  const double span = jkr_delta(a_top, kEs, s) - jkr_delta(a_end, kEs, s);
  Rig r;
  r.sP = P_noise_of_pull_off * 1.5 * kPi * kW * kR;
  r.sd = d_noise_of_span * span;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const auto sample = [&](double a0, double a1, int segment) {
    for (int k = 0; k < 150; ++k) {
      const double a = a0 + (a1 - a0) * k / 149.0;
      r.curve.delta.push_back(jkr_delta(a, kEs, s) + kDelta0 + r.sd * g(rng));
      r.curve.P.push_back(jkr_force(a, kEs, s) + r.sP * g(rng));
      r.curve.segment.push_back(segment);
    }
  };
  sample(loading_from * a_zero, a_top, 0);
  sample(a_top, a_end, 1);
  r.curve.source = "rig " + std::to_string(seed);
  return r;
}

FitOptions odr_options(const Rig& r) {
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  o.branch = Branch::all;
  o.errors_in_displacement = true;
  o.force_noise = r.sP;
  o.displacement_noise = r.sd;
  return o;
}

// The second method: theta = (ln E*, sqrt(w), delta0) and every a_i, DENSE_SCHUR.
struct LatentSample {
  double delta, P, sP, sd;
  template <class T>
  bool operator()(const T* th, const T* a, T* r) const {
    const T Es = exp(th[0]);
    r[0] = (jkr_force(a[0], Es, th[1]) - P) / sP;
    r[1] = (jkr_delta(a[0], Es, th[1]) + th[2] - delta) / sd;
    return true;
  }
};

std::vector<double> latent_fit(const Rig& r, double E, double w, double delta0) {
  std::vector<double> th{std::log(E / (1.0 - kNu * kNu)), std::sqrt(w), delta0};
  std::vector<double> a(r.curve.P.size());
  ceres::Problem problem;
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // Each radius starts at the best of a coarse grid (the fit finds it by Gauss-Newton instead).
    const LatentSample sample{r.curve.delta[i], r.curve.P[i], r.sP, r.sd};
    double best = INFINITY;
    for (int k = 0; k <= 4000; ++k) {
      const double trial = 1e-5 + 1e-3 * k / 4000.0;
      double res[2];
      sample(th.data(), &trial, res);
      if (res[0] * res[0] + res[1] * res[1] < best) best = res[0] * res[0] + res[1] * res[1], a[i] = trial;
    }
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LatentSample, 2, 3, 1>(new LatentSample(sample)), nullptr,
                             th.data(), &a[i]);
    problem.SetParameterLowerBound(&a[i], 0, 1e-6);
    ordering->AddElementToGroup(&a[i], 0);
  }
  ordering->AddElementToGroup(th.data(), 1);
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_SCHUR;
  o.linear_solver_ordering.reset(ordering);
  o.max_num_iterations = 500;
  o.function_tolerance = o.gradient_tolerance = o.parameter_tolerance = 1e-15;
  ceres::Solver::Summary s;
  ceres::Solve(o, &problem, &s);
  REQUIRE(s.IsSolutionUsable());
  return {std::exp(th[0]) * (1.0 - kNu * kNu), th[1] * th[1], th[2]};
}

}  // namespace

TEST_CASE("errors in the displacement: the fit reaches the latent-radius problem's minimum", "[fit][eiv]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Rig r = rig(seed);
    FitOptions o = odr_options(r);
    o.function_tolerance = 1e-14;
    o.parameter_tolerance = 1e-14;
    const FitSummary s = fit(r.curve, half_space(0.7e6), o);
    REQUIRE(s.converged);
    CHECK(s.points_in_contact == r.curve.P.size());
    const std::vector<double> l = latent_fit(r, s[FitParameter::E].value, s[FitParameter::w].value,
                                             s[FitParameter::delta0].value);
    INFO("seed " << seed << ": E " << s[FitParameter::E].value << " vs " << l[0] << ", w " << s[FitParameter::w].value
                 << " vs " << l[1]);
    CHECK(s[FitParameter::E].value == Approx(l[0]).epsilon(1e-7));
    CHECK(s[FitParameter::w].value == Approx(l[1]).epsilon(1e-6));
    CHECK(s[FitParameter::delta0].value == Approx(l[2]).epsilon(1e-6));
    // The residual is the distance in the force's units: its rms is the force noise.
    CHECK(s.rms_residual == Approx(r.sP).epsilon(0.15));
    CHECK(s.displacement_noise_given);
  }
}

TEST_CASE("errors in the displacement: an exact displacement is least squares in the force", "[fit][eiv]") {
  const Rig r = rig(7, 0.0);
  FitOptions ls = odr_options(r);
  ls.errors_in_displacement = false;
  ls.force_noise.reset();
  ls.displacement_noise.reset();
  const FitSummary a = fit(r.curve, half_space(1e6), ls);
  FitOptions o = odr_options(r);
  o.displacement_noise = 1e-15;
  const FitSummary b = fit(r.curve, half_space(1e6), o);
  for (FitParameter q : {FitParameter::E, FitParameter::w, FitParameter::delta0}) {
    CHECK(b[q].value == Approx(a[q].value).epsilon(1e-6));
    CHECK(b[q].standard_error == Approx(a[q].standard_error).epsilon(1e-3));
  }
}

TEST_CASE("errors in the displacement: estimates centre on the truth and the error bars cover them", "[fit][eiv]") {
  // 40 draws unloading past the pull-off, both noises estimated from the data (third differences).
  // With honest error bars
  // z = (estimate - truth) / SE has mean 0 (its own error 0.16 here) and rms 1.
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  const double truth[3] = {kE, kW, kDelta0};
  const int draws = 40;
  for (int d = 0; d < draws; ++d) {
    const Rig r = rig(100 + static_cast<unsigned>(d), 0.01, 1.2, 0.002, 1.15);
    FitOptions o = odr_options(r);
    o.force_noise.reset();
    o.displacement_noise.reset();
    const FitSummary s = fit(r.curve, half_space(2e6), o);
    REQUIRE(s.converged);
    REQUIRE_FALSE(s.displacement_noise_given);
    CHECK(s.displacement_noise == Approx(r.sd).epsilon(0.3));
    int k = 0;
    for (FitParameter q : {FitParameter::E, FitParameter::w, FitParameter::delta0}) {
      const double z = (s[q].value - truth[k]) / s[q].standard_error;
      sum[k] += z;
      sum2[k] += z * z;
      ++k;
    }
  }
  for (int k = 0; k < 3; ++k) {
    INFO("parameter " << k << ": mean z " << sum[k] / draws << ", rms z " << std::sqrt(sum2[k] / draws));
    CHECK(std::abs(sum[k] / draws) < 0.8);
    CHECK(std::sqrt(sum2[k] / draws) == Approx(1.0).margin(0.35));
  }
}

TEST_CASE("errors in the displacement: a sample short of the branch's start is in contact if nearer it",
          "[fit][eiv]") {
  // Loading from the zero-load contact itself: the displacement's noise puts some of the first
  // samples short of the branch's start, though their force is above the baseline. Read as free,
  // such a sample is a residual of many force noises.
  const double a_zero = std::cbrt(4.0 * 9.0 * kPi * kW * kR * kR / (8.0 * kEs));
  const double delta_zero = jkr_delta(a_zero, kEs, std::sqrt(kW)) + kDelta0;
  int short_of_start = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Rig r = rig(seed, 0.01, 1.0, 2e-5, 1.15);  // a force far better resolved than the displacement
    for (std::size_t i = 0; i < 10; ++i) short_of_start += r.curve.delta[i] < delta_zero ? 1 : 0;
    const FitSummary s = fit(r.curve, half_space(1e6), odr_options(r));
    REQUIRE(s.converged);
    CHECK(s.points_in_contact + 1 >= r.curve.P.size());  // the first sample, at zero load, is on both
    CHECK(std::abs(s[FitParameter::E].value - kE) < 4.0 * s[FitParameter::E].standard_error);
  }
  CHECK(short_of_start > 0);  // the case arises
}

TEST_CASE("errors in the displacement: a model that misses the data is said to, against the force noise",
          "[fit][eiv]") {
  // w held at 0 on an adhesive rig: the distances are tens of force noises. Judged against the
  // force noise widened by the slope x displacement noise (as without errors in the displacement),
  // the misfit hid 200x below its own scale.
  const Rig r = rig(5, 0.01, 1.2, 0.002, 1.15);
  FitOptions o = odr_options(r);
  o.free = {FitParameter::E, FitParameter::delta0};
  o.force_noise.reset();
  o.displacement_noise.reset();
  Scene no_adhesion = half_space(1e6);
  no_adhesion.w = 0.0;
  const FitSummary s = fit(r.curve, no_adhesion, o);
  INFO(s.brief_report());
  CHECK(s.rms_residual > 10.0 * s.force_noise);
  CHECK(s.noise == Approx(s.force_noise));
  CHECK(s.residual_structure);
  CHECK_FALSE(s.identifiable);
}

TEST_CASE("errors in the displacement: refused where it cannot apply", "[fit][eiv]") {
  Rig r = rig(1);
  FitOptions o = odr_options(r);
  o.errors_in_displacement = false;
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("displacement_noise") && Catch::Contains("errors_in_displacement"));
  o = odr_options(r);
  o.displacement_noise = -1.0;
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("displacement_noise [m]") && Catch::Contains("> 0"));
  o = odr_options(r);
  CurveData with_radius = r.curve;
  with_radius.a.assign(with_radius.P.size(), 1e-4);
  CHECK_THROWS_WITH(fit(with_radius, half_space(1e6), o), Catch::Contains("rig 1") && Catch::Contains("contact radii"));
  // A constant displacement, whose noise would estimate as 0 (any other column's is floored at 1e-6
  // of its span), is refused before.
  CurveData flat = r.curve;
  flat.delta.assign(flat.P.size(), 1e-5);
  o = odr_options(r);
  o.displacement_noise.reset();
  CHECK_THROWS_WITH(fit(flat, half_space(1e6), o), Catch::Contains("rig 1") && Catch::Contains("delta is constant"));
  // Fits in time follow the clock, not the curve; joint fits share a law in time.
  Scene relaxing = half_space(1e6);
  relaxing.medium.relaxation = RelaxationLaw::standard_linear_solid(0.4, 0.2);
  CurveData timed = r.curve;
  for (std::size_t i = 0; i < timed.P.size(); ++i) timed.t.push_back(1e-3 * static_cast<double>(i));
  o = odr_options(r);
  CHECK_THROWS_WITH(fit(timed, relaxing, o), Catch::Contains("not in fits in time"));
  CHECK_THROWS_WITH(fit_joint({timed, timed}, relaxing, o), Catch::Contains("not in joint fits"));
  FitOptions plain;
  plain.free = {FitParameter::E};
  plain.force_noise = 1e-6;
  CHECK_THROWS_WITH(fit(r.curve, half_space(1e6), plain), Catch::Contains("force_noise") && Catch::Contains("exact"));
}
