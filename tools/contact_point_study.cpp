// How the fitted modulus moves with the contact-point method and the indentation range, on
// the bundled real approach curves (../shared/data/real, tip radii from reference_fits.json)
// and the Bruker NanoScope curve (../shared/data/instrument/bruker, a 35 degree cone).
// Prints the Markdown table of docs/fitting.md:
//   build/bin/contact_point_study [shared-data-dir]
// Method fit frees E, delta0 and P0; the other methods free E only (delta0 and P0 fixed at the
// method's point and baseline), as a peer analysis with a preset contact point does.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

struct Curve {
  std::string name;
  CurveData data;
  Scene scene;
  std::string tip;
};

std::string cell(const FitSummary& s) {
  char b[96];
  std::snprintf(b, sizeof b, "%.4g", s[FitParameter::E].value);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string shared = argc > 1 ? argv[1] : std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data";
  std::vector<Curve> curves;
  std::ifstream ref_file(shared + "/real/reference_fits.json");
  if (!ref_file) {
    std::fprintf(stderr, "contact_point_study: %s/real/reference_fits.json is absent\n", shared.c_str());
    return 1;
  }
  const nlohmann::json refs = nlohmann::json::parse(ref_file);
  std::vector<std::string> seen;
  for (const auto& f : refs) {
    const std::string csv = f["data_csv"].get<std::string>();
    if (std::find(seen.begin(), seen.end(), csv) != seen.end()) continue;
    seen.push_back(csv);
    Curve c;
    c.name = csv.substr(0, csv.size() - 4);
    c.data = read_curve_csv(shared + "/real/" + csv);
    c.data.segment.assign(c.data.size(), 0);  // an approach export: every sample is approach
    c.scene = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
        "medium": {"type": "half_space", "E": 3e3, "nu": 0.5}})");
    c.scene.profile = make_paraboloid(f["R"].get<double>());
    c.scene.medium.nu = f["nu"].get<double>();
    char b[64];
    std::snprintf(b, sizeof b, "paraboloid R = %g um", f["R"].get<double>() * 1e6);
    c.tip = b;
    curves.push_back(std::move(c));
  }
  {
    const std::string spm = shared + "/instrument/bruker/20200904_Egel4-Z1.0_00025.spm";
    if (std::ifstream(spm).good()) {
      const InstrumentFile file = read_instrument_file(spm);
      Curve c;
      c.name = "bruker_Egel4-Z1.0_00025";
      c.data = to_curve_data(file.curves.at(0), spm);
      c.scene = parse_scene(R"({"indenter": {"shape": "cone", "semi_angle_deg": 35},
          "medium": {"type": "half_space", "E": 3e3, "nu": 0.5}})");
      c.tip = "cone 35 deg";
      curves.push_back(std::move(c));
    }
  }
  const std::vector<ContactPointMethod> methods{ContactPointMethod::fit, ContactPointMethod::threshold,
                                                ContactPointMethod::rov, ContactPointMethod::gof};
  const std::vector<std::optional<Interval>> ranges{std::nullopt, Interval{0.0, 1e-7}, Interval{0.0, 3e-7},
                                                    Interval{0.0, 1e-6}};
  std::printf("| curve | tip | method | contact point [um] | +- [um] | E [Pa], all samples | 0-100 nm | 0-300 nm | 0-1 um | kept (all / 0-1 um) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Curve& c : curves) {
    for (ContactPointMethod m : methods) {
      std::string row = "| " + c.name + " | " + c.tip + " | " + to_string(m) + " | ";
      std::string kept;
      bool first = true;
      for (const auto& r : ranges) {
        FitOptions o;
        o.free = {FitParameter::E};
        if (m == ContactPointMethod::fit) o.free = {FitParameter::E, FitParameter::delta0, FitParameter::P0};
        o.branch = Branch::approach;
        o.contact_point = m;
        o.indentation_range = r;
        try {
          const FitSummary s = fit(c.data, c.scene, o);
          if (first) {
            char b[96];
            std::snprintf(b, sizeof b, "%.5g | %.2g | ", s.contact_point.value * 1e6, s.contact_point.standard_error * 1e6);
            row += b;
          }
          row += cell(s) + (s.converged ? "" : " (not converged)") + " | ";
          if (first || r == ranges.back())
            kept += (kept.empty() ? "" : " / ") + std::to_string(s.contact_point.samples_in_range);
        } catch (const Error& e) {
          if (first) row += "- | - | ";
          row += std::string("failed: ") + e.what() + " | ";
          if (first || r == ranges.back()) kept += (kept.empty() ? "" : " / ") + std::string("-");
        }
        first = false;
      }
      std::printf("%s%s |\n", row.c_str(), kept.c_str());
    }
  }
  return 0;
}
