// The fit's covariance from its own Jacobian (src/fit/uncertainty/fit_covariance.cpp) against the oracle it
// replaces, ceres::Covariance with DENSE_SVD on the same Jacobian: full rank, a held slot
// (SubsetManifold), a rank-deficient Jacobian truncated or refused, and a badly scaled one.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <ceres/ceres.h>

#include "fit/run/fit_steps.hpp"
#include "support/catch_after_glog.hpp"

using namespace layerjkr;

namespace {

// A fixed Jacobian and residuals, as an evaluator's last evaluation holds them.
class FixedJacobian final : public detail::ResidualStore {
 public:
  FixedJacobian(std::size_t m, std::size_t p, std::vector<double> J) : m_(m), p_(p) {
    r_.assign(m, 0.0);
    J_ = std::move(J);
    P_fit_.assign(m, 0.0);
    detached_.assign(m, 0);
  }
  bool evaluate(const double*, bool) override { return true; }
  void invalidate() override {}
  std::size_t points() const override { return m_; }
  std::size_t row(std::size_t i) const override { return i; }
  std::size_t rows(std::size_t) const override { return 1; }
  std::size_t p() const { return p_; }

 private:
  std::size_t m_, p_;
};

// The same Jacobian as one Ceres residual block (residuals r = J x at x = 0).
class LinearCost final : public ceres::CostFunction {
 public:
  explicit LinearCost(const FixedJacobian& f) : f_(f) {
    set_num_residuals(static_cast<int>(f.points()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(f.p()));
  }
  bool Evaluate(double const* const* x, double* r, double** jac) const override {
    const std::size_t m = f_.points(), p = f_.p();
    for (std::size_t i = 0; i < m; ++i) {
      r[i] = 0.0;
      for (std::size_t j = 0; j < p; ++j) r[i] += f_.jacobian()[i * p + j] * x[0][j];
    }
    if (jac && jac[0]) std::copy(f_.jacobian().begin(), f_.jacobian().end(), jac[0]);
    return true;
  }

 private:
  const FixedJacobian& f_;
};

// ceres::Covariance's answer, or an empty vector where it refuses.
std::vector<double> ceres_covariance(const FixedJacobian& f, std::size_t held, bool truncate, double rcn) {
  std::vector<double> x(f.p(), 0.0);
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  problem.AddResidualBlock(new LinearCost(f), nullptr, x.data());
  if (held < f.p()) problem.SetManifold(x.data(), new ceres::SubsetManifold(static_cast<int>(f.p()), {static_cast<int>(held)}));
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  co.null_space_rank = truncate ? -1 : 0;
  co.min_reciprocal_condition_number = rcn;
  ceres::Covariance cov(co);
  std::vector<const double*> blocks{x.data()};
  if (!cov.Compute(blocks, &problem)) return {};
  std::vector<double> C(f.p() * f.p());
  cov.GetCovarianceBlock(x.data(), x.data(), C.data());
  return C;
}

FixedJacobian random_jacobian(std::size_t m, std::size_t p, unsigned seed, const std::vector<double>& column_scale) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> J(m * p);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < p; ++j) J[i * p + j] = column_scale[j] * g(rng);
  return FixedJacobian(m, p, J);
}

void check_same(const FixedJacobian& f, std::size_t held, bool truncate, double rcn) {
  const std::vector<double> oracle = ceres_covariance(f, held, truncate, rcn);
  std::vector<double> C;
  const bool ok = detail::svd_covariance(f, held, truncate, rcn, &C);
  REQUIRE(ok == !oracle.empty());
  if (!ok) return;
  double largest = 0.0;
  for (double v : oracle) largest = std::max(largest, std::abs(v));
  for (std::size_t k = 0; k < C.size(); ++k) CHECK(std::abs(C[k] - oracle[k]) <= 1e-10 * largest);
}

}  // namespace

TEST_CASE("the covariance from the fit's Jacobian is ceres::Covariance's DENSE_SVD", "[fit][covariance]") {
  SECTION("full rank, one to four parameters, with and without a held slot") {
    for (std::size_t p = 1; p <= 4; ++p)
      for (unsigned seed = 1; seed <= 3; ++seed) {
        const FixedJacobian f = random_jacobian(200, p, seed, std::vector<double>(p, 1.0));
        check_same(f, p, false, 1e-14);
        if (p > 1) check_same(f, seed % p, false, 1e-14);
      }
  }
  SECTION("columns scaled over twelve decades, as moduli, radii and forces are") {
    const FixedJacobian f = random_jacobian(300, 3, 7, {1e-6, 1.0, 1e6});
    check_same(f, 3, false, 1e-14);
  }
  SECTION("a rank-deficient Jacobian: refused without truncation, a pseudo-inverse with it") {
    FixedJacobian base = random_jacobian(100, 2, 11, {1.0, 1.0});
    std::vector<double> J(100 * 3);
    for (std::size_t i = 0; i < 100; ++i) {
      J[i * 3] = base.jacobian()[i * 2];
      J[i * 3 + 1] = base.jacobian()[i * 2 + 1];
      J[i * 3 + 2] = 2.0 * base.jacobian()[i * 2] - base.jacobian()[i * 2 + 1];  // in the span of the others
    }
    const FixedJacobian f(100, 3, J);
    std::vector<double> C;
    CHECK_FALSE(detail::svd_covariance(f, 3, false, 1e-14, &C));
    check_same(f, 3, false, 1e-14);
    check_same(f, 3, true, 1e-14);
  }
}
