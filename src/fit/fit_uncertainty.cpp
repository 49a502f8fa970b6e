// fit() step 4: error bars from ceres::Covariance, and which parameters the data cannot
// separate (a null direction of J^T J, or a correlation above the limit).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include "fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// w ends "at its bound" when its dimensionless sqrt(w) coordinate is below this.
constexpr double kAtBound = 1e-9;
// Eigenvalues of the column-normalised J^T J below this fraction of the largest (singular
// values 1e-6 apart) are null directions; a parameter whose component in one exceeds
// kNullComponent belongs to the group the data cannot separate.
constexpr double kNullEigenvalueRatio = 1e-12;
constexpr double kNullComponent = 0.1;
// ceres::Covariance (DENSE_SVD) treats smaller reciprocal condition numbers as singular.
constexpr double kCovarianceMinReciprocalCondition = 1e-14;

// Which free parameters the column-scaled Jacobian can separate (false: in a null
// direction, or a zero column). w held at its bound 0 is left out: dP/d sqrt(w) at fixed
// delta vanishes at w = 0 (the shifts of P and delta cancel to first order).
std::vector<bool> separable_parameters(const CurveEvaluator& ev, std::size_t p_free, std::size_t held_slot) {
  const Eigen::Map<const RowMajorMatrix> J(ev.jacobian().data(), static_cast<Eigen::Index>(ev.residuals().size()),
                                           static_cast<Eigen::Index>(p_free));
  std::vector<bool> separable(p_free, true);
  Eigen::MatrixXd JtJ = J.transpose() * J;
  if (held_slot < p_free) {
    const auto h = static_cast<Eigen::Index>(held_slot);
    JtJ.row(h).setZero();
    JtJ.col(h).setZero();
    JtJ(h, h) = 1.0;
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
    if (ev2[k] > kNullEigenvalueRatio * ev2[ev2.size() - 1]) continue;
    const Eigen::VectorXd v = eig.eigenvectors().col(k);
    for (Eigen::Index j = 0; j < v.size(); ++j)
      if (std::abs(v[j]) > kNullComponent) separable[static_cast<std::size_t>(j)] = false;
  }
  return separable;
}

// Names the rank-deficient group in the summary.
void report_rank_deficiency(const std::vector<bool>& separable, const FitOptions& options, FitSummary* out) {
  std::string group;
  for (std::size_t j = 0; j < separable.size(); ++j)
    if (!separable[j]) {
      group += (group.empty() ? "" : ", ") + std::string(to_string(options.free[j]));
      out->parameters[j].identifiable = false;
    }
  if (!group.empty()) {
    out->identifiable = false;
    out->unidentifiable.push_back(group + " (the Jacobian is rank-deficient: the data constrain only a combination)");
  }
}

// Pairs whose correlation exceeds the limit cannot be separated either: no error bars.
void report_correlated_pairs(const std::vector<bool>& separable, const FitOptions& options, FitSummary* out) {
  const std::size_t p_free = separable.size();
  for (std::size_t i = 0; i < p_free; ++i)
    for (std::size_t j = i + 1; j < p_free; ++j)
      if (separable[i] && separable[j] && std::abs(out->correlation[i][j]) > options.correlation_limit) {
        out->identifiable = false;
        out->unidentifiable.push_back(std::string(to_string(options.free[i])) + " and " + to_string(options.free[j]) +
                                      " (correlation " + format_double(out->correlation[i][j]) + ")");
        for (std::size_t k : {i, j}) {
          out->parameters[k].standard_error = std::numeric_limits<double>::quiet_NaN();
          out->parameters[k].identifiable = false;
        }
      }
}

// Standard errors (scaled by the residual variance) and correlations from ceres::Covariance.
void compute_error_bars(ceres::Problem* problem, double final_cost, const ParameterMap& map,
                        std::vector<double>& x, const FitOptions& options, std::size_t residuals,
                        const std::vector<bool>& separable, std::size_t held_slot, FitSummary* out) {
  const std::size_t p_free = x.size();
  const bool w_held = held_slot < p_free;
  if (w_held)
    problem->SetManifold(x.data(), new ceres::SubsetManifold(static_cast<int>(p_free), {static_cast<int>(held_slot)}));
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  const bool deficient = std::find(separable.begin(), separable.end(), false) != separable.end();
  co.null_space_rank = deficient ? -1 : 0;
  co.min_reciprocal_condition_number = kCovarianceMinReciprocalCondition;
  ceres::Covariance cov(co);
  std::vector<const double*> blocks{x.data()};
  if (!cov.Compute(blocks, problem)) {
    out->warnings.push_back("the covariance could not be computed (ceres::Covariance failed)");
    return;
  }
  std::vector<double> C(p_free * p_free);
  cov.GetCovarianceBlock(x.data(), x.data(), C.data());
  const double dof = static_cast<double>(residuals - p_free);
  const double s2 = 2.0 * final_cost / dof;  // scaled by the residual variance
  // Symmetric by construction: C from ceres may differ from its transpose in the last bit.
  for (std::size_t i = 0; i < p_free; ++i)
    for (std::size_t j = 0; j <= i; ++j)
      if (!(w_held && (i == held_slot || j == held_slot)))
        out->correlation[i][j] = out->correlation[j][i] =
            C[i * p_free + j] / std::sqrt(C[i * p_free + i] * C[j * p_free + j]);
  for (std::size_t j = 0; j < p_free; ++j) {
    if (!separable[j] || out->parameters[j].at_bound) continue;
    out->parameters[j].standard_error = std::abs(map.derivative(options.free[j], x.data())) * std::sqrt(C[j * p_free + j] * s2);
  }
  report_correlated_pairs(separable, options, out);
}

}  // namespace

void assess_uncertainty(const CurveEvaluator& ev, ceres::Problem* problem, double final_cost,
                        const ParameterMap& map, std::vector<double>& x, const FitOptions& options,
                        std::size_t residuals, FitSummary* out) {
  const std::size_t p_free = options.free.size();
  const std::size_t w_slot = map.is_free(FitParameter::w) ? static_cast<std::size_t>(map.index(FitParameter::w)) : p_free;
  std::size_t held_slot = p_free;  // none
  if (w_slot < p_free && x[w_slot] <= kAtBound) {
    out->parameters[w_slot].at_bound = true;
    out->warnings.push_back("w = 0 at its lower bound: the data show no adhesion on this branch; "
                            "its error bar is one-sided and not reported");
    held_slot = w_slot;
  }
  const std::vector<bool> separable = separable_parameters(ev, p_free, held_slot);
  report_rank_deficiency(separable, options, out);
  const bool only_w_held = held_slot < p_free && p_free == 1;
  if (options.compute_covariance && residuals > p_free && !only_w_held)
    compute_error_bars(problem, final_cost, map, x, options, residuals, separable, held_slot, out);
}

}  // namespace layerjkr::detail
