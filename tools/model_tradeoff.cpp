// What this teaches: what each thin-layer model costs and how wrong it is, measured
// against the exact layer solver - the numbers behind docs/models.md, "which model do I
// need" - and how the bottom-effect corrections experimentalists use today (Dimitriadis et
// al. 2002, Garcia & Garcia 2018, as AtomicJ and PyFMRheo implement them) compare.
//
// How the data is made: nothing is measured in a lab. A rigid paraboloid with R = 100 h
// (the paper's Appendix A ratio) indents a layer (E = 1, h = 1: the errors are
// dimensionless) for nu in {0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45, 0.49, 0.5} on a bonded and a
// frictionless base. At each a/h the non-adhesive P_H and delta_H of every model "auto"
// may choose (layer_model_candidates) are compared with the exact solver's. For adhesion, w
// is set so that the Winkler pull-off radius is the target a/h (w = K a^4 / (8 R^2); at
// nu = 1/2 the same w as at 0.49), and each model's pull-off force is compared with the
// exact one. The peers' corrections give a force at a given indentation, so they and the
// library's models are compared at the exact layer's delta_H (P(delta) error), for the
// paraboloid and for a cone of half-opening angle 35 degrees, at nu = 0.45, 0.49 and 0.5
// (the corrections carry nu = 1/2 coefficients; the Hertz/Sneddon prefactor uses the
// layer's E*). Costs are medians of repeated wall-clock timings on this machine.
//
// Run: build/bin/model_tradeoff DOCS_DIR PLOT_PNG   (a few minutes on 2 cores)
// Prints the error table; writes DOCS_DIR/model_tradeoff.csv, model_tradeoff_pulloff.csv,
// model_tradeoff_peers.csv and, with gnuplot, PLOT_PNG.
// `cmake --build build --target regenerate_model_tradeoff` rewrites the committed copies.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
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

// The reduced models "auto" may choose for this layer, cheapest first.
std::vector<Named> reduced_models(const ProfilePtr& p, const ElasticLayer& layer) {
  std::vector<Named> out;
  for (ModelKind kind : layer_model_candidates(layer))
    out.push_back({to_string(kind), make_contact_model(p, layer_model_spec(kind, layer))});
  return out;
}

// The peers' bottom-effect corrections: the factor multiplying Hertz (paraboloid, chi =
// sqrt(R delta)/h) or Sneddon (cone, chi = delta tan(theta)/h), nu = 1/2 coefficients.
struct Peer {
  const char* name;
  bool bonded;
  bool cone;
  double c[4];
};
const Peer kPeers[] = {
    {"dimitriadis_bonded", true, false, {1.133, 1.283, 0.769, 0.0975}},       // eq. (12)
    {"dimitriadis_nonbonded", false, false, {0.884, 0.781, 0.386, 0.0048}},   // eq. (11)
    {"garcia_paraboloid", true, false, {1.133, 1.497, 1.469, 0.755}},
    {"garcia_cone", true, true, {0.721, 0.650, 0.491, 0.225}},
};

double peer_force(const Peer& peer, double E_star, const Profile& p, double delta, double h) {
  double chi = 0.0, base = 0.0;
  if (peer.cone) {
    const double tan_theta = 1.0 / p.power_law_form()->B;  // f = r / tan(theta)
    chi = delta * tan_theta / h;
    base = 2.0 / M_PI * E_star * tan_theta * delta * delta;
  } else {
    const double R = 0.5 / p.power_law_form()->B;  // f = r^2 / (2R)
    chi = std::sqrt(R * delta) / h;
    base = 4.0 / 3.0 * E_star * std::sqrt(R) * std::pow(delta, 1.5);
  }
  double factor = 1.0, power = 1.0;
  for (double c : peer.c) factor += c * (power *= chi);
  return base * factor;
}

// The peers' study: P(delta) error of each correction and of the library's models at the
// exact layer's delta_H, for a paraboloid and a cone, nu = 0.45, 0.49, 0.5.
void peers_study(std::ostream& csv) {
  csv << "profile,nu,base,a_over_h,chi,model,P_at_delta_rel_err\n";
  const std::vector<double> ratios{0.5, 1, 2, 5, 10, 20, 50, 100};
  std::printf("\nP(delta) error against the exact layer, %%, at a/h = 0.5 1 2 5 10 20 50 100\n");
  for (bool cone : {false, true}) {
    const ProfilePtr p = cone ? make_cone(35.0 * M_PI / 180.0) : make_paraboloid(100.0);
    for (Base base : {Base::bonded, Base::frictionless}) {
      for (double nu : {0.45, 0.49, 0.5}) {
        const ElasticLayer layer{1.0, nu, 1.0, base};
        const double E_star = effective_modulus(layer.E, nu);
        const auto exact = make_exact_layer(p, layer);
        std::vector<std::pair<std::string, std::function<double(double)>>> laws;
        for (const Peer& peer : kPeers)
          if (peer.cone == cone && peer.bonded == (base == Base::bonded))
            laws.push_back({peer.name, [&, peer](double d) { return peer_force(peer, E_star, *p, d, layer.h); }});
        for (const Named& m : reduced_models(p, layer))
          if (m.name == "uniform" || m.name == "incompressible" || m.name == "edge_corrected")
            laws.push_back({m.name, [model = m.model](double d) { return JkrSolution(model, 0.0).force_at_delta(d); }});
        for (const auto& [name, force] : laws) {
          std::printf("%-10s %-5.2f %-12s %-22s", cone ? "cone 35deg" : "paraboloid", nu,
                      base == Base::bonded ? "bonded" : "frictionless", name.c_str());
          for (double r : ratios) {
            const NonAdhesiveState e = exact->state(r * layer.h);
            double err = NAN;
            try {
              err = force(e.delta_H) / e.P_H - 1.0;
            } catch (const Error&) {  // e.g. edge_corrected below -beta h
            }
            const double chi = cone ? e.delta_H / p->power_law_form()->B / layer.h
                                    : std::sqrt(0.5 / p->power_law_form()->B * e.delta_H) / layer.h;
            csv << (cone ? "cone35" : "paraboloid") << ',' << nu << ',' << (base == Base::bonded ? "bonded" : "frictionless")
                << ',' << r << ',' << chi << ',' << name << ',' << err << '\n';
            std::printf(" %+8.2f", 100 * err);
          }
          std::printf("\n");
        }
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: model_tradeoff DOCS_DIR PLOT_PNG\n");
    return 2;
  }
  const std::string dir = argv[1], png = argv[2];
  const double h = 1.0, R = 100.0;
  const auto paraboloid = make_paraboloid(R);
  const std::vector<double> nus{0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45, 0.49, 0.5};
  const std::vector<double> ratios{0.5, 1, 2, 4, 5, 10, 20, 50, 100};
  const std::vector<double> pulloff_ratios{0.5, 1, 2, 5, 10, 20};

  std::ofstream csv(dir + "/model_tradeoff.csv"), pcsv(dir + "/model_tradeoff_pulloff.csv"),
      peers(dir + "/model_tradeoff_peers.csv");
  csv << "nu,base,a_over_h,model,P_rel_err,delta_rel_err,seconds_per_point\n";
  pcsv << "nu,base,a_over_h_target,model,pull_off_rel_err,pull_off_force,pull_off_a_over_h\n";
  csv.precision(6);
  pcsv.precision(6);
  peers.precision(6);

  std::printf("relative error against the exact layer, %%, at a/h = 0.5 1 2 4 5 10 20 50 100\n");
  std::printf("%-5s %-12s %-16s %-2s\n", "nu", "base", "model", "of");
  for (Base base : {Base::bonded, Base::frictionless}) {
    const char* base_name = base == Base::bonded ? "bonded" : "frictionless";
    for (double nu : nus) {
      const ElasticLayer layer{1.0, nu, h, base};
      ExactLayerOptions options;
      options.estimate_error = false;
      const auto exact = make_exact_layer(paraboloid, layer, options);
      const auto models = reduced_models(paraboloid, layer);
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
        const NonAdhesiveState e = exact->state(a);
        const double t_exact = median_seconds([&] { (void)exact->state(a); }, 3, 1);
        csv << nu << ',' << base_name << ',' << r << ",exact,0,0," << t_exact << '\n';
        for (std::size_t m = 0; m < models.size(); ++m) {
          if (!(a > models[m].model->min_radius())) {  // edge_corrected with a + beta h <= 0
            rows[2 * m] += "     n/a";
            rows[2 * m + 1] += "     n/a";
            continue;
          }
          const NonAdhesiveState s = models[m].model->state(a);
          const double eP = s.P_H / e.P_H - 1, ed = s.delta_H / e.delta_H - 1;
          const double t = median_seconds([&] { (void)models[m].model->state(a); }, 5, 200);
          csv << nu << ',' << base_name << ',' << r << ',' << models[m].name << ',' << eP << ','
              << ed << ',' << t << '\n';
          char cell[16];
          std::snprintf(cell, sizeof cell, " %+7.2f", 100 * eP);
          rows[2 * m] += cell;
          std::snprintf(cell, sizeof cell, " %+7.2f", 100 * ed);
          rows[2 * m + 1] += cell;
        }
      }
      for (const auto& row : rows) std::printf("%s\n", row.c_str());
      if (models.empty()) std::printf("%-5.2f %-12s (no reduced model: exact only)\n", nu, base_name);

      // Adhesion: pull-off forces against the exact layer's.
      if (models.empty()) continue;
      const double K = thin_layer_constants({layer.E, std::min(nu, 0.49), h, base}).K;
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
        }
      }
    }
  }
  peers_study(peers);
  csv.close();
  pcsv.close();
  peers.close();
  if (!csv || !pcsv || !peers) {
    std::fprintf(stderr, "model_tradeoff: cannot write to %s\n", dir.c_str());
    return 1;
  }
  std::fprintf(stderr, "wrote %s/model_tradeoff.csv, model_tradeoff_pulloff.csv and model_tradeoff_peers.csv\n",
               dir.c_str());

  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string gp_path = png + ".gp", data = dir + "/model_tradeoff.csv";
    std::ofstream gp(gp_path);
    const std::string peers_data = dir + "/model_tradeoff_peers.csv";
    gp << "set terminal pngcairo size 1300,540 font 'DejaVu Sans,11'\n"
       << "set output '" << png << "'\nset datafile separator ','\n"
       << "set logscale xy\nset grid\nset xlabel 'a/h'\n"
       << "set yrange [1e-6:5]\nset format y '10^{%L}'\nset key bottom left font ',9'\n"
       << "set multiplot layout 1,2 title \"Against the exact layer: the library's reduced models (left, paraboloid R = 100 h) "
          "and the peers' bottom-effect corrections (right, bonded nu = 1/2)\"\n";
    // column 5: P error
    auto series = [&](const char* base, const char* model, double nu, const char* style, const char* title) {
      char s[512];
      std::snprintf(s, sizeof s,
                    "'%s' u ((stringcolumn(2) eq '%s' && stringcolumn(4) eq '%s' && "
                    "abs($1-%g) < 1e-9) ? $3 : 1/0):(abs($5)) w lp %s t '%s'",
                    data.c_str(), base, model, nu, style, title);
      return std::string(s);
    };
    auto peer = [&](const char* profile, const char* model, const char* style, const char* title) {
      char s[512];
      std::snprintf(s, sizeof s,
                    "'%s' u ((stringcolumn(1) eq '%s' && stringcolumn(3) eq 'bonded' && stringcolumn(6) eq '%s' && "
                    "abs($2-0.5) < 1e-9) ? $4 : 1/0):(abs($7)) w lp %s t '%s'",
                    peers_data.c_str(), profile, model, style, title);
      return std::string(s);
    };
    gp << "set title 'force P_H at the same a'\nset ylabel '|relative error of P_H|'\nplot "
       << series("bonded", "winkler", 0.3, "ps 1.2 lc rgb '#1f77b4' pt 7", "Winkler, nu = 0.3") << ", \\\n "
       << series("bonded", "edge_corrected", 0.3, "ps 1.2 lc rgb '#8c564b' pt 13", "edge-corrected, nu = 0.3") << ", \\\n "
       << series("bonded", "full_foundation", 0.2, "ps 1.2 lc rgb '#2ca02c' pt 5", "full foundation, nu = 0.2") << ", \\\n "
       << series("bonded", "winkler", 0.45, "ps 1.2 lc rgb '#9467bd' pt 6", "Winkler, nu = 0.45") << ", \\\n "
       << series("bonded", "uniform", 0.45, "ps 1.2 lc rgb '#e377c2' pt 9", "uniform, nu = 0.45") << ", \\\n "
       << series("bonded", "uniform", 0.49, "ps 1.2 lc rgb '#d62728' pt 11", "uniform, nu = 0.49") << ", \\\n "
       << series("bonded", "incompressible", 0.5, "ps 1.2 lc rgb '#7f7f7f' pt 4", "incompressible, nu = 0.5") << ", \\\n "
       << series("bonded", "uniform", 0.5, "ps 1.2 lc rgb '#17becf' pt 8", "uniform, nu = 0.5") << "\n"
       << "set title 'force at the same indentation, P(delta)'\nset ylabel '|relative error of P(delta)|'\nplot "
       << peer("paraboloid", "dimitriadis_bonded", "ps 1.2 lc rgb '#ff7f0e' pt 7 dt 2", "Dimitriadis 2002 (sphere)") << ", \\\n "
       << peer("paraboloid", "garcia_paraboloid", "ps 1.2 lc rgb '#bcbd22' pt 5 dt 2", "Garcia 2018 (sphere)") << ", \\\n "
       << peer("paraboloid", "uniform", "ps 1.2 lc rgb '#17becf' pt 8", "uniform (sphere)") << ", \\\n "
       << peer("cone35", "garcia_cone", "ps 1.2 lc rgb '#8c564b' pt 13 dt 2", "Garcia 2018 (cone 35 deg)") << ", \\\n "
       << peer("cone35", "uniform", "ps 1.2 lc rgb '#d62728' pt 11", "uniform (cone 35 deg)") << "\n"
       << "unset multiplot\n";
    gp.close();
    const bool plotted = std::system(("gnuplot '" + gp_path + "'").c_str()) == 0;
    std::remove(gp_path.c_str());
    if (plotted) std::fprintf(stderr, "wrote %s\n", png.c_str());
  }
  return 0;
}
