// libFuzzer target: the JSON scene reader. Any input must either parse or throw a
// layerjkr::Error (deep nesting and repeated keys included: corpus regression_*); a parsed scene with a cheap model must give a finite state.
#include <cmath>
#include <cstdint>
#include <string>

#include "layerjkr/layerjkr.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const layerjkr::Scene scene = layerjkr::parse_scene(text, "fuzz");
    using layerjkr::SceneModel;
    if (scene.model == SceneModel::exact || scene.model == SceneModel::automatic ||
        scene.model == SceneModel::edge_corrected)
      return 0;
    const layerjkr::BuiltScene built = layerjkr::build_scene(scene);
    const double a = std::min(scene.profile->length_scale(), 0.5 * scene.profile->max_radius());
    const layerjkr::NonAdhesiveState s = built.model->state(a);
    if (!std::isfinite(s.P_H) || !std::isfinite(s.delta_H) || !std::isfinite(s.S)) __builtin_trap();
  } catch (const layerjkr::Error&) {
  }
  return 0;
}
