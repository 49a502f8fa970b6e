// Measured tip table: mirrored C2 cubic spline (GSL), exact piecewise moments.
//
// Why C2 and not a monotone C1 spline (Steffen, Akima): the two-term model uses f''(a),
// so with a C1 interpolant delta_H(a) and P_H(a) would jump at every knot. The cubic
// spline is instead checked to be monotone on every segment (exactly: f' is a
// quadratic there), and a table it cannot follow monotonically is rejected.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_spline.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <boost/math/quadrature/gauss.hpp>

#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/profile.hpp"

namespace layerjkr {
namespace {

struct SplineDeleter {
  void operator()(gsl_spline* s) const { gsl_spline_free(s); }
};

class TableProfile final : public Profile {
 public:
  TableProfile(std::vector<double> r, std::vector<double> z) : r_(std::move(r)) {
    detail::silence_gsl_errors();
    const double z0 = z.front();
    for (double& v : z) v -= z0;  // exact: the apex offset never costs precision
    const std::size_t n = r_.size();
    std::vector<double> x(2 * n - 1), y(2 * n - 1);
    for (std::size_t i = 0; i < n; ++i) {
      x[n - 1 - i] = -r_[i];
      x[n - 1 + i] = r_[i];
      y[n - 1 - i] = z[i];
      y[n - 1 + i] = z[i];
    }
    spline_.reset(gsl_spline_alloc(gsl_interp_cspline, x.size()));
    if (!spline_ || gsl_spline_init(spline_.get(), x.data(), y.data(), x.size()) != GSL_SUCCESS)
      throw NumericalError("layerjkr::make_table_profile: GSL could not build the spline");
    require_monotone();
    // Cumulative moments at the knots; 3-point Gauss is exact for cubic * r.
    cumulative_.assign(n, 0.0);
    for (std::size_t i = 0; i + 1 < n; ++i)
      cumulative_[i + 1] = cumulative_[i] + segment_moment(r_[i], r_[i + 1]);
    if (!std::isfinite(cumulative_.back()))  // found by fuzzing: r up to 1e294 m
      throw DomainError("make_table_profile", "moment M(r_max) = int f r dr", cumulative_.back(),
                        "finite: the table's extent overflows double precision (lengths are in m)");
  }

  ProfileDerivatives derivatives(double r) const override {
    check(r);
    // A null accelerator makes GSL bisect, so concurrent queries are safe.
    const gsl_spline* s = spline_.get();
    ProfileDerivatives d;
    d.f = gsl_spline_eval(s, r, nullptr);
    d.df = gsl_spline_eval_deriv(s, r, nullptr);
    d.d2f = gsl_spline_eval_deriv2(s, r, nullptr);
    // f'' is linear on a segment, so f''' is the exact difference quotient of two
    // interior samples of f''.
    const std::size_t i = segment(r);
    const double lo = r_[i], h = r_[i + 1] - r_[i];
    d.d3f = (gsl_spline_eval_deriv2(s, lo + 0.75 * h, nullptr) -
             gsl_spline_eval_deriv2(s, lo + 0.25 * h, nullptr)) /
            (0.5 * h);
    return d;
  }

  double f(double r) const override {
    check(r);
    return gsl_spline_eval(spline_.get(), r, nullptr);
  }

  double moment(double a) const override {
    require_contact_radius("TableProfile::moment", a);
    const std::size_t i = segment(a);
    return cumulative_[i] + segment_moment(r_[i], a);
  }

  double max_radius() const override { return r_.back(); }
  double length_scale() const override { return r_.back() / 4.0; }

  std::vector<double> breakpoints(double a) const override {
    std::vector<double> knots;
    for (double v : r_)
      if (v > 0.0 && v < a) knots.push_back(v);
    return knots;
  }

  std::string describe() const override {
    return "table(" + std::to_string(r_.size()) + " points, r_max=" + format_double(r_.back()) +
           ")";
  }

 private:
  // On [r_i, r_i + h]: f'(r_i + t) = d + c t + k t^2 / 2 with k = f''' constant.
  void require_monotone() const {
    constexpr double kRounding = 64.0 * std::numeric_limits<double>::epsilon();
    for (std::size_t i = 0; i + 1 < r_.size(); ++i) {
      const double lo = r_[i], h = r_[i + 1] - lo;
      const ProfileDerivatives p = derivatives(0.5 * (lo + r_[i + 1]));
      const double k = p.d3f;
      const double c = p.d2f - k * 0.5 * h;
      const double d = p.df - c * 0.5 * h - k * 0.125 * h * h;
      auto slope = [&](double t) { return d + c * t + 0.5 * k * t * t; };
      double lowest = std::min(slope(0.0), slope(h));
      double where = slope(0.0) < slope(h) ? lo : lo + h;
      if (k != 0.0 && -c / k > 0.0 && -c / k < h && slope(-c / k) < lowest)
        lowest = slope(-c / k), where = lo - c / k;
      const double scale = std::abs(d) + std::abs(c) * h + std::abs(k) * h * h;
      if (!std::isfinite(lowest) || !std::isfinite(scale))  // found by fuzzing
        throw DomainError("make_table_profile",
                          "interpolated slope f' between r[" + std::to_string(i) + "] and r[" +
                              std::to_string(i + 1) + "]",
                          lowest, "finite: the table's heights or spacing overflow double precision");
      if (lowest < -kRounding * scale)
        throw DomainError("make_table_profile",
                          "interpolated slope f'(" + format_double(where) + ")", lowest,
                          ">= 0: the C2 spline through the table decreases between r[" +
                              std::to_string(i) + "] and r[" + std::to_string(i + 1) +
                              "]; smooth or resample the measured profile");
    }
  }

  void check(double r) const {
    if (!contains(r))
      throw DomainError("TableProfile", "r", r, "[0, " + format_double(r_.back()) + "]");
  }
  // Index i with r_[i] <= r < r_[i+1] (the last segment for r = r_max).
  std::size_t segment(double r) const {
    const auto it = std::upper_bound(r_.begin(), r_.end(), r);
    const std::size_t i = static_cast<std::size_t>(it - r_.begin());
    return std::min(i == 0 ? 0 : i - 1, r_.size() - 2);
  }
  double segment_moment(double lo, double hi) const {
    if (hi <= lo) return 0.0;
    return boost::math::quadrature::gauss<double, 3>::integrate(
        [this](double t) { return gsl_spline_eval(spline_.get(), t, nullptr) * t; }, lo, hi);
  }

  std::vector<double> r_;
  std::unique_ptr<gsl_spline, SplineDeleter> spline_;
  std::vector<double> cumulative_;
};

}  // namespace

ProfilePtr make_table_profile(std::vector<double> r, std::vector<double> z) {
  const char* fn = "make_table_profile";
  if (r.size() != z.size())
    throw DomainError(fn, "size of z (size of r is " + std::to_string(r.size()) + ")",
                      static_cast<double>(z.size()), "equal to the size of r");
  if (r.size() < 3)
    throw DomainError(fn, "number of points", static_cast<double>(r.size()), ">= 3");
  for (std::size_t i = 0; i < r.size(); ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    if (!std::isfinite(r[i])) throw DomainError(fn, "r" + idx, r[i], "finite");
    if (!std::isfinite(z[i])) throw DomainError(fn, "z" + idx, z[i], "finite");
    if (i == 0 && r[0] != 0.0)
      throw DomainError(fn, "r[0]", r[0], "exactly 0 (the table starts at the apex)");
    if (i > 0 && !(r[i] > r[i - 1]))
      throw DomainError(fn, "r" + idx, r[i],
                        "> r[" + std::to_string(i - 1) + "] = " + format_double(r[i - 1]) +
                            " (strictly increasing)");
    if (i > 0 && z[i] < z[i - 1])
      throw DomainError(fn, "z" + idx, z[i],
                        ">= z[" + std::to_string(i - 1) + "] = " + format_double(z[i - 1]) +
                            " (non-decreasing: a convex indenter rises from its apex)");
    if (i > 0 && !std::isfinite((z[i] - z[i - 1]) / (r[i] - r[i - 1])))
      throw DomainError(fn, "slope (z" + idx + " - z[" + std::to_string(i - 1) + "]) / (r" + idx +
                                " - r[" + std::to_string(i - 1) + "])",
                        (z[i] - z[i - 1]) / (r[i] - r[i - 1]), "finite");
  }
  return std::make_shared<TableProfile>(std::move(r), std::move(z));
}

}  // namespace layerjkr
