// The three curve families a fit can vary: closed-form foundations, Hertz, and a spline
// table of any other model whose stiffness scales with E.
#include "fit/evaluators/fit_model.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/constants/constants.hpp>
#include <gsl/gsl_spline.h>

#include "adhesion/dmt_formula.hpp"
#include "fit/evaluators/adhesive_curve.hpp"
#include "fit/evaluators/dugdale_curve.hpp"
#include "core/gsl_support.hpp"
#include "core/scalar.hpp"
#include "core/short_number.hpp"
#include "jkr/jkr_transform.hpp"
#include "models/state_formulas.hpp"
#include "layerjkr/adhesion.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/built_scene.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr::detail {
namespace {


// Profile values at a scalar or Jet radius; a paraboloid is evaluated in T so R can vary.
template <class T>
ProfileAt<T> profile_at(const Profile& p, bool paraboloid, const T& a, const T& R) {
  if (paraboloid) {
    const T a2 = a * a;
    return {a2 / (2.0 * R), a / R, T(1.0) / R, a2 * a2 / (8.0 * R)};
  }
  const double av = value_of(a);
  const ProfileDerivatives d = p.derivatives(av);
  return {lift(d.f, d.df, a), lift(d.df, d.d2f, a), lift(d.d2f, d.d3f, a),
          lift(p.moment(av), av * d.f, a)};
}

// Two-term / Winkler (asymptotic) or full Pasternak / Filonenko-Borodich.
class FoundationCurve final : public CurveModelBase<FoundationCurve> {
 public:
  FoundationCurve(ProfilePtr profile, bool full, bool layer, ModelKind name, StateLaw law)
      : profile_(std::move(profile)), paraboloid_(profile_->is_paraboloid()), full_(full),
        layer_(layer), name_(name), law_(law) {}

  template <class T>
  void curve(const T& a, const CurveParameters<T>& p, T* delta, T* P) const {
    using std::sqrt;
    if (paraboloid_ && !full_) {
      law_.apply(a, two_term_paraboloid_state(a, p.R, p.K, p.G), p, delta, P);
      return;
    }
    const ProfileAt<T> g = profile_at(*profile_, paraboloid_, a, p.R);
    const StateOf<T> h =
        full_ ? full_foundation_state(a, g, p.K, p.G, T(sqrt(p.K / p.G))) : two_term_state(a, g, p.K, p.G);
    law_.apply(a, h, p, delta, P);
  }

  // Paraboloid, asymptotic: delta = a^2/(2R) - 2G/(KR) - sqrt(2w/K) is a quadratic in a
  // (DMT's delta = delta_H as well, without the root).
  bool invert(const CurveParameters<double>& p, double target, double* a, double* P) const override {
    if (!paraboloid_ || full_) return false;
    const double root = law_.model == AdhesionModel::dmt ? 0.0 : p.s * std::sqrt(2.0 / p.K);
    const double a2 = 2.0 * p.R * (target + 2.0 * p.G / (p.K * p.R) + root);
    if (!(a2 > 0.0)) return false;
    *a = std::sqrt(a2);
    double delta = 0.0;
    curve(*a, p, &delta, P);
    return true;
  }

  bool supports(FitParameter q) const override {
    switch (q) {
      case FitParameter::E: return layer_;
      case FitParameter::R: return paraboloid_;
      case FitParameter::sigma0: return false;
      default: return true;
    }
  }
  double min_radius() const override { return 0.0; }
  double max_radius() const override { return profile_->max_radius(); }
  FitFamily family() const override { return FitFamily::foundation; }
  std::string model_name() const override { return law_.name(to_string(name_)); }

 private:
  ProfilePtr profile_;
  bool paraboloid_, full_, layer_;
  ModelKind name_;
  StateLaw law_;
};

// Half-space with a paraboloid: delta_H = a^2/R, P_H = 4 E* a^3 / (3R); JKR, DMT or
// Maugis-Dugdale (which, with w = 0, is Hertz).
class HertzCurve final : public CurveModelBase<HertzCurve> {
 public:
  HertzCurve(double nu, StateLaw law, bool maugis)
      : one_minus_nu2_((1.0 - nu) * (1.0 + nu)), law_(law), maugis_(maugis) {}
  template <class T>
  void curve(const T& a, const CurveParameters<T>& p, T* delta, T* P) const {
    const T E_star = p.E / one_minus_nu2_;
    if (maugis_ && value_of(p.s) > 0.0) {
      maugis_curve(a, E_star, T(p.s * p.s), p.R, p.sigma0, delta, P);
      return;
    }
    const T a_R = a / p.R;  // a paraboloid's Sneddon integrals: I0 = a/R, I2 = 2a/(3R)
    law_.apply(a, half_space_state(a, a_R, (2.0 / 3.0) * a_R, E_star), p, delta, P);
  }
  // Without adhesion delta = a^2/R inverts in closed form.
  bool invert(const CurveParameters<double>& p, double target, double* a, double* P) const override {
    if (p.s != 0.0 || !(target > 0.0)) return false;
    *a = std::sqrt(p.R * target);
    double delta = 0.0;
    curve(*a, p, &delta, P);
    return true;
  }
  bool supports(FitParameter q) const override {
    if (q == FitParameter::sigma0) return maugis_;
    return q != FitParameter::K && q != FitParameter::G;
  }
  double min_radius() const override { return 0.0; }
  double max_radius() const override { return std::numeric_limits<double>::infinity(); }
  FitFamily family() const override { return FitFamily::hertz; }
  std::string model_name() const override {
    const std::string medium = to_string(ModelKind::half_space);
    return maugis_ ? std::string(to_string(AdhesionModel::maugis_dugdale)) + " on " + medium : law_.name(medium);
  }

 private:
  double one_minus_nu2_;
  StateLaw law_;
  bool maugis_;
};

// Natural cubic spline in t = ln a, evaluated with a NULL accelerator (thread-safe).
class LogSpline {
 public:
  LogSpline(const std::vector<double>& t, const std::vector<double>& y)
      : spline_(gsl_spline_alloc(gsl_interp_cspline, t.size()), gsl_spline_free) {
    silence_gsl_errors();
    gsl_spline_init(spline_.get(), t.data(), y.data(), t.size());
  }
  double value(double t) const { return gsl_spline_eval(spline_.get(), t, nullptr); }
  double slope(double t) const { return gsl_spline_eval_deriv(spline_.get(), t, nullptr); }

 private:
  std::unique_ptr<gsl_spline, void (*)(gsl_spline*)> spline_;
};

// Any model whose P_H, S, S' scale with E at fixed nu, h and profile (exact layer, edge
// corrected, auto, half-space with a general profile), tabulated once at the scene's E.
// ln P_H, ln S, ln S' and delta_H (or ln delta_H when positive) are splined in ln a.
class TabulatedCurve final : public CurveModelBase<TabulatedCurve> {
 public:
  TabulatedCurve(ContactModelPtr model, double E_ref, double delta_span, int per_decade, StateLaw law)
      : model_(std::move(model)), E_ref_(E_ref), law_(law) {
    const double lo_bound = model_->min_radius();
    const double hi_bound = model_->max_radius();
    // Upper radius: delta_H reaches 4x the data's span, or the model's bound.
    double a_hi = model_->profile().length_scale();
    if (!(a_hi < hi_bound)) a_hi = 0.5 * hi_bound;
    for (int i = 0; i < 200 && model_->state(a_hi).delta_H < 4.0 * delta_span; ++i) {
      const double next = 2.0 * a_hi;
      if (!(next < hi_bound)) {
        a_hi = std::isfinite(hi_bound) ? hi_bound * (1.0 - 1e-9) : a_hi;
        break;
      }
      a_hi = next;
    }
    for (int i = 0; i < 200 && a_hi > lo_bound && model_->state(0.5 * a_hi).delta_H > 4.0 * delta_span; ++i)
      a_hi *= 0.5;
    const double decades = 6.0;
    double a_lo = a_hi * std::pow(10.0, -decades);
    if (a_lo <= lo_bound) a_lo = lo_bound * (1.0 + 1e-6);
    const int n = std::max(8, static_cast<int>(std::ceil(per_decade * std::log10(a_hi / a_lo)))) + 1;
    std::vector<double> t(n), lnP(n), lnS(n), lnSp(n), dH(n);
    positive_delta_ = true;
    for (int i = 0; i < n; ++i) {
      t[i] = std::log(a_lo) + (std::log(a_hi) - std::log(a_lo)) * i / (n - 1);
      const NonAdhesiveState st = model_->state(std::exp(t[i]));
      if (!(st.P_H > 0.0 && st.S > 0.0 && st.dS_da > 0.0))
        throw NumericalError("fit: model '" + model_->name() + "' has P_H, S or S' <= 0 at a = " +
                             format_double(std::exp(t[i])) + " m; it cannot be tabulated for a fit");
      lnP[i] = std::log(st.P_H);
      lnS[i] = std::log(st.S);
      lnSp[i] = std::log(st.dS_da);
      dH[i] = st.delta_H;
      positive_delta_ = positive_delta_ && st.delta_H > 0.0;
    }
    if (positive_delta_)
      for (auto& v : dH) v = std::log(v);
    a_lo_ = std::exp(t.front());
    a_hi_ = std::exp(t.back());
    lnP_ = std::make_unique<LogSpline>(t, lnP);
    lnS_ = std::make_unique<LogSpline>(t, lnS);
    lnSp_ = std::make_unique<LogSpline>(t, lnSp);
    delta_ = std::make_unique<LogSpline>(t, dH);
    // Interpolation error, measured at the midpoints of every 8th interval.
    for (int i = 0; i + 1 < n; i += 8) {
      const double tm = 0.5 * (t[i] + t[i + 1]);
      const NonAdhesiveState st = model_->state(std::exp(tm));
      const double dh = positive_delta_ ? std::exp(delta_->value(tm)) : delta_->value(tm);
      max_error_ = std::max({max_error_, std::abs(std::exp(lnP_->value(tm)) / st.P_H - 1.0),
                             std::abs(dh / st.delta_H - 1.0),
                             std::abs(std::exp(lnSp_->value(tm)) / st.dS_da - 1.0)});
    }
  }

  template <class T>
  void curve(const T& a, const CurveParameters<T>& p, T* delta, T* P) const {
    using std::exp;
    const double av = value_of(a);
    const double tv = std::log(av);
    const T dt = (a - T(av)) / av;  // d ln a
    const T kappa = p.E / E_ref_;
    const double lp = lnP_->value(tv), ls = lnS_->value(tv), lsp = lnSp_->value(tv);
    const T P_H = exp(lp) * (T(1.0) + lnP_->slope(tv) * dt);
    const T S = exp(ls) * (T(1.0) + lnS_->slope(tv) * dt);
    const T Sp = exp(lsp) * (T(1.0) + lnSp_->slope(tv) * dt);
    T delta_H;
    if (positive_delta_) {
      const double dv = std::exp(delta_->value(tv));
      delta_H = dv * (T(1.0) + delta_->slope(tv) * dt);
    } else {
      delta_H = T(delta_->value(tv)) + delta_->slope(tv) * dt;
    }
    // P_H, S and S' scale with E; delta_H does not.
    law_.apply(a, StateOf<T>{kappa * P_H, delta_H, kappa * S, kappa * Sp}, p, delta, P);
  }

  bool supports(FitParameter q) const override {
    return q != FitParameter::K && q != FitParameter::G && q != FitParameter::R && q != FitParameter::sigma0;
  }
  double min_radius() const override { return a_lo_; }
  double max_radius() const override { return a_hi_; }
  FitFamily family() const override { return FitFamily::tabulated; }
  std::string model_name() const override { return law_.name(model_->name()); }
  double measured_error() const override { return max_error_; }
  std::vector<std::string> notes() const override {
    return {"model '" + model_->name() + "' tabulated on a in [" + short_number(a_lo_) + ", " +
            short_number(a_hi_) + "] m; measured interpolation error " +
            short_number(max_error_) + " (relative)"};
  }

 private:
  ContactModelPtr model_;
  double E_ref_;
  StateLaw law_;
  bool positive_delta_ = true;
  double a_lo_ = 0.0, a_hi_ = 0.0, max_error_ = 0.0;
  std::unique_ptr<LogSpline> lnP_, lnS_, lnSp_, delta_;
};

constexpr double kDugdaleGridSpans = 2.0;

// The Dugdale family of the scene, with the same medium under JKR (tabulated) for the start.
std::unique_ptr<CurveModel> dugdale_curve(const Scene& scene, const ModelSpec& spec, const FitOptions& options,
                                          double delta_span, const CurveParameters<double>& values) {
  const BuiltScene built = build_scene(scene, 0.0, false);
  auto start = std::make_unique<TabulatedCurve>(built.model, spec.layer.E, delta_span,
                                                options.table_points_per_decade, StateLaw{});
  // The grid ends where delta_H reaches twice the data's span: the adhesive curve's delta lies
  // below delta_H, by less than the span on any curve whose pull-off the data show.
  double lo = 0.0, a_max = start->max_radius();
  for (int i = 0; i < 60 && a_max - lo > 1e-3 * a_max; ++i) {
    const double mid = lo > 0.0 ? std::sqrt(lo * a_max) : 0.5 * a_max;
    (built.model->state(mid).delta_H < kDugdaleGridSpans * delta_span ? lo : a_max) = mid;
  }
  const DugdaleKind kind =
      scene.adhesion.model == AdhesionModel::maugis_dugdale ? DugdaleKind::maugis_dugdale : DugdaleKind::dmt;
  return make_dugdale_curve(make_dugdale_solver(*built.model, spec, "fit: a Dugdale law"), kind, spec.layer.E, a_max,
                            values.s * values.s, values.sigma0, built.model->name(), std::move(start));
}

double paraboloid_radius(const Profile& p) {
  return p.is_paraboloid() ? 1.0 / p.derivatives(1.0).d2f : 0.0;
}

// The scene's adhesion as the law the families apply, refusing what a fit does not offer.
StateLaw state_law(const Scene& scene, bool paraboloid) {
  const AdhesionSpec& adhesion = scene.adhesion;
  StateLaw law;
  law.model = adhesion.model;
  if (adhesion.model != AdhesionModel::dmt) return law;
  if (adhesion.sigma0 || adhesion.z0) return law;  // the Dugdale DMT: its own family
  law.R_varies = paraboloid;
  if (!paraboloid) {
    law.tip_radius = dmt_tip_radius(*scene.profile, "fit: adhesion 'dmt'", "");
  }
  return law;
}

}  // namespace

std::unique_ptr<CurveModel> make_curve_model(const Scene& scene, const ResolvedModel& resolved,
                                             const FitOptions& options, double delta_span, SceneParameters* fixed) {
  const ModelSpec& spec = resolved.spec;
  SceneParameters sp;
  sp.values.s = std::sqrt(scene.w);
  sp.values.R = paraboloid_radius(*scene.profile);
  std::unique_ptr<CurveModel> model;
  const bool foundation = !resolved.automatic && (spec.kind == ModelKind::winkler || spec.kind == ModelKind::two_term ||
                                                  spec.kind == ModelKind::full_foundation);
  const bool hertz = !foundation && spec.kind == ModelKind::half_space && scene.profile->is_paraboloid();
  const StateLaw law = state_law(scene, scene.profile->is_paraboloid());
  const bool maugis = scene.adhesion.model == AdhesionModel::maugis_dugdale;
  // A Dugdale law other than Maugis' closed form is solved on the medium (dugdale_curve.hpp).
  const bool dugdale = (maugis && !hertz) || (scene.adhesion.model == AdhesionModel::dmt &&
                                             (scene.adhesion.sigma0 || scene.adhesion.z0));
  if (dugdale && (foundation || resolved.automatic ||
                  (spec.kind != ModelKind::half_space && spec.kind != ModelKind::exact)))
    throw InputError("fit: adhesion '" + std::string(to_string(scene.adhesion.model)) +
                     "' with a Dugdale stress is solved on model half_space or exact (a layer or a stack); this "
                     "scene has model '" + std::string(resolved.automatic ? "auto" : to_string(spec.kind)) +
                     "', whose law gives no gap outside the contact: fit it with adhesion 'jkr' or the classical "
                     "'dmt' (no sigma0, no z0), or choose model 'exact'");
  if (maugis || dugdale) {
    // sigma0 given: fixed (or the start of a free sigma0); z0 given: sigma0 follows w.
    scene.adhesion.validate();
    if (scene.adhesion.sigma0) {
      sp.values.sigma0 = *scene.adhesion.sigma0;
    } else {
      sp.sigma0_per_w = scene.adhesion.dugdale_stress(1.0);
      sp.values.sigma0 = sp.sigma0_per_w * scene.w;
    }
  }
  if (foundation && resolved.constants_from_layer) {
    // K and G scale with E at fixed nu and h: the unit layer's constants, and its warnings
    // (they depend on nu only, so they are the scene's).
    const ElasticLayer& layer = spec.layer;
    const ThinLayerConstants unit = thin_layer_constants({1.0, layer.nu, layer.h, layer.base});
    sp.layer_foundation = true;
    sp.warnings = unit.warnings;
    sp.k_per_E = unit.K;
    sp.g_per_E = spec.kind == ModelKind::winkler ? 0.0 : unit.G;
    sp.values.E = layer.E;
    sp.values.K = layer.E * sp.k_per_E;
    sp.values.G = layer.E * sp.g_per_E;
    model = std::make_unique<FoundationCurve>(scene.profile, false, true, spec.kind, law);
  } else if (foundation) {  // a foundation medium's own constants
    sp.values.K = spec.K;
    sp.values.G = spec.G;
    const bool full = spec.kind == ModelKind::full_foundation;
    const ModelKind name = full ? ModelKind::full_foundation : spec.G == 0.0 ? ModelKind::winkler : ModelKind::two_term;
    model = std::make_unique<FoundationCurve>(scene.profile, full, false, name, law);
  } else if (dugdale) {
    sp.values.E = spec.layer.E;
    sp.nu = spec.layer.nu;
    if (std::count(options.free.begin(), options.free.end(), FitParameter::sigma0) && !scene.profile->is_paraboloid())  // Maugis' lambda places its limits
      sp.values.R = dmt_tip_radius(*scene.profile, "fit: free parameter sigma0",
                                   " (its JKR and DMT limits are placed by Maugis' lambda of the tip's radius)");
    model = dugdale_curve(scene, spec, options, delta_span, sp.values);
  } else if (hertz) {
    sp.values.E = spec.layer.E;
    sp.nu = spec.layer.nu;
    effective_modulus(spec.layer.E, spec.layer.nu);  // validates nu
    model = std::make_unique<HertzCurve>(spec.layer.nu, law, maugis);
  } else {
    // Any other model (exact, edge_corrected, incompressible, uniform, auto, the half-space
    // with another profile, a full foundation of a layer) is tabulated; nothing is judged here,
    // so no reference is built. "auto" chooses for the radii a fit needs: down to 1/20 of the
    // data's span scale.
    sp.values.E = spec.layer.E;
    sp.nu = spec.layer.nu;
    const double a_min =
        resolved.automatic ? std::sqrt(delta_span * scene.profile->length_scale()) / 20.0 : 0.0;
    const BuiltScene built = build_scene(scene, a_min, false);
    model = std::make_unique<TabulatedCurve>(built.model, spec.layer.E, delta_span, options.table_points_per_decade,
                                             law);
  }
  if (fixed) *fixed = sp;
  return model;
}

}  // namespace layerjkr::detail
