// ContactModel "exact": the exact layer's solver (exact_layer_solver.cpp) behind the
// ContactModel interface, with states from the power-law tables where the profile allows.
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model_spec.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "models/exact_layer_solver.hpp"
#include "models/exact_power_law_table.hpp"

namespace layerjkr {
namespace {

// The power-law tables' interpolation error, as the tests bound it against direct solves
// (tests/models/test_exact_power_law_table.cpp).
constexpr double kTableAccuracy = 1e-9;

// True for radii a_max j / n, j = 1..n, to rounding.
bool evenly_spaced(const std::vector<double>& radii) {
  const double a_max = radii.back(), n = static_cast<double>(radii.size());
  if (!(a_max > 0.0) || !std::isfinite(a_max)) return false;
  for (std::size_t j = 0; j < radii.size(); ++j)
    if (std::abs(radii[j] - a_max * static_cast<double>(j + 1) / n) > 1e-12 * a_max) return false;
  return true;
}

// Flops of a sweep (one Cholesky of the largest grid, one triangular solve per radius)
// against solving each radius on its own grid (a Cholesky each): the sweep forces a panel
// boundary at every step, which over-resolves small radii, so it is not always cheaper.
bool sweep_is_cheaper(const ExactLayerOptions& o, double rho, int count) {
  const double per_step = detail::sweep_panels_per_step(o, rho, count), p = o.points_per_panel;
  const double n = per_step * count * p;
  double sweep = n * n * n / 3.0, single = 0.0;
  for (int j = 1; j <= count; ++j) {
    const detail::Discretisation d = detail::discretise(o, rho * j / count);
    const double nj = static_cast<double>(d.panels) * d.nodes;
    sweep += (j * per_step * p) * (j * per_step * p);
    single += nj * nj * nj / 3.0;
  }
  return sweep < single;
}


class ExactLayerModel final : public ContactModel {
 public:
  template <class Medium>
  ExactLayerModel(ProfilePtr p, const Medium& medium, const ExactLayerOptions& o)
      : ContactModel(std::move(p)), kernel_(medium, o) {
    if (o.tabulate_power_laws)
      if (const auto form = profile().power_law_form()) {
        form_ = *form;
        table_ = detail::shared_power_law_table(kernel_.medium(), form->d, o);
      }
  }
  // A ContactModel returns no error estimate, so none is computed (solve() has it).
  NonAdhesiveState state(double a) const override {
    if (table_) {
      const double h = kernel_.layer().h, rho = detail::checked_a_over_h(kernel_, "exact_layer", profile(), a);
      if (table_->covers(rho)) {  // the unit profile's moments, scaled to B r^d on this layer
        detail::ExactMoments m = table_->at(rho);
        const double scale = form_.B * std::pow(h, form_.d);
        m.intf *= scale;
        m.endf *= scale;
        return exact_state_from(m, a, h, kernel_.effective_modulus());
      }
    }
    return kernel_.state(profile(), a);
  }
  // A tabulated power law is cheapest radius by radius. Otherwise an evenly spaced grid a_max j / n (as `layerjkr curve --a-max A --points N` asks for)
  // comes from one factorisation; any other set of radii is solved radius by radius.
  std::vector<NonAdhesiveState> states(const std::vector<double>& radii) const override {
    const std::size_t n = radii.size();
    if (table_ || n < 2 || !evenly_spaced(radii) || !(radii.back() <= max_radius()) ||
        !sweep_is_cheaper(kernel_.options(), radii.back() / kernel_.layer().h, static_cast<int>(n)))
      return ContactModel::states(radii);
    std::vector<NonAdhesiveState> out = kernel_.sweep(profile(), radii.back(), static_cast<int>(n));
    for (std::size_t j = 0; j < n; ++j) out[j].a = radii[j];
    return out;
  }
  std::string name() const override { return to_string(ModelKind::exact); }
  double numerical_error(double a) const override {
    const ExactLayerState s = kernel_.solve(profile(), a);
    const double solve_error = std::max(s.P_H_error, s.delta_H_error);
    const double estimate = std::isfinite(solve_error) ? solve_error : kTableAccuracy;
    return table_ ? std::max(estimate, kTableAccuracy) : std::max(estimate, 1e-13);
  }
  double max_radius() const override {
    return std::min(profile().max_radius(),
                    kernel_.options().max_a_over_h * kernel_.layer().h);
  }
  // Searches seeded at a/h <= 1 meet the cheap small-a/h states (and table pieces) first and
  // double outwards only as far as the root, instead of halving down from a/h = 500.
  double typical_radius() const override { return std::min(profile().length_scale(), kernel_.layer().h); }

 private:
  ExactLayerKernel kernel_;
  PowerLawForm form_;
  std::shared_ptr<const detail::ExactPowerLawTable> table_;  // null: solve every radius
};

}  // namespace

ContactModelPtr make_exact_layer(ProfilePtr profile, const ElasticLayer& layer,
                                 const ExactLayerOptions& options) {
  return std::make_shared<ExactLayerModel>(std::move(profile), layer, options);
}

ContactModelPtr make_exact_layer(ProfilePtr profile, const LayeredMedium& medium, const ExactLayerOptions& options) {
  return std::make_shared<ExactLayerModel>(std::move(profile), medium, options);
}

}  // namespace layerjkr
