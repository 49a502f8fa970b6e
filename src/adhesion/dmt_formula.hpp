// Internal: the classical DMT force, written once and templated on the scalar: dmt_transform
// (adhesive_law.cpp) runs it on double, the fit differentiates it on ceres::Jet.
#pragma once

#include <boost/math/constants/constants.hpp>

namespace layerjkr::detail {

/// P = P_H - 2 pi w R: the non-adhesive force less the attraction outside the contact of a tip
/// of radius R [m] with work of adhesion w [J/m^2] (Derjaguin, Muller & Toporov 1975); the
/// approach is the non-adhesive one.
template <class T>
T dmt_force(const T& P_H, const T& w, const T& R) {
  return P_H - 2.0 * boost::math::constants::pi<double>() * w * R;
}

}  // namespace layerjkr::detail
