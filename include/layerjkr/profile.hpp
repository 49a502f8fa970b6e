// layerjkr: axisymmetric rigid indenter profiles z = f(r).
//
// A profile is the gap between the indenter and the undeformed flat surface at
// polar radius r, measured from the apex: f(0) = 0 always (profiles built from
// data or callables subtract f(0) exactly, so an offset never costs precision).
// All lengths are in metres.
//
// Every profile supplies f and its first three derivatives (exact closed forms
// where they exist, forward-mode automatic differentiation for callables), the
// moment M(a) = int_0^a f(r) r dr and the two Sneddon integrals used by the
// half-space solution. Profiles are immutable and safe to share across threads.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace layerjkr {

/// f and its derivatives at one radius r. Units: f [m], df [-], d2f [1/m], d3f [1/m^2].
struct ProfileDerivatives {
  double f = 0.0;
  double df = 0.0;
  double d2f = 0.0;
  double d3f = 0.0;
};

/// Sneddon's half-space integrals at contact radius a (dimensionless):
///   I0(a) = int_0^{pi/2} f'(a sin t) dt,  I2(a) = int_0^{pi/2} f'(a sin t) sin^2 t dt,
/// so that delta_H = a I0 and P_H = 2 E* a^2 I2 (equivalent to Galin's eq. (21)).
struct SneddonIntegrals {
  double I0 = 0.0;
  double I2 = 0.0;
};

/// f = B r^d: the form for which the exact layer's state is a function of a/h alone,
/// tabulated once per (nu, base, d) (exact_layer.hpp).
struct PowerLawForm {
  double B = 0.0;  ///< [m^(1-d)]
  double d = 0.0;  ///< exponent >= 1
};

class Profile {
 public:
  virtual ~Profile() = default;

  /// f, f', f'', f''' at radius r in [0, max_radius()]. Throws DomainError outside.
  virtual ProfileDerivatives derivatives(double r) const = 0;

  /// f(r) [m]. Same domain as derivatives().
  virtual double f(double r) const { return derivatives(r).f; }

  /// M(a) = int_0^a f(r) r dr [m^4]. Closed form where one exists; otherwise adaptive
  /// Gauss-Kronrod quadrature to 1e-13 relative (or exact piecewise Gauss for tables).
  virtual double moment(double a) const;

  /// Sneddon integrals I0, I2 at a (closed form where known, else adaptive quadrature
  /// to 1e-13 relative).
  virtual SneddonIntegrals sneddon(double a) const;

  /// Largest admissible contact radius [m]; +inf if unbounded. A sphere returns R
  /// (exclusive), a table its last radius (inclusive); see contains().
  virtual double max_radius() const { return std::numeric_limits<double>::infinity(); }

  /// True if r is an admissible contact radius for this profile.
  virtual bool contains(double r) const;

  /// A typical length [m] used only to seed root brackets (never changes a result).
  virtual double length_scale() const = 0;

  /// Radii in (0, a) where f'' or f''' is discontinuous (table knots); quadratures
  /// split there.
  virtual std::vector<double> breakpoints(double a) const;

  /// True if f = r^2/(2R) exactly (paraboloid, or power law with d = 2): the profile for
  /// which model "auto"'s error table was measured.
  virtual bool is_paraboloid() const { return false; }
  /// {B, d} if f = B r^d exactly (paraboloid: {1/(2R), 2}, cone: {cot alpha, 1}, power
  /// law), else nothing.
  virtual std::optional<PowerLawForm> power_law_form() const { return std::nullopt; }

  /// Human-readable description, e.g. "paraboloid(R=0.01)".
  virtual std::string describe() const = 0;

  /// Set where the profile only approximates the indenter the user named (a pyramid by its
  /// equivalent cone): one line saying so, with the estimated relative error it brings. Every
  /// answer and fit of the profile carries it as a warning.
  virtual std::optional<std::string> approximation() const { return std::nullopt; }

  /// Throws DomainError naming `function` unless a > 0 and contains(a).
  void require_contact_radius(const char* function, double a) const;
};

using ProfilePtr = std::shared_ptr<const Profile>;

/// f = r^2 / (2R). R [m] > 0.
ProfilePtr make_paraboloid(double R);

/// Exact spherical cap f = R - sqrt(R^2 - r^2), for contact radii a < R. R [m] > 0.
ProfilePtr make_sphere(double R);

/// Cone f = r cot(alpha) with semi-angle alpha [rad] in (0, pi/2).
ProfilePtr make_cone(double semi_angle_rad);

/// A regular pyramid with `sides` faces and its axisymmetric equivalent cone.
struct PyramidEquivalence {
  int sides = 4;
  double face_semi_angle_rad = 0.0;  ///< the angle between a face and the axis, as vendors quote it
  double cone_semi_angle_rad = 0.0;  ///< the equivalent cone's semi-angle beta
  /// The estimated relative error [-] of the force the cone gives for the real pyramid on a
  /// half-space (the spread of the published pyramid solutions; docs/models.md).
  double relative_error = 0.0;
};

/// The cone whose Sneddon force F = (2/pi) E* tan(beta) delta^2 equals the pyramid's
/// F = c_n E* tan(theta) delta^2 on a half-space: tan(beta) = (pi/2) c_n tan(theta), with
/// theta the face semi-angle [rad] in (0, pi/2) and c_n of docs/models.md (sides 3 or 4).
/// Approximate: a pyramid's contact is not axisymmetric. Throws DomainError for other sides
/// or angles.
PyramidEquivalence pyramid_equivalent_cone(double face_semi_angle_rad, int sides);

/// The pyramid as its equivalent cone (pyramid_equivalent_cone); its approximation() says so.
ProfilePtr make_pyramid(double face_semi_angle_rad, int sides);

/// Power law f = B r^d with B > 0 [m^(1-d)] and d in [1, 50] (beyond, a flat punch).
ProfilePtr make_power_law(double B, double d);

/// Measured profile from a table (r_i [m], z_i [m]): r strictly increasing from
/// r_0 = 0, z non-decreasing, all finite, at least 3 points. z_0 is subtracted
/// exactly. The table is mirrored to r < 0 (so f'(0) = 0: a measured tip is rounded
/// at its apex) and interpolated with GSL's natural cubic spline, which is C2 - the
/// two-term model needs a continuous f''. The spline is verified to be monotone on
/// every segment; a table it cannot follow monotonically throws DomainError. f''' is
/// piecewise constant; moments are exact (Gauss-Legendre per segment). Contact radii
/// up to the last r are admissible.
ProfilePtr make_table_profile(std::vector<double> r, std::vector<double> z);

}  // namespace layerjkr
