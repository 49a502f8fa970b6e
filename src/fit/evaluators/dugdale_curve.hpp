// Internal: the fit family of a Dugdale law (Maugis-Dugdale, or DMT with a Dugdale stress)
// solved on the medium - the half-space with any profile, the exact layer or a stack.
#pragma once

#include <memory>

#include "adhesion/dugdale_solver.hpp"
#include "fit/evaluators/fit_model.hpp"

namespace layerjkr::detail {

/// Which Dugdale law the family fits.
enum class DugdaleKind { maugis_dugdale, dmt };

/// The curve of `solver` (built at the scene's modulus E_ref [Pa]) as a fit family. No closed
/// form and no table in (E, w, sigma0) exists: the medium's stresses scale with E, so the curve at
/// (E, w, sigma0) is the curve at (E_ref, w k, sigma0 k) with P scaled by 1/k (k = E_ref / E),
/// a function of two parameters. It is therefore solved per parameter vector on a fixed grid of
/// radii in [0, a_max] [m] and interpolated in a; its derivatives in w and sigma0 come from
/// forward differences of two more grids, solved only when a Jacobian needs them. `start` is the
/// same medium under JKR, which the data-driven start scans instead (it is ~1000x cheaper).
/// The grid is built and its interpolation error measured at the scene's w [J/m^2] and sigma0
/// [Pa]; a_max shrinks (by halves, at most 8 times) while the zone there would leave the solver's
/// range. Throws InputError naming `medium` when no grid can be solved.
std::unique_ptr<CurveModel> make_dugdale_curve(std::shared_ptr<const DugdaleSolver> solver, DugdaleKind kind,
                                               double E_ref, double a_max, double w, double sigma0,
                                               std::string medium, std::unique_ptr<CurveModel> start);

}  // namespace layerjkr::detail
