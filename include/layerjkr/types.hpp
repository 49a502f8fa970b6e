// layerjkr: every enumeration of the public API and its one spelling registry.
//
// As in Ceres (ceres/types.h), options and answers hold enums; strings exist only at the
// edges - scene files, the CLI, the Python module, reports - and every one of them converts
// through the functions below, so an enumerator has exactly one spelling:
//
//   layerjkr::to_string(layerjkr::Branch::retract)          // "retract"
//   layerjkr::from_string<layerjkr::Branch>("retract")      // std::optional<Branch>
//   layerjkr::known_names<layerjkr::Branch>()               // "approach, retract, all"
//
// The spellings are the scene schema's and the reports' (docs/fitting.md, scene.hpp).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

namespace layerjkr {

/// How a layer is attached to its rigid base: "bonded", "frictionless".
enum class Base { bonded, frictionless };

/// Which foundation the ODE route integrates: "asymptotic", "full".
enum class FoundationKind { asymptotic, full };

/// Every contact model the library builds (model_spec.hpp): "winkler", "two_term",
/// "full_foundation", "half_space", "edge_corrected", "exact", "incompressible", "uniform".
enum class ModelKind {
  winkler,          ///< p = K w (eq. 41)
  two_term,         ///< p = K w - G lap w inside the contact (eqs. 43-45, corrected force)
  full_foundation,  ///< Pasternak / Filonenko-Borodich on the whole plane (G > 0)
  half_space,       ///< elastic half-space (Galin / Sneddon)
  edge_corrected,   ///< Winkler at a + beta h (exact_layer.hpp)
  exact,            ///< the exact elastic layer (exact_layer.hpp)
  incompressible,   ///< thin incompressible bonded layer, lubrication law (model.hpp)
  uniform,          ///< bonded thin layer, two-term compliance form uniform in nu (model.hpp)
};

/// A scene's medium (scene.hpp): "winkler", "pasternak", "filonenko_borodich", "layer",
/// "half_space", "layers" (a stack of bonded layers, layered_medium.hpp).
enum class MediumType { winkler, pasternak, filonenko_borodich, layer, half_space, layers };

/// The scene's "model" key: what the user asked for. Spelled as the enumerator, except
/// automatic, which is "auto". Which ones a medium accepts: scene.hpp.
enum class SceneModel { winkler, half_space, leading, two_term, edge_corrected, exact, automatic,
                        asymptotic, full, incompressible, uniform };

/// How a foundation's P_H is computed: "closed_form", or the ODE route "ode" (model.hpp).
enum class Solver { closed_form, ode };

/// Which part of a curve a fit uses: "approach", "retract", "all"; and for fits in time of a
/// curve with a dwell (segment 2 between approach and retract), "dwell" (the dwell's samples, the
/// approach as their history) and "approach_dwell" (both: everything before the retract).
enum class Branch { approach, retract, all, dwell, approach_dwell };

/// A fitted quantity (fit.hpp): "K", "G", "w", "delta0", "P0", "E", "R", "sigma0" (the
/// Dugdale stress of a Maugis-Dugdale fit), and in time "E_inf" and "tau" (a standard linear
/// solid's relaxed modulus and time), "beta" (a power law's exponent), "v_star" and "n" (crack
/// kinetics), "drag" (the lever's hydrodynamic drag coefficient b [N s/m]: the measured force
/// carries b v, v the base's speed towards the sample), "E_2" and "tau_2" (the second arm of a
/// two-term generalised Maxwell law, "maxwell2": its modulus [Pa] and time [s]). from_string also reads "T" (a Filonenko-Borodich tension) as G, "w0" as w, "V" as
/// v_star and "N" as n.
enum class FitParameter { K, G, w, delta0, P0, E, R, sigma0, E_inf, tau, beta, v_star, n, drag, E_2, tau_2 };
/// How many FitParameter values there are.
inline constexpr int kFitParameterCount = 16;
/// The SI unit of a fitted quantity: "N/m^3", "N/m", "J/m^2", "m", "N", "Pa", "s", "m/s" or "" (beta, n).
const char* unit_of(FitParameter p);

/// Robust loss on force residuals (fit.hpp): "none", "huber", "cauchy".
enum class LossType { none, huber, cauchy };

/// Which unloading samples a retract fit uses (fit.hpp): "all", "pull_off", "fraction".
enum class RetractWindow { all, to_pull_off, force_fraction };

/// What controls the retract (fit.hpp): "auto", "load", "cantilever", "grips".
enum class RetractControl {
  automatic,    ///< a cantilever where its stiffness is known (given or the curve's own), else load
  load,         ///< load control: the tip lets go at the pull-off force
  cantilever,   ///< a cantilever of known stiffness (given or the curve's own; required)
  fixed_grips,  ///< displacement control: the tip lets go at the fixed-grips instability
};

/// The baseline a fit subtracts (fit.hpp): "constant" (P0), "tilt" (P0 + slope delta).
enum class Baseline { constant, tilt };

/// How adhesion acts (maugis_dugdale.hpp, scene.hpp "adhesion"): "jkr" (at the contact edge
/// only: the explicit transform, jkr.hpp), "dmt" (outside the contact, without deforming it),
/// "maugis_dugdale" (a constant tensile stress sigma0 over a < r < c: the transition between them).
enum class AdhesionModel { jkr, dmt, maugis_dugdale };

/// How an approach fit finds the contact point (contact_point.hpp): "fit" (delta0 is a
/// fitted parameter), "threshold" (baseline deviation), "rov" (ratio of variances), "gof"
/// (goodness-of-fit scan of a power law).
enum class ContactPointMethod { fit, threshold, rov, gof };

/// How a fit evaluates its model (fit.hpp): "foundation" (closed forms in K, G or E),
/// "hertz" (half-space with a paraboloid), "tabulated" (a spline of any other model),
/// "dugdale" (a Dugdale law - Maugis-Dugdale, DMT with sigma0 - solved on the medium per
/// parameter vector), and in time "hereditary" (a relaxing medium: Lee-Radok and Ting over the
/// measured indentation history) and "kinetic" (crack kinetics: the retract's ODE).
enum class FitFamily { foundation, hertz, tabulated, dugdale, hereditary, kinetic };

/// A segment of an instrument curve (instrument.hpp): "extend", "retract", "pause",
/// "modulation" (JPK's oscillation segments).
enum class SegmentStyle { extend, retract, pause, modulation };

/// An instrument file's format (instrument.hpp): "jpk-force", "jpk-force-map",
/// "jpk-qi-data", "ibw", "nanoscope" (Bruker force curves and force volumes), "ibw-map" (an
/// Asylum force map exported as one Igor wave per channel per point, read from its folder),
/// "jpk-qi-series", "afm-workshop-map" (a .zip of AFM Workshop's CSV exports, one per point),
/// "afmformats-hdf5" (afmformats' .h5 export; read where libhdf5 is linked, instrument.hpp).
enum class InstrumentFormat { jpk_force, jpk_force_map, jpk_qi_data, ibw, nanoscope, ibw_map, jpk_qi_series, afm_workshop_map,
                              afmformats_hdf5 };

/// Smoothing of discrete data (discrete.hpp): "log_polynomial", "log_spline".
enum class Smoothing { log_polynomial, log_spline };

/// Which reconstruction from discrete data (discrete.hpp): "two_models", "single_model".
enum class DiscreteApproach { two_models, single_model };

/// True for the enumerations above (those the registry knows).
template <class E>
struct is_registered_enum : std::false_type {};
#define LAYERJKR_REGISTERED_ENUM(E) \
  template <>                       \
  struct is_registered_enum<E> : std::true_type {};
LAYERJKR_REGISTERED_ENUM(Base)
LAYERJKR_REGISTERED_ENUM(FoundationKind)
LAYERJKR_REGISTERED_ENUM(ModelKind)
LAYERJKR_REGISTERED_ENUM(MediumType)
LAYERJKR_REGISTERED_ENUM(SceneModel)
LAYERJKR_REGISTERED_ENUM(Solver)
LAYERJKR_REGISTERED_ENUM(Branch)
LAYERJKR_REGISTERED_ENUM(FitParameter)
LAYERJKR_REGISTERED_ENUM(LossType)
LAYERJKR_REGISTERED_ENUM(RetractWindow)
LAYERJKR_REGISTERED_ENUM(RetractControl)
LAYERJKR_REGISTERED_ENUM(Baseline)
LAYERJKR_REGISTERED_ENUM(ContactPointMethod)
LAYERJKR_REGISTERED_ENUM(AdhesionModel)
LAYERJKR_REGISTERED_ENUM(FitFamily)
LAYERJKR_REGISTERED_ENUM(SegmentStyle)
LAYERJKR_REGISTERED_ENUM(InstrumentFormat)
LAYERJKR_REGISTERED_ENUM(Smoothing)
LAYERJKR_REGISTERED_ENUM(DiscreteApproach)
#undef LAYERJKR_REGISTERED_ENUM

/// The spelling of `value` (a static string; "unknown" for a value outside the enumeration).
template <class E, class = std::enable_if_t<is_registered_enum<E>::value>>
const char* to_string(E value);

/// The enumerator spelled `name`, or nullopt.
template <class E, class = std::enable_if_t<is_registered_enum<E>::value>>
std::optional<E> from_string(std::string_view name);

/// Every spelling of E, comma-separated, in declaration order (for error messages).
template <class E, class = std::enable_if_t<is_registered_enum<E>::value>>
std::string known_names();

/// The enumerator spelled `name`; throws InputError "<what> = "<name>" is unknown (known:
/// ...)" otherwise. `what` names the key or option the text came from.
template <class E, class = std::enable_if_t<is_registered_enum<E>::value>>
E parse_enum(std::string_view name, const std::string& what);

}  // namespace layerjkr
