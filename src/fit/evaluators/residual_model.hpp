// Internal: what a fit's Ceres solves, error bars and diagnoses need of a forward model - the
// residuals of its samples and their Jacobian at a parameter vector x, with what the model predicts
// there. The equilibrium curves (curve_evaluator.hpp), the hereditary and kinetic models in time
// (time_evaluators.hpp) and a joint fit of several curves (joint_evaluator.hpp) implement it over
// ResidualStore.
#pragma once

#include <cstddef>
#include <vector>

namespace layerjkr::detail {

class ResidualModel {
 public:
  virtual ~ResidualModel() = default;
  /// Residuals (and the row-major Jacobian, residuals x free) at x. False if the model cannot be
  /// evaluated there.
  virtual bool evaluate(const double* x, bool jacobian) = 0;
  virtual const std::vector<double>& residuals() const = 0;
  virtual const std::vector<double>& jacobian() const = 0;
  /// Model force at each sample (P0 included) of the last evaluation.
  virtual const std::vector<double>& predicted() const = 0;
  /// Samples the model put in contact in the last evaluation.
  virtual std::size_t in_contact() const = 0;
  /// Per sample of the last evaluation: a retract sample the model has already let go of.
  virtual const std::vector<char>& detached() const = 0;
  /// Forget cached residuals (after the data's weights changed).
  virtual void invalidate() = 0;
  /// Number of samples (residual groups); the rows of sample i are [row(i), row(i) + rows(i)).
  virtual std::size_t points() const = 0;
  virtual std::size_t row(std::size_t i) const = 0;
  virtual std::size_t rows(std::size_t i) const = 0;
};

/// The least-squares cost of residuals r, sum r^2 / 2 (Ceres' convention).
inline double least_squares_cost(const std::vector<double>& r) {
  double c = 0.0;
  for (double v : r) c += 0.5 * v * v;
  return c;
}

/// What every evaluator keeps of its last evaluation, and the accessors over it.
class ResidualStore : public ResidualModel {
 public:
  const std::vector<double>& residuals() const final { return r_; }
  const std::vector<double>& jacobian() const final { return J_; }
  const std::vector<double>& predicted() const final { return P_fit_; }
  std::size_t in_contact() const final { return contact_count_; }
  const std::vector<char>& detached() const final { return detached_; }

 protected:
  std::vector<double> r_, J_, P_fit_;
  std::vector<char> detached_;
  std::size_t contact_count_ = 0;
};

}  // namespace layerjkr::detail
