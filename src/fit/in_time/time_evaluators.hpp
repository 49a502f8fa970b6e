// Internal: the forward models of a fit in time (time_fit.cpp) - each sample's force from the
// whole measured history of the indentation delta_i - delta0 at the samples' times.
//
//   HereditaryEvaluator: a relaxing medium without adhesion (viscoelastic.hpp): Lee-Radok up to
//     the deepest sample, Ting's rule after (src/time/hereditary.hpp), over the elastic
//     force of the medium's curve model at the instantaneous modulus; exact Jacobians through
//     ceres::Jet (the kernel's weights and rates, the contact's start, each sample's radius by
//     implicit differentiation).
//   KineticEvaluator: an elastic medium whose JKR edge crack has Maugis-Barquins kinetics
//     (kinetics.hpp): the approach and the dwell at equilibrium (the curve evaluator), the retract
//     by the crack's ODE from the equilibrium contact at the deepest sample, driven by the measured
//     indentation; the retract's Jacobian by central differences of the ODE's answer.
//   RelaxingAdhesionEvaluator: adhesion on a relaxing half-space (viscoelastic_adhesion.hpp): the
//     Maugis-Dugdale contact stepped in time over the measured indentation from its snap-in at the
//     instantaneous elastic contact's zero load; the Jacobian by central differences (P0 and drag
//     exactly), with the stepping's grid and step held from the first evaluation.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "fit/evaluators/curve_evaluator.hpp"
#include "layerjkr/profile.hpp"
#include "layerjkr/viscoelastic.hpp"
#include "layerjkr/viscoelastic_adhesion.hpp"
#include "fit/evaluators/residual_model.hpp"
#include "time/relaxation_kernel.hpp"

namespace layerjkr::detail {

/// The relaxation kernel of `law` at the physical parameters p: one-term Prony laws from E_inf
/// and tau (E_inf in Pa held where the law came from "sls", the ratio E_inf/E otherwise), longer
/// Prony laws as given, the power law from beta (over [t_lo, t_hi]).
template <class T>
RelaxationKernel<T> kernel_at(const RelaxationLaw& law, const CurveParameters<T>& p, double t_lo, double t_hi);

/// A sample's derivative by differences at x - step, x, x + step [x's units]: central where the
/// model's contact there is the same on both sides, one-sided where it changes on one, 0 where on
/// both (a sample the model takes in or lets go of) - the kinetic and the relaxing adhesive
/// evaluators' Jacobians.
inline double contact_difference(bool same_plus, bool same_minus, double plus, double at, double minus, double step) {
  if (same_plus && same_minus) return (plus - minus) / (2.0 * step);
  if (same_plus) return (plus - at) / step;
  if (same_minus) return (at - minus) / step;
  return 0.0;
}

class HereditaryEvaluator final : public ResidualStore {
 public:
  /// model: the medium's elastic curve family (its adhesion unused: w = 0); data.t: the times.
  /// Borrows everything; they outlive the evaluator.
  HereditaryEvaluator(const CurveModel& model, const ParameterMap& map, const FitData& data, const RelaxationLaw& law);

  bool evaluate(const double* x, bool jacobian) override;
  void invalidate() override { have_cache_ = false; }
  std::size_t points() const override { return data_.P.size(); }
  std::size_t row(std::size_t i) const override { return i; }
  std::size_t rows(std::size_t) const override { return 1; }

 private:
  template <class J>
  bool sweep(const double* x, bool jacobian);

  const CurveModel& model_;
  const ParameterMap& map_;
  const FitData& data_;
  const RelaxationLaw& law_;
  CurveEvaluator radii_;  // its radius solver (delta_H(a) = delta - delta0), nothing else
  double t_lo_ = 0.0, t_hi_ = 0.0;
  std::vector<double> a_cache_, x_cache_;
  bool have_cache_ = false, have_jac_ = false, cache_ok_ = false;
};

class KineticEvaluator final : public ResidualStore {
 public:
  /// model: the medium's JKR curve family; data: every sample in acquisition order with its time
  /// and segment; kinetics: the law's shape (v_star and n come from the parameters).
  KineticEvaluator(const CurveModel& model, const ParameterMap& map, const FitData& data);
  ~KineticEvaluator() override;

  bool evaluate(const double* x, bool jacobian) override;
  void invalidate() override;
  std::size_t points() const override { return data_.P.size(); }
  std::size_t row(std::size_t i) const override { return i; }
  std::size_t rows(std::size_t) const override { return 1; }

 private:
  struct Retract;  // the retract's forces at one parameter vector
  bool retract_at(const double* x, Retract* out) const;

  const CurveModel& model_;
  const ParameterMap& map_;
  const FitData& data_;
  FitData equilibrium_data_;               // the approach and dwell samples
  std::vector<std::size_t> equilibrium_;   // their indices in data_
  std::vector<std::size_t> retract_;       // the retract samples' indices
  std::size_t turn_ = 0;                   // the last sample before the retract
  std::unique_ptr<CurveEvaluator> equilibrium_ev_;
  std::vector<double> x_cache_;
  bool have_cache_ = false, have_jac_ = false, cache_ok_ = false;
};

class RelaxingAdhesionEvaluator final : public ResidualStore {
 public:
  /// profile: the indenter; nu: the half-space's Poisson's ratio (E* = E/(1 - nu^2)); data: every
  /// sample in acquisition order with its time; law: the scene's law, whose parameters come from
  /// x. Borrows everything; they outlive the evaluator.
  RelaxingAdhesionEvaluator(const Profile& profile, double nu, const ParameterMap& map, const FitData& data,
                            const RelaxationLaw& law);

  bool evaluate(const double* x, bool jacobian) override;
  void invalidate() override { have_cache_ = false; }
  std::size_t points() const override { return data_.P.size(); }
  std::size_t row(std::size_t i) const override { return i; }
  std::size_t rows(std::size_t) const override { return 1; }
  /// What the stepping was and how far the held step is from a converged one at x (a notice).
  std::string stepping_note(const double* x);

 private:
  struct Forces {
    std::vector<double> P;         // the contact's force at each sample [N] (0 off contact)
    std::vector<char> in_contact;
    double force_error = 0.0;
    int substeps = 0;
  };
  bool forces_at(const double* x, Forces* out, const RelaxingDugdaleOptions* stepping = nullptr);

  const Profile& profile_;
  double nu_;
  const ParameterMap& map_;
  const FitData& data_;
  const RelaxationLaw& law_;
  RelaxingDugdaleOptions stepping_;
  bool stepping_set_ = false;
  std::array<double, 3> snap_key_{};  // E*, w, sigma0 of the last snap-in indentation, snap_
  double snap_ = 0.0;
  std::vector<double> x_cache_;
  bool have_cache_ = false, have_jac_ = false, cache_ok_ = false;
};

}  // namespace layerjkr::detail
