// Profiles from user callables: one autodiff pass gives f, f', f'', f'''.
#include "layerjkr/callable_profile.hpp"

#include <cmath>

#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

class CallableProfile final : public Profile {
 public:
  CallableProfile(std::function<double(double)> value,
                  std::function<ProfileJet(const ProfileJet&)> g, double length_scale,
                  double max_radius, std::string name)
      : value_(std::move(value)),
        g_(std::move(g)),
        scale_(length_scale),
        max_(max_radius),
        name_(std::move(name)) {
    f0_ = value_(0.0);
    if (!std::isfinite(f0_))
      throw DomainError("make_callable_profile", "f(0)", f0_, "finite");
  }

  ProfileDerivatives derivatives(double r) const override {
    if (!contains(r)) throw DomainError(name_, "r", r, "[0, " + format_double(max_) + "]");
    const ProfileJet y = g_(boost::math::differentiation::make_fvar<double, 3>(r));
    ProfileDerivatives d{y.derivative(0) - f0_, y.derivative(1), y.derivative(2),
                         y.derivative(3)};
    if (!std::isfinite(d.f) || !std::isfinite(d.df) || !std::isfinite(d.d2f) ||
        !std::isfinite(d.d3f))
      throw DomainError(name_, "r (callable or a derivative is not finite there)", r,
                        "radii where the callable is three times differentiable");
    return d;
  }

  double f(double r) const override {
    if (!contains(r)) throw DomainError(name_, "r", r, "[0, " + format_double(max_) + "]");
    const double v = value_(r) - f0_;
    if (!std::isfinite(v)) throw DomainError(name_, "r (callable is not finite there)", r, "radii where f is finite");
    return v;
  }

  double max_radius() const override { return max_; }
  double length_scale() const override { return scale_; }
  std::string describe() const override { return name_; }

 private:
  std::function<double(double)> value_;
  std::function<ProfileJet(const ProfileJet&)> g_;
  double scale_, max_;
  std::string name_;
  double f0_ = 0.0;
};

}  // namespace

ProfilePtr make_callable_profile_erased(std::function<double(double)> value,
                                        std::function<ProfileJet(const ProfileJet&)> jet,
                                        double length_scale, double max_radius,
                                        std::string name) {
  if (!jet || !value) throw Error("layerjkr::make_callable_profile: the callable is empty");
  detail::require_positive("make_callable_profile", "length_scale", length_scale);
  if (std::isnan(max_radius) || !(max_radius > 0.0))
    throw DomainError("make_callable_profile", "max_radius", max_radius, "> 0 (may be +inf)");
  return std::make_shared<CallableProfile>(std::move(value), std::move(jet), length_scale, max_radius,
                                           std::move(name));
}

}  // namespace layerjkr
