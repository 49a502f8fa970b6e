// What this teaches: what each thin-layer model costs and how wrong it is, measured
// against the exact layer solver - the numbers behind docs/models.md, "which model do I need".
//
// How the data is made: nothing is measured in a lab. A rigid paraboloid with R = 100 h
// (the paper's Appendix A ratio) indents a layer (E = 1, h = 1: the errors are
// dimensionless) for nu in {0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45, 0.49, 0.5} on a bonded and a
// frictionless base. At each a/h the non-adhesive P_H and delta_H of every applicable
// model are compared with the exact solver's (accurate to < 1e-8). For adhesion, w is set so that
// the Winkler pull-off radius is the target a/h (w = K a^4 / (8 R^2)), and each model's
// pull-off force is compared with the exact one (targets a/h <= 20: the exact search
// costs ~150 solves). Costs are medians of repeated wall-clock timings on this machine.
//
// Run: build/bin/model_tradeoff TABLE_FILE [DOCS_DIR PLOT_PNG]   (a few minutes on 2 cores)
// Writes TABLE_FILE, the worst measured error per model, base, nu and a/h, which
// "model": "auto" uses (committed as src/models/model_error_table.inc), and, given
// DOCS_DIR, the timed study: model_tradeoff.csv, model_tradeoff_pulloff.csv and, with
// gnuplot, model_tradeoff.png. `cmake --build build --target regenerate_model_tradeoff`
// rewrites both committed copies; the test generated_model_error_table fails when the
// committed table is stale.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

template <class F>
double median_seconds(F f, int repeats, int inner) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < inner; ++i) f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / inner);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

struct Named {
  std::string name;
  ContactModelPtr model;
};

// The asymptotic models that apply to this layer (none at nu = 0.5).
std::vector<Named> asymptotic_models(const ProfilePtr& p, const ElasticLayer& layer) {
  if (layer.nu >= 0.5) return {};
  const ThinLayerConstants c = thin_layer_constants(layer);
  std::vector<Named> out{{"winkler", make_winkler(p, c.K)},
                         {"edge_corrected", make_edge_corrected(p, layer)}};
  if (c.G != 0.0) out.push_back({"two_term", make_two_term(p, c.K, c.G)});
  if (c.G > 0.0) out.push_back({"full_foundation", make_full_foundation(p, c.K, c.G)});
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 4) {
    std::fprintf(stderr, "usage: model_tradeoff TABLE_FILE [DOCS_DIR PLOT_PNG]\n");
    return 2;
  }
  const std::string table_path = argv[1];
  const bool study = argc == 4;  // the timed study for docs/, beside the table
  const std::string dir = study ? argv[2] : "", png = study ? argv[3] : "";
  const double h = 1.0, R = 100.0;
  const auto paraboloid = make_paraboloid(R);
  const std::vector<double> nus{0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45, 0.49, 0.5};
  const std::vector<double> ratios{0.5, 1, 2, 4, 5, 10, 20, 50, 100};
  const std::vector<double> pulloff_ratios{0.5, 1, 2, 5, 10, 20};

  // Without DOCS_DIR the study streams go nowhere: only the error table is written.
  std::ofstream csv, pcsv;
  if (study) {
    csv.open(dir + "/model_tradeoff.csv");
    pcsv.open(dir + "/model_tradeoff_pulloff.csv");
  }
  csv << "nu,base,a_over_h,model,P_rel_err,delta_rel_err,seconds_per_point\n";
  pcsv << "nu,base,a_over_h_target,model,pull_off_rel_err,pull_off_force,pull_off_a_over_h\n";
  csv.precision(6);
  pcsv.precision(6);

  // Worst of |P_H|, |delta_H| and pull-off error per (base, nu, a/h, model).
  std::map<std::tuple<int, double, double, std::string>, double> worst;
  auto record = [&](int base, double nu, double r, const std::string& m, double e) {
    double& slot = worst[{base, nu, r, m}];
    slot = std::max(slot, std::abs(e));
  };

  std::printf("relative error against the exact layer, %%, at a/h = 0.5 1 2 4 5 10 20 50 100\n");
  std::printf("%-5s %-12s %-16s %-2s\n", "nu", "base", "model", "of");
  for (Base base : {Base::bonded, Base::frictionless}) {
    const char* base_name = base == Base::bonded ? "bonded" : "frictionless";
    for (double nu : nus) {
      const ElasticLayer layer{1.0, nu, h, base};
      ExactLayerOptions options;
      options.estimate_error = false;
      const auto exact = make_exact_layer(paraboloid, layer, options);
      const auto models = asymptotic_models(paraboloid, layer);
      std::vector<std::string> rows(2 * models.size());
      for (std::size_t m = 0; m < models.size(); ++m) {
        char head[64];
        std::snprintf(head, sizeof head, "%-5.2f %-12s %-16s P ", nu, base_name, models[m].name.c_str());
        rows[2 * m] = head;
        std::snprintf(head, sizeof head, "%-5s %-12s %-16s d ", "", "", "");
        rows[2 * m + 1] = head;
      }
      for (double r : ratios) {
        const double a = r * h;
        const HertzState e = exact->state(a);
        const double t_exact = study ? median_seconds([&] { (void)exact->state(a); }, 3, 1) : 0.0;
        csv << nu << ',' << base_name << ',' << r << ",exact,0,0," << t_exact << '\n';
        for (std::size_t m = 0; m < models.size(); ++m) {
          if (!(a > models[m].model->min_radius())) {  // edge_corrected with a + beta h <= 0
            rows[2 * m] += "     n/a";
            rows[2 * m + 1] += "     n/a";
            continue;
          }
          const HertzState s = models[m].model->state(a);
          const double eP = s.P_H / e.P_H - 1, ed = s.delta_H / e.delta_H - 1;
          const double t = study ? median_seconds([&] { (void)models[m].model->state(a); }, 5, 2000) : 0.0;
          csv << nu << ',' << base_name << ',' << r << ',' << models[m].name << ',' << eP << ','
              << ed << ',' << t << '\n';
          record(base == Base::bonded, nu, r, models[m].name, std::max(std::abs(eP), std::abs(ed)));
          char cell[16];
          std::snprintf(cell, sizeof cell, " %+7.2f", 100 * eP);
          rows[2 * m] += cell;
          std::snprintf(cell, sizeof cell, " %+7.2f", 100 * ed);
          rows[2 * m + 1] += cell;
        }
      }
      for (const auto& row : rows) std::printf("%s\n", row.c_str());
      if (models.empty()) std::printf("%-5.2f %-12s (no asymptotic model: exact only)\n", nu, base_name);

      // Adhesion: pull-off forces against the exact layer's.
      if (models.empty()) continue;
      const double K = thin_layer_constants(layer).K;
      for (double r : pulloff_ratios) {
        const double w = K * std::pow(r * h, 4) / (8 * R * R);
        const auto po_exact = JkrSolution(exact, w).pull_off();
        if (!po_exact) continue;
        pcsv << nu << ',' << base_name << ',' << r << ",exact,0," << po_exact->P << ','
             << po_exact->a / h << '\n';
        for (const auto& m : models) {
          const auto po = JkrSolution(m.model, w).pull_off();
          if (!po) continue;
          pcsv << nu << ',' << base_name << ',' << r << ',' << m.name << ','
               << po->P / po_exact->P - 1 << ',' << po->P << ',' << po->a / h << '\n';
          record(base == Base::bonded, nu, r, m.name, po->P / po_exact->P - 1);
        }
      }
    }
  }
  csv.close();
  pcsv.close();
  std::ofstream inc(table_path);
  inc << "// Generated by tools/model_tradeoff.cpp (target regenerate_model_tradeoff): the\n"
         "// worst measured relative error of P_H, delta_H and pull-off force against the exact\n"
         "// layer (paraboloid, R = 100 h).\n"
         "// {bonded, nu, a/h, model, error}\n";
  for (const auto& [key, err] : worst) {
    char line[128];
    std::snprintf(line, sizeof line, "{%d, %.2f, %g, ModelKind::%s, %.4g},\n", std::get<0>(key),
                  std::get<1>(key), std::get<2>(key), std::get<3>(key).c_str(), err);
    inc << line;
  }
  inc.close();
  if (!inc) {
    std::fprintf(stderr, "model_tradeoff: cannot write %s\n", table_path.c_str());
    return 1;
  }
  std::fprintf(stderr, "wrote %s\n", table_path.c_str());
  if (!study) return 0;
  std::fprintf(stderr, "wrote %s/model_tradeoff.csv and %s/model_tradeoff_pulloff.csv\n", dir.c_str(),
              dir.c_str());

  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string gp_path = png + ".gp", data = dir + "/model_tradeoff.csv";
    std::ofstream gp(gp_path);
    gp << "set terminal pngcairo size 1200,520 font 'DejaVu Sans,11'\n"
       << "set output '" << png << "'\nset datafile separator ','\n"
       << "set logscale xy\nset grid\nset xlabel 'a/h'\nset ylabel '|relative error of P_H|'\n"
       << "set yrange [1e-6:2]\nset format y '10^{%L}'\nset key bottom left font ',9'\n"
       << "set multiplot layout 1,2 title 'Thin-layer models against the exact layer "
          "(paraboloid, R = 100 h)'\n";
    // column 5: P error, column 6: delta error
    auto series = [&](int column, const char* base, const char* model, double nu,
                      const char* style, const char* title) {
      char s[512];
      std::snprintf(s, sizeof s,
                    "'%s' u ((stringcolumn(2) eq '%s' && stringcolumn(4) eq '%s' && "
                    "abs($1-%g) < 1e-9) ? $3 : 1/0):(abs($%d)) w p %s t '%s'",
                    data.c_str(), base, model, nu, column, style, title);
      return std::string(s);
    };
    gp << "set title 'force P_H'\nplot "
       << series(5, "bonded", "winkler", 0.3, "ps 1.5 lc rgb '#1f77b4' pt 7", "Winkler = two-term, bonded, nu = 0.3") << ", \\\n "
       << series(5, "bonded", "winkler", 0.45, "ps 1.5 lc rgb '#9467bd' pt 6", "Winkler = two-term, bonded, nu = 0.45") << ", \\\n "
       << series(5, "frictionless", "winkler", 0.3, "ps 1.5 lc rgb '#ff7f0e' pt 9", "Winkler, frictionless, any nu") << ", \\\n "
       << series(5, "bonded", "full_foundation", 0.2, "ps 1.5 lc rgb '#2ca02c' pt 5", "full foundation, bonded, nu = 0.2") << ", \\\n "
       << series(5, "bonded", "edge_corrected", 0.3, "ps 1.5 lc rgb '#8c564b' pt 13", "edge-corrected, bonded, nu = 0.3") << "\n"
       << "set title 'approach delta_H'\nset ylabel '|relative error of delta_H|'\nplot "
       << series(6, "bonded", "winkler", 0.3, "ps 1.5 lc rgb '#1f77b4' pt 7", "Winkler, bonded, nu = 0.3") << ", \\\n "
       << series(6, "bonded", "two_term", 0.3, "ps 1.5 lc rgb '#d62728' pt 5", "two-term, bonded, nu = 0.3") << ", \\\n "
       << series(6, "bonded", "two_term", 0.45, "ps 1.5 lc rgb '#9467bd' pt 4", "two-term, bonded, nu = 0.45") << ", \\\n "
       << series(6, "bonded", "full_foundation", 0.2, "ps 1.5 lc rgb '#2ca02c' pt 5", "full foundation, bonded, nu = 0.2") << ", \\\n "
       << series(6, "bonded", "edge_corrected", 0.3, "ps 1.5 lc rgb '#8c564b' pt 13", "edge-corrected, bonded, nu = 0.3") << "\n"
       << "unset multiplot\n";
    gp.close();
    const bool plotted = std::system(("gnuplot '" + gp_path + "'").c_str()) == 0;
    std::remove(gp_path.c_str());
    if (plotted) std::fprintf(stderr, "wrote %s\n", png.c_str());
  }
  return 0;
}
