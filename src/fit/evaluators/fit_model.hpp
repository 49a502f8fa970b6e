// Internal: the adhesive curve delta(a), P(a) of a scene as a function of the physical
// parameters, templated so ceres::Jet carries derivatives in the parameters and in a.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <ceres/jet.h>

#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"

namespace layerjkr::detail {

/// Jets for the Jacobian: slots 0..N-2 hold the free parameters, slot N-1 the radius a.
/// Named by their slot count; four sizes, so a fit with few free parameters does not
/// carry unused slots.
using Jet1 = ceres::Jet<double, 1>;
using Jet2 = ceres::Jet<double, 2>;
using Jet4 = ceres::Jet<double, 4>;
using Jet8 = ceres::Jet<double, 8>;

/// Physical parameters of one curve. s = sqrt(w) [sqrt(J/m^2)] keeps w = 0 regular.
template <class T>
struct CurveParameters {
  T K{}, G{};  ///< foundation [N/m^3], [N/m] (foundation family)
  T E{};    ///< Young's modulus [Pa] (hertz, tabulated; layer foundations via K, G)
  T s{};    ///< sqrt(work of adhesion)
  T R{};    ///< paraboloid radius [m] (when the profile is a paraboloid)
  T sigma0{};  ///< Dugdale stress [Pa] (Maugis-Dugdale adhesion)
  /// In time (time_fit.hpp): a standard linear solid's relaxed modulus [Pa] and time [s], a power
  /// law's exponent, crack kinetics' speed [m/s] and exponent, a two-term Maxwell law's second arm
  /// (modulus [Pa], time [s]). The curve families ignore them.
  T E_inf{}, tau{}, beta{}, v_star{}, n{}, E_2{}, tau_2{};
};

/// delta(a) and P(a) of the adhesive curve for one model family.
class CurveModel {
 public:
  virtual ~CurveModel() = default;
  virtual void evaluate(const Jet1& a, const CurveParameters<Jet1>& p, Jet1* delta, Jet1* P) const = 0;
  virtual void evaluate(const Jet2& a, const CurveParameters<Jet2>& p, Jet2* delta, Jet2* P) const = 0;
  virtual void evaluate(const Jet4& a, const CurveParameters<Jet4>& p, Jet4* delta, Jet4* P) const = 0;
  virtual void evaluate(const Jet8& a, const CurveParameters<Jet8>& p, Jet8* delta, Jet8* P) const = 0;
  /// Closed-form inverse of delta(a) = target where one exists: sets *a and *P (the
  /// force at that radius) and returns true; false means "use Newton iteration".
  virtual bool invert(const CurveParameters<double>& p, double target, double* a, double* P) const {
    (void)p, (void)target, (void)a, (void)P;
    return false;
  }
  /// Which physical parameters this family can vary.
  virtual bool supports(FitParameter p) const = 0;
  /// Admissible radii (a_min may be 0, exclusive).
  virtual double min_radius() const = 0;
  virtual double max_radius() const = 0;
  virtual FitFamily family() const = 0;
  virtual std::string model_name() const = 0;
  /// How the model was built (e.g. the table's interpolation error): FitSummary::notices, or
  /// warnings where measured_error() matters against the data's noise.
  virtual std::vector<std::string> notes() const { return {}; }
  /// The measured relative interpolation error of the model's curve (0 for a closed form).
  virtual double measured_error() const { return 0.0; }
  /// Makes the model meet its accuracy target at the parameters p where it is built per parameter
  /// vector (a finer grid); true if it changed, and the fit must then evaluate again.
  virtual bool refine_at(const CurveParameters<double>& p) {
    (void)p;
    return false;
  }
  /// Extra lines for the warnings at the fitted parameters p (e.g. an interpolation error
  /// that exceeds its target there).
  virtual std::vector<std::string> notes_at(const CurveParameters<double>& p) const {
    (void)p;
    return {};
  }
  /// A cheaper model of the same medium and parameters for the data-driven start (null: this
  /// one). Non-owning; lives as long as this model.
  virtual const CurveModel* start_model() const { return nullptr; }
};

/// Implements the four Jet overloads with one template, Derived::curve(a, p, delta, P).
template <class Derived>
class CurveModelBase : public CurveModel {
 public:
  void evaluate(const Jet1& a, const CurveParameters<Jet1>& p, Jet1* d, Jet1* P) const override {
    static_cast<const Derived*>(this)->curve(a, p, d, P);
  }
  void evaluate(const Jet2& a, const CurveParameters<Jet2>& p, Jet2* d, Jet2* P) const override {
    static_cast<const Derived*>(this)->curve(a, p, d, P);
  }
  void evaluate(const Jet4& a, const CurveParameters<Jet4>& p, Jet4* d, Jet4* P) const override {
    static_cast<const Derived*>(this)->curve(a, p, d, P);
  }
  void evaluate(const Jet8& a, const CurveParameters<Jet8>& p, Jet8* d, Jet8* P) const override {
    static_cast<const Derived*>(this)->curve(a, p, d, P);
  }
};

/// The scene's fixed values as CurveParameters<double> (s = sqrt(w)).
struct SceneParameters {
  CurveParameters<double> values;
  double k_per_E = 0.0, g_per_E = 0.0;  ///< layer foundations: K = k E, G = g E
  bool layer_foundation = false;
  double nu = 0.0;                      ///< hertz / tabulated: E* = E / (1 - nu^2)
  /// Maugis-Dugdale with a spacing z0: sigma0 = sigma0_per_w * w while sigma0 is not free
  /// (0: sigma0 is values.sigma0).
  double sigma0_per_w = 0.0;
  std::vector<std::string> warnings;    ///< the thin-layer warnings of a layer foundation
};

/// Builds the curve model of `scene` for a fit, dispatching on its resolved model (`resolved`,
/// resolve_model(scene)). `delta_span` [m] > 0 sizes the tabulated family's radius range so
/// that delta_H reaches several times the data's span.
std::unique_ptr<CurveModel> make_curve_model(const Scene& scene, const ResolvedModel& resolved,
                                             const FitOptions& options, double delta_span, SceneParameters* fixed);

}  // namespace layerjkr::detail
