// Closed-form profiles, the default quadratures, and the tabulated profile.
#include "layerjkr/profile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/atanh.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include "layerjkr/error.hpp"
#include "profiles/profile_quadrature.hpp"

namespace layerjkr {
namespace {

constexpr double kHalfPi = boost::math::constants::half_pi<double>();
constexpr double kDegree = boost::math::constants::degree<double>();
constexpr double kInf = std::numeric_limits<double>::infinity();

// coef * r^e, with the exact limits at r = 0 (0 * inf would be NaN).
double power_term(double coef, double r, double e) {
  if (coef == 0.0) return 0.0;
  if (r == 0.0) {
    if (e > 0.0) return 0.0;
    if (e == 0.0) return coef;
    return coef > 0.0 ? kInf : -kInf;
  }
  return coef * std::pow(r, e);
}

// int_0^{pi/2} sin^n t dt = sqrt(pi) Gamma((n+1)/2) / (2 Gamma(n/2 + 1)), n > -1.
double wallis(double n) {
  return 0.5 * boost::math::constants::root_pi<double>() *
         boost::math::tgamma_ratio((n + 1.0) / 2.0, n / 2.0 + 1.0);
}

class Paraboloid final : public Profile {
 public:
  explicit Paraboloid(double R) : R_(R) {}
  ProfileDerivatives derivatives(double r) const override {
    check(r);
    return {r * r / (2.0 * R_), r / R_, 1.0 / R_, 0.0};
  }
  double moment(double a) const override {
    check(a);
    return a * a * a * a / (8.0 * R_);
  }
  SneddonIntegrals sneddon(double a) const override {
    check(a);
    return {a / R_, 2.0 * a / (3.0 * R_)};
  }
  double length_scale() const override { return R_; }
  bool is_paraboloid() const override { return true; }
  std::optional<PowerLawForm> power_law_form() const override { return PowerLawForm{0.5 / R_, 2.0}; }
  std::string describe() const override { return "paraboloid(R=" + format_double(R_) + ")"; }

 private:
  void check(double r) const {
    if (!contains(r)) throw DomainError("Paraboloid", "r", r, "finite and >= 0");
  }
  double R_;
};

class Sphere final : public Profile {
 public:
  explicit Sphere(double R) : R_(R) {}
  ProfileDerivatives derivatives(double r) const override {
    check(r);
    const double s2 = (R_ - r) * (R_ + r);  // R^2 - r^2 without cancellation
    const double s = std::sqrt(s2);
    return {r * r / (R_ + s), r / s, R_ * R_ / (s2 * s), 3.0 * R_ * R_ * r / (s2 * s2 * s)};
  }
  // int_0^a f r dr = a^4 (R + 2s) / (6 (R + s)^2), s = sqrt(R^2 - a^2): no cancellation.
  double moment(double a) const override {
    check(a);
    const double s = std::sqrt((R_ - a) * (R_ + a));
    const double a2 = a * a;
    return a2 * a2 * (R_ + 2.0 * s) / (6.0 * (R_ + s) * (R_ + s));
  }
  // delta = a atanh(x), P = E* R^2 [(1 + x^2) atanh x - x], x = a/R (exact sphere on a
  // half-space); the bracket is summed as a series for x < 1/2 to avoid cancellation.
  SneddonIntegrals sneddon(double a) const override {
    check(a);
    const double x = a / R_;
    const double at = boost::math::atanh(x);
    double i2;
    if (x < 0.5) {
      // [(1+x^2) atanh x - x] / (2 x^2) = sum_{k>=1} 2k x^(2k-1) / (4k^2 - 1)
      const double x2 = x * x;
      double term_x = x, sum = 0.0;
      for (int k = 1; k < 200; ++k) {
        const double t = 2.0 * k * term_x / (4.0 * k * k - 1.0);
        sum += t;
        if (t <= sum * 1e-17) break;
        term_x *= x2;
      }
      i2 = sum;
    } else {
      i2 = ((1.0 + x * x) * at - x) / (2.0 * x * x);
    }
    return {at, i2};
  }
  double max_radius() const override { return R_; }
  bool contains(double r) const override { return r >= 0.0 && r < R_; }
  double length_scale() const override { return R_; }
  std::string describe() const override { return "sphere(R=" + format_double(R_) + ")"; }

 private:
  void check(double r) const {
    if (!contains(r))
      throw DomainError("Sphere", "r", r, "[0, R) with R = " + format_double(R_));
  }
  double R_;
};

// F = force x E* tan(theta) delta^2 for a regular pyramid of face semi-angle theta on a half-space.
// Bilodeau (1992, J. Appl. Mech. 59, 519), as AtomicJ (4 sides) and nanite (3 sides) use it. The
// published alternatives spread by relative_error: 1/sqrt(2) = 0.7071 (Rico et al. 2005,
// PyFMRheo) is 5.1 % below 0.7453; the equal-area cone's 0.8188 is 7.9 % below 0.8887.
struct PyramidCoefficient {
  double force;
  double relative_error;
};

const PyramidCoefficient* pyramid_coefficient(int sides) {
  static constexpr PyramidCoefficient kThree{0.8887, 0.079}, kFour{0.7453, 0.051};
  return sides == 3 ? &kThree : sides == 4 ? &kFour : nullptr;
}

class Cone final : public Profile {
 public:
  /// `pyramid`: set when the cone stands for a pyramid (make_pyramid); it names the pyramid.
  explicit Cone(double alpha, std::optional<PyramidEquivalence> pyramid = std::nullopt)
      : alpha_(alpha), cot_(1.0 / std::tan(alpha)), pyramid_(pyramid) {}
  ProfileDerivatives derivatives(double r) const override {
    check(r);
    return {r * cot_, cot_, 0.0, 0.0};
  }
  double moment(double a) const override {
    check(a);
    return a * a * a * cot_ / 3.0;
  }
  SneddonIntegrals sneddon(double a) const override {
    check(a);
    return {cot_ * kHalfPi, cot_ * kHalfPi / 2.0};
  }
  double length_scale() const override { return 1e-6; }  // scale-free: any seed works
  std::optional<PowerLawForm> power_law_form() const override { return PowerLawForm{cot_, 1.0}; }
  std::string describe() const override {
    std::string cone = "cone(semi_angle_rad=" + format_double(alpha_) + ")";
    if (!pyramid_) return cone;
    return "pyramid(sides=" + std::to_string(pyramid_->sides) +
           ", face_semi_angle_rad=" + format_double(pyramid_->face_semi_angle_rad) + ") as " + cone;
  }
  std::optional<std::string> approximation() const override {
    if (!pyramid_) return std::nullopt;
    char text[200];
    std::snprintf(text, sizeof text,
                  "the %d-sided pyramid is modelled by its axisymmetric equivalent cone (semi-angle %.4g deg): "
                  "its forces carry a model error of about %.2g %% (docs/models.md)",
                  pyramid_->sides, alpha_ / kDegree, 100.0 * pyramid_->relative_error);
    return std::string(text);
  }

 private:
  void check(double r) const {
    if (!contains(r)) throw DomainError("Cone", "r", r, "finite and >= 0");
  }
  double alpha_, cot_;
  std::optional<PyramidEquivalence> pyramid_;
};

class PowerLaw final : public Profile {
 public:
  PowerLaw(double B, double d) : B_(B), d_(d) {}
  ProfileDerivatives derivatives(double r) const override {
    check(r);
    const double d = d_;
    return {power_term(B_, r, d), power_term(B_ * d, r, d - 1.0),
            power_term(B_ * d * (d - 1.0), r, d - 2.0),
            power_term(B_ * d * (d - 1.0) * (d - 2.0), r, d - 3.0)};
  }
  double moment(double a) const override {
    check(a);
    return B_ * std::pow(a, d_ + 2.0) / (d_ + 2.0);
  }
  SneddonIntegrals sneddon(double a) const override {
    check(a);
    const double c = B_ * d_ * std::pow(a, d_ - 1.0);
    return {c * wallis(d_ - 1.0), c * wallis(d_ + 1.0)};
  }
  double length_scale() const override {
    // f(L) = L; a scale-free cone (d = 1) uses an arbitrary seed.
    return d_ > 1.0 ? std::pow(B_, -1.0 / (d_ - 1.0)) : 1e-6;
  }
  bool is_paraboloid() const override { return d_ == 2.0; }
  std::optional<PowerLawForm> power_law_form() const override { return PowerLawForm{B_, d_}; }
  std::string describe() const override {
    return "power_law(B=" + format_double(B_) + ", d=" + format_double(d_) + ")";
  }

 private:
  void check(double r) const {
    if (!contains(r)) throw DomainError("PowerLaw", "r", r, "finite and >= 0");
  }
  double B_, d_;
};

}  // namespace

bool Profile::contains(double r) const {
  return std::isfinite(r) && r >= 0.0 && r <= max_radius();
}

std::vector<double> Profile::breakpoints(double) const { return {}; }

void Profile::require_contact_radius(const char* function, double a) const {
  if (!(a > 0.0) || !contains(a)) {
    const double m = max_radius();
    std::string range = std::isfinite(m) ? "(0, " + format_double(m) + "] for " + describe()
                                         : "finite and > 0";
    if (std::isfinite(m) && !contains(m)) range.back() = ')';
    throw DomainError(function, "contact radius a", a, range);
  }
}

double Profile::moment(double a) const {
  if (a == 0.0) return 0.0;
  require_contact_radius("Profile::moment", a);
  // Dimensionless t = r/a: tanh-sinh's endpoint thresholds are absolute, so on
  // [0, 2e-7 m] it stopped at a 4e-9 error estimate; on [0, 1] it reaches 1e-15.
  std::vector<double> cuts;
  for (double b : breakpoints(a)) cuts.push_back(b / a);
  return a * a *
         detail::integrate_split([&](double t) { return f(a * t) * t; }, 0.0, 1.0, cuts,
                                 "Profile::moment");
}

SneddonIntegrals Profile::sneddon(double a) const {
  require_contact_radius("Profile::sneddon", a);
  // Knots at r_k map to t_k = asin(r_k / a).
  std::vector<double> cuts;
  for (double b : breakpoints(a)) cuts.push_back(std::asin(b / a));
  const double i0 = detail::integrate_split(
      [&](double t) { return derivatives(a * std::sin(t)).df; }, 0.0, kHalfPi, cuts,
      "Profile::sneddon");
  const double i2 = detail::integrate_split(
      [&](double t) {
        const double s = std::sin(t);
        return derivatives(a * s).df * s * s;
      },
      0.0, kHalfPi, cuts, "Profile::sneddon");
  return {i0, i2};
}

ProfilePtr make_paraboloid(double R) {
  detail::require_positive("make_paraboloid", "R", R);
  return std::make_shared<Paraboloid>(R);
}

ProfilePtr make_sphere(double R) {
  detail::require_positive("make_sphere", "R", R);
  return std::make_shared<Sphere>(R);
}

ProfilePtr make_cone(double semi_angle_rad) {
  detail::require_in_open_interval("make_cone", "semi_angle_rad", semi_angle_rad, 0.0, kHalfPi);
  return std::make_shared<Cone>(semi_angle_rad);
}

PyramidEquivalence pyramid_equivalent_cone(double face_semi_angle_rad, int sides) {
  detail::require_in_open_interval("pyramid_equivalent_cone", "face_semi_angle_rad", face_semi_angle_rad, 0.0,
                                   kHalfPi);
  const PyramidCoefficient* c = pyramid_coefficient(sides);
  if (c == nullptr) throw DomainError("pyramid_equivalent_cone", "sides", sides, "3 or 4");
  PyramidEquivalence e;
  e.sides = sides;
  e.face_semi_angle_rad = face_semi_angle_rad;
  e.cone_semi_angle_rad = std::atan(kHalfPi * c->force * std::tan(face_semi_angle_rad));
  e.relative_error = c->relative_error;
  return e;
}

ProfilePtr make_pyramid(double face_semi_angle_rad, int sides) {
  const PyramidEquivalence e = pyramid_equivalent_cone(face_semi_angle_rad, sides);
  return std::make_shared<Cone>(e.cone_semi_angle_rad, e);
}

ProfilePtr make_power_law(double B, double d) {
  detail::require_positive("make_power_law", "B", B);
  // Beyond d = 50 the exact layer's moment tables overflow (rho^(d+1) over a/h in [1e-6, 220]),
  // and the profile is a flat punch to within 2 % of its radius: use a table or a punch.
  if (!std::isfinite(d) || d < 1.0 || d > 50.0) throw DomainError("make_power_law", "d", d, "[1, 50]");
  return std::make_shared<PowerLaw>(B, d);
}

}  // namespace layerjkr
