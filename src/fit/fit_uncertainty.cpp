// fit() step 4: error bars from ceres::Covariance, and which parameters the data cannot
// separate (a null direction of J^T J, or a correlation above the limit).
#include <cmath>
#include <limits>
#include <string>

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include "fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {

void assess_uncertainty(const CurveEvaluator& ev, ceres::Problem* problem, double final_cost,
                        const ParameterMap& map, std::vector<double>& x, const FitOptions& options,
                        std::size_t residuals, FitSummary* out) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t p_free = options.free.size();
  // Identifiability: the column-scaled Jacobian's null space names the parameters the
  // data cannot separate.
  const std::size_t m = ev.residuals().size();
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
      ev.jacobian().data(), static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(p_free));
  std::vector<bool> separable(p_free, true);
  const std::size_t w_slot = map.is_free(FitParameter::w) ? static_cast<std::size_t>(map.index(FitParameter::w)) : p_free;
  if (w_slot < p_free && x[w_slot] <= 1e-9) {
    out->parameters[w_slot].at_bound = true;
    out->warnings.push_back("w = 0 at its lower bound: the data show no adhesion on this branch; "
                           "its error bar is one-sided and not reported");
  }
  {
    // Eigenvalues of the column-normalised J^T J are the squared singular values; a
    // ratio below 1e-12 (singular values 1e-6 apart) is a null direction.
    // w held at its bound 0 is left out: dP/d sqrt(w) at fixed delta vanishes at w = 0
    // (the shifts of P and delta cancel to first order), so its column is zero there.
    const bool held = w_slot < p_free && out->parameters[w_slot].at_bound;
    Eigen::MatrixXd JtJ = J.transpose() * J;
    if (held) {
      JtJ.row(static_cast<Eigen::Index>(w_slot)).setZero();
      JtJ.col(static_cast<Eigen::Index>(w_slot)).setZero();
      JtJ(static_cast<Eigen::Index>(w_slot), static_cast<Eigen::Index>(w_slot)) = 1.0;
    }
    Eigen::VectorXd norms = JtJ.diagonal().cwiseSqrt();
    for (Eigen::Index j = 0; j < norms.size(); ++j) {
      if (norms[j] == 0.0) {
        separable[static_cast<std::size_t>(j)] = false;
        norms[j] = 1.0;
      }
    }
    const Eigen::VectorXd inv = norms.cwiseInverse();
    JtJ = inv.asDiagonal() * JtJ * inv.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(JtJ);
    const Eigen::VectorXd& ev2 = eig.eigenvalues();  // ascending
    for (Eigen::Index k = 0; k < ev2.size(); ++k) {
      if (ev2[k] > 1e-12 * ev2[ev2.size() - 1]) continue;
      const Eigen::VectorXd v = eig.eigenvectors().col(k);
      for (Eigen::Index j = 0; j < v.size(); ++j)
        if (std::abs(v[j]) > 0.1) separable[static_cast<std::size_t>(j)] = false;
    }
    std::string group;
    for (std::size_t j = 0; j < p_free; ++j)
      if (!separable[j]) {
        group += (group.empty() ? "" : ", ") + std::string(to_string(options.free[j]));
        out->parameters[j].identifiable = false;
      }
    if (!group.empty()) {
      out->identifiable = false;
      out->unidentifiable.push_back(group + " (the Jacobian is rank-deficient: the data constrain only a combination)");
    }
  }

  const bool w_held = w_slot < p_free && out->parameters[w_slot].at_bound;
  if (options.compute_covariance && residuals > p_free && !(w_held && p_free == 1)) {
    if (w_held) problem->SetManifold(x.data(), new ceres::SubsetManifold(static_cast<int>(p_free), {static_cast<int>(w_slot)}));
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    int deficient = 0;
    for (bool s : separable) deficient += s ? 0 : 1;
    co.null_space_rank = deficient > 0 ? -1 : 0;
    co.min_reciprocal_condition_number = 1e-14;
    ceres::Covariance cov(co);
    std::vector<const double*> blocks{x.data()};
    if (cov.Compute(blocks, problem)) {
      std::vector<double> C(p_free * p_free);
      cov.GetCovarianceBlock(x.data(), x.data(), C.data());
      const double dof = static_cast<double>(residuals - p_free);
      const double s2 = 2.0 * final_cost / dof;  // scaled by the residual variance
      for (std::size_t i = 0; i < p_free; ++i)
        for (std::size_t j = 0; j < p_free; ++j)
          if (!(w_held && (i == w_slot || j == w_slot)))
            out->correlation[i][j] = C[i * p_free + j] / std::sqrt(C[i * p_free + i] * C[j * p_free + j]);
      for (std::size_t j = 0; j < p_free; ++j) {
        if (!separable[j] || out->parameters[j].at_bound) continue;
        out->parameters[j].stderr_ =
            std::abs(map.derivative(options.free[j], x.data())) * std::sqrt(C[j * p_free + j] * s2);
      }
      for (std::size_t i = 0; i < p_free; ++i)
        for (std::size_t j = i + 1; j < p_free; ++j)
          if (separable[i] && separable[j] && std::abs(out->correlation[i][j]) > options.correlation_limit) {
            out->identifiable = false;
            out->unidentifiable.push_back(std::string(to_string(options.free[i])) + " and " +
                                         to_string(options.free[j]) + " (correlation " +
                                         format_double(out->correlation[i][j]) + ")");
            out->parameters[i].stderr_ = kNaN;
            out->parameters[j].stderr_ = kNaN;
            out->parameters[i].identifiable = false;
            out->parameters[j].identifiable = false;
          }
    } else {
      out->warnings.push_back("the covariance could not be computed (ceres::Covariance failed)");
    }
  }
}

}  // namespace layerjkr::detail
