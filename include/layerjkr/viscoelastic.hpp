// layerjkr: linear viscoelastic media - relaxation laws and the hereditary (Lee-Radok) response
// of a contact whose radius does not decrease.
//
// Conventions (docs/models.md, "Viscoelastic media"): a medium's Young's modulus relaxes as
// E(t) = E psi(t) with psi(0+) = 1, so the scene's E is the instantaneous modulus, and its
// Poisson's ratio is constant in time. Every medium layerjkr solves with a modulus then scales
// with E at fixed nu (and h): its elastic force at a given contact radius is E times a function of
// the radius alone, and delta_H(a) does not depend on E. By the correspondence principle
// (Lee & Radok 1960) a contact whose radius a(t) never decreases carries
//
//   P(t) = integral_0^t psi(t - s) dP_H(a(s))/ds ds,
//
// with P_H the medium's elastic force at the instantaneous modulus E - for a half-space, a layer
// or a stack alike (one normalised law for all the layers of a stack).
//
//   RelaxationLaw law = RelaxationLaw::standard_linear_solid(0.4, 0.5);  // E_inf = 0.4 E, tau 0.5 s
//   std::vector<double> P = lee_radok_loading(t, P_H, law);             // P_H[i] at t[i]
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace layerjkr {

/// psi(t) = E(t)/E, the relaxation modulus relative to the instantaneous one.
///   elastic:   psi = 1.
///   prony:     psi = g_inf + sum_i g_i exp(-t/tau_i), g_inf = 1 - sum_i g_i (>= 0); the standard
///              linear solid is one term, g_1 = 1 - E_inf/E.
///   power_law: psi = (t/t0)^-beta for t > 0 (Efremov et al. 2017); E is then the modulus at t0,
///              not an instantaneous one (psi is infinite at t = 0+), and beta in [0, 1).
///   power_law_plateau (a power law with `plateau_form`): psi = p + (1 - p)(t/t0)^-beta, p =
///              E_inf/E in [0, 1): E(t) = E_inf + (E - E_inf)(t/t0)^-beta, which relaxes towards
///              E_inf instead of 0 (the scene's "power_law_plateau" with E_inf in Pa).
///   fractional: psi = p + (1 - p) E_beta(-(t/tau)^beta), E_beta the Mittag-Leffler function, p =
///              E_inf/E in [0, 1), beta in [0.01, 0.95], tau [s] > 0: the fractional standard linear
///              solid (a spring E_inf in parallel with a spring E - E_inf in series with a springpot of
///              exponent beta; "fractional_sls"), the fractional Maxwell model at p = 0
///              ("fractional_maxwell"). E is instantaneous (psi(0+) = 1); psi ~ 1 - (t/tau)^beta /
///              Gamma(1 + beta) early and p + (1 - p)(t/tau)^-beta / Gamma(1 - beta) late. beta -> 1
///              is the standard linear solid. (The fractional Kelvin-Voigt model, a spring E_inf in
///              parallel with a springpot, E_inf + c t^-beta / Gamma(1 - beta), is power_law_plateau
///              with E = E(t0): docs/models.md.)
struct RelaxationLaw {
  enum class Kind { elastic, prony, power_law, fractional };
  Kind kind = Kind::elastic;
  std::vector<double> g, tau;  ///< prony: weights in (0, 1] summing to <= 1, times [s] > 0
  double beta = 0.0;           ///< power_law: exponent in [0, 1); fractional: in [0.01, 0.95]
  double t0 = 1.0;             ///< power_law: the time [s] at which E(t0) = E, > 0
  double tau_f = 1.0;          ///< fractional: the relaxation time tau [s], > 0
  double plateau = 0.0;        ///< power_law, fractional: E_inf/E in [0, 1) (0: no plateau)
  /// Made by power_law_plateau or fractional_sls (a scene's "power_law_plateau", "fractional_sls"):
  /// its E_inf was given in Pa, and a fit may free E_inf.
  bool plateau_form = false;
  /// Made by maxwell2 (a scene's "maxwell2"): two Prony terms whose moduli were given in Pa, so a
  /// fit may free E_inf, tau, E_2 and tau_2.
  bool two_term_form = false;
  /// Made by standard_linear_solid (a scene's "sls"): one Prony term whose relaxed modulus E_inf
  /// was given in Pa, so a fit that frees E holds E_inf (not the ratio) where it is not free.
  bool standard_linear_solid_form = false;

  /// The standard linear solid: E(t) = E_inf + (E - E_inf) exp(-t/tau), as a one-term Prony law
  /// (`E_inf_ratio` = E_inf/E in [0, 1], `tau` [s] > 0).
  static RelaxationLaw standard_linear_solid(double E_inf_ratio, double tau);
  static RelaxationLaw prony(std::vector<double> g, std::vector<double> tau);
  /// The two-term generalised Maxwell law E(t) = E_inf + (E - E_inf - E_2) exp(-t/tau) + E_2 exp(-t/tau_2)
  /// (`E_inf_ratio` = E_inf/E, `E2_ratio` = E_2/E, both >= 0 with E_inf + E_2 < E; times [s] > 0).
  static RelaxationLaw maxwell2(double E_inf_ratio, double tau, double E2_ratio, double tau_2);
  static RelaxationLaw power_law(double beta, double t0);
  /// E(t) = E_inf + (E - E_inf)(t/t0)^-beta (`E_inf_ratio` = E_inf/E in [0, 1)).
  static RelaxationLaw power_law_plateau(double beta, double t0, double E_inf_ratio);
  /// E(t) = E_inf + (E - E_inf) E_beta(-(t/tau)^beta) (`E_inf_ratio` = E_inf/E in [0, 1)).
  static RelaxationLaw fractional_sls(double beta, double tau, double E_inf_ratio);
  /// E(t) = E E_beta(-(t/tau)^beta): the fractional SLS without its parallel spring.
  static RelaxationLaw fractional_maxwell(double beta, double tau);

  /// psi(t) for t > 0 [s]; accurate to rounding (the fractional law: to 1e-10, from its spectrum).
  double relative_modulus(double t) const;
  /// Throws DomainError naming the first invalid field, its value and the valid range.
  void validate() const;
  /// One line: e.g. "prony(g = [0.6], tau = [0.5] s)", "sls(E_inf/E = 0.4, tau = 0.5 s)".
  std::string describe() const;
};

/// The Lee-Radok force of a contact whose radius does not decrease: samples t[i] [s] (strictly
/// increasing, t[0] >= 0 with the contact starting at t = 0 from P_H = 0) of the medium's
/// elastic force P_H[i] [N] at the instantaneous modulus (for a power law: at E(t0)).
///
/// P_H is taken as piecewise linear in time between the samples (and from 0 at t = 0 to P_H[0]),
/// and the hereditary integral of each piece is exact for a Prony law (a recursion, O(N)); a power
/// law's history is carried by a sum of exponentials accurate to 4e-10 relative over the samples'
/// time scales (O(N M), M ~ 6 per decade of t / dt plus 35), its newest piece integrated exactly.
/// The error is therefore that of linear interpolation of P_H(t), second order where P_H(t) is
/// smooth; for a paraboloid loaded at constant speed (P_H ~ t^1.5 from the start) it is of order
/// 1.75 in the spacing: 1.6e-6 relative with 4 000 even samples on a power law of beta = 0.2
/// against Efremov's closed form, 1e-6 against quadrature for a standard linear solid
/// (tests/time/test_relaxation.cpp).
/// Throws DomainError for a law that does not validate, InputError for vectors of different
/// lengths or times that are not increasing, and for P_H that decreases (an unloading:
/// hereditary_response follows it).
std::vector<double> lee_radok_loading(const std::vector<double>& t, const std::vector<double>& P_H,
                                      const RelaxationLaw& law);

/// The force of a contact on a relaxing medium under a prescribed indentation history, and the
/// contact radius as the elastic radius at an indentation delta1 (docs/theory.md s.8).
struct HereditaryResponse {
  std::vector<double> P;       ///< force [N]; 0 before the first contact and once it is lost
  /// The contact radius is the elastic one at this indentation [m]: delta itself while the contact
  /// grows, delta(t1) once it recedes (Ting), 0 out of contact.
  std::vector<double> delta1;
  /// The loading time whose radius the contact has [s]: t itself while it grows; NaN out of contact.
  std::vector<double> t1;
};

/// Samples t[i] [s] (strictly increasing) of the indentation delta[i] [m] (positive into the
/// medium, starting out of contact: delta[0] <= 0), on a medium whose elastic force at the
/// instantaneous modulus is elastic_force(delta) [N] for delta > 0 (called once per sample in
/// contact), relaxing by `law`: Lee & Radok (1960) up to the deepest sample, then Ting (1966) -
/// P(t) = int_tc^t1 psi(t - s) dP_H(s) with int_t1^t psi(t - s) d delta(s) = 0 - which holds on the
/// half-space, the layer and the stack alike (theory.md s.8; verified on a layer against a direct
/// time-stepping solution, tests/time/test_layer_time_stepping.cpp). delta and P_H are
/// piecewise linear in time between the samples; cost O(N M) as for lee_radok_loading. Accuracy:
/// against Efremov's closed forms for a power-law paraboloid (loading and Ting's unloading),
/// tests/time/test_hereditary.cpp gives the measured errors.
/// Throws InputError for vectors of different lengths, times that do not increase, values that
/// are not finite, or a history that starts in contact (delta[0] > 0: the loading before it is
/// unknown); DomainError for a law that does not validate.
HereditaryResponse hereditary_response(const std::vector<double>& t, const std::vector<double>& delta,
                                       const std::function<double(double)>& elastic_force,
                                       const RelaxationLaw& law);

}  // namespace layerjkr
