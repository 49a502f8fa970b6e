// The one spelling registry of the public enums (types.hpp): a table per enum, and the three
// conversions instantiated for each.
#include "layerjkr/types.hpp"

#include <utility>

#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr {
namespace {

template <class E>
struct Names;

#define LAYERJKR_NAMES(E, ...)                                          \
  template <>                                                           \
  struct Names<E> {                                                     \
    static constexpr std::pair<E, const char*> table[] = {__VA_ARGS__}; \
  };

LAYERJKR_NAMES(Base, {Base::bonded, "bonded"}, {Base::frictionless, "frictionless"})
LAYERJKR_NAMES(FoundationKind, {FoundationKind::asymptotic, "asymptotic"}, {FoundationKind::full, "full"})
LAYERJKR_NAMES(ModelKind, {ModelKind::winkler, "winkler"}, {ModelKind::two_term, "two_term"},
               {ModelKind::full_foundation, "full_foundation"}, {ModelKind::half_space, "half_space"},
               {ModelKind::edge_corrected, "edge_corrected"}, {ModelKind::exact, "exact"},
               {ModelKind::incompressible, "incompressible"}, {ModelKind::uniform, "uniform"})
LAYERJKR_NAMES(MediumType, {MediumType::winkler, "winkler"}, {MediumType::pasternak, "pasternak"},
               {MediumType::filonenko_borodich, "filonenko_borodich"}, {MediumType::layer, "layer"},
               {MediumType::half_space, "half_space"}, {MediumType::layers, "layers"})
LAYERJKR_NAMES(SceneModel, {SceneModel::winkler, "winkler"}, {SceneModel::half_space, "half_space"},
               {SceneModel::leading, "leading"}, {SceneModel::two_term, "two_term"},
               {SceneModel::edge_corrected, "edge_corrected"}, {SceneModel::exact, "exact"},
               {SceneModel::automatic, "auto"}, {SceneModel::asymptotic, "asymptotic"},
               {SceneModel::full, "full"}, {SceneModel::incompressible, "incompressible"},
               {SceneModel::uniform, "uniform"})
LAYERJKR_NAMES(Solver, {Solver::closed_form, "closed_form"}, {Solver::ode, "ode"})
LAYERJKR_NAMES(Branch, {Branch::approach, "approach"}, {Branch::retract, "retract"}, {Branch::all, "all"},
               {Branch::dwell, "dwell"}, {Branch::approach_dwell, "approach_dwell"})
LAYERJKR_NAMES(FitParameter, {FitParameter::K, "K"}, {FitParameter::G, "G"}, {FitParameter::w, "w"},
               {FitParameter::delta0, "delta0"}, {FitParameter::P0, "P0"}, {FitParameter::E, "E"},
               {FitParameter::R, "R"}, {FitParameter::sigma0, "sigma0"}, {FitParameter::E_inf, "E_inf"},
               {FitParameter::tau, "tau"}, {FitParameter::beta, "beta"}, {FitParameter::v_star, "v_star"},
               {FitParameter::n, "n"}, {FitParameter::drag, "drag"}, {FitParameter::E_2, "E_2"},
               {FitParameter::tau_2, "tau_2"})
LAYERJKR_NAMES(LossType, {LossType::none, "none"}, {LossType::huber, "huber"}, {LossType::cauchy, "cauchy"})
LAYERJKR_NAMES(RetractWindow, {RetractWindow::all, "all"}, {RetractWindow::to_pull_off, "pull_off"},
               {RetractWindow::force_fraction, "fraction"})
LAYERJKR_NAMES(RetractControl, {RetractControl::automatic, "auto"}, {RetractControl::load, "load"},
               {RetractControl::cantilever, "cantilever"}, {RetractControl::fixed_grips, "grips"})
LAYERJKR_NAMES(Baseline, {Baseline::constant, "constant"}, {Baseline::tilt, "tilt"})
LAYERJKR_NAMES(ContactPointMethod, {ContactPointMethod::fit, "fit"}, {ContactPointMethod::threshold, "threshold"},
               {ContactPointMethod::rov, "rov"}, {ContactPointMethod::gof, "gof"})
LAYERJKR_NAMES(AdhesionModel, {AdhesionModel::jkr, "jkr"}, {AdhesionModel::dmt, "dmt"},
               {AdhesionModel::maugis_dugdale, "maugis_dugdale"})
LAYERJKR_NAMES(FitFamily, {FitFamily::foundation, "foundation"}, {FitFamily::hertz, "hertz"},
               {FitFamily::tabulated, "tabulated"}, {FitFamily::dugdale, "dugdale"},
               {FitFamily::hereditary, "hereditary"}, {FitFamily::kinetic, "kinetic"})
LAYERJKR_NAMES(SegmentStyle, {SegmentStyle::extend, "extend"}, {SegmentStyle::retract, "retract"},
               {SegmentStyle::pause, "pause"}, {SegmentStyle::modulation, "modulation"})
LAYERJKR_NAMES(InstrumentFormat, {InstrumentFormat::jpk_force, "jpk-force"},
               {InstrumentFormat::jpk_force_map, "jpk-force-map"}, {InstrumentFormat::jpk_qi_data, "jpk-qi-data"},
               {InstrumentFormat::ibw, "ibw"}, {InstrumentFormat::nanoscope, "nanoscope"},
               {InstrumentFormat::ibw_map, "ibw-map"}, {InstrumentFormat::jpk_qi_series, "jpk-qi-series"},
               {InstrumentFormat::afm_workshop_map, "afm-workshop-map"},
               {InstrumentFormat::afmformats_hdf5, "afmformats-hdf5"})
LAYERJKR_NAMES(Smoothing, {Smoothing::log_polynomial, "log_polynomial"}, {Smoothing::log_spline, "log_spline"})
LAYERJKR_NAMES(DiscreteApproach, {DiscreteApproach::two_models, "two_models"},
               {DiscreteApproach::single_model, "single_model"})
#undef LAYERJKR_NAMES

}  // namespace

const char* unit_of(FitParameter p) {
  switch (p) {
    case FitParameter::K: return "N/m^3";
    case FitParameter::G: return "N/m";
    case FitParameter::w: return "J/m^2";
    case FitParameter::delta0:
    case FitParameter::R: return "m";
    case FitParameter::P0: return "N";
    case FitParameter::E:
    case FitParameter::sigma0:
    case FitParameter::E_inf:
    case FitParameter::E_2: return "Pa";
    case FitParameter::tau:
    case FitParameter::tau_2: return "s";
    case FitParameter::v_star: return "m/s";
    case FitParameter::beta:
    case FitParameter::n: return "";
    case FitParameter::drag: return "N s/m";
  }
  return "";
}

template <class E, class>
const char* to_string(E value) {
  for (const auto& [e, name] : Names<E>::table)
    if (e == value) return name;
  return "unknown";
}

template <class E, class>
std::optional<E> from_string(std::string_view name) {
  for (const auto& [e, spelling] : Names<E>::table)
    if (name == spelling) return e;
  if constexpr (std::is_same_v<E, FitParameter>) {
    if (name == "T") return FitParameter::G;  // a Filonenko-Borodich tension plays G's role
    if (name == "w0") return FitParameter::w;  // crack kinetics' name for the work of adhesion
    if (name == "V") return FitParameter::v_star;
    if (name == "N") return FitParameter::n;
  }
  return std::nullopt;
}

template <class E, class>
std::string known_names() {
  std::string list;
  for (const auto& [e, name] : Names<E>::table) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

template <class E, class>
E parse_enum(std::string_view name, const std::string& what) {
  if (const std::optional<E> e = from_string<E>(name)) return *e;
  // Shortened and made printable: the text may come from a binary file.
  throw InputError(what + " = \"" + printable(name, 40) + "\" is unknown (known: " + known_names<E>() + ")");
}

#define LAYERJKR_INSTANTIATE(E)                                  \
  template const char* to_string<E, void>(E);                    \
  template std::optional<E> from_string<E, void>(std::string_view); \
  template std::string known_names<E, void>();                   \
  template E parse_enum<E, void>(std::string_view, const std::string&);
LAYERJKR_INSTANTIATE(Base)
LAYERJKR_INSTANTIATE(FoundationKind)
LAYERJKR_INSTANTIATE(ModelKind)
LAYERJKR_INSTANTIATE(MediumType)
LAYERJKR_INSTANTIATE(SceneModel)
LAYERJKR_INSTANTIATE(Solver)
LAYERJKR_INSTANTIATE(Branch)
LAYERJKR_INSTANTIATE(FitParameter)
LAYERJKR_INSTANTIATE(LossType)
LAYERJKR_INSTANTIATE(RetractWindow)
LAYERJKR_INSTANTIATE(RetractControl)
LAYERJKR_INSTANTIATE(Baseline)
LAYERJKR_INSTANTIATE(ContactPointMethod)
LAYERJKR_INSTANTIATE(AdhesionModel)
LAYERJKR_INSTANTIATE(FitFamily)
LAYERJKR_INSTANTIATE(SegmentStyle)
LAYERJKR_INSTANTIATE(InstrumentFormat)
LAYERJKR_INSTANTIATE(Smoothing)
LAYERJKR_INSTANTIATE(DiscreteApproach)
#undef LAYERJKR_INSTANTIATE

}  // namespace layerjkr
