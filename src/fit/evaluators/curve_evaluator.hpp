// Internal: residuals and their exact Jacobian for one fit, cached per parameter vector.
#pragma once

#include <array>
#include <string>
#include <memory>
#include <vector>

#include "fit/evaluators/fit_model.hpp"
#include "fit/evaluators/residual_model.hpp"

namespace layerjkr::detail {

/// Maps the internal dimensionless vector x to physical parameters (see fit.hpp).
struct ParameterMap {
  std::vector<FitParameter> free;
  std::array<int, kFitParameterCount> slot{};    ///< index into x per FitParameter, -1 if fixed
  std::array<double, kFitParameterCount> ref{};  ///< reference value per FitParameter
  SceneParameters fixed;
  double L = 1.0, F = 1.0;          ///< length and force scales [m], [N]
  double G_scale = 1.0;             ///< linear G: G = G_scale * x
  bool G_log = false;               ///< full foundation: G = ref * exp(x)
  double s_scale = 1.0;             ///< s = sqrt(w) = s_scale * x
  double beta_scale = 0.1;          ///< beta = ref + beta_scale * x (E_inf, tau, E_2, tau_2, v_star, n: ref * exp(x))
  double drag_scale = 0.0;          ///< drag = drag_scale * x [N s/m]: the force span over the largest speed

  /// A joint fit's global map (joint_fit.cpp): per slot, the curve a delta0 or P0 belongs to (-1
  /// shared) and its reference; empty for one curve, whose slot[] says everything.
  std::vector<int> slot_curve;
  std::vector<double> slot_ref;
  /// A joint fit's curves as messages name them (their sources), by curve.
  std::vector<std::string> curve_names;

  int index(FitParameter p) const { return slot[static_cast<int>(p)]; }
  bool is_free(FitParameter p) const { return index(p) >= 0; }
  /// The scene's value of q (fixed.values; w for w), where q is not free.
  double fixed_value(FitParameter q) const;
  /// The name of slot j in messages: "E", or in a joint fit "delta0 of curve 2".
  std::string name_at(std::size_t j) const;
  /// The reported value of slot j at x, and its derivative with respect to x[j].
  double value_at(std::size_t j, const double* x) const;
  double derivative_at(std::size_t j, const double* x) const;

  /// Physical parameters and offsets from x (T = double or a Jet seeded in slots 0..n-1).
  template <class T>
  void physical(const T* x, CurveParameters<T>* p, T* delta0, T* P0) const;
  /// The drag coefficient b [N s/m] at x (0 where not free): the model adds b v at each sample.
  template <class T>
  T drag(const T* x) const;
  /// d(physical)/dx for the reported parameter p at x.
  double derivative(FitParameter q, const double* x) const;
  /// Reported physical value of p at x (w, not s).
  double value(FitParameter q, const double* x) const;
  /// The internal coordinate of free q at which its reported value is v, the other coordinates
  /// as in x (each map is increasing in its coordinate): -infinity where v lies below every value
  /// the map reaches, +infinity above (a bound there binds nothing); FitOptions::bounds.
  double coordinate(FitParameter q, double v, const double* x) const;
};

/// The samples of one fit.
struct FitData {
  std::vector<double> delta, P, a, sqrt_weight;  ///< a: NaN where not measured
  std::vector<bool> retract;
  /// Per sample: 1 in contact, 0 free, -1 the model decides (empty = all -1). Retract
  /// samples up to the observed pull-off are in contact whatever the parameters, which
  /// keeps the cost continuous where the model's pull-off moves across samples.
  std::vector<signed char> contact;
  double a_scale = 1.0;                          ///< divides contact-radius residuals [m]
  /// Errors in the displacement (FitOptions::errors_in_displacement): the force noise over the
  /// displacement noise [N/m], which turns a displacement residual into force units; each contact
  /// sample's residual is then its distance to the curve in that metric. 0: delta is exact.
  double displacement_weight = 0.0;
  /// Fits in time: the base's speed towards the sample at each sample [m/s] - per segment, the
  /// slope of the base position delta + P/k (delta without k) over time, read from the data before
  /// the fit - which a free drag multiplies (empty otherwise).
  std::vector<double> velocity;
  /// Median force and MAD noise of the shallowest quarter of the samples [N].
  double baseline = 0.0, noise = 0.0;
  /// The offset [N] subtracted from P (FitOptions::remove_offset), 0 when none was.
  double offset = 0.0;
  /// The retract is controlled by a cantilever (FitOptions::cantilever_stiffness > 0).
  bool cantilever = false;
  /// The contact point and baseline were found beforehand and the data shifted there: a free
  /// delta0 and P0 start at 0 instead of the scan's values (FitOptions::contact_point).
  bool contact_given = false;
  /// The contact region was found on the unloading samples before the observed pull-off
  /// (retract data without a baseline; fit_data.cpp), and noise is their second-difference noise.
  bool unloading_only = false;
  /// The measured pull-off: the lowest retract force below the retract's baseline [N], and
  /// whether it exceeds the noise - read from the data before the fit (retract_reading.hpp).
  double dip = 0.0;
  bool adhesive = false;
  /// (P, a) data - a rig's load and contact radius, no displacement: `delta` holds the measured
  /// radius (an order of depth for the steps that sort by it), each sample's one residual is the
  /// model's force at its radius against the measured force.
  bool radius_driven = false;
  /// With a known spring constant k: d(deflection)/dz over the contact samples, deflection P/k
  /// and piezo z = delta + P/k (1 where the sample does not deform, 0 where the lever does not
  /// bend); NaN without k or with fewer than 5 samples clearly in contact.
  double contact_slope = std::numeric_limits<double>::quiet_NaN();
  double spring_constant = 0.0;  ///< [N/m] the curve's or the options', 0 if unknown
  /// A fit in time (time_fit.cpp): every sample's time [s] and segment (2: dwell); empty otherwise.
  std::vector<double> t;
  std::vector<int> segment;
  /// The residuals the cost counts: every sample of weight > 0, with its measured radius.
  std::size_t residuals() const;
};

/// Where a branch starts: zero load (approach), pull-off (retract under load control),
/// the fixed-grips point min delta(a) (the end of every curve that still exists), or where a
/// cantilever of stiffness k lets go, dP/d delta = -k (between pull-off and fixed grips).
enum class StartKind { zero_load = 0, pull_off = 1, fixed_grips = 2, cantilever = 3 };

struct BranchStart {
  double a = 0.0, delta = 0.0;
};

class CurveEvaluator final : public ResidualStore {
 public:
  /// cantilever_k [N/m]: 0 for a load-controlled retract, > 0 for one a cantilever of that
  /// stiffness controls (infinity: fixed grips).
  CurveEvaluator(const CurveModel& model, const ParameterMap& map, const FitData& data, double cantilever_k = 0.0);

  /// Residuals (and the row-major Jacobian, residuals x free) at x. False if the
  /// model cannot be evaluated there (a radius outside the model's domain).
  bool evaluate(const double* x, bool jacobian) override;
  /// Forget cached residuals (after the data's weights changed).
  void invalidate() override { have_cache_ = have_saved_ = false; }
  /// Number of samples (residual groups).
  std::size_t points() const override { return row_.size() - 1; }
  /// Row where sample i's residuals start, and how many rows it has.
  std::size_t row(std::size_t i) const override { return row_[i]; }
  std::size_t rows(std::size_t i) const override { return row_[i + 1] - row_[i]; }

  /// Stable-branch start for given physical parameters (double).
  bool branch_start(const CurveParameters<double>& p, StartKind kind, BranchStart* out) const;
  /// Radius with delta(a) = target on a >= lo (delta(lo) <= target); NaN on failure.
  /// If P is given it receives the force there (to ~1e-15 relative).
  double solve_radius(const CurveParameters<double>& p, double target, double lo, double guess,
                      double* P = nullptr) const;
  /// Errors in the displacement: the radius a >= lo whose point (delta(a), P(a)) is nearest the
  /// sample (target_delta, target_P) in the metric (P, kappa delta) [N], by safeguarded Gauss-Newton
  /// from `guess` (the radius at the sample's delta); sets *P there and, if given, *misfit to the
  /// squared distance [N^2]. NaN on failure.
  double nearest_radius(const CurveParameters<double>& p, double target_delta, double target_P, double kappa,
                        double lo, double guess, double* P, double* misfit = nullptr) const;
  /// delta(a), P(a) and their a-derivatives (double).
  void curve(const CurveParameters<double>& p, double a, double* delta, double* P, double* ddelta,
             double* dP) const;
  double typical_radius() const { return a_typ_; }
  /// Per sample, at the last evaluation: held in contact (FitData::contact 1) beyond the end of
  /// the model's branch under its control, so placed at the end.
  const std::vector<char>& clamped() const { return clamped_; }

 private:
  template <class J>
  bool sweep(const double* x, bool jacobian);
  /// Errors in the displacement: sample i's residual (and Jacobian row r0) as its signed distance
  /// to the curve at its nearest radius a (t = delta_i - delta0), along the curve's normal; *P the
  /// model's force there. The normal is orthogonal to the curve at a, so the row is the partial
  /// derivative at fixed a (a moves along the tangent), as for a latent a_i eliminated by Schur.
  template <class J>
  bool distance_residual(const CurveParameters<double>& p, const CurveParameters<J>& pj, std::size_t i, double a,
                         double t, double P0, const J& P0j, const J& d0j, double kappa, bool jacobian, double* P);
  /// Exchanges the cached evaluation with the one kept aside (buffers swap, nothing is copied).
  void swap_saved();

  const CurveModel& model_;
  const ParameterMap& map_;
  const FitData& data_;
  std::size_t n_free_;
  std::vector<std::size_t> row_;
  std::array<std::vector<std::size_t>, 2> branch_order_;  ///< the approach's and the retract's, each sorted by delta
  std::vector<double> a_cache_;
  std::vector<char> clamped_;
  double a_typ_ = 0.0;
  std::array<double, 4> start_cache_{0.0, 0.0, 0.0, 0.0};
  double cantilever_k_ = 0.0;
  std::vector<double> x_cache_;
  bool have_cache_ = false, have_jac_ = false, cache_ok_ = false, reuse_radii_ = false;
  /// The last evaluation with a Jacobian, kept aside when a step is tried beyond it: Ceres ends on
  /// a rejected step, and the solution's report and covariance then need no sweep of their own.
  struct Saved {
    std::vector<double> x, r, J, P_fit;
    std::vector<char> detached, clamped;
    std::size_t contact_count = 0;
  } saved_;
  bool have_saved_ = false;
};

}  // namespace layerjkr::detail
