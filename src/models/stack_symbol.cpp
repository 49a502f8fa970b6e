// The stack's surface-compliance symbol by a bottom-up recursion without growing exponentials.
#include "models/stack_symbol.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <string>

#include <boost/math/constants/constants.hpp>

#include "layerjkr/error.hpp"

namespace layerjkr {

LayeredMedium LayeredMedium::single(const ElasticLayer& layer) {
  LayeredMedium m;
  m.layers = {{layer.E, layer.nu, layer.h}};
  m.base = layer.base;
  return m;
}

ElasticLayer LayeredMedium::top() const {
  if (layers.empty()) return {};
  return {layers.front().E, layers.front().nu, layers.front().h, substrate ? Base::bonded : base};
}

void LayeredMedium::validate(const char* function) const {
  if (layers.empty()) throw DomainError(function, "layers", 0.0, "at least one layer (the count given)");
  if (layers.size() > kMaxStackLayers)
    throw DomainError(function, "layers", static_cast<double>(layers.size()),
                      "at most " + std::to_string(kMaxStackLayers) + " layers (the count given; docs/development.md, Limits)");
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const std::string at = "layers[" + std::to_string(i) + "].";
    const StackLayer& l = layers[i];
    if (!(l.E > 0.0 && std::isfinite(l.E))) throw DomainError(function, at + "E", l.E, "finite and > 0 [Pa]");
    if (!(l.nu > -1.0 && l.nu <= 0.5)) throw DomainError(function, at + "nu", l.nu, "(-1, 0.5]");
    if (!(l.h > 0.0 && std::isfinite(l.h))) throw DomainError(function, at + "h", l.h, "finite and > 0 [m]");
  }
  if (substrate) {
    if (!(substrate->E > 0.0 && std::isfinite(substrate->E)))
      throw DomainError(function, "substrate.E", substrate->E, "finite and > 0 [Pa]");
    if (!(substrate->nu > -1.0 && substrate->nu <= 0.5))
      throw DomainError(function, "substrate.nu", substrate->nu, "(-1, 0.5]");
  }
}

ThinStackConstants thin_stack_constants(const LayeredMedium& medium) {
  const char* fn = "thin_stack_constants";
  medium.validate(fn);
  if (medium.substrate)
    throw DomainError(fn, "substrate.E", medium.substrate->E,
                      "none: a stack on an elastic half-space has no thin-layer law (theory.md s.4a); use the exact model");
  const std::size_t n = medium.layers.size();
  // per layer: 1/mu, 1/M (0 at nu = 1/2), beta
  std::vector<double> inv_mu(n), inv_M(n), beta(n), z(n + 1, 0.0);
  ThinStackConstants c;
  double beta_h = 0.0, stretch = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const StackLayer& l = medium.layers[i];
    const double mu = l.E / (2.0 * (1.0 + l.nu));
    inv_mu[i] = 1.0 / mu;
    inv_M[i] = (1.0 + l.nu) * (1.0 - 2.0 * l.nu) / (l.E * (1.0 - l.nu));
    beta[i] = l.nu / (1.0 - l.nu);
    z[i + 1] = z[i] + l.h;
    c.eps += l.h * inv_M[i];
    beta_h += l.h * beta[i];
    stretch += 2.0 * mu * l.h / (1.0 - l.nu);
  }
  // D: inside layer i, B(z) and beta_i a(z) - b(z) are linear in z, so Simpson's rule is exact.
  std::vector<double> a_bottom(n + 1, 0.0), b_bottom(n + 1, 0.0), B_top(n + 1, 0.0);
  for (std::size_t i = n; i-- > 0;) {
    a_bottom[i] = a_bottom[i + 1] + medium.layers[i].h * inv_mu[i];  // a at z_i (layer i's top)
    b_bottom[i] = b_bottom[i + 1] + medium.layers[i].h * inv_M[i];
  }
  for (std::size_t i = 0; i < n; ++i) B_top[i + 1] = B_top[i] + beta[i] * medium.layers[i].h;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = medium.layers[i].h;
    auto integrand = [&](double s) {  // s in [0, h] below the layer's top
      const double a = a_bottom[i + 1] + (h - s) * inv_mu[i], b = b_bottom[i + 1] + (h - s) * inv_M[i];
      return (B_top[i] + beta[i] * s) * (beta[i] * a - b);
    };
    c.D += 2.0 * h / 6.0 * (integrand(0.0) + 4.0 * integrand(0.5 * h) + integrand(h));
  }
  c.frictionless = c.eps + beta_h * beta_h / stretch;
  const double C0 = medium.base == Base::bonded ? c.eps : c.frictionless;
  c.K = C0 > 0.0 ? 1.0 / C0 : std::numeric_limits<double>::infinity();
  c.G = c.eps > 0.0 ? -c.D / (c.eps * c.eps) : std::numeric_limits<double>::quiet_NaN();
  return c;
}

ElasticLayer equivalent_incompressible_layer(const LayeredMedium& medium) {
  const char* fn = "equivalent_incompressible_layer";
  medium.validate(fn);
  if (medium.substrate || medium.base != Base::bonded)
    throw DomainError(fn, "base", 0.0, "a bonded rigid base (the lubrication law needs u = 0 at the base)");
  double H = 0.0;
  for (std::size_t i = 0; i < medium.layers.size(); ++i) {
    if (medium.layers[i].nu != 0.5)
      throw DomainError(fn, "layers[" + std::to_string(i) + "].nu", medium.layers[i].nu,
                        "0.5 in every layer (an incompressible stack)");
    H += medium.layers[i].h;
  }
  const double J = thin_stack_constants(medium).D;
  return {H * H * H / J, 0.5, H, Base::bonded};
}

double stack_compliance_ratio(const LayeredMedium& medium, double u) {
  if (!(u >= 0.0 && std::isfinite(u)))
    throw DomainError("stack_compliance_ratio", "u", u, "finite and >= 0 (u = k h1)");
  return detail::StackSymbol(medium, "stack_compliance_ratio").L(u);
}

namespace detail {
namespace {

using cplx = std::complex<double>;

template <class T>
struct Mat2 {
  T a, b, c, d;  // [[a, b], [c, d]]
  Mat2 operator*(const Mat2& o) const {
    return {a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d};
  }
  Mat2 operator+(const Mat2& o) const { return {a + o.a, b + o.b, c + o.c, d + o.d}; }
  Mat2 operator-(const Mat2& o) const { return {a - o.a, b - o.b, c - o.c, d - o.d}; }
  Mat2 scaled(T f) const { return {a * f, b * f, c * f, d * f}; }
  // this * o^{-1}
  Mat2 right_divide(const Mat2& o) const {
    const T det = o.a * o.d - o.b * o.c;
    const Mat2 inv{o.d / det, -o.b / det, -o.c / det, o.a / det};
    return *this * inv;
  }
};

template <class T>
Mat2<T> identity() {
  return {T(1), T(0), T(0), T(1)};
}

// The half-space's surface flexibility in its own units: (U, W) = F_hs (t, s).
Mat2<double> halfspace_flexibility(double nu) { return {nu - 1.0, 0.5 - nu, 0.5 - nu, nu - 1.0}; }

// e^{-x}(x cosh x - sinh x) without cancellation: its series below 1.
double xcosh_minus_sinh_scaled(double x) {
  if (x < 1.0) {
    double term = x * x * x / 3.0, sum = term;  // sum_{n>=1} 2n x^(2n+1)/(2n+1)!
    for (int n = 2; n < 14; ++n) {
      term *= x * x * n / ((n - 1.0) * (2.0 * n) * (2.0 * n + 1.0));
      sum += term;
    }
    return std::exp(-x) * sum;
  }
  return 0.5 * (x * (1.0 + std::exp(-2.0 * x)) + std::expm1(-2.0 * x));
}

// Q = c0 I + c1 A + c2 N + c3 AN for crossing a layer of thickness x upwards: in double the
// scaled e^{-x} exp(-A x) (the factor drops out of F), in complex exp(-A x) itself (|x| small).
void propagator_coefficients(double x, double c[4]) {
  const double em1 = std::expm1(-2.0 * x);
  c[0] = 0.5 * (2.0 + em1);
  c[1] = 0.5 * em1;
  c[2] = -0.25 * x * em1;
  c[3] = -0.5 * xcosh_minus_sinh_scaled(x);
}

void propagator_coefficients(cplx x, cplx c[4]) {
  cplx s3 = x * x * x / 3.0, term = s3;
  for (int n = 2; n < 30; ++n) {
    term *= x * x * static_cast<double>(n) / ((n - 1.0) * (2.0 * n) * (2.0 * n + 1.0));
    s3 += term;
  }
  c[0] = std::cosh(x);
  c[1] = -std::sinh(x);
  c[2] = 0.5 * x * std::sinh(x);
  c[3] = -0.5 * s3;
}

// Crossing layer `l` upwards by its propagator: the subspace (Mu; Mt) in common units in,
// the flexibility F of everything from the layer's top down out (common units).
template <class T>
Mat2<T> propagate_layer(const StackSymbol::Layer& l, T x, const Mat2<T>& Mu, const Mat2<T>& Mt) {
  T c[4];
  propagator_coefficients(x, c);
  T Q[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      Q[i][j] = (i == j ? c[0] : T(0)) + c[1] * l.A[i][j] + c[2] * l.N[i][j] + c[3] * l.AN[i][j];
  const T inv_m = T(1.0 / l.m);
  const T M[4][2] = {{Mu.a, Mu.b}, {Mu.c, Mu.d}, {Mt.a * inv_m, Mt.b * inv_m}, {Mt.c * inv_m, Mt.d * inv_m}};
  T out[4][2];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 2; ++j) {
      T s(0);
      for (int k = 0; k < 4; ++k) s += Q[i][k] * M[k][j];
      out[i][j] = s;
    }
  const Mat2<T> top_u{out[0][0], out[0][1], out[1][0], out[1][1]};
  const Mat2<T> top_t{out[2][0], out[2][1], out[3][0], out[3][1]};
  return top_u.right_divide(top_t).scaled(inv_m);
}

// Crossing layer `l` upwards by its reflection matrix: returns F and sets D = F - F_hs(nu)
// (both common units).
Mat2<double> reflect_layer(const StackSymbol::Layer& l, double x, const Mat2<double>& Mu,
                           const Mat2<double>& Mt, Mat2<double>& D) {
  const double inv_m = 1.0 / l.m, two = 2.0 * (1.0 - l.nu);
  const Mat2<double> Fhs = halfspace_flexibility(l.nu);
  const Mat2<double> Mt_own = Mt.scaled(inv_m);
  const Mat2<double> Yp = (Mu - Fhs * Mt_own).scaled(1.0 / two);
  const Mat2<double> Ym = Mt_own - Yp;
  Mat2<double> R{0.0, 0.0, 0.0, 0.0};
  if (x < 400.0) {  // beyond, e^{-2x} underflows while x^2 R may overflow: R is 0
    const Mat2<double> left{1.0 - x, -x, x, 1.0 + x}, right{1.0 - x, x, -x, 1.0 + x};
    R = (left * Yp.right_divide(Ym) * right).scaled(std::exp(-2.0 * x));
  }
  const Mat2<double> Down = R.right_divide(identity<double>() + R).scaled(two);
  D = Down.scaled(inv_m);
  return (Fhs + Down).scaled(inv_m);
}

double shear_modulus(double E, double nu) { return E / (2.0 * (1.0 + nu)); }

}  // namespace

StackSymbol::StackSymbol(const LayeredMedium& medium, const char* function) {
  medium.validate(function);
  const StackLayer& top = medium.layers.front();
  const double mu1 = shear_modulus(top.E, top.nu);
  base_ = medium.substrate ? BaseKind::half_space
                           : (medium.base == Base::bonded ? BaseKind::bonded : BaseKind::frictionless);
  signature_ = {static_cast<double>(base_), top.nu};
  total_ = 0.0;
  for (std::size_t i = 0; i < medium.layers.size(); ++i) {
    const StackLayer& s = medium.layers[i];
    Layer l{};
    l.nu = s.nu;
    l.m = shear_modulus(s.E, s.nu) / mu1;
    l.r = s.h / top.h;
    total_ += l.r;
    const double b = s.nu / (1.0 - s.nu), g = (1.0 - 2.0 * s.nu) / (2.0 * (1.0 - s.nu)), c = 2.0 / (1.0 - s.nu);
    const double A[4][4] = {{0, 1, 1, 0}, {-b, 0, 0, g}, {c, 0, 0, b}, {0, 0, -1, 0}};
    // N = A^2 - I = N0/(1 - nu), N^2 = 0: exp(A x) is a closed form.
    const double N0[4][4] = {{1, 0, 0, 0.5}, {0, -1, -0.5, 0}, {0, 2, 1, 0}, {-2, 0, 0, -1}};
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) {
        l.A[r][k] = A[r][k];
        l.N[r][k] = N0[r][k] / (1.0 - s.nu);
      }
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) {
        double v = 0.0;
        for (int j = 0; j < 4; ++j) v += l.A[r][j] * l.N[j][k];
        l.AN[r][k] = v;
      }
    layers_.push_back(l);
    if (i > 0) signature_.insert(signature_.end(), {s.E / top.E, s.nu, l.r});
  }
  if (medium.substrate) {
    ms_ = shear_modulus(medium.substrate->E, medium.substrate->nu) / mu1;
    nus_ = medium.substrate->nu;
    signature_.insert(signature_.end(), {medium.substrate->E / top.E, nus_});
    // L(0) = E1*/Es*: the substrate's half-space carries the load far out.
    const double E1s = top.E / (1.0 - top.nu * top.nu);
    const double Ess = medium.substrate->E / (1.0 - nus_ * nus_);
    q0_ = 1.0 - E1s / Ess;
    for (const Layer& l : layers_) stiff_film_ = std::max(stiff_film_, l.m / ms_);
  }
}

template <class T>
void StackSymbol::propagate(T u, T& L, T& q, bool reflection_allowed) const {
  Mat2<T> Mu{}, Mt{};
  switch (base_) {
    case BaseKind::bonded: Mu = {T(0), T(0), T(0), T(0)}; Mt = identity<T>(); break;
    // F_uu is infinite on a frictionless base: the base is kept as the subspace {e_U, e_s}.
    case BaseKind::frictionless: Mu = {T(1), T(0), T(0), T(0)}; Mt = {T(0), T(0), T(0), T(1)}; break;
    case BaseKind::half_space: {
      const Mat2<double> F = halfspace_flexibility(nus_).scaled(1.0 / ms_);
      Mu = {T(F.a), T(F.b), T(F.c), T(F.d)};
      Mt = identity<T>();
      break;
    }
  }
  const double one_minus_nu1 = 1.0 - layers_.front().nu;
  for (std::size_t i = layers_.size(); i-- > 0;) {
    const Layer& l = layers_[i];
    const T x = u * l.r;
    Mat2<T> F{};
    if constexpr (std::is_same_v<T, double>) {
      if (reflection_allowed && x > 1.0) {
        Mat2<double> D{};
        F = reflect_layer(l, x, Mu, Mt, D);
        if (i == 0) {
          q = D.d / one_minus_nu1;
          L = 1.0 - q;
          return;
        }
        Mu = F;
        Mt = identity<T>();
        continue;
      }
    }
    F = propagate_layer(l, x, Mu, Mt);
    Mu = F;
    Mt = identity<T>();
  }
  L = -Mu.d / one_minus_nu1;
  q = T(1) - L;
}

void StackSymbol::evaluate(double u, double& L, double& q) const {
  // The limit (error below 1e-100): at k = 0 the recursion's frictionless base is singular,
  // and near it the cubes of x (an incompressible layer's L ~ u^3) would be subnormal.
  if (!(u > 1e-100)) {
    q = q0_;
    L = 1.0 - q0_;
    return;
  }
  propagate<double>(u, L, q, true);
}

double StackSymbol::L(double u) const {
  double L = 0.0, q = 0.0;
  evaluate(u, L, q);
  return L;
}

double StackSymbol::q(double u) const {
  double L = 0.0, q = 0.0;
  evaluate(u, L, q);
  return q;
}

std::vector<double> StackSymbol::switch_points() const {
  std::vector<double> u;
  for (const Layer& l : layers_) u.push_back(1.0 / l.r);
  std::sort(u.begin(), u.end());
  u.erase(std::unique(u.begin(), u.end()), u.end());
  return u;
}

std::complex<double> StackSymbol::q(std::complex<double> u) const {
  cplx L, q;
  propagate<cplx>(u, L, q, false);
  return q;
}

std::vector<double> StackSymbol::taylor(int count, double rho, int points) const {
  const double two_pi = boost::math::constants::two_pi<double>();
  std::vector<cplx> values(static_cast<std::size_t>(points));
  for (int j = 0; j < points; ++j) values[static_cast<std::size_t>(j)] = q(std::polar(rho, two_pi * j / points));
  std::vector<double> out(static_cast<std::size_t>(count));
  double scale = 1.0;
  for (int k = 0; k < count; ++k) {
    double sum = 0.0;  // Re of (1/n) sum q_j e^{-i k theta_j}; q is real on the real axis
    for (int j = 0; j < points; ++j) {
      const double th = two_pi * static_cast<double>((static_cast<long>(k) * j) % points) / points;
      sum += values[static_cast<std::size_t>(j)].real() * std::cos(th) +
             values[static_cast<std::size_t>(j)].imag() * std::sin(th);
    }
    out[static_cast<std::size_t>(k)] = sum / points / scale;
    scale *= rho;
  }
  return out;
}

}  // namespace detail
}  // namespace layerjkr
