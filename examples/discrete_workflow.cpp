// What this teaches: the paper's section 5 workflow on discrete data - JKR curves for a sample
// with no closed-form solution, from FEM-like flat-punch and convex-indenter runs - both ways:
// the two-model approach (S(a) from flat punches, differentiated once) and the single model
// (everything from the convex run, S' by differentiating twice), each with bootstrap error bars,
// against the truth the data came from.
//
// How the data is made: data/discrete/ (tools/make_discrete_data.cpp) - the exact bonded layer
// of the paper's Appendix A top layer (E = 3 MPa, nu = 0.3, h = 0.1 mm) under flat punches of
// radius 0.1 .. 0.6 mm and a 10 mm sphere, 20 substeps to 0.025 mm each, 0.3 % force noise, the
// sphere's contact radius read off a 5 um mesh. The truth is that exact layer, evaluated here.
//
// Run: build/bin/discrete_workflow [PLOT.png]   (the README's plot: docs/images/discrete_workflow.png)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

constexpr double kW = 0.2;  // work of adhesion [J/m^2]: puts the pull-off inside the data's radii

struct Reconstruction {
  const char* name;
  ContactModelPtr model;
  DiscreteApproach approach;
};

void write_plot(const std::string& png, const std::string& table) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::fprintf(stderr, "gnuplot not found: no plot\n");
    return;
  }
  const std::string gp_path = png + ".gp";
  std::ofstream gp(gp_path);
  gp << "set terminal pngcairo size 1200,480 font 'DejaVu Sans,11'\nset output '" << png << "'\n"
     << "set datafile separator ','\nset grid\nset key top left\n"
     << "set multiplot layout 1,2 title 'JKR from discrete data (exact layer, 0.3 % noise): reconstructions against the truth'\n"
     << "set xlabel 'approach delta [um]'\nset ylabel 'force P [mN]'\n"
     << "plot '" << table << "' u ($5*1e6):($4*1e3) w l lw 2 lc rgb 'black' t 'truth (exact layer)', "
     << "'' u ($7*1e6):($6*1e3):($9*1e3) w yerrorbars pt 7 ps 0.6 lc rgb '#1f77b4' t 'two models', "
     << "'' u ($11*1e6):($10*1e3):($13*1e3) w yerrorbars pt 5 ps 0.6 lc rgb '#d62728' t 'single model'\n"
     << "set xlabel 'contact radius a [mm]'\nset ylabel 'P - P_{true} [uN]'\nset key bottom left\n"
     << "plot '" << table << "' u ($1*1e3):(($6-$4)*1e6):($9*1e6) w yerrorbars pt 7 ps 0.6 lc rgb '#1f77b4' t 'two models (+- bootstrap std)', "
     << "'' u ($1*1e3):(($10-$4)*1e6):($13*1e6) w yerrorbars pt 5 ps 0.6 lc rgb '#d62728' t 'single model', 0 w l lc rgb 'black' notitle\n"
     << "unset multiplot\n";
  gp.close();
  const bool plotted = std::system(("gnuplot '" + gp_path + "'").c_str()) == 0;
  std::remove(gp_path.c_str());
  std::fprintf(stderr, plotted ? "wrote %s\n" : "gnuplot failed on %s\n", png.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string dir = LAYERJKR_SOURCE_DIR "/data/discrete/";
    const FlatPunchData flat = read_flat_punch_csv(dir + "flat_punch.csv");
    const ConvexData convex = read_convex_csv(dir + "convex.csv");
    const auto truth = make_exact_layer(make_sphere(10e-3), {3e6, 0.3, 0.1e-3, Base::bonded});
    const Reconstruction rows[] = {{"two models", make_discrete_model(flat, convex), DiscreteApproach::two_models},
                                   {"single model", make_single_model(convex), DiscreteApproach::single_model}};
    // Radii both reconstructions cover.
    const double lo = std::max(rows[0].model->min_radius(), rows[1].model->min_radius()) * 1.01;
    const double hi = std::min(rows[0].model->max_radius(), rows[1].model->max_radius()) * 0.99;
    std::vector<double> radii;
    for (int i = 0; i < 40; ++i) radii.push_back(lo + (hi - lo) * i / 39);

    const JkrSolution exact(truth, kW);
    const auto po_true = exact.pull_off();
    std::printf("JKR from discrete data, w = %g J/m^2, radii %.3f .. %.3f mm; truth pull-off %.6g N\n\n", kW, lo * 1e3,
                hi * 1e3, po_true->P);
    std::printf("%-13s %12s %12s %14s %12s %12s\n", "approach", "max|dP|/Pmax", "max|dd|/dmax", "pull-off [N]", "error", "bootstrap");
    std::vector<std::vector<AdhesiveState>> curves;
    std::vector<DiscreteUncertainty> errors;
    for (const Reconstruction& r : rows) {
      const JkrSolution jkr(r.model, kW);
      curves.push_back(jkr.curve(radii));
      errors.push_back(bootstrap_discrete(flat, convex, kW, radii, r.approach));
      double dP = 0, dd = 0, Pmax = 0, dmax = 0;
      for (std::size_t k = 0; k < radii.size(); ++k) {
        const AdhesiveState t = exact.at(radii[k]), &s = curves.back()[k];
        dP = std::max(dP, std::abs(s.P - t.P)), Pmax = std::max(Pmax, std::abs(t.P));
        dd = std::max(dd, std::abs(s.delta - t.delta)), dmax = std::max(dmax, std::abs(t.delta));
      }
      const auto po = jkr.pull_off();
      std::printf("%-13s %11.3f%% %11.3f%% %14.6g %+11.3f%% %11.3f%%\n", r.name, 100 * dP / Pmax, 100 * dd / dmax, po->P,
                  100 * (po->P / po_true->P - 1), 100 * std::abs(errors.back().pull_off_force_err / po_true->P));
      std::fflush(stdout);
    }
    if (argc > 1) {
      const std::string table = std::string(argv[1]) + ".csv";
      std::ofstream out(table);
      for (std::size_t k = 0; k < radii.size(); ++k) {
        const AdhesiveState t = exact.at(radii[k]);
        out << radii[k] << ",0,0," << t.P << "," << t.delta;
        for (std::size_t r = 0; r < 2; ++r)
          out << "," << curves[r][k].P << "," << curves[r][k].delta << ",0," << errors[r].P_err[k];
        out << "\n";
      }
      out.close();
      write_plot(argv[1], table);
      std::remove(table.c_str());
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "discrete_workflow: %s\n", e.what());
    return 1;
  }
  return 0;
}
