// Stage B and the mapping of the two-model approach (discrete.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <Eigen/Dense>
#include <boost/math/tools/roots.hpp>

#include "io/csv_rows.hpp"
#include "io/read_file.hpp"
#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {

ConvexData parse_convex_csv(const std::string& text, const std::string& source) {
  auto fail = [&](const std::string& what) { throw InputError(source + ": " + what); };
  detail::CsvRows rows(text);
  std::vector<std::string_view> cells;
  if (!rows.next(cells)) fail("is empty (expected the header delta,P[,a])");
  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; c < cells.size(); ++c) column[std::string(cells[c])] = c;
  const bool has_a = column.count("a") > 0;
  if (cells.size() != (has_a ? 3u : 2u) || !column.count("delta") || !column.count("P"))
    fail("the header must name the columns delta and P, and optionally a (SI units)");
  ConvexData d;
  d.source = source;
  std::vector<double> v(cells.size());
  while (rows.next(cells)) {
    if (cells.size() != v.size())
      fail("line " + std::to_string(rows.line()) + " has " + std::to_string(cells.size()) + " cells, not " + std::to_string(v.size()));
    for (std::size_t c = 0; c < v.size(); ++c)
      if (!detail::parse_finite(cells[c], v[c]))
        fail("line " + std::to_string(rows.line()) + ": '" + std::string(cells[c]) + "' is not a finite number");
    d.delta.push_back(v[column["delta"]]);
    d.P.push_back(v[column["P"]]);
    if (has_a) d.a.push_back(v[column["a"]]);
  }
  if (d.delta.empty()) fail("has a header but no data rows");
  return d;
}

ConvexData read_convex_csv(const std::string& path) {
  return parse_convex_csv(detail::read_file(path, "the convex-indenter data"), path);
}

LogPolynomialFit::LogPolynomialFit(const std::vector<double>& x, const std::vector<double>& y, int max_degree,
                                   const std::string& what) {
  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] > 0.0 && y[i] > 0.0) {
      lx.push_back(std::log(x[i]));
      ly.push_back(std::log(y[i]));
    }
  const auto n = static_cast<Eigen::Index>(lx.size());
  if (n < 3) throw InputError(what + ": " + std::to_string(n) + " positive samples; a smooth fit needs 3 or more");
  double mean = 0.0, var = 0.0;
  for (double v : lx) mean += v;
  mean /= static_cast<double>(n);
  for (double v : lx) var += (v - mean) * (v - mean);
  center_ = mean;
  scale_ = std::sqrt(var / static_cast<double>(n));
  if (!(scale_ > 0.0)) throw InputError(what + ": every sample has the same abscissa");
  Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(ly.data(), n);
  double best = std::numeric_limits<double>::infinity();
  for (int q = 1; q <= std::min<int>(max_degree, static_cast<int>(n) - 2); ++q) {
    Eigen::MatrixXd A(n, q + 1);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = (lx[static_cast<std::size_t>(i)] - center_) / scale_;
      double p = 1.0;
      for (int k = 0; k <= q; ++k, p *= t) A(i, k) = p;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    const Eigen::VectorXd c = qr.solve(b);
    // Leave-one-out residuals from the hat matrix: r_i / (1 - h_ii).
    const Eigen::MatrixXd H = A * (A.transpose() * A).ldlt().solve(A.transpose());
    const Eigen::VectorXd r = b - A * c;
    double cv = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double e = r(i) / std::max(1.0 - H(i, i), 1e-12);
      cv += e * e;
    }
    cv = std::sqrt(cv / static_cast<double>(n));
    if (cv < best * (1.0 - 1e-9)) {  // a higher degree must pay for itself
      best = cv;
      c_.assign(c.data(), c.data() + c.size());
    }
  }
  cv_ = best;
}

double LogPolynomialFit::value(double x) const {
  const double t = u(x);
  double s = 0.0;
  for (auto k = c_.size(); k-- > 0;) s = s * t + c_[k];
  return std::exp(s);
}

double LogPolynomialFit::log_curvature(double x) const {
  const double t = u(x);
  double s = 0.0;
  for (auto k = c_.size(); k-- > 2;) s = s * t + static_cast<double>(k * (k - 1)) * c_[k];
  return s / (scale_ * scale_);
}

double LogPolynomialFit::log_slope(double x) const {
  const double t = u(x);
  double s = 0.0;
  for (auto k = c_.size(); k-- > 1;) s = s * t + static_cast<double>(k) * c_[k];
  return s / scale_;
}

namespace {

class DiscreteModel final : public ContactModel {
 public:
  DiscreteModel(LogPolynomialFit S, LogPolynomialFit P, double a_lo, double a_hi, double d_lo, double d_hi)
      : ContactModel(FromData{}), S_(std::move(S)), P_(std::move(P)), a_lo_(a_lo), a_hi_(a_hi), d_lo_(d_lo), d_hi_(d_hi) {}

  HertzState state(double a) const override {
    if (!(a >= a_lo_ && a <= a_hi_))
      throw DomainError("discrete model", "contact radius a", a,
                        "[" + format_double(a_lo_) + ", " + format_double(a_hi_) + "] m (the flat-punch radii the convex data reach)");
    const double S = S_.value(a);
    const double dS = S * S_.log_slope(a) / a;
    // delta_H: where the convex curve's slope dP/d delta = P slope / delta equals S(a).
    auto g = [&](double d) { return P_.value(d) * P_.log_slope(d) / d - S; };
    std::uintmax_t iters = 200;
    const auto r = boost::math::tools::toms748_solve(g, d_lo_, d_hi_, boost::math::tools::eps_tolerance<double>(50), iters);
    const double delta = 0.5 * (r.first + r.second);
    return {a, P_.value(delta), delta, S, dS};
  }
  std::string name() const override { return "discrete"; }
  double min_radius() const override { return a_lo_ * (1.0 - 1e-12); }
  double max_radius() const override { return a_hi_; }
  double typical_radius() const override { return std::sqrt(a_lo_ * a_hi_); }

 private:
  LogPolynomialFit S_, P_;
  double a_lo_, a_hi_, d_lo_, d_hi_;
};

// Everything from the convex data: delta(a) inverted from the fitted a(delta), S = P'(delta),
// S' = P''(delta) / a'(delta) - the second derivative the two-model approach avoids.
class SingleModel final : public ContactModel {
 public:
  SingleModel(LogPolynomialFit A, LogPolynomialFit P, double a_lo, double a_hi, double d_lo, double d_hi)
      : ContactModel(FromData{}), A_(std::move(A)), P_(std::move(P)), a_lo_(a_lo), a_hi_(a_hi), d_lo_(d_lo), d_hi_(d_hi) {}

  HertzState state(double a) const override {
    if (!(a >= a_lo_ && a <= a_hi_))
      throw DomainError("single model", "contact radius a", a,
                        "[" + format_double(a_lo_) + ", " + format_double(a_hi_) + "] m (the convex data's radii)");
    std::uintmax_t iters = 200;
    const auto r = boost::math::tools::toms748_solve([&](double d) { return A_.value(d) - a; }, d_lo_, d_hi_,
                                                     boost::math::tools::eps_tolerance<double>(50), iters);
    const double d = 0.5 * (r.first + r.second);
    const double P = P_.value(d), m = P_.log_slope(d), mc = P_.log_curvature(d);
    const double S = P * m / d;
    const double dS_ddelta = P / (d * d) * (m * m - m + mc);
    const double da_ddelta = a * A_.log_slope(d) / d;
    return {a, P, d, S, dS_ddelta / da_ddelta};
  }
  std::string name() const override { return "single"; }
  double min_radius() const override { return a_lo_ * (1.0 - 1e-12); }
  double max_radius() const override { return a_hi_; }
  double typical_radius() const override { return std::sqrt(a_lo_ * a_hi_); }

 private:
  LogPolynomialFit A_, P_;
  double a_lo_, a_hi_, d_lo_, d_hi_;
};

}  // namespace

ContactModelPtr make_single_model(const ConvexData& convex, const DiscreteOptions& options) {
  if (options.max_degree < 1 || options.max_degree > 6)
    throw DomainError("make_single_model", "max_degree", options.max_degree, "1 .. 6");
  if (convex.a.size() != convex.delta.size())
    throw InputError(convex.source + ": the single-model approach needs the contact radius a of every sample");
  LogPolynomialFit A(convex.delta, convex.a, options.max_degree, convex.source + " (a)");
  LogPolynomialFit P(convex.delta, convex.P, options.max_degree, convex.source);
  double d_lo = std::numeric_limits<double>::infinity(), d_hi = 0.0;
  for (std::size_t i = 0; i < convex.delta.size(); ++i)
    if (convex.delta[i] > 0.0 && convex.P[i] > 0.0 && convex.a[i] > 0.0)
      d_lo = std::min(d_lo, convex.delta[i]), d_hi = std::max(d_hi, convex.delta[i]);
  const double a_lo = A.value(d_lo), a_hi = A.value(d_hi);
  if (!(a_hi > a_lo)) throw InputError(convex.source + ": the contact radius does not grow with delta");
  return std::make_shared<SingleModel>(std::move(A), std::move(P), a_lo, a_hi, d_lo, d_hi);
}

ContactModelPtr make_discrete_model(const FlatPunchData& flat, const ConvexData& convex, const DiscreteOptions& options) {
  if (options.max_degree < 1 || options.max_degree > 6)
    throw DomainError("make_discrete_model", "max_degree", options.max_degree, "1 .. 6");
  const FlatPunchStiffness stiff = fit_flat_punch(flat, options.linearity_tolerance);
  LogPolynomialFit S(stiff.a, stiff.S, options.max_degree, flat.source);
  LogPolynomialFit P(convex.delta, convex.P, options.max_degree, convex.source);
  double d_lo = std::numeric_limits<double>::infinity(), d_hi = 0.0;
  for (std::size_t i = 0; i < convex.delta.size(); ++i)
    if (convex.delta[i] > 0.0 && convex.P[i] > 0.0) d_lo = std::min(d_lo, convex.delta[i]), d_hi = std::max(d_hi, convex.delta[i]);
  // The radii whose stiffness the convex curve's slope spans (slope assumed increasing: convex).
  auto slope = [&](double d) { return P.value(d) * P.log_slope(d) / d; };
  const double s_lo = slope(d_lo), s_hi = slope(d_hi);
  if (!(s_hi > s_lo)) throw InputError(convex.source + ": P(delta) is not convex (its slope does not grow)");
  double a_lo = stiff.a.front(), a_hi = stiff.a.back();
  auto radius_at = [&](double s_target, double lo, double hi) {
    std::uintmax_t iters = 200;
    const auto r = boost::math::tools::toms748_solve([&](double a) { return S.value(a) - s_target; }, lo, hi,
                                                     boost::math::tools::eps_tolerance<double>(50), iters);
    return 0.5 * (r.first + r.second);
  };
  if (S.value(a_lo) < s_lo) a_lo = S.value(a_hi) > s_lo ? radius_at(s_lo, a_lo, a_hi) : a_hi;
  if (S.value(a_hi) > s_hi) a_hi = S.value(a_lo) < s_hi ? radius_at(s_hi, a_lo, a_hi) : a_lo;
  if (!(a_hi > a_lo))
    throw InputError(flat.source + ": the flat-punch stiffness (" + format_double(stiff.S.front()) + " .. " +
                     format_double(stiff.S.back()) + " N/m) lies outside the convex data's slopes (" +
                     format_double(s_lo) + " .. " + format_double(s_hi) + " N/m): the two data sets do not overlap");
  return std::make_shared<DiscreteModel>(std::move(S), std::move(P), a_lo, a_hi, d_lo, d_hi);
}

}  // namespace layerjkr
