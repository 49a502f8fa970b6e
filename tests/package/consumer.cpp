// The installed package works when this compiles against the installed headers, links the
// installed library, reproduces the half-space JKR pull-off -3/2 pi w R, and answers a scene
// file (argv[1]: data/scenes/sphere_pdms_film_two_term.json) with its error estimates and
// warnings, written exactly as the README shows a user; and writes a map report's page without
// the source tree.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "layerjkr/layerjkr.hpp"

namespace {

bool fail(const char* what) {
  std::fprintf(stderr, "consumer: %s\n", what);
  return false;
}

bool half_space_pull_off() {
  const double R = 1e-3, w = 0.05;
  const auto model = layerjkr::make_half_space(layerjkr::make_paraboloid(R), 1e6, 0.3);
  const auto pull_off = layerjkr::JkrSolution(model, w).pull_off();
  const double expected = -1.5 * M_PI * w * R;
  if (!pull_off || std::abs(pull_off->P / expected - 1.0) > 1e-8) return fail("pull-off differs from -3/2 pi w R");
  std::printf("installed layerjkr: pull-off %.9g N (-3/2 pi w R = %.9g N)\n", pull_off->P, expected);
  return true;
}

// The two-term law at the sphere scene's pull-off (a/h = 1.8) is 10 % off the exact layer:
// the answer must say so, in its estimate and in a warning.
bool scene_answers(const std::string& path) {
  layerjkr::Scene scene = layerjkr::load_scene(path);
  layerjkr::SummaryAnswer s = layerjkr::solve_summary(scene);
  if (!s.contact.pull_off || !(s.error.pull_off_force > 0.05 && s.error.pull_off_force < 0.2))
    return fail("the summary's pull-off or its error estimate is missing or off");
  if (s.error.reference != "exact" || s.warnings.empty() ||
      s.warnings.back().find("in the pull-off force") == std::string::npos)
    return fail("the summary does not warn about its model error");
  if (!s.K || !s.G || !s.E_star || s.choice) return fail("the summary's typed constants are wrong");
  const std::vector<double> radii = {2e-4, 4e-4};
  layerjkr::CurveAnswer c = layerjkr::solve_curve(scene, radii);
  if (c.states.size() != 2 || c.error_estimate.size() != 2 || !(c.error_estimate[1] > 0.05))
    return fail("the curve's states or error estimates are wrong");
  if (c.warnings.empty() || c.warnings.back().find("at a = ") == std::string::npos)
    return fail("the curve does not warn about its model error");
  std::printf("installed layerjkr: %s pull-off %.9g N, estimated %.3g off; curve warning: %s\n",
              s.contact.model.c_str(), s.contact.pull_off->P, s.error.pull_off_force, c.warnings.back().c_str());
  return true;
}

// The map report's page, plotting library included, comes from the installed library alone.
bool report_is_self_contained() {
  layerjkr::BatchItem item;
  item.source = "curve.csv";
  item.error = "not fitted";
  layerjkr::MapReportOptions options;
  options.free = {layerjkr::FitParameter::E};
  const std::string html = layerjkr::map_report_html({item}, options);
  if (html.size() < 1500000 || html.find("Permission is hereby granted") == std::string::npos ||
      html.find("\"not fitted\"") == std::string::npos)
    return fail("the map report lacks its plotting library, its licence or its data");
  std::printf("installed layerjkr: a map report of %zu bytes\n", html.size());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return fail("usage: consumer SCENE.json"), 2;
  return half_space_pull_off() && scene_answers(argv[1]) && report_is_self_contained() ? 0 : 1;
}
