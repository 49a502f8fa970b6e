// Internal: a scene's fields as compact JSON text (provenance.cpp). parse_scene stores it in
// SceneOrigin::description, so a provenance record can tell whether the scene still holds what its
// JSON gives without parsing the JSON again (a table indenter of 10^5 points costs a second).
#pragma once

#include <string>

#include "layerjkr/scene.hpp"

namespace layerjkr::detail {

std::string describe_scene(const Scene& scene);

}  // namespace layerjkr::detail
