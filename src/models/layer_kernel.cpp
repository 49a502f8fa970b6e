// The exact layer's kernel: Chebyshev tables near the origin, an asymptotic series beyond.
#include "models/layer_kernel.hpp"

#include <gsl/gsl_chebyshev.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/ooura_fourier_integrals.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <utility>

#include "core/context_caches.hpp"
#include "core/gsl_support.hpp"
#include "core/parallel.hpp"
#include "models/kernel_transform.hpp"
#include "models/stack_symbol.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kBeta = 2.0;  // decay rate of the subtracted model (A + B u) e^{-beta u}: the top layer's
constexpr int kChebOrder = 20;      // terms a piece
constexpr int kTailTerms = 24;      // asymptotic terms beyond kNear
// Pieces of the Chebyshev table. The remainder's transform is singular only on the imaginary
// axis (at +-2i, +-4i, ...: q(u) is a series in e^{-2u} times polynomials for large u), so a
// piece may be as wide as its distance from the origin: 21 points a piece reach rounding.
constexpr double kBreaks[] = {0, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};

// q(u) = 1 - L(u), written with E = exp(-2u): no overflow and no cancellation.
double closed_form_q(double u, double kappa, bool bonded) {
  const double E = std::exp(-2.0 * u);
  if (bonded) {
    const double s = 1.0 + 2.0 * u;
    return E * (2.0 * kappa * E + s * s + kappa * kappa) /
           (kappa * (1.0 + E * E) + (4.0 * u * u + 1.0 + kappa * kappa) * E);
  }
  if (u == 0.0) return 1.0;  // 0/0 below; quadrature rules with end nodes evaluate it
  const double one_minus_E = -std::expm1(-2.0 * u);
  return 2.0 * E * (one_minus_E + 2.0 * u) / (-std::expm1(-4.0 * u) + 4.0 * u * E);
}

// Truncated power series in u: coefficient k of u^k.
using Series = std::vector<double>;

Series exp_series(double c, int n) {  // e^{c u}
  Series s(static_cast<std::size_t>(n));
  double term = 1.0;
  for (int k = 0; k < n; ++k) {
    s[static_cast<std::size_t>(k)] = term;
    term *= c / (k + 1);
  }
  return s;
}

Series operator*(const Series& a, const Series& b) {
  Series c(a.size(), 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; i + j < a.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

Series operator+(Series a, const Series& b) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
  return a;
}

Series operator*(double c, Series a) {
  for (double& v : a) v *= c;
  return a;
}

Series operator/(const Series& a, const Series& b) {  // b[0] != 0
  Series c(a.size(), 0.0);
  for (std::size_t k = 0; k < a.size(); ++k) {
    double v = a[k];
    for (std::size_t j = 1; j <= k; ++j) v -= b[j] * c[k - j];
    c[k] = v / b[0];
  }
  return c;
}

Series polynomial(std::initializer_list<double> coefficients, int n) {
  Series s(static_cast<std::size_t>(n), 0.0);
  std::size_t k = 0;
  for (double c : coefficients) s[k++] = c;
  return s;
}

// (1 - e^{c u}) / u, exactly: the constant terms cancel before the division.
Series one_minus_exp_over_u(double c, int n) {
  const Series e = exp_series(c, n + 1);
  Series s(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = -e[k + 1];
  return s;
}

// q(u) minus the subtracted model (A + B u) e^{-2u}.
template <class Q>
struct Remainder {
  const Q* q;
  double A, B;
  static double at(double u, void* p) {
    const auto* r = static_cast<const Remainder*>(p);
    return (*r->q)(u) - std::exp(-kBeta * u) * (r->A + r->B * u);
  }
};

double slope_at_zero(double kappa, bool bonded) {  // q'(0) = -L'(0)
  return bonded ? -4.0 * (kappa - 1.0) / ((kappa + 1.0) * (kappa + 1.0)) : -0.5;
}

struct ChebFree {
  void operator()(gsl_cheb_series* s) const { gsl_cheb_free(s); }
};
using Cheb = std::unique_ptr<gsl_cheb_series, ChebFree>;

}  // namespace

struct LayerKernelFunction::Pieces {
  std::vector<Cheb> value, slope;  // on [breaks[i], breaks[i + 1]]
};

namespace {
// The piece holding x in [0, near).
std::size_t piece_index(const std::vector<double>& breaks, double x) {
  return static_cast<std::size_t>(std::upper_bound(breaks.begin(), breaks.end(), x) - breaks.begin()) - 1;
}

// tail[k] = (-1)^(k+1) (2k+1)! q_(2k+1) from q's Taylor coefficients q_n.
std::vector<double> tail_from(const std::vector<double>& q) {
  std::vector<double> tail;
  double factorial = 1.0;  // (2k+1)!
  for (int k = 0; k < kTailTerms; ++k) {
    factorial *= (k == 0) ? 1.0 : (2.0 * k) * (2.0 * k + 1.0);
    const double sign = (k % 2 == 0) ? -1.0 : 1.0;
    tail.push_back(sign * factorial * q[2 * static_cast<std::size_t>(k) + 1]);
  }
  return tail;
}

// The asymptotic series' terms at x: |tail[k]| / x^(2k+2).
std::vector<double> tail_terms(const std::vector<double>& tail, double x) {
  std::vector<double> t;
  double p = 1.0 / (x * x);
  for (double c : tail) {
    t.push_back(std::abs(c) * p);
    p /= x * x;
  }
  return t;
}
}  // namespace

std::size_t LayerKernelFunction::pieces() const { return pieces_->value.size(); }

template <class Q>
void LayerKernelFunction::build(const Q& q, const std::vector<double>& splits, double size) {
  silence_gsl_errors();
  Remainder<Q> rem{&q, model_a_, model_b_};
  struct Transform {
    Remainder<Q>* rem;
    const std::vector<double>* splits;
    double scale;
    static double at(double sigma, void* p) {
      const auto* t = static_cast<Transform*>(p);
      return cosine_transform(gsl_function{&Remainder<Q>::at, t->rem}, sigma, *t->splits, t->scale,
                              t->splits->empty() ? 60 : 30);
    }
  } transform{&rem, &splits, std::max({1.0, std::abs(model_a_), 0.5 * std::abs(model_b_), size})};
  // The transforms at every point gsl_cheb_init will sample (its documented Chebyshev points, in
  // its own arithmetic), on several threads; gsl_cheb_init then looks them up, so the series are
  // bit for bit those of sampling in turn.
  const std::size_t pieces = breaks_.size() - 1, n = kChebOrder + 1;
  std::vector<double> x(pieces * n), value(pieces * n);
  for (std::size_t i = 0; i < pieces; ++i) {
    const double bma = 0.5 * (breaks_[i + 1] - breaks_[i]), bpa = 0.5 * (breaks_[i + 1] + breaks_[i]);
    for (std::size_t k = 0; k < n; ++k) {
      const double y = std::cos(M_PI * (static_cast<double>(k) + 0.5) / static_cast<double>(n));
      x[i * n + k] = y * bma + bpa;
    }
  }
  parallel_for(static_cast<int>(x.size()), [&](int j) {
    value[static_cast<std::size_t>(j)] = Transform::at(x[static_cast<std::size_t>(j)], &transform);
  });
  struct Lookup {
    const std::vector<double>* x;
    const std::vector<double>* value;
    std::size_t begin, n;
    Transform* transform;
    static double at(double xs, void* p) {
      const auto* l = static_cast<const Lookup*>(p);
      for (std::size_t k = l->begin; k < l->begin + l->n; ++k)
        if ((*l->x)[k] == xs) return (*l->value)[k];
      return Transform::at(xs, l->transform);  // a point computed otherwise than here: solved again
    }
  };
  for (std::size_t i = 0; i < pieces; ++i) {
    Lookup lookup{&x, &value, i * n, n, &transform};
    gsl_function f{&Lookup::at, &lookup};
    Cheb c(gsl_cheb_alloc(kChebOrder));
    gsl_cheb_init(c.get(), &f, breaks_[i], breaks_[i + 1]);
    if (!std::isfinite(gsl_cheb_eval(c.get(), 0.5 * (breaks_[i] + breaks_[i + 1]))))
      throw NumericalError("layerjkr exact layer: the kernel table's piece " + std::to_string(i) + " is not finite");
    Cheb d(gsl_cheb_alloc(kChebOrder));
    gsl_cheb_calc_deriv(d.get(), c.get());
    pieces_->value.push_back(std::move(c));
    pieces_->slope.push_back(std::move(d));
  }
}

std::vector<double> LayerKernelFunction::taylor_one_minus_L(double nu, bool bonded, int count) {
  const int n = count;
  const double kappa = 3.0 - 4.0 * nu;
  const Series E = exp_series(-2.0, n);
  if (bonded) {
    const Series s2 = polynomial({1.0, 4.0, 4.0}, n);  // (1 + 2u)^2
    const Series num = E * ((2.0 * kappa) * E + s2 + polynomial({kappa * kappa}, n));
    const Series den = kappa * (E * E + polynomial({1.0}, n)) +
                       polynomial({1.0 + kappa * kappa, 0.0, 4.0}, n) * E;
    return num / den;
  }
  // q = 2E (1 - E + 2u) / (1 - E^2 + 4u E): numerator and denominator divided by u.
  const Series num = 2.0 * (E * (one_minus_exp_over_u(-2.0, n) + polynomial({2.0}, n)));
  const Series den = one_minus_exp_over_u(-4.0, n) + 4.0 * E;
  return num / den;
}

double LayerKernelFunction::one_minus_L(double nu, bool bonded, double u) {
  return closed_form_q(u, 3.0 - 4.0 * nu, bonded);
}

double LayerKernelFunction::direct(const StackSymbol& symbol, double sigma) {
  auto q = [&](double u) { return symbol.q(u); };
  sigma = std::abs(sigma);
  if (sigma == 0.0) return boost::math::quadrature::exp_sinh<double>().integrate(q, 1e-15);
  static thread_local boost::math::quadrature::ooura_fourier_cos<double> rule(1e-15);
  return rule.integrate(q, sigma).first;
}

double LayerKernelFunction::direct(double nu, bool bonded, double sigma) {
  // Boost's Ooura double-exponential Fourier rule: independent of the GSL table it checks.
  const double kappa = 3.0 - 4.0 * nu;
  auto q = [&](double u) { return closed_form_q(u, kappa, bonded); };
  sigma = std::abs(sigma);
  if (sigma == 0.0) return boost::math::quadrature::exp_sinh<double>().integrate(q, 1e-15);
  static thread_local boost::math::quadrature::ooura_fourier_cos<double> rule(1e-15);
  return rule.integrate(q, sigma).first;
}

LayerKernelFunction::LayerKernelFunction(double nu, bool bonded) : pieces_(std::make_unique<Pieces>()) {
  const double kappa = 3.0 - 4.0 * nu;
  model_a_ = 1.0;
  model_b_ = slope_at_zero(kappa, bonded) + kBeta;
  tail_ = tail_from(taylor_one_minus_L(nu, bonded, 2 * kTailTerms + 1));
  breaks_.assign(std::begin(kBreaks), std::end(kBreaks));
  near_ = kNear;
  const auto q = [kappa, bonded](double u) { return closed_form_q(u, kappa, bonded); };
  build(q, {}, 1.0);
}

LayerKernelFunction::LayerKernelFunction(const StackSymbol& symbol) : pieces_(std::make_unique<Pieces>()) {
  // Cauchy radius for q's Taylor coefficients: inside q's nearest complex singularity, which
  // moves in like h1/H, and like mu_s/mu_film for a stiff film on a soft substrate.
  double rho = 0.25 / std::max(1.0, symbol.total_thickness());
  if (symbol.max_layer_over_substrate() > 1.0) rho /= symbol.max_layer_over_substrate();
  constexpr int kCount = 2 * kTailTerms + 1, kPoints = 512;
  const std::vector<double> q = symbol.taylor(kCount, rho, kPoints);
  const std::vector<double> check = symbol.taylor(kCount, 0.8 * rho, kPoints);
  model_a_ = symbol.q0();
  model_b_ = q[1] + kBeta * symbol.q0();
  tail_ = tail_from(q);
  const std::vector<double> tail_check = tail_from(check);
  // The tail starts at the first break where its last terms are below 1e-18 and the two
  // Cauchy radii agree on the sum to 1e-16: both the truncation and the coefficients' own
  // rounding (amplified by rho^-n) are then negligible.
  breaks_.assign(std::begin(kBreaks), std::end(kBreaks));
  bool factor_one_and_half = true;
  for (;;) {
    const double x = breaks_.back();
    const std::vector<double> t = tail_terms(tail_, x), tc = tail_terms(tail_check, x);
    double spread = 0.0;
    {
      const double y = 1.0 / (x * x);
      double a = 0.0, b = 0.0;
      for (int k = kTailTerms - 1; k >= 0; --k) {
        a = a * y + tail_[static_cast<std::size_t>(k)];
        b = b * y + tail_check[static_cast<std::size_t>(k)];
      }
      spread = std::abs(a - b) * y;
    }
    if (t[kTailTerms - 1] < 1e-18 && t[kTailTerms - 2] < 1e-18 && spread < 1e-16) break;
    // No solve asks beyond 2 max_a_over_h (<= 2000): where the series cannot be trusted by then
    // (a top layer thin against the stack, or a stiff layer near the surface, moves q's nearest
    // singularity in), the table simply ends there and the kernel has no tail.
    if (x >= kMaxSigma) {
      tail_.clear();
      break;
    }
    breaks_.push_back(std::min(kMaxSigma, x * (factor_one_and_half ? 1.5 : 4.0 / 3.0)));
    factor_one_and_half = !factor_one_and_half;
  }
  near_ = breaks_.back();
  if (tail_.empty()) {
    // Without the series the model's only use would be the tail; its Taylor slope q'(0) is
    // moreover meaningless for a stack whose compliance changes on scales u ~ h1/H far below 1
    // (1e12 for a thick soft layer under a stiff one): the table holds the transform of q itself.
    model_a_ = model_b_ = 0.0;
  }
  const auto qfun = [&symbol](double u) { return symbol.q(u); };
  build(qfun, symbol.switch_points(), integral_of_abs(qfun, symbol.switch_points()));
}

LayerKernelFunction::~LayerKernelFunction() = default;

// Layout: a, b, near, #breaks, breaks, #tail, tail, then each piece's Chebyshev order and its
// order + 1 coefficients (its interval is its breaks; the slope's series is derived again).
std::vector<double> LayerKernelFunction::serialized() const {
  std::vector<double> out{model_a_, model_b_, near_, static_cast<double>(breaks_.size())};
  out.insert(out.end(), breaks_.begin(), breaks_.end());
  out.push_back(static_cast<double>(tail_.size()));
  out.insert(out.end(), tail_.begin(), tail_.end());
  for (const Cheb& c : pieces_->value) {
    out.push_back(static_cast<double>(c->order));
    out.insert(out.end(), c->c, c->c + c->order + 1);
  }
  return out;
}

LayerKernelFunction::LayerKernelFunction(const std::vector<double>& serialized)
    : pieces_(std::make_unique<Pieces>()) {
  std::size_t at = 0;
  auto next = [&]() {
    if (at >= serialized.size()) throw NumericalError("layerjkr: a cached kernel is shorter than its layout");
    return serialized[at++];
  };
  auto count = [&](double limit) {
    const double n = next();
    if (!(n >= 0.0 && n <= limit && n == std::floor(n))) throw NumericalError("layerjkr: a cached kernel's count is invalid");
    return static_cast<std::size_t>(n);
  };
  model_a_ = next();
  model_b_ = next();
  near_ = next();
  breaks_.resize(count(1e6));
  for (double& b : breaks_) b = next();
  tail_.resize(count(1e3));
  for (double& t : tail_) t = next();
  if (breaks_.size() < 2 || (!tail_.empty() && tail_.size() != static_cast<std::size_t>(kTailTerms)))
    throw NumericalError("layerjkr: a cached kernel has no pieces or another tail");
  for (std::size_t i = 0; i + 1 < breaks_.size(); ++i) {
    const std::size_t order = count(1e3);
    Cheb c(gsl_cheb_alloc(order));
    c->a = breaks_[i];
    c->b = breaks_[i + 1];
    c->order_sp = order;
    for (std::size_t k = 0; k <= order; ++k) c->c[k] = next();
    Cheb d(gsl_cheb_alloc(order));
    gsl_cheb_calc_deriv(d.get(), c.get());
    pieces_->value.push_back(std::move(c));
    pieces_->slope.push_back(std::move(d));
  }
  if (at != serialized.size()) throw NumericalError("layerjkr: a cached kernel is longer than its layout");
}

void LayerKernelFunction::beyond_table(double sigma) const {
  throw DomainError("LayerKernelFunction", "sigma", sigma,
                    "|sigma| < " + format_double(near_) + " (this stack's kernel table; 2 max_a_over_h is within it)");
}

double LayerKernelFunction::value(double sigma) const {
  const double x = std::abs(sigma);
  if (x >= near_ && tail_.empty()) beyond_table(sigma);
  if (x < near_) {
    const double b2 = kBeta * kBeta, s2 = x * x, d = b2 + s2;
    const double model = model_a_ * kBeta / d + model_b_ * (b2 - s2) / (d * d);
    return model + gsl_cheb_eval(pieces_->value[piece_index(breaks_, x)].get(), x);
  }
  const double y = 1.0 / (x * x);
  double sum = 0.0;
  for (auto c = tail_.rbegin(); c != tail_.rend(); ++c) sum = sum * y + *c;
  return sum * y;
}

double LayerKernelFunction::derivative(double sigma) const {
  const double x = std::abs(sigma);
  if (x >= near_ && tail_.empty()) beyond_table(sigma);
  double value = 0.0;
  if (x < near_) {
    const double b2 = kBeta * kBeta, s2 = x * x, d = b2 + s2;
    const double model = -2.0 * model_a_ * kBeta * x / (d * d) +
                         model_b_ * (-2.0 * x / (d * d) - 4.0 * x * (b2 - s2) / (d * d * d));
    value = model + gsl_cheb_eval(pieces_->slope[piece_index(breaks_, x)].get(), x);
  } else {
    // d/dx sum c_k x^-(2k+2) = -sum (2k+2) c_k x^-(2k+3)
    const double y = 1.0 / (x * x);
    double sum = 0.0;
    for (int k = kTailTerms - 1; k >= 0; --k) sum = sum * y - (2.0 * k + 2.0) * tail_[static_cast<std::size_t>(k)];
    value = sum * y / x;
  }
  return sigma < 0.0 ? -value : value;
}

namespace {
// The disk cache's kinds: a new revision whenever a build's numbers change.
constexpr const char* kLayerKernelKind = "layer-kernel-1";
constexpr const char* kStackKernelKind = "stack-kernel-3";
}  // namespace

std::shared_ptr<const LayerKernelFunction> shared_layer_kernel(double nu, bool bonded,
                                                               const std::shared_ptr<Context>& context) {
  auto& caches = context_caches(context);
  return caches.kernels.get({nu, bonded}, [&] {
    return load_or_build<LayerKernelFunction>(*caches.disk, kLayerKernelKind, {nu, bonded ? 1.0 : 0.0}, [&] {
      return std::make_shared<const LayerKernelFunction>(nu, bonded);
    });
  });
}

std::shared_ptr<const LayerKernelFunction> shared_stack_kernel(const LayeredMedium& medium,
                                                               const std::shared_ptr<Context>& context) {
  if (medium.is_single_layer()) {
    medium.validate("shared_stack_kernel");
    return shared_layer_kernel(medium.layers[0].nu, medium.base == Base::bonded, context);
  }
  const StackSymbol symbol(medium, "shared_stack_kernel");
  auto& caches = context_caches(context);
  return caches.stack_kernels.get(symbol.signature(), [&] {
    return load_or_build<LayerKernelFunction>(*caches.disk, kStackKernelKind, symbol.signature(), [&] {
      return std::make_shared<const LayerKernelFunction>(symbol);
    });
  });
}

}  // namespace layerjkr::detail
