// FitRun's exact path for a model linear in its free parameters (fit_run.hpp): a non-adhesive
// model's force scales with its one stiffness (E, or K where K alone is the medium's), and P0
// adds to it. With the contact point given - a map's fit after contact-point detection - the
// least-squares problem is linear and its solution is one QR away; a trust-region solve would
// need three steps and six sweeps over the samples to find the same point.
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "fit/run/fit_run.hpp"

namespace layerjkr::detail {
namespace {

// The model's own force at the solution must equal the linear prediction to this fraction of
// the force scale at every sample, or the model was not linear (a Pasternak medium with only K
// free, a stack with only the top's E): then Ceres solves from the original start.
constexpr double kLinearTolerance = 1e-9;

}  // namespace

bool FitRun::linear_candidate() const {
  // The exact solution knows no ranges: with bounds Ceres solves.
  if (options_.loss != LossType::none || held_ >= 0 || data_.radius_driven || !map_.slot_curve.empty() ||
      !options_.bounds.empty() || data_.displacement_weight > 0.0)
    return false;
  if (!dynamic_cast<const CurveEvaluator*>(&ev_) || map_.fixed.values.s != 0.0) return false;
  int stiffness = 0;
  for (FitParameter q : map_.free) {
    if (q == FitParameter::E || q == FitParameter::K)
      ++stiffness;
    else if (q != FitParameter::P0)
      return false;
  }
  return stiffness == 1;
}

bool FitRun::solve_linear() {
  const std::vector<double> start = x_;
  if (!ev_.evaluate(x_.data(), false)) return false;
  const double initial_cost = least_squares_cost(ev_.residuals());
  CurveParameters<double> p;
  double delta0 = 0.0, P0 = 0.0;
  map_.physical(x_.data(), &p, &delta0, &P0);
  const bool P0_free = map_.is_free(FitParameter::P0);
  const auto stiffness_slot = static_cast<std::size_t>(
      map_.index(map_.is_free(FitParameter::E) ? FitParameter::E : FitParameter::K));
  // Columns in units of the force scale: the model's force at the start's stiffness (P0 taken
  // off), and 1 for P0; weighted as the residuals are.
  const std::vector<double> model = ev_.predicted();
  const std::size_t n = data_.P.size();
  const double F = map_.F;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(n), P0_free ? 2 : 1);
  Eigen::VectorXd b(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const double sw = data_.sqrt_weight[i];
    A(k, 0) = sw * (model[i] - P0) / F;
    if (P0_free) A(k, 1) = sw;
    b(k) = sw * (data_.P[i] - (P0_free ? 0.0 : P0)) / F;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < A.cols()) return false;
  const Eigen::VectorXd c = qr.solve(b);
  const double scale = c[0], P0_new = P0_free ? c[1] * F : P0;
  if (!(scale > 0.0) || !std::isfinite(scale) || !std::isfinite(P0_new)) return false;
  x_[stiffness_slot] += std::log(scale);
  if (P0_free)
    x_[static_cast<std::size_t>(map_.index(FitParameter::P0))] =
        (P0_new - map_.ref[static_cast<int>(FitParameter::P0)]) / F;
  bool linear = ev_.evaluate(x_.data(), true);
  for (std::size_t i = 0; linear && i < n; ++i)
    linear = std::abs(ev_.predicted()[i] - (P0_new + scale * (model[i] - P0))) <= kLinearTolerance * F;
  if (!linear) {
    x_ = start;
    return false;
  }
  summary_ = ceres::Solver::Summary();
  summary_.termination_type = ceres::CONVERGENCE;
  summary_.message = "linear least squares: the model is linear in its free parameters here, solved exactly";
  summary_.initial_cost = initial_cost;
  summary_.final_cost = least_squares_cost(ev_.residuals());
  summary_.num_residual_evaluations = 1;  // the model at the start
  summary_.num_jacobian_evaluations = 1;  // and at the solution, checked
  ceres::IterationSummary it;
  it.cost = initial_cost;
  it.gradient_max_norm = 0.0;
  summary_.iterations.push_back(it);
  it.cost = summary_.final_cost;
  summary_.iterations.push_back(it);
  return true;
}

}  // namespace layerjkr::detail
