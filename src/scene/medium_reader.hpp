// Internal: the "medium" object of a scene JSON (medium_reader.cpp).
#pragma once

#include "json_reader.hpp"
#include "layerjkr/scene.hpp"

namespace layerjkr::detail {

/// The medium of `root` ("medium": half_space, layer, layers, foundations; its viscoelastic law):
/// InputError naming the key, its value and the valid range.
MediumSpec read_medium(const JsonReader& in, const json& root);

}  // namespace layerjkr::detail
