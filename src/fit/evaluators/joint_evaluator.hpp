// Internal: several curves' forward models as one (fit_joint, joint_fit.cpp). The global parameter
// vector holds the shared parameters and each curve's own; each part sees its local vector, in
// the order of its own ParameterMap, gathered from the global one, and its Jacobian's columns are
// scattered back. Samples and residual rows follow the parts in order.
#pragma once

#include <vector>

#include "fit/evaluators/residual_model.hpp"

namespace layerjkr::detail {

class JointEvaluator final : public ResidualStore {
 public:
  struct Part {
    ResidualModel* model = nullptr;  ///< borrowed; outlives the evaluator
    std::vector<std::size_t> slot;   ///< local parameter j is global parameter slot[j]
  };
  JointEvaluator(std::vector<Part> parts, std::size_t globals);

  bool evaluate(const double* x, bool jacobian) override;
  void invalidate() override;
  std::size_t points() const override { return first_point_.back(); }
  std::size_t row(std::size_t i) const override;
  std::size_t rows(std::size_t i) const override;
  /// Where part k's samples begin (and, at parts.size(), the total).
  const std::vector<std::size_t>& first_point() const { return first_point_; }

 private:
  std::size_t part_of(std::size_t i) const;

  std::vector<Part> parts_;
  std::size_t globals_;
  std::vector<std::size_t> first_point_, first_row_;
  std::vector<double> local_;
};

}  // namespace layerjkr::detail
