// ContactModel "edge_corrected": Winkler at the effective radius a + beta h, beta fitted
// from the exact layer (docs/theory.md s.6).
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model_spec.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

class EdgeCorrected final : public ContactModel {
 public:
  EdgeCorrected(ProfilePtr p, double K, double shift)
      : ContactModel(p), winkler_(make_winkler(std::move(p), K)), shift_(shift) {}
  NonAdhesiveState state(double a) const override {
    if (!(a + shift_ > 0.0))
      throw DomainError("edge_corrected", "contact radius a", a,
                        "> -beta h = " + format_double(-shift_) +
                            " (the effective radius a + beta h must be positive)");
    NonAdhesiveState s = winkler_->state(a + shift_);
    s.a = a;  // the JKR energy term uses the true contact radius
    return s;
  }
  std::string name() const override { return to_string(ModelKind::edge_corrected); }
  double min_radius() const override { return std::max(0.0, -shift_); }

 private:
  ContactModelPtr winkler_;
  double shift_;
};

}  // namespace

double edge_correction_beta(const ElasticLayer& layer) {
  if (!(layer.nu < 0.5))
    throw DomainError("edge_correction_beta", "nu", layer.nu,
                      "(-1, 0.5): the Winkler constant of an incompressible bonded layer is infinite");
  ExactLayerOptions o;
  o.max_a_over_h = 50.0;
  o.estimate_error = false;
  const ExactLayerKernel kernel({1.0, layer.nu, 1.0, layer.base}, o);  // dimensionless
  const double R = 1e4, a = 50.0;
  const auto paraboloid = make_paraboloid(R);
  // Winkler on a paraboloid: delta = (a + beta h)^2 / (2R).
  const double delta = kernel.solve(*paraboloid, a).state.delta_H;
  return std::sqrt(2.0 * R * delta) - a;
}

ContactModelPtr make_edge_corrected(ProfilePtr profile, const ElasticLayer& layer) {
  const ThinLayerConstants c = thin_layer_constants(layer);  // validates the layer
  return std::make_shared<EdgeCorrected>(std::move(profile), c.K,
                                         edge_correction_beta(layer) * layer.h);
}

}  // namespace layerjkr
