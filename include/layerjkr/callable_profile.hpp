// layerjkr: a profile from any user callable, differentiated automatically.
//
// The callable must be generic in its scalar type (a template or a generic lambda)
// so Boost.Math's forward-mode autodiff can evaluate f, f', f'', f''' exactly in
// one pass:
//
//   auto tip = layerjkr::make_callable_profile(
//       [](auto r) { using std::cosh; return 1e-6 * (cosh(r / 1e-6) - 1.0); },
//       /*length_scale=*/1e-6);
//
// f(0) is subtracted. The moment and Sneddon integrals use adaptive quadrature.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <utility>

#include <boost/math/differentiation/autodiff.hpp>

#include "layerjkr/profile.hpp"

namespace layerjkr {

/// Third-order forward-mode dual number used for callable profiles.
using ProfileJet = boost::math::differentiation::autodiff_fvar<double, 3>;

/// Builds a profile from type-erased callables: `value` on double (f itself, and f(0),
/// which autodiff of e.g. pow(r, 2.5) cannot give) and `jet` on ProfileJet (the
/// derivatives). length_scale [m] > 0 seeds root brackets; max_radius [m] > 0 bounds
/// admissible contact radii.
ProfilePtr make_callable_profile_erased(std::function<double(double)> value,
                                        std::function<ProfileJet(const ProfileJet&)> jet,
                                        double length_scale, double max_radius,
                                        std::string name);

/// Builds a profile from a generic callable (see file comment).
template <class F>
ProfilePtr make_callable_profile(F f, double length_scale,
                                 double max_radius = std::numeric_limits<double>::infinity(),
                                 std::string name = "callable") {
  return make_callable_profile_erased([f](double r) { return static_cast<double>(f(r)); },
                                     [f](const ProfileJet& r) { return ProfileJet(f(r)); },
                                     length_scale, max_radius, std::move(name));
}

}  // namespace layerjkr
