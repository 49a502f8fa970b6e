// The covariance of a least-squares fit from its Jacobian (fit_steps.hpp: svd_covariance).
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "fit/run/fit_steps.hpp"

namespace layerjkr::detail {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace

// As ceres::Covariance's DENSE_SVD (J = U S V^T, C = V S^-2 V^T over the singular values whose ratio
// to the largest is at least sqrt(min reciprocal condition number); below it: truncated with
// `truncate`, a failure without) from the evaluator's Jacobian at the solution: the singular
// values of J through the p x p triangle of its QR, without Ceres' second evaluation and m x p SVD.
// A held slot (SubsetManifold in Ceres) is left out: its row and column are 0.
bool svd_covariance(const ResidualModel& ev, std::size_t held_slot, bool truncate, double min_reciprocal_condition,
                    std::vector<double>* C) {
  const auto m = static_cast<Eigen::Index>(ev.residuals().size());
  const std::size_t p = m > 0 ? ev.jacobian().size() / ev.residuals().size() : 0;
  const Eigen::Map<const RowMajorMatrix> J(ev.jacobian().data(), m, static_cast<Eigen::Index>(p));
  std::vector<Eigen::Index> cols;
  for (std::size_t j = 0; j < p; ++j)
    if (j != held_slot) cols.push_back(static_cast<Eigen::Index>(j));
  const auto q = static_cast<Eigen::Index>(cols.size());
  Eigen::MatrixXd A(m, q);
  for (Eigen::Index k = 0; k < q; ++k) A.col(k) = J.col(cols[static_cast<std::size_t>(k)]);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(q).triangularView<Eigen::Upper>();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  Eigen::VectorXd inverse_squared = Eigen::VectorXd::Zero(q);
  const double min_ratio = std::sqrt(min_reciprocal_condition);
  for (Eigen::Index i = 0; i < q; ++i) {
    if (sv[i] / sv[0] < min_ratio) {
      if (truncate) break;
      return false;
    }
    inverse_squared[i] = 1.0 / (sv[i] * sv[i]);
  }
  const Eigen::MatrixXd Cq = svd.matrixV() * inverse_squared.asDiagonal() * svd.matrixV().transpose();
  C->assign(p * p, 0.0);
  for (Eigen::Index a = 0; a < q; ++a)
    for (Eigen::Index b = 0; b < q; ++b)
      (*C)[static_cast<std::size_t>(cols[static_cast<std::size_t>(a)]) * p + static_cast<std::size_t>(cols[static_cast<std::size_t>(b)])] = Cq(a, b);
  return true;
}

}  // namespace layerjkr::detail
