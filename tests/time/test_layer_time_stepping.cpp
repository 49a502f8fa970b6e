// Ting's rule on a layer (theory.md s.8) against a second method written differently: a direct
// time-stepping solution of the hereditary contact problem on the exact layer's kernel. No t1, no
// loading history: at every step the contact radius is where the edge's pressure is bounded, for
// the pressure that makes the surface follow the indenter now, given everything the surface did
// before - the relaxation form pi h(x, t) = int E(t - s) d_s D(x, s) of the Copson/Fredholm
// formulation (theory.md s.4), whose surface term D is carried on a fixed grid in x, and solved by
// its own Gauss-Legendre Nystrom discretisation on [0, a(t)] at every step. The loading is also
// checked against Gauss-Kronrod quadrature of the Lee-Radok integral of the exact layer's
// stiffness. A bonded layer with nu = 0.45 relaxing as a standard linear solid, a paraboloid
// pressed to a/h = 5 in 2 tau and withdrawn twice as fast.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/roots.hpp>

#include "layerjkr/contact.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/viscoelastic.hpp"
#include "models/layer_kernel.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

// Lengths in units of h, E* = 1, times in units of tau.
constexpr double kNu = 0.45, kR = 50.0, kTau = 1.0, kRelaxed = 0.3;
constexpr double kPi = 3.14159265358979323846;

// The time-stepping solution's state: the surface term D and its relaxation state Y on a fixed
// grid, and the previous step's indentation and contact radius.
class TimeStepper {
 public:
  TimeStepper(const detail::LayerKernelFunction& kernel, double extent, int grid_points, int nodes)
      : kernel_(kernel), dx_(extent / (grid_points - 1)), X_(grid_points), D_(grid_points, 0.0), Y_(grid_points, 0.0) {
    for (int k = 0; k < grid_points; ++k) X_[k] = k * dx_;
    const auto& abscissa = boost::math::quadrature::gauss<double, 48>::abscissa();
    const auto& weight = boost::math::quadrature::gauss<double, 48>::weights();
    (void)nodes;
    for (std::size_t i = 0; i < abscissa.size(); ++i) {  // on [-1, 1], symmetric halves
      xi_.push_back(abscissa[i]);
      wi_.push_back(weight[i]);
      if (abscissa[i] != 0.0) {
        xi_.push_back(-abscissa[i]);
        wi_.push_back(weight[i]);
      }
    }
  }

  struct Result {
    double a = 0.0, P = 0.0;
  };

  // One step of length dt to indentation delta.
  Result step(double dt, double delta) {
    e_ = std::exp(-dt / kTau);
    phi_ = -std::expm1(-dt / kTau) / (dt / kTau);
    c_ = kRelaxed + (1.0 - kRelaxed) * phi_;
    delta_ = delta;
    Solve best;
    const double a = find_radius(&best);
    a_prev_ = a;
    delta_prev_ = delta;
    update(best);
    return {a, best.P};
  }

 private:
  struct Solve {
    double a = 0.0, edge = 0.0, P = 0.0;
    std::vector<double> x, w, g;
  };

  double F(double s) const { return kernel_.value(std::abs(s)); }

  // b(x) = (1 - r)(e Y_prev - phi D_prev): the history's part of pi h at x.
  double history(double x) const {
    const double D = x < a_prev_ ? delta_prev_ - x * x / kR : interpolate(D_, x);
    return (1.0 - kRelaxed) * (e_ * interpolate(Y_, x) - phi_ * D);
  }
  double interpolate(const std::vector<double>& v, double x) const {  // cubic Lagrange on the grid
    const int n = static_cast<int>(v.size());
    int k = std::clamp(static_cast<int>(x / dx_) - 1, 0, n - 4);
    const double s = x / dx_ - k;
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) {
      double l = 1.0;
      for (int j = 0; j < 4; ++j)
        if (j != i) l *= (s - j) / (i - j);
      sum += l * v[k + i];
    }
    return sum;
  }
  double rhs(double x) const { return (c_ * (delta_ - x * x / kR) + history(x)) / kPi; }

  Solve solve_at(double a) const {
    Solve s;
    s.a = a;
    const std::size_t n = xi_.size();
    s.x.resize(n);
    s.w.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      s.x[j] = 0.5 * a * (xi_[j] + 1.0);
      s.w[j] = 0.5 * a * wi_[j];
    }
    Eigen::MatrixXd M(n, n);
    Eigen::VectorXd b(n);
    for (std::size_t i = 0; i < n; ++i) {
      b[i] = rhs(s.x[i]);
      for (std::size_t j = 0; j < n; ++j)
        M(i, j) = (i == j ? 1.0 : 0.0) - s.w[j] * (F(s.x[i] - s.x[j]) + F(s.x[i] + s.x[j])) / kPi;
    }
    const Eigen::VectorXd g = M.partialPivLu().solve(b);
    s.g.assign(g.data(), g.data() + n);
    s.edge = rhs(a);
    for (std::size_t j = 0; j < n; ++j) {
      s.edge += s.w[j] * g[j] * (F(a - s.x[j]) + F(a + s.x[j])) / kPi;
      s.P += 2.0 * kPi * s.w[j] * g[j];
    }
    return s;
  }

  // The radius whose edge pressure is bounded (g(a) = 0), next to the previous one; 0 once lost.
  double find_radius(Solve* best) const {
    const double floor = 1e-4;
    const auto edge = [&](double a) { return solve_at(a).edge; };
    double lo = std::max(a_prev_, 2.0 * floor), hi = lo;
    if (edge(lo) > 0.0) {
      do {
        lo = hi;
        hi *= 1.05;
      } while (edge(hi) > 0.0);
    } else {
      do {
        hi = lo;
        lo /= 1.05;
        if (lo < floor) {
          *best = Solve{};
          return 0.0;
        }
      } while (edge(lo) <= 0.0);
    }
    std::uintmax_t it = 100;
    const auto r = boost::math::tools::toms748_solve(edge, lo, hi, boost::math::tools::eps_tolerance<double>(45), it);
    const double a = 0.5 * (r.first + r.second);
    *best = solve_at(a);
    return a;
  }

  // The surface term at every grid point: geometric inside the contact, from pi h = c D + b outside.
  void update(const Solve& s) {
    for (std::size_t k = 0; k < X_.size(); ++k) {
      const double x = X_[k];
      double D;
      const double b = (1.0 - kRelaxed) * (e_ * Y_[k] - phi_ * D_[k]);
      if (x < s.a) {
        D = delta_ - x * x / kR;
      } else {
        double pih = 0.0;
        for (std::size_t j = 0; j < s.g.size(); ++j) pih -= s.w[j] * s.g[j] * (F(x - s.x[j]) + F(x + s.x[j]));
        D = (pih - b) / c_;
      }
      Y_[k] = e_ * Y_[k] + phi_ * (D - D_[k]);
      D_[k] = D;
    }
  }

  const detail::LayerKernelFunction& kernel_;
  double dx_;
  std::vector<double> X_, D_, Y_, xi_, wi_;
  double e_ = 0.0, phi_ = 0.0, c_ = 1.0, delta_ = 0.0, delta_prev_ = 0.0, a_prev_ = 0.0;
};

// One medium (E1* = 1, h1 = 1), pressed to a/h = 5 in 2 tau and withdrawn at twice the speed,
// three quarters of the way back, in `steps` even steps: the largest differences, relative to the
// largest force and radius, of the library's answer against quadrature (loading) and against the
// time-stepping solution (everything).
struct Differences {
  double loading = 0.0, force = 0.0, radius = 0.0;
};
Differences compare(const ModelSpec& spec, const detail::LayerKernelFunction& kernel, int steps) {
  const ContactModelPtr model = make_contact_model(make_paraboloid(kR), spec);
  const AdhesiveSolution elastic(model, 0.0);
  const double a_max = 5.0, delta_max = model->state(a_max).delta_H;
  const double t_m = 2.0 * kTau, v = delta_max / t_m, v_r = 2.0 * v;
  const auto delta_at = [&](double t) { return t <= t_m ? v * t : delta_max - v_r * (t - t_m); };
  const double t_end = t_m + 0.75 * delta_max / v_r;
  const RelaxationLaw law = RelaxationLaw::standard_linear_solid(kRelaxed, kTau);
  std::vector<double> t, delta;
  for (int i = 0; i <= steps; ++i) {
    t.push_back(t_end * i / steps);
    delta.push_back(delta_at(t.back()));
  }
  const HereditaryResponse ting = hereditary_response(t, delta, [&](double d) { return elastic.force_at_delta(d); }, law);
  Differences out;
  // Loading: the library's piecewise-linear recursion against quadrature of the exact integral.
  using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
  const auto stiffness = [&](double s) {
    return model->state(elastic.contact_radius_at_delta(std::max(delta_at(s), 1e-12))).S;
  };
  for (int i = steps / 8; t[i] <= t_m; i += steps / 8) {
    const double P = GK::integrate([&](double s) { return law.relative_modulus(t[i] - s) * stiffness(s) * v; }, 0.0,
                                   t[i], 10, 1e-11);
    out.loading = std::max(out.loading, std::abs(ting.P[i] - P) / P);
  }
  // The whole history against the time-stepping solution.
  TimeStepper stepper(kernel, 1.2 * a_max, 1201, 48);
  const double P_max = *std::max_element(ting.P.begin(), ting.P.end());
  for (int i = 1; i <= steps; ++i) {
    const TimeStepper::Result r = stepper.step(t[i] - t[i - 1], delta[i]);
    const double a_ting = ting.delta1[i] > 0.0 ? elastic.contact_radius_at_delta(ting.delta1[i]) : 0.0;
    out.force = std::max(out.force, std::abs(r.P - ting.P[i]) / P_max);
    out.radius = std::max(out.radius, std::abs(r.a - a_ting) / a_max);
  }
  return out;
}

void check_converges(const ModelSpec& spec, const detail::LayerKernelFunction& kernel, const std::string& what) {
  Differences previous;
  for (int steps : {100, 200, 400}) {
    const Differences d = compare(spec, kernel, steps);
    INFO(what << ", " << steps << " steps: loading against quadrature " << d.loading << ", time stepping against Ting: "
              << "force " << d.force << " of the largest, radius " << d.radius << " of the largest");
    if (previous.force > 0.0) {  // both second order in the step
      CHECK(d.loading < previous.loading / 3.0);
      CHECK(d.force < previous.force / 3.0);
    }
    previous = d;
  }
  CHECK(previous.loading < 2e-5);
  CHECK(previous.force < 1e-5);
  CHECK(previous.radius < 1e-5);
}

}  // namespace

TEST_CASE("a layer at a/h 1-5: Lee-Radok against quadrature, Ting's unloading against time stepping",
          "[viscoelastic]") {
  for (const auto& [nu, base] : {std::pair{0.45, Base::bonded}, std::pair{0.3, Base::frictionless}}) {
    ModelSpec spec;
    spec.kind = ModelKind::exact;
    spec.layer = ElasticLayer{1.0 - nu * nu, nu, 1.0, base};  // E* = 1
    check_converges(spec, *detail::shared_layer_kernel(nu, base == Base::bonded, nullptr),
                    "nu = " + std::to_string(nu) + " " + to_string(base));
  }
}

TEST_CASE("a stack: Ting's unloading against time stepping on the stack's kernel", "[viscoelastic]") {
  LayeredMedium stack;  // a soft film on a stiffer one, bonded to a rigid base
  stack.layers = {{1.0 - 0.45 * 0.45, 0.45, 1.0}, {10.0, 0.3, 2.0}};
  ModelSpec spec;
  spec.kind = ModelKind::exact;
  spec.layer = ElasticLayer{stack.layers[0].E, stack.layers[0].nu, 1.0, Base::bonded};
  spec.stack = stack;
  check_converges(spec, *detail::shared_stack_kernel(stack, nullptr), "two-layer stack");
}
