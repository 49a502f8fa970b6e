// A Dugdale law solved on the medium as a fit family (dugdale_curve.hpp): one grid of radii per
// parameter vector, interpolated in a, with forward-difference derivatives in w and sigma0.
#include "fit/evaluators/dugdale_curve.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <boost/math/interpolators/barycentric_rational.hpp>

#include "core/scalar.hpp"
#include "core/short_number.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.141592653589793238462643383279502884;

// Radii per grid: Chebyshev-Lobatto in u = sqrt(a) over [0, sqrt(a_max)], where the curve is
// smooth (near the JKR limit it carries a^(1/2) and a^(3/2) terms). Measured on the 10 nm film
// of the tests at Floater-Hormann order 7, lambda ~ 0.5: 41 radii in a itself left 1e-5 of the
// force near the pull-off; in u, 21 / 25 / 31 / 41 radii give 7e-6 / 5e-7 / 1.3e-7 / 1.5e-8 of
// the spans. Towards JKR the curve turns from the adhesive disc's to JKR's within a few zone
// widths c - a, which shrink as lambda grows: at lambda ~ 4 on a 1 GPa film 31 radii leave 1e-4.
// So the grid starts at 31 radii and doubles its intervals until the error measured at the
// scene's parameters is below the target.
constexpr int kGridRadii[] = {31, 61, 121};
constexpr double kTargetError = 1e-6;  // of the force and indentation spans (the notes say 1e-6)
constexpr std::size_t kInterpolationOrder = 7;
// Relative step of the forward differences in w and sigma0. The states are not smooth in the
// parameters below ~1e-9 (the solver's root tolerance and its panels, which follow c), and sigma0
// moves the curve weakly: measured on a 1 GPa film at lambda ~ 2 with 0.5 % noise, a step of 1e-6
// stopped after 124 iterations at a point of higher cost with sigma0's error bar 3.5x too small;
// 1e-4 and 1e-3 agree to 4 digits in the values and error bars, 1e-3 in 12 iterations.
constexpr double kDifferenceStep = 1e-3;
// Grids kept: a Jacobian needs three, a line search a few more.
constexpr std::size_t kCachedGrids = 12;

template <class T>
bool varies(const T& x) {
  if constexpr (std::is_same_v<T, double>) {
    (void)x;
    return false;
  } else {
    return !x.v.isZero();
  }
}

// delta(a) and P(a) at E_ref for one (w, sigma0), interpolated on the grid.
struct Grid {
  double w = 0.0, sigma0 = 0.0;
  bool ok = false;
  std::vector<double> delta_nodes, P_nodes;
  std::unique_ptr<boost::math::barycentric_rational<double>> delta, P;
};

class DugdaleCurve final : public CurveModelBase<DugdaleCurve> {
 public:
  DugdaleCurve(std::shared_ptr<const DugdaleSolver> solver, DugdaleKind kind, double E_ref, double a_max,
               std::string medium, std::unique_ptr<CurveModel> start)
      : solver_(std::move(solver)), kind_(kind), E_ref_(E_ref), medium_(std::move(medium)), start_(std::move(start)) {
    set_radii(a_max, kGridRadii[0]);
  }

  // Shrinks the grid until the scene's parameters solve on it, then refines it until the
  // interpolation error there meets the target (or the finest grid is reached).
  void prepare(double w, double sigma0) {
    if (w == 0.0) sigma0 = 1.0;  // the non-adhesive curve (sigma0 is 0 when it follows w)
    std::string why;
    for (int shrink = 0; shrink <= 8; ++shrink) {
      if (shrink > 0) set_radii(0.5 * a_max_, kGridRadii[0]);
      why.clear();
      if (build(w, sigma0, &why)->ok) break;
    }
    if (!grid(w, sigma0)->ok)
      throw InputError("fit: the " + std::string(kind_name()) + " curve on '" + medium_ +
                       "' cannot be solved at the scene's w = " + format_double(w) + " J/m^2, sigma0 = " +
                       format_double(sigma0) + " Pa: " + why);
    refine(w, sigma0);
  }

  bool refine_at(const CurveParameters<double>& p) override {
    const double kappa = p.E / E_ref_;
    return refine(p.s * p.s / kappa, p.sigma0 / kappa);
  }

  // The largest error of the grid at (w, sigma0) [at E_ref] against the solver midway between
  // every fourth pair of radii, relative to the force and indentation spans (NaN if unsolvable).
  double interpolation_error(double w, double sigma0) const {
    const std::shared_ptr<const Grid> g = grid(w, sigma0);
    if (!g->ok) return std::numeric_limits<double>::quiet_NaN();
    double P_span = 0.0, delta_span = 0.0, error = 0.0;
    for (std::size_t i = 0; i < radii_.size(); ++i) {
      P_span = std::max(P_span, std::abs(g->P_nodes[i]));
      delta_span = std::max(delta_span, std::abs(g->delta_nodes[i]));
    }
    try {
      for (std::size_t i = 0; i + 1 < radii_.size(); i += 4) {
        const double a = 0.5 * (radii_[i] + radii_[i + 1]);
        const AdhesiveState s = solve(a, g->w, g->sigma0);  // the grid's own (normalised) parameters
        error = std::max({error, std::abs((*g->P)(std::sqrt(a)) - s.P) / P_span,
                          std::abs((*g->delta)(std::sqrt(a)) - s.delta) / delta_span});
      }
    } catch (const Error&) {
      return std::numeric_limits<double>::quiet_NaN();
    }
    return error;
  }

  template <class T>
  void curve(const T& a, const CurveParameters<T>& p, T* delta, T* P) const {
    const T kappa = p.E / E_ref_;  // P(a; E, w, sigma0) = kappa P(a; E_ref, w/kappa, sigma0/kappa)
    const T w = p.s * p.s / kappa;
    const T sigma0 = p.sigma0 / kappa;
    const double av = value_of(a), wv = value_of(w), sv = value_of(sigma0);
    const std::shared_ptr<const Grid> g = grid(wv, sv);
    if (!g->ok || !(av >= 0.0 && av <= a_max_)) {
      *delta = T(kNaN);
      *P = T(kNaN);
      return;
    }
    // Interpolated in u = sqrt(a); d/da = (d/du) / (2u), u kept off 0 (at a = 0 itself the
    // slope of the first node's u is used: the curve's a-derivative is finite there).
    const double u = std::sqrt(av), du_da = 0.5 / std::max(u, nodes_[1]);
    const T da = a - T(av);
    T d = T((*g->delta)(u)) + g->delta->prime(std::max(u, nodes_[1])) * du_da * da;
    T f = T((*g->P)(u)) + g->P->prime(std::max(u, nodes_[1])) * du_da * da;
    // With w = 0 the curve is the non-adhesive one and does not move to first order in w
    // (the Dugdale zone's force grows as w^(2/3)), nor in sigma0.
    if (wv > 0.0 && varies(w)) add_difference(*g, grid(wv * (1.0 + kDifferenceStep), sv), av, w - T(wv), &d, &f);
    if (wv > 0.0 && varies(sigma0))
      add_difference(*g, grid(wv, sv * (1.0 + kDifferenceStep)), av, sigma0 - T(sv), &d, &f);
    *delta = d;
    *P = kappa * f;
  }

  bool supports(FitParameter q) const override {
    if (q == FitParameter::sigma0) return kind_ == DugdaleKind::maugis_dugdale;
    return q != FitParameter::K && q != FitParameter::G && q != FitParameter::R;
  }
  double min_radius() const override { return 0.0; }
  double max_radius() const override { return a_max_; }
  FitFamily family() const override { return FitFamily::dugdale; }
  std::string model_name() const override { return std::string(kind_name()) + " on " + medium_; }
  double measured_error() const override { return error_; }
  std::vector<std::string> notes() const override {
    return {std::string(kind_name()) + " on '" + medium_ + "' solved per parameter vector on " +
            std::to_string(radii_.size()) + " radii in [0, " + short_number(a_max_) +
            "] m and interpolated; measured interpolation error " + short_number(error_) +
            " of the force and indentation spans at the start (target 1e-6)" +
            (solver_->tabulated() ? "; states from the medium's Dugdale table, measured error " +
                                        short_number(solver_->table_error()) + " of each part"
                                  : std::string())};
  }
  std::vector<std::string> notes_at(const CurveParameters<double>& p) const override {
    const double kappa = p.E / E_ref_;
    const double error = interpolation_error(p.s * p.s / kappa, p.sigma0 / kappa);
    if (error <= kTargetError) return {};
    return {"at the fitted parameters the " + std::string(kind_name()) + " grid's measured interpolation error is " +
            short_number(error) + " of the force and indentation spans (target 1e-6): the fit's precision is limited by it"};
  }
  const CurveModel* start_model() const override { return start_.get(); }

 private:
  const char* kind_name() const { return kind_ == DugdaleKind::maugis_dugdale ? "maugis_dugdale" : "dmt (Dugdale)"; }

  // Doubles the grid's intervals until its error at (w, sigma0) [at E_ref] meets the target or
  // the finest grid is reached; error_ keeps the last measurement. True if the grid changed.
  bool refine(double w, double sigma0) {
    const std::size_t before = radii_.size();
    error_ = interpolation_error(w, sigma0);
    for (int n : kGridRadii) {
      if (!(error_ > kTargetError)) break;  // met, or NaN (not solvable there: the fit's step fails)
      if (static_cast<std::size_t>(n) <= radii_.size()) continue;
      set_radii(a_max_, n);
      error_ = interpolation_error(w, sigma0);
    }
    return radii_.size() != before;
  }

  void set_radii(double a_max, int n) {
    a_max_ = a_max;
    radii_.resize(static_cast<std::size_t>(n));
    nodes_.resize(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < radii_.size(); ++i) {
      nodes_[i] = 0.5 * std::sqrt(a_max) * (1.0 - std::cos(kPi * static_cast<double>(i) / (n - 1)));
      radii_[i] = nodes_[i] * nodes_[i];
    }
    nodes_.back() = std::sqrt(a_max);
    radii_.back() = a_max;
    std::lock_guard<std::mutex> lock(mutex_);
    cache_.clear();
  }

  AdhesiveState solve(double a, double w, double sigma0) const {
    return kind_ == DugdaleKind::maugis_dugdale ? solver_->maugis_dugdale(a, w, sigma0) : solver_->dmt(a, w, sigma0);
  }

  // The difference quotient of the grids g and h (one parameter stepped) at av, times the step dx.
  template <class T>
  static void add_difference(const Grid& g, const std::shared_ptr<const Grid>& h, double av, const T& dx, T* d, T* f) {
    const double step = (h->w - g.w) + (h->sigma0 - g.sigma0);  // one of the two is zero
    if (!h->ok) {
      *d = T(kNaN);
      *f = T(kNaN);
      return;
    }
    const double u = std::sqrt(av);
    *d += ((*h->delta)(u) - (*g.delta)(u)) / step * dx;
    *f += ((*h->P)(u) - (*g.P)(u)) / step * dx;
  }

  std::shared_ptr<const Grid> grid(double w, double sigma0) const {
    if (w == 0.0) sigma0 = 1.0;  // the non-adhesive curve, whatever sigma0 (0 when it follows w)
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& g : cache_)
        if (g->w == w && g->sigma0 == sigma0) return g;
    }
    return build(w, sigma0, nullptr);
  }

  // Solves the grid; a parameter vector the solver refuses (the zone leaving its range, a bad
  // value) gives a grid that is not ok, and the fit's step is rejected.
  std::shared_ptr<const Grid> build(double w, double sigma0, std::string* why) const {
    auto g = std::make_shared<Grid>();
    g->w = w;
    g->sigma0 = sigma0;
    try {
      if (!(std::isfinite(w) && w >= 0.0 && std::isfinite(sigma0) && sigma0 > 0.0))
        throw Error("w = " + format_double(w) + " J/m^2, sigma0 = " + format_double(sigma0) + " Pa");
      for (double a : radii_) {
        const AdhesiveState s = solve(a, w, sigma0);
        g->delta_nodes.push_back(s.delta);
        g->P_nodes.push_back(s.P);
      }
      g->delta = std::make_unique<boost::math::barycentric_rational<double>>(
          nodes_.data(), g->delta_nodes.data(), nodes_.size(), kInterpolationOrder);
      g->P = std::make_unique<boost::math::barycentric_rational<double>>(nodes_.data(), g->P_nodes.data(),
                                                                         nodes_.size(), kInterpolationOrder);
      g->ok = true;
    } catch (const Error& e) {
      if (why) *why = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    cache_.push_front(g);
    if (cache_.size() > kCachedGrids) cache_.pop_back();
    return g;
  }

  std::shared_ptr<const DugdaleSolver> solver_;
  DugdaleKind kind_;
  double E_ref_;
  std::string medium_;
  std::unique_ptr<CurveModel> start_;
  double a_max_ = 0.0, error_ = 0.0;
  std::vector<double> radii_, nodes_;  // nodes_: sqrt(radii_), where the curve is interpolated
  mutable std::mutex mutex_;
  mutable std::deque<std::shared_ptr<const Grid>> cache_;
};

}  // namespace

std::unique_ptr<CurveModel> make_dugdale_curve(std::shared_ptr<const DugdaleSolver> solver, DugdaleKind kind,
                                               double E_ref, double a_max, double w, double sigma0,
                                               std::string medium, std::unique_ptr<CurveModel> start) {
  auto model = std::make_unique<DugdaleCurve>(std::move(solver), kind, E_ref, a_max, std::move(medium),
                                              std::move(start));
  model->prepare(w, sigma0);
  return model;
}

}  // namespace layerjkr::detail
