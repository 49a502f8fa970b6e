// Internal: the classical DMT force, written once and templated on the scalar: dmt_transform
// (adhesive_law.cpp) runs it on double, the fit differentiates it on ceres::Jet.
#pragma once

#include <string>

#include <boost/math/constants/constants.hpp>

#include "layerjkr/profile.hpp"

namespace layerjkr::detail {

/// The classical DMT's tip radius 1/f''(0) [m]. Throws InputError, beginning with `who` and
/// ending with `remedy` (what to give instead), for a profile without one (a cone: f''(0) = 0).
double dmt_tip_radius(const Profile& profile, const std::string& who, const std::string& remedy);

/// P = P_H - 2 pi w R: the non-adhesive force less the attraction outside the contact of a tip
/// of radius R [m] with work of adhesion w [J/m^2] (Derjaguin, Muller & Toporov 1975); the
/// approach is the non-adhesive one.
template <class T>
T dmt_force(const T& P_H, const T& w, const T& R) {
  return P_H - 2.0 * boost::math::constants::pi<double>() * w * R;
}

}  // namespace layerjkr::detail
