// Internal: one fit's Ceres solves and the steps that refine them - extra starts, the
// exclusion of non-JKR retract samples, the baseline detilt - over one shared state (the
// evaluator, the parameter map, the options, the data and the current solution), so no step
// passes that state around.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <ceres/ceres.h>

#include "fit/evaluators/curve_evaluator.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr::detail {

/// True if every cost and gradient a solve saw was finite: Ceres can stop a solve whose cost
/// became NaN with "convergence" (|cost_change|/cost: nan), which is a failure, never a result.
bool finite_solve(const ceres::Solver::Summary& s);

class FitRun {
 public:
  /// Borrows everything (ownership stays with the caller, which outlives the run); `x` is
  /// the start on entry and the solution after each step.
  FitRun(ResidualModel& ev, const ParameterMap& map, const FitOptions& options, FitData& data,
         std::vector<double>& x);

  /// The first trust-region solve from x. Throws NumericalError, saying where, if the cost or
  /// its gradient is not finite at the start or at the solution (a solve that reports
  /// convergence on NaN is a failure, never a result).
  void solve();
  /// The model is linear in the free parameters as far as their kinds tell (one stiffness, E or
  /// K, that scales a non-adhesive model, and P0; least squares; one curve; nothing held): solve()
  /// then tries the exact linear least-squares solution first (fit_linear.cpp).
  bool linear_candidate() const;
  /// Solves again from `count` perturbed starts (options.extra_starts when negative); keeps the
  /// lowest cost. A w at its bound restarts from the data-driven w where `w_from_start`.
  void try_extra_starts(int count = -1, bool w_from_start = false);
  /// Fits in time: the rule of FitOptions::exclusion_sigmas by the model - marks the retract
  /// samples the model has let go of that have not returned to the baseline, and refits without
  /// them (weight 0). Elastic fits read the tail from the data instead (retract_reading.hpp).
  std::vector<bool> exclude_non_jkr();
  /// Solves again from x after the data (weights, forces) changed, in place; keeps x and the
  /// old solve if the new one is not usable (false).
  bool resolve_in_place();
  /// Baseline::tilt: the baseline's slope from the samples off contact, removed from the data,
  /// then one more solve; the slope and its error go into `out`.
  void detilt_baseline(FitSummary* out);
  /// The solution, the fitted curve and its rms into `out` (errors: NaN until assessed).
  void record(FitSummary* out);

  /// Holds w (its internal coordinate) at xw from now on and solves again in place, without its
  /// bound; false if that solve is not usable (then nothing changed).
  bool hold_w(double xw);
  /// The same for any free parameter q at its internal coordinate xq (one parameter is held at
  /// a time: a later hold replaces an earlier one).
  bool hold(FitParameter q, double xq);
  /// The cost with w held at xw and the other parameters refitted from the current solution;
  /// the run's state is unchanged. NaN if that solve is not usable.
  double cost_with_w_held(double xw);
  /// The same for any free parameter q held at its internal coordinate xq.
  double cost_with_held(FitParameter q, double xq);
  /// The slot of x held fixed (w at its bound), or -1.
  int held_slot() const { return held_; }

  ceres::Problem* problem() { return problem_.get(); }
  double final_cost() const { return summary_.final_cost; }
  /// The first solve from the data-driven start: did it move (>= 1 iteration and a cost
  /// decrease beyond function_tolerance), and its Ceres termination.
  bool moved_from_start() const { return moved_; }
  ceres::TerminationType first_termination() const { return first_termination_; }
  const std::string& first_message() const { return first_message_; }

 private:
  // Marks, walking back from the first detached sample `first`, the samples of a tail that
  // began before the model let go (see the definition).
  void hold_tail_start(std::size_t first, double band, std::vector<bool>* tail) const;
  std::unique_ptr<ceres::Problem> solve_from(std::vector<double>& xs, ceres::Solver::Summary* summary,
                                             int held) const;
  // The linear least-squares solution from the model's force at x (one evaluation), kept if the
  // model's own evaluation there agrees with the linear prediction at every sample; otherwise
  // x is restored and false returned (Ceres solves from the same start as without it).
  bool solve_linear();

  ResidualModel& ev_;
  /// The problem's own scale: the cost of the best constant force (the weighted mean), from
  /// the data; Ceres' gradient tolerance is relative to it.
  double cost_scale_ = 0.0;
  const ParameterMap& map_;
  const FitOptions& options_;
  FitData& data_;
  std::vector<double>& x_;
  ceres::Solver::Summary summary_;
  std::unique_ptr<ceres::Problem> problem_;
  int held_ = -1;
  bool solved_ = false;  ///< solve() has run once (the first solve's termination is kept)
  int iterations_ = 0;
  int evaluations_ = 0;  ///< residual and Jacobian evaluations over the same solves  ///< summed over the solves that produced x (record() reports it)
  bool moved_ = true;
  ceres::TerminationType first_termination_ = ceres::CONVERGENCE;
  std::string first_message_;
};

}  // namespace layerjkr::detail
