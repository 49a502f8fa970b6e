// Elastic half-space for any profile: delta_H = a I0(a), P_H = 2 E* a^2 I2(a).
#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"
#include "models/state_formulas.hpp"

namespace layerjkr {
namespace {

class HalfSpace final : public ContactModel {
 public:
  HalfSpace(ProfilePtr p, double E_star) : ContactModel(std::move(p)), E_star_(E_star) {}
  NonAdhesiveState state(double a) const override {
    profile().require_contact_radius(to_string(ModelKind::half_space), a);
    const SneddonIntegrals I = profile().sneddon(a);
    const auto s = detail::half_space_state(a, I.I0, I.I2, E_star_);
    return {a, s.P_H, s.delta_H, s.S, s.dS_da};
  }
  std::string name() const override { return to_string(ModelKind::half_space); }

 private:
  double E_star_;
};

}  // namespace

ContactModelPtr make_half_space(ProfilePtr profile, double E, double nu) {
  return std::make_shared<HalfSpace>(std::move(profile), effective_modulus(E, nu));
}

}  // namespace layerjkr
