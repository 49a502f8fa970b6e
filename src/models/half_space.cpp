// Elastic half-space for any profile: delta_H = a I0(a), P_H = 2 E* a^2 I2(a).
#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr {
namespace {

class HalfSpace final : public ContactModel {
 public:
  HalfSpace(ProfilePtr p, double E_star) : ContactModel(std::move(p)), E_star_(E_star) {}
  HertzState state(double a) const override {
    profile().require_contact_radius("half_space", a);
    const SneddonIntegrals I = profile().sneddon(a);
    HertzState s;
    s.a = a;
    s.delta_H = a * I.I0;
    s.P_H = 2.0 * E_star_ * a * a * I.I2;
    s.S = 2.0 * E_star_ * a;
    s.dS_da = 2.0 * E_star_;
    return s;
  }
  std::string name() const override { return "half_space"; }

 private:
  double E_star_;
};

}  // namespace

ContactModelPtr make_half_space(ProfilePtr profile, double E, double nu) {
  return std::make_shared<HalfSpace>(std::move(profile), effective_modulus(E, nu));
}

}  // namespace layerjkr
