// layerjkr CLI: the JSON keys every summary prints (summary, discrete --summary).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "layerjkr/contact.hpp"

namespace layerjkr::cli {

inline nlohmann::ordered_json summary_json(const ContactSummary& s, const std::string& profile) {
  nlohmann::ordered_json j;
  j["model"] = s.model;
  j["profile"] = profile;
  j["w"] = s.w;
  auto opt = [](const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; };
  j["pull_off_force"] = s.pull_off ? nlohmann::ordered_json(s.pull_off->P) : nullptr;
  j["pull_off_radius"] = s.pull_off ? nlohmann::ordered_json(s.pull_off->a) : nullptr;
  j["pull_off_delta"] = s.pull_off ? nlohmann::ordered_json(s.pull_off->delta) : nullptr;
  j["zero_load_radius"] = opt(s.zero_load_radius);
  if (s.fixed_grips)
    j["fixed_grips_critical"] = {{"force", s.fixed_grips->P}, {"radius", s.fixed_grips->a}, {"delta", s.fixed_grips->delta}};
  else
    j["fixed_grips_critical"] = nullptr;
  return j;
}

}  // namespace layerjkr::cli
