// The JKR edge crack with Maugis-Barquins kinetics, stepped by GSL's implicit Bulirsch-Stoer (bsimp)
// (crack_kinetics.hpp).
#include "time/crack_kinetics.hpp"

#include <cmath>
#include <limits>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The contact is lost below this fraction of its starting radius (crack_kinetics.hpp).
constexpr double kLostFraction = 1e-6;
// The integrator's tolerances on a: relative, and absolute in units of the starting radius.
constexpr double kRelTol = 1e-10, kAbsTol = 1e-12;
// Steps one advance() may take before it is called a failure.
constexpr unsigned long kMaxSteps = 200000;

}  // namespace

CrackPoint crack_point(const NonAdhesiveState& s, RetractControl control, double stiffness, double c) {
  CrackPoint p;
  switch (control) {
    case RetractControl::load:
      p.P = c;
      p.delta = s.delta_H + (c - s.P_H) / s.S;
      break;
    case RetractControl::cantilever:
      // P = P_H + S (z - P/k - delta_H)  ->  P (1 + S/k) = P_H + S (z - delta_H)
      p.P = (s.P_H + s.S * (c - s.delta_H)) / (1.0 + s.S / stiffness);
      p.delta = c - p.P / stiffness;
      break;
    default:  // fixed grips: c is the approach
      p.delta = c;
      p.P = s.P_H + s.S * (c - s.delta_H);
      break;
  }
  const double d = s.P_H - p.P;
  p.G = d * d * s.dS_da / (4.0 * kPi * s.a * s.S * s.S);
  return p;
}

struct KineticStepper::Gsl {
  gsl_odeiv2_system sys{};
  gsl_odeiv2_driver* driver = nullptr;
  ~Gsl() {
    if (driver) gsl_odeiv2_driver_free(driver);
  }
};

struct KineticSystem {
  static int rhs(double t, const double y[], double f[], void* params) {
    f[0] = static_cast<const KineticStepper*>(params)->rate(t, y[0]);
    return std::isfinite(f[0]) ? GSL_SUCCESS : GSL_EBADFUNC;
  }
  static int jacobian(double t, const double y[], double* dfdy, double dfdt[], void* params) {
    const auto* s = static_cast<const KineticStepper*>(params);
    const double a = y[0], ha = 1e-7 * std::max(std::abs(a), s->a_scale_);
    dfdy[0] = (s->rate(t, a + ha) - s->rate(t, a - ha)) / (2.0 * ha);
    const double ht = 1e-7 * std::max(std::abs(t), 1e-9);
    dfdt[0] = (s->rate(t + ht, a) - s->rate(t - ht, a)) / (2.0 * ht);
    return std::isfinite(dfdy[0]) && std::isfinite(dfdt[0]) ? GSL_SUCCESS : GSL_EBADFUNC;
  }
};

KineticStepper::KineticStepper(StateAt state, double w0, const CrackKinetics& kinetics, RetractControl control,
                               double stiffness)
    : state_(std::move(state)), w0_(w0), kinetics_(kinetics), control_(control), stiffness_(stiffness),
      gsl_(std::make_unique<Gsl>()) {
  kinetics.validate();
  detail::require_positive("KineticStepper", "w0", w0);
  if (control == RetractControl::automatic)
    throw InputError("kinetic retract: the control must be load, fixed grips or cantilever, not automatic");
  if (control == RetractControl::cantilever) detail::require_positive("KineticStepper", "stiffness", stiffness);
  silence_gsl_errors();
}

KineticStepper::~KineticStepper() = default;

double KineticStepper::rate(double t, double a) const {
  if (!(a > a_floor_)) return std::numeric_limits<double>::quiet_NaN();  // lost: the caller stops
  const CrackPoint p = crack_point(state_(a), control_, stiffness_, control_at(t));
  return -kinetics_.crack_speed(p.G, w0_);
}

void KineticStepper::start(double t, double a, double c) {
  detail::require_positive("KineticStepper::start", "a", a);
  t_ = t;
  a_ = a;
  c_ = c;
  slope_ = 0.0;
  a_scale_ = a;
  a_floor_ = kLostFraction * a;
  separated_ = false;
  if (gsl_->driver) gsl_odeiv2_driver_free(gsl_->driver);
  gsl_->sys = {KineticSystem::rhs, KineticSystem::jacobian, 1, this};
  gsl_->driver = gsl_odeiv2_driver_alloc_y_new(&gsl_->sys, gsl_odeiv2_step_bsimp, 1e-6, kAbsTol * a, kRelTol);
  if (!gsl_->driver) throw NumericalError("kinetic retract: GSL could not allocate its integrator");
  gsl_odeiv2_driver_set_nmax(gsl_->driver, kMaxSteps);
}

void KineticStepper::begin_segment(double t1, double c1) { slope_ = t1 > t_ ? (c1 - c_) / (t1 - t_) : 0.0; }

bool KineticStepper::advance(double t1, double c1) {
  begin_segment(t1, c1);
  if (separated_) {
    t_ = t1;
    c_ = c1;
    return true;
  }
  double t = t_, y[1] = {a_};
  // The driver's first step from a new segment: a tenth of it at most (the control turned).
  gsl_odeiv2_driver_reset_hstart(gsl_->driver, std::min(0.1 * (t1 - t_), std::max(gsl_->driver->h, 1e-15)));
  const int status = gsl_odeiv2_driver_apply(gsl_->driver, &t, t1, y);
  if (status != GSL_SUCCESS && status != GSL_EBADFUNC) return false;
  // EBADFUNC: the crack ran below the floor inside the interval - the contact is lost.
  if (status == GSL_EBADFUNC || !(y[0] > a_floor_)) separated_ = true;
  a_ = y[0];
  t_ = t1;
  c_ = c1;
  gsl_odeiv2_driver_reset(gsl_->driver);
  return true;
}

bool KineticStepper::step(double t1, double c1, double h_max) {
  begin_segment(t1, c1);
  if (separated_) return true;
  gsl_odeiv2_driver* d = gsl_->driver;
  double t = t_, y[1] = {a_};
  double h = std::min(d->h, h_max);
  const int status = gsl_odeiv2_evolve_apply(d->e, d->c, d->s, d->sys, &t, t1, &h, y);
  d->h = std::min(h, h_max);
  if (status == GSL_EBADFUNC) {
    separated_ = true;
    t_ = t;
    c_ = control_at(t);
    return true;
  }
  if (status != GSL_SUCCESS) return false;
  c_ = control_at(t);  // before t_ moves: the control is linear from the old (t_, c_)
  t_ = t;
  a_ = y[0];
  if (!(a_ > a_floor_)) separated_ = true;
  return true;
}

CrackPoint KineticStepper::point() const {
  if (separated_) {  // free: no force; the tip is where the grips or the unbent lever hold it
    CrackPoint p;
    p.delta = control_ == RetractControl::load ? std::numeric_limits<double>::quiet_NaN() : c_;
    return p;
  }
  return crack_point(state_(a_), control_, stiffness_, c_);
}

double KineticStepper::speed() const {
  if (separated_) return 0.0;
  return -rate(t_, a_);
}

}  // namespace layerjkr::detail
