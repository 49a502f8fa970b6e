// What this teaches: whether JKR applies to a contact, and what to use when it does not.
// One AFM tip is pressed into three media - a soft gel, a stiff polymer, and the same polymer
// as a 10 nm film on silicon - and each is answered three ways: JKR (adhesion at the contact
// edge), DMT (adhesion outside the contact) and Maugis-Dugdale (a Dugdale zone of stress
// sigma0 and range h0 = w / sigma0, the transition between them). The summary's adhesion check
// reports Maugis' lambda of each contact and how far the JKR pull-off force is from
// Maugis-Dugdale (solved on the medium when the estimate exceeds 1 %). A thin film on a rigid
// base has a lower lambda than its own half-space, yet JKR's error there is smaller than the
// half-space's at that lambda: the check's estimate is an upper bound, the solve the number.
//
// How the data is made: nothing is measured. Tip R = 20 nm, w = 0.05 J/m^2, sigma0 from a
// Lennard-Jones law with z0 = 0.3 nm (16 w / (9 sqrt(3) z0) = 171 MPa); gel E = 10 kPa,
// polymer E = 3 GPa, nu = 0.4.
//
// Run: build/bin/jkr_or_dmt
#include <cmath>
#include <cstdio>
#include <string>

#include "layerjkr/layerjkr.hpp"

namespace {

double pull_off(const std::string& medium, const std::string& model, const std::string& adhesion) {
  const std::string text = R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": )" + medium +
                           R"(, "model": ")" + model + R"(", "w": 0.05, "adhesion": )" + adhesion + "}";
  return layerjkr::solve_summary(layerjkr::parse_scene(text)).contact.pull_off->P;
}

}  // namespace

int main() {
  struct Medium {
    const char* label;
    std::string json, model;
  };
  const Medium media[] = {
      {"gel, 10 kPa", R"({"type": "half_space", "E": 1e4, "nu": 0.4})", "half_space"},
      {"polymer, 3 GPa", R"({"type": "half_space", "E": 3e9, "nu": 0.4})", "half_space"},
      {"10 nm polymer film on Si", R"({"type": "layer", "E": 3e9, "nu": 0.4, "h": 1e-8, "base": "bonded"})", "exact"},
  };
  std::printf("%-26s %8s %12s %12s %12s %10s\n", "medium", "lambda", "JKR [nN]", "DMT [nN]", "MD [nN]",
              "JKR off");
  for (const Medium& m : media) {
    const std::string scene = R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": )" + m.json +
                              R"(, "model": ")" + m.model + R"(", "w": 0.05})";
    const layerjkr::SummaryAnswer jkr = layerjkr::solve_summary(layerjkr::parse_scene(scene));
    const double dmt = pull_off(m.json, m.model, R"({"model": "dmt"})");
    const double md = pull_off(m.json, m.model, R"({"model": "maugis_dugdale", "z0": 3e-10})");
    std::printf("%-26s %8.3g %12.4g %12.4g %12.4g %9.1f %%\n", m.label, jkr.adhesion->lambda,
                jkr.contact.pull_off->P * 1e9, dmt * 1e9, md * 1e9, 100.0 * (jkr.contact.pull_off->P / md - 1.0));
    std::printf("  check: %s\n", jkr.adhesion->brief_report().c_str());
  }
}
