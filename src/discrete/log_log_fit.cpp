// The smoothing of the two-model approach (discrete.hpp): log-log polynomials and cubic
// B-splines, each with its complexity chosen by leave-one-out cross-validation.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <gsl/gsl_bspline.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>
#include <Eigen/Dense>

#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

struct LogSamples {
  std::vector<double> u, v;  // ln x, ln y of the positive samples
};

LogSamples positive_logs(const std::vector<double>& x, const std::vector<double>& y, const std::string& what) {
  if (x.size() != y.size()) throw InputError(what + ": columns of different lengths");
  LogSamples s;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] > 0.0 && y[i] > 0.0) {
      s.u.push_back(std::log(x[i]));
      s.v.push_back(std::log(y[i]));
    }
  if (s.u.size() < 4) throw InputError(what + ": " + std::to_string(s.u.size()) + " positive samples; a smooth fit needs 4 or more");
  if (*std::max_element(s.u.begin(), s.u.end()) == *std::min_element(s.u.begin(), s.u.end()))
    throw InputError(what + ": every sample has the same abscissa");
  return s;
}

struct LeastSquares {
  Eigen::VectorXd coefficients;
  double cv_rms = 0.0;  // leave-one-out rms residual, from the hat matrix: r_i / (1 - h_ii)
};

LeastSquares solve_with_cv(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  LeastSquares out;
  out.coefficients = qr.solve(b);
  const Eigen::MatrixXd H = A * (A.transpose() * A).ldlt().solve(A.transpose());
  const Eigen::VectorXd r = b - A * out.coefficients;
  double cv = 0.0;
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    const double e = r(i) / std::max(1.0 - H(i, i), 1e-12);
    cv += e * e;
  }
  out.cv_rms = std::sqrt(cv / static_cast<double>(A.rows()));
  return out;
}

// A more complex fit must lower the cross-validation score by more than rounding to be taken.
bool pays_for_itself(double cv, double best) { return cv < best * (1.0 - 1e-9); }

}  // namespace

LogPolynomialFit::LogPolynomialFit(const std::vector<double>& x, const std::vector<double>& y, int max_degree,
                                   const std::string& what) {
  const LogSamples s = positive_logs(x, y, what);
  const auto n = static_cast<Eigen::Index>(s.u.size());
  double mean = 0.0, var = 0.0;
  for (double v : s.u) mean += v;
  mean /= static_cast<double>(n);
  for (double v : s.u) var += (v - mean) * (v - mean);
  center_ = mean;
  scale_ = std::sqrt(var / static_cast<double>(n));
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(s.v.data(), n);
  double best = std::numeric_limits<double>::infinity();
  for (int q = 1; q <= std::min<int>(max_degree, static_cast<int>(n) - 2); ++q) {
    Eigen::MatrixXd A(n, q + 1);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = (s.u[static_cast<std::size_t>(i)] - center_) / scale_;
      double p = 1.0;
      for (int k = 0; k <= q; ++k, p *= t) A(i, k) = p;
    }
    const LeastSquares ls = solve_with_cv(A, b);
    if (pays_for_itself(ls.cv_rms, best)) {
      best = ls.cv_rms;
      c_.assign(ls.coefficients.data(), ls.coefficients.data() + ls.coefficients.size());
    }
  }
  cv_ = best;
}

std::string LogPolynomialFit::complexity() const { return "degree " + std::to_string(degree()); }

double LogPolynomialFit::value(double x) const {
  const double t = u(x);
  double s = 0.0;
  for (auto k = c_.size(); k-- > 0;) s = s * t + c_[k];
  return std::exp(s);
}

double LogPolynomialFit::log_slope(double x) const {
  const double t = u(x);
  double s = 0.0;
  for (auto k = c_.size(); k-- > 1;) s = s * t + static_cast<double>(k) * c_[k];
  return s / scale_;
}

double LogPolynomialFit::log_curvature(double x) const {
  const double t = u(x);
  double s = 0.0;
  for (auto k = c_.size(); k-- > 2;) s = s * t + static_cast<double>(k * (k - 1)) * c_[k];
  return s / (scale_ * scale_);
}

namespace {

// GSL's B-spline basis on uniform breakpoints; owns its workspace and scratch matrix.
class SplineBasis {
 public:
  SplineBasis(std::size_t order, double lo, double hi, std::size_t breaks)
      : w_(gsl_bspline_alloc(order, breaks)), dB_(gsl_matrix_alloc(gsl_bspline_ncoeffs(w_), order)), order_(order) {
    gsl_bspline_knots_uniform(lo, hi, w_);
  }
  ~SplineBasis() {
    gsl_matrix_free(dB_);
    gsl_bspline_free(w_);
  }
  SplineBasis(const SplineBasis&) = delete;
  SplineBasis& operator=(const SplineBasis&) = delete;
  std::size_t size() const { return gsl_bspline_ncoeffs(w_); }
  double breakpoint(std::size_t j) const { return gsl_bspline_breakpoint(j, w_); }
  // Every basis function's derivatives 0 .. order - 1 at u: column d of the scratch matrix.
  const gsl_matrix& derivatives(double u) {
    gsl_bspline_deriv_eval(u, order_ - 1, dB_, w_);
    return *dB_;
  }

 private:
  gsl_bspline_workspace* w_;
  gsl_matrix* dB_;
  std::size_t order_;
};

}  // namespace

LogSplineFit::LogSplineFit(const std::vector<double>& x, const std::vector<double>& y, const std::string& what) {
  const LogSamples s = positive_logs(x, y, what);
  const auto n = static_cast<Eigen::Index>(s.u.size());
  const double lo = *std::min_element(s.u.begin(), s.u.end()), hi = *std::max_element(s.u.begin(), s.u.end());
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(s.v.data(), n);
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_breaks = 2;
  Eigen::VectorXd best_c;
  // Cubic where the samples allow; with 4 or 5 samples one polynomial piece of lower order,
  // keeping two residual degrees of freedom. Never more coefficients than half the samples:
  // on noiseless data cross-validation keeps rewarding knots until the spline oscillates.
  order_ = static_cast<std::size_t>(std::min<Eigen::Index>(4, n - 2));
  const Eigen::Index most = std::max<Eigen::Index>(static_cast<Eigen::Index>(order_), std::min<Eigen::Index>(n - 2, n / 2));
  for (std::size_t breaks = 2; static_cast<Eigen::Index>(breaks + order_ - 2) <= most; ++breaks) {
    SplineBasis basis(order_, lo, hi, breaks);
    Eigen::MatrixXd A(n, static_cast<Eigen::Index>(basis.size()));
    for (Eigen::Index i = 0; i < n; ++i) {
      const gsl_matrix& dB = basis.derivatives(s.u[static_cast<std::size_t>(i)]);
      for (Eigen::Index j = 0; j < A.cols(); ++j) A(i, j) = gsl_matrix_get(&dB, static_cast<std::size_t>(j), 0);
    }
    const LeastSquares ls = solve_with_cv(A, b);
    if (pays_for_itself(ls.cv_rms, best)) {
      best = ls.cv_rms;
      best_breaks = breaks;
      best_c = ls.coefficients;
    }
  }
  cv_ = best;
  basis_ = static_cast<int>(best_c.size());
  // Convert to one cubic per interval (Taylor coefficients at its left end), so that queries
  // are pure arithmetic: thread-safe and free of GSL state.
  SplineBasis basis(order_, lo, hi, best_breaks);
  for (std::size_t j = 0; j < best_breaks; ++j) breaks_.push_back(basis.breakpoint(j));
  for (std::size_t j = 0; j + 1 < best_breaks; ++j) {
    const gsl_matrix& dB = basis.derivatives(breaks_[j]);
    std::array<double, 4> c{};
    for (std::size_t d = 0; d < order_; ++d) {
      double sum = 0.0;
      for (std::size_t i = 0; i < basis.size(); ++i) sum += best_c(static_cast<Eigen::Index>(i)) * gsl_matrix_get(&dB, i, d);
      c[d] = sum / std::tgamma(static_cast<double>(d) + 1.0);
    }
    cubic_.push_back(c);
  }
}

std::size_t LogSplineFit::interval(double u) const {
  const auto it = std::upper_bound(breaks_.begin() + 1, breaks_.end() - 1, u);
  return static_cast<std::size_t>(it - breaks_.begin()) - 1;
}

std::string LogSplineFit::complexity() const {
  return std::to_string(basis_) + " B-splines of order " + std::to_string(order_);
}

double LogSplineFit::value(double x) const {
  const double u = std::log(x);
  const std::size_t j = interval(u);
  const double t = u - breaks_[j];
  const auto& c = cubic_[j];
  return std::exp(((c[3] * t + c[2]) * t + c[1]) * t + c[0]);
}

double LogSplineFit::log_slope(double x) const {
  const double u = std::log(x);
  const std::size_t j = interval(u);
  const double t = u - breaks_[j];
  const auto& c = cubic_[j];
  return (3.0 * c[3] * t + 2.0 * c[2]) * t + c[1];
}

double LogSplineFit::log_curvature(double x) const {
  const double u = std::log(x);
  const std::size_t j = interval(u);
  const double t = u - breaks_[j];
  const auto& c = cubic_[j];
  return 6.0 * c[3] * t + 2.0 * c[2];
}

std::shared_ptr<const LogLogFit> fit_log_log(const std::vector<double>& x, const std::vector<double>& y,
                                             Smoothing smoothing, int max_degree, const std::string& what) {
  if (smoothing == Smoothing::log_spline) return std::make_shared<LogSplineFit>(x, y, what);
  return std::make_shared<LogPolynomialFit>(x, y, max_degree, what);
}

}  // namespace layerjkr
