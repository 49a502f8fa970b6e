// Stage B and the mapping of the two-model approach (discrete.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <functional>
#include <map>
#include <memory>

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

void DiscreteOptions::validate() const {
  if (!(linearity_tolerance > 0.0) || !std::isfinite(linearity_tolerance))
    throw DomainError("DiscreteOptions", "linearity_tolerance", linearity_tolerance, "finite and > 0");
  if (max_degree < 1 || max_degree > 6) throw DomainError("DiscreteOptions", "max_degree", max_degree, "1 .. 6");
}

namespace {

// A model known only on the radii its data cover: the range check and the radius hints.
class DataModel : public ContactModel {
 public:
  DataModel(std::string name, std::string range, double a_lo, double a_hi)
      : ContactModel(FromData{}), name_(std::move(name)), range_(std::move(range)), a_lo_(a_lo), a_hi_(a_hi) {}
  std::string name() const override { return name_; }
  double min_radius() const override { return a_lo_ * (1.0 - 1e-12); }
  double max_radius() const override { return a_hi_; }
  double typical_radius() const override { return std::sqrt(a_lo_ * a_hi_); }

 protected:
  void check_radius(double a) const {
    if (!(a >= a_lo_ && a <= a_hi_))
      throw DomainError(name_ + " model", "contact radius a", a,
                        "[" + format_double(a_lo_) + ", " + format_double(a_hi_) + "] m (" + range_ + ")");
  }

 private:
  std::string name_, range_;
  double a_lo_, a_hi_;
};

using FitPtr = std::shared_ptr<const LogLogFit>;

double solve_in(const std::function<double(double)>& g, double lo, double hi) {
  std::uintmax_t iters = 200;
  const auto r = boost::math::tools::toms748_solve(g, lo, hi, boost::math::tools::eps_tolerance<double>(50), iters);
  return 0.5 * (r.first + r.second);
}

// The slope dP/d delta of a convex fit: P d ln P / d ln delta / delta.
double slope_of(const LogLogFit& P, double delta) { return P.value(delta) * P.log_slope(delta) / delta; }

class DiscreteModel final : public DataModel {
 public:
  DiscreteModel(FitPtr S, FitPtr P, double a_lo, double a_hi, double d_lo, double d_hi)
      : DataModel("discrete", "the flat-punch radii the convex data reach", a_lo, a_hi),
        S_(std::move(S)), P_(std::move(P)), d_lo_(d_lo), d_hi_(d_hi) {}

  NonAdhesiveState state(double a) const override {
    check_radius(a);
    const double S = S_->value(a);
    const double dS = S * S_->log_slope(a) / a;
    // delta_H: where the convex curve's slope equals S(a). At the ends of the radii the convex
    // data reach S(a) equals an end's slope, to rounding (the range is made from those slopes).
    const double s_lo = slope_of(*P_, d_lo_), s_hi = slope_of(*P_, d_hi_);
    constexpr double kEndTolerance = 1e-12;
    if (std::abs(S - s_lo) <= kEndTolerance * std::abs(S)) return {a, P_->value(d_lo_), d_lo_, S, dS};
    if (std::abs(S - s_hi) <= kEndTolerance * std::abs(S)) return {a, P_->value(d_hi_), d_hi_, S, dS};
    if (!((s_lo - S) * (s_hi - S) <= 0.0))
      throw DomainError("discrete model", "contact radius a", a,
                        "radii whose flat-punch stiffness S(a) (here " + format_double(S) +
                            " N/m) lies between the convex curve's slopes at its ends, " + format_double(s_lo) +
                            " and " + format_double(s_hi) + " N/m (the two data sets share no indentation there)");
    const double delta = solve_in([&](double d) { return slope_of(*P_, d) - S; }, d_lo_, d_hi_);
    return {a, P_->value(delta), delta, S, dS};
  }

 private:
  FitPtr S_, P_;
  double d_lo_, d_hi_;
};

// Everything from the convex data: delta(a) inverted from the fitted a(delta), S = P'(delta),
// S' = P''(delta) / a'(delta) - the second derivative the two-model approach avoids.
class SingleModel final : public DataModel {
 public:
  SingleModel(FitPtr A, FitPtr P, double a_lo, double a_hi, double d_lo, double d_hi)
      : DataModel("single", "the convex data's radii", a_lo, a_hi), A_(std::move(A)), P_(std::move(P)), d_lo_(d_lo), d_hi_(d_hi) {}

  NonAdhesiveState state(double a) const override {
    check_radius(a);
    const double d = solve_in([&](double x) { return A_->value(x) - a; }, d_lo_, d_hi_);
    const double P = P_->value(d), m = P_->log_slope(d), mc = P_->log_curvature(d);
    const double S = P * m / d;
    const double dS_ddelta = P / (d * d) * (m * m - m + mc);
    const double da_ddelta = a * A_->log_slope(d) / d;
    return {a, P, d, S, dS_ddelta / da_ddelta};
  }

 private:
  FitPtr A_, P_;
  double d_lo_, d_hi_;
};

// The approach range of the convex samples that are in contact.
std::pair<double, double> contact_range(const ConvexData& convex) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (std::size_t i = 0; i < convex.delta.size(); ++i)
    if (convex.delta[i] > 0.0 && convex.P[i] > 0.0 && (convex.a.empty() || convex.a[i] > 0.0))
      lo = std::min(lo, convex.delta[i]), hi = std::max(hi, convex.delta[i]);
  return {lo, hi};
}

}  // namespace

ContactModelPtr make_single_model(const ConvexData& convex, const DiscreteOptions& options) {
  options.validate();
  if (convex.a.size() != convex.delta.size())
    throw InputError(convex.source + ": the single-model approach needs the contact radius a of every sample");
  auto A = fit_log_log(convex.delta, convex.a, options.smoothing, options.max_degree, convex.source + " (a)");
  auto P = fit_log_log(convex.delta, convex.P, options.smoothing, options.max_degree, convex.source);
  const auto [d_lo, d_hi] = contact_range(convex);
  const double a_lo = A->value(d_lo), a_hi = A->value(d_hi);
  if (!(a_hi > a_lo)) throw InputError(convex.source + ": the contact radius does not grow with delta");
  return std::make_shared<SingleModel>(std::move(A), std::move(P), a_lo, a_hi, d_lo, d_hi);
}

ContactModelPtr make_discrete_model(const FlatPunchData& flat, const ConvexData& convex, const DiscreteOptions& options) {
  options.validate();
  const FlatPunchStiffness stiff = fit_flat_punch(flat, options.linearity_tolerance);
  auto S = fit_log_log(stiff.a, stiff.S, options.smoothing, options.max_degree, flat.source);
  auto P = fit_log_log(convex.delta, convex.P, options.smoothing, options.max_degree, convex.source);
  const auto [d_lo, d_hi] = contact_range(convex);
  // The radii whose stiffness the convex curve's slope spans (slope assumed increasing: convex).
  const double s_lo = slope_of(*P, d_lo), s_hi = slope_of(*P, d_hi);
  if (!(s_hi > s_lo)) throw InputError(convex.source + ": P(delta) is not convex (its slope does not grow)");
  double a_lo = stiff.a.front(), a_hi = stiff.a.back();
  auto radius_at = [&](double s_target, double lo, double hi) {
    return solve_in([&](double a) { return S->value(a) - s_target; }, lo, hi);
  };
  if (S->value(a_lo) < s_lo) a_lo = S->value(a_hi) > s_lo ? radius_at(s_lo, a_lo, a_hi) : a_hi;
  if (S->value(a_hi) > s_hi) a_hi = S->value(a_lo) < s_hi ? radius_at(s_hi, a_lo, a_hi) : a_lo;
  if (!(a_hi > a_lo))
    throw InputError(flat.source + ": the flat-punch stiffness (" + format_double(stiff.S.front()) + " .. " +
                     format_double(stiff.S.back()) + " N/m) lies outside the convex data's slopes (" +
                     format_double(s_lo) + " .. " + format_double(s_hi) + " N/m): the two data sets do not overlap");
  return std::make_shared<DiscreteModel>(std::move(S), std::move(P), a_lo, a_hi, d_lo, d_hi);
}

}  // namespace layerjkr
