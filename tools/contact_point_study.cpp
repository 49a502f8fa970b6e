// How the fitted modulus moves with the contact-point method and the indentation range, on
// the bundled real approach curves (../shared/data/real, tip radii from reference_fits.json)
// and the Bruker NanoScope curve (../shared/data/instrument/bruker, a 35 degree 4-sided pyramid).
// Prints the Markdown table of docs/fitting.md:
//   build/bin/contact_point_study [shared-data-dir]
// Method fit frees E, delta0 and P0; the other methods free E only (delta0 and P0 fixed at the
// method's point and baseline), as a peer analysis with a preset contact point does.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
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

// Synthetic Hertz approaches (1000 samples over delta in [-1, 1] um, contact uniform in
// [-0.2, 0.2] um, Gaussian noise a fraction of the largest force): how far each method's point
// lies from the truth, against its stated uncertainty.
void synthetic_table() {
  std::printf("| method | noise / max force | bias [nm] | rms error [nm] | median uncertainty [nm] | |error| <= uncertainty | max |error| / uncertainty |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (ContactPointMethod m : {ContactPointMethod::threshold, ContactPointMethod::rov, ContactPointMethod::gof})
    for (double noise : {0.002, 0.01, 0.03}) {
      std::mt19937 rng(42);
      std::normal_distribution<double> g(0.0, 1.0);
      std::uniform_real_distribution<double> u(-2e-7, 2e-7);
      const int runs = 50, n = 1000;
      double bias = 0.0, sq = 0.0, worst = 0.0;
      int inside = 0;
      std::vector<double> unc;
      for (int k = 0; k < runs; ++k) {
        const double dc = u(rng);
        std::vector<double> d(n), P(n);
        const double top = std::pow(1e-6 - dc, 1.5);
        for (int i = 0; i < n; ++i) {
          d[i] = -1e-6 + 2e-6 * i / (n - 1);
          P[i] = (d[i] > dc ? std::pow(d[i] - dc, 1.5) : 0.0) + noise * top * g(rng);
        }
        const ContactPoint c = find_contact_point(d, P, m, 1.5);
        const double e = c.delta - dc;
        bias += e / runs;
        sq += e * e / runs;
        worst = std::max(worst, std::abs(e) / c.uncertainty);
        inside += std::abs(e) <= c.uncertainty ? 1 : 0;
        unc.push_back(c.uncertainty);
      }
      std::sort(unc.begin(), unc.end());
      std::printf("| %s | %.1f %% | %+.1f | %.1f | %.1f | %d / %d | %.1f |\n", to_string(m), noise * 100, bias * 1e9,
                  std::sqrt(sq) * 1e9, unc[unc.size() / 2] * 1e9, inside, runs, worst);
    }
  std::printf("\n");
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
      c.scene = parse_scene(R"({"indenter": {"shape": "pyramid", "semi_angle_deg": 35, "sides": 4},
          "medium": {"type": "half_space", "E": 3e3, "nu": 0.5}})");
      c.tip = "4-sided pyramid 35 deg";
      curves.push_back(std::move(c));
    }
  }
  synthetic_table();
  const std::vector<ContactPointMethod> methods{ContactPointMethod::fit, ContactPointMethod::threshold,
                                                ContactPointMethod::rov, ContactPointMethod::gof};
  // Each range keeps 0.5 um of baseline: without it, delta0 and P0 of method fit cannot be told
  // apart from E on a window all in contact (the fit says so: not identifiable).
  const std::vector<std::optional<Interval>> ranges{std::nullopt, Interval{-5e-7, 1e-7}, Interval{-5e-7, 3e-7},
                                                    Interval{-5e-7, 1e-6}};
  std::printf("| curve | tip | method | contact point [um] | +- [um] | E [Pa], all samples | -0.5 um to 100 nm | to 300 nm | to 1 um | kept (all / to 1 um) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Curve& c : curves) {
    // On the long JPK approaches the baseline drifts: the variants with a baseline window take
    // the 2 um that end 0.5 um before gof's point.
    const double span = *std::max_element(c.data.delta.begin(), c.data.delta.end()) -
                        *std::min_element(c.data.delta.begin(), c.data.delta.end());
    const double gof_point = find_contact_point(c.data.delta, c.data.P, ContactPointMethod::gof,
                                                1.0 + 1.0 / c.scene.profile->power_law_form()->d).delta;
    std::vector<std::pair<ContactPointMethod, std::optional<Interval>>> variants;
    for (ContactPointMethod m : methods) variants.emplace_back(m, std::nullopt);
    if (span > 5e-6)
      for (ContactPointMethod m : {ContactPointMethod::threshold, ContactPointMethod::rov})
        variants.emplace_back(m, Interval{gof_point - 2.5e-6, gof_point - 0.5e-6});
    for (const auto& [m, window] : variants) {
      std::string row = "| " + c.name + " | " + c.tip + " | " + to_string(m) + (window ? " + window" : "") + " | ";
      std::string kept;
      bool first = true;
      for (const auto& r : ranges) {
        FitOptions o;
        o.free = {FitParameter::E};
        if (m == ContactPointMethod::fit) o.free = {FitParameter::E, FitParameter::delta0, FitParameter::P0};
        o.branch = Branch::approach;
        o.contact_point = m;
        o.indentation_range = r;
        o.baseline_window = window;
        try {
          const FitSummary s = fit(c.data, c.scene, o);
          if (first) {
            char b[96];
            std::snprintf(b, sizeof b, "%.5g | %.2g | ", s.contact_point.value * 1e6, s.contact_point.standard_error * 1e6);
            row += b;
          }
          row += cell(s) + (s.converged ? "" : " (not converged)") + (s.identifiable ? "" : " (n.i.)") + " | ";
          if (first || r == ranges.back())
            kept += (kept.empty() ? "" : " / ") + std::to_string(s.contact_point.samples_in_range);
        } catch (const Error& e) {
          if (first) row += "- | - | ";
          row += "failed | ";
          std::fprintf(stderr, "%s, %s: %s\n", c.name.c_str(), to_string(m), e.what());
          if (first || r == ranges.back()) kept += (kept.empty() ? "" : " / ") + std::string("-");
        }
        first = false;
      }
      std::printf("%s%s |\n", row.c_str(), kept.c_str());
    }
  }
  return 0;
}
