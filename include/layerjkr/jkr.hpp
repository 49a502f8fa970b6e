// layerjkr: the explicit JKR transform (paper eq. 19) and its closed forms.
//
//   P(a)     = P_H(a)     - sqrt(4 pi w a S(a)^2 / S'(a))
//   delta(a) = delta_H(a) - sqrt(4 pi w a / S'(a))
//
// valid for any medium obeying superposition whose flat-punch stiffness S(a) grows
// with a (S' > 0). w [J/m^2] is the work of adhesion; w = 0 returns the
// non-adhesive state exactly.
#pragma once

#include "layerjkr/model.hpp"
#include "layerjkr/profile.hpp"

namespace layerjkr {

/// Adhesive state at contact radius a, with the non-adhesive state it came from (JKR, DMT) or
/// the contact problem's own values (Maugis-Dugdale: hertz.a = a, the rest NaN).
struct AdhesiveState {
  double a = 0.0;      ///< contact radius [m]
  double c = 0.0;      ///< outer radius of the adhesive zone [m]: a for JKR, > a for Maugis-Dugdale and DMT
  double P = 0.0;      ///< force [N], negative = tensile
  double delta = 0.0;  ///< approach [m]
  NonAdhesiveState hertz;    ///< the non-adhesive state at the same a
};

/// Generic transform (19). Throws DomainError for w < 0 or non-finite, and, when
/// w > 0, for S <= 0 or S' <= 0. Accuracy: a few ulps of the inputs.
AdhesiveState jkr_transform(const NonAdhesiveState& hertz, double w);

/// Explicit leading-order (Winkler) solution, eq. (42):
///   delta = f(a) - sqrt(2w/K),  P = pi K [a^2 f(a) - 2 M(a) - a^2 sqrt(2w/K)].
AdhesiveState jkr_leading_order(const Profile& profile, double K, double w, double a);

/// Explicit two-term solution, eqs. (50)-(51) with the corrected G-term:
///   delta = f - (G/K)(f'' + f'/a) - sqrt(2w/K)
///   P     = pi K [a^2 f - 2M + (G a/K)(f' - a f'') - a^2 sqrt(2w/K)].
/// (The printed (51) has 2f' instead of f'; see docs/erratum.md.)
AdhesiveState jkr_two_term(const Profile& profile, double K, double G, double w, double a);

}  // namespace layerjkr
