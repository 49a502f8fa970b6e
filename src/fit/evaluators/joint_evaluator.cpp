// Several curves' forward models as one (joint_evaluator.hpp).
#include "fit/evaluators/joint_evaluator.hpp"

#include <algorithm>

namespace layerjkr::detail {

JointEvaluator::JointEvaluator(std::vector<Part> parts, std::size_t globals) : parts_(std::move(parts)), globals_(globals) {
  first_point_.push_back(0);
  first_row_.push_back(0);
  for (const Part& p : parts_) {
    const std::size_t n = p.model->points();
    first_point_.push_back(first_point_.back() + n);
    first_row_.push_back(first_row_.back() + (n == 0 ? 0 : p.model->row(n - 1) + p.model->rows(n - 1)));
  }
}

std::size_t JointEvaluator::part_of(std::size_t i) const {
  return static_cast<std::size_t>(std::upper_bound(first_point_.begin(), first_point_.end(), i) - first_point_.begin()) - 1;
}

std::size_t JointEvaluator::row(std::size_t i) const {
  const std::size_t k = part_of(i);
  return first_row_[k] + parts_[k].model->row(i - first_point_[k]);
}

std::size_t JointEvaluator::rows(std::size_t i) const {
  const std::size_t k = part_of(i);
  return parts_[k].model->rows(i - first_point_[k]);
}

void JointEvaluator::invalidate() {
  for (Part& p : parts_) p.model->invalidate();
}

bool JointEvaluator::evaluate(const double* x, bool jacobian) {
  const std::size_t rows_total = first_row_.back();
  r_.assign(rows_total, 0.0);
  if (jacobian) J_.assign(rows_total * globals_, 0.0);
  P_fit_.clear();
  detached_.clear();
  contact_count_ = 0;
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    const Part& p = parts_[k];
    const std::size_t n_local = p.slot.size();
    local_.resize(n_local);
    for (std::size_t j = 0; j < n_local; ++j) local_[j] = x[p.slot[j]];
    if (!p.model->evaluate(local_.data(), jacobian)) return false;
    const std::vector<double>& r = p.model->residuals();
    std::copy(r.begin(), r.end(), r_.begin() + static_cast<long>(first_row_[k]));
    if (jacobian) {
      const std::vector<double>& J = p.model->jacobian();
      for (std::size_t i = 0; i < r.size(); ++i)
        for (std::size_t j = 0; j < n_local; ++j) J_[(first_row_[k] + i) * globals_ + p.slot[j]] = J[i * n_local + j];
    }
    P_fit_.insert(P_fit_.end(), p.model->predicted().begin(), p.model->predicted().end());
    detached_.insert(detached_.end(), p.model->detached().begin(), p.model->detached().end());
    contact_count_ += p.model->in_contact();
  }
  return true;
}

}  // namespace layerjkr::detail
