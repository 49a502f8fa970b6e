// What this teaches: the paper's section 4 in code - a rigid sphere on a thin bonded
// layer, non-adhesive and adhesive (JKR) curves at leading order (Winkler, eq. 41/42)
// and two-term order (eqs. 43-51, force corrected), all through the one generic
// transform (19).
//
// How the data is made: no measurement. The layer is the paper's Appendix A top
// layer (E = 3 MPa, nu = 0.3, h = 0.1 mm, bonded), the indenter an exact sphere of
// R = 10 mm, and w = 0.05 J/m^2 (PDMS on glass is 0.04-0.06). The program samples
// a in (0, 1 mm] on an even grid, writes section4_curves.csv, and - if gnuplot is on
// the PATH - section4_curves.png (docs/images/ has the committed copy).
//
// Run: build/bin/paper_section4_curves [OUTPUT_DIR]
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "layerjkr/layerjkr.hpp"

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  const double R = 10e-3, w = 0.05;
  const layerjkr::ElasticLayer film{3e6, 0.3, 0.1e-3, layerjkr::Base::bonded};
  const layerjkr::ThinLayerConstants c = layerjkr::thin_layer_constants(film);
  const auto sphere = layerjkr::make_sphere(R);
  const auto leading = layerjkr::make_winkler(sphere, c.K);
  const auto two_term = layerjkr::make_two_term(sphere, c.K, c.G);
  const layerjkr::JkrSolution leading_jkr(leading, w), two_term_jkr(two_term, w);

  std::ofstream csv(dir + "/section4_curves.csv");
  csv << "a,delta_leading,P_leading,delta_two_term,P_two_term,"
         "delta_leading_jkr,P_leading_jkr,delta_two_term_jkr,P_two_term_jkr\n";
  csv.precision(17);
  const int n = 200;
  for (int i = 1; i <= n; ++i) {
    const double a = 1e-3 * i / n;
    const auto l = leading_jkr.at(a), t = two_term_jkr.at(a);
    csv << a << ',' << l.hertz.delta_H << ',' << l.hertz.P_H << ',' << t.hertz.delta_H << ','
        << t.hertz.P_H << ',' << l.delta << ',' << l.P << ',' << t.delta << ',' << t.P << '\n';
  }
  csv.close();

  std::cout << "Sphere R = 10 mm on a bonded layer E = 3 MPa, nu = 0.3, h = 0.1 mm; w = 0.05 J/m^2\n"
            << "K = " << c.K << " N/m^3, G = " << c.G << " N/m (G < 0 for nu > 1/4)\n\n"
            << "                       leading (Winkler)    two-term       -2 pi w R\n";
  const auto pl = leading_jkr.pull_off(), pt = two_term_jkr.pull_off();
  std::printf("pull-off force [mN]   %14.6f  %14.6f  %14.6f\n", 1e3 * pl->P, 1e3 * pt->P,
              -2e3 * 3.141592653589793 * w * R);
  std::printf("pull-off radius [um]  %14.6f  %14.6f\n", 1e6 * pl->a, 1e6 * pt->a);
  std::printf("pull-off delta [um]   %14.6f  %14.6f\n", 1e6 * pl->delta, 1e6 * pt->delta);
  std::printf("zero-load radius [um] %14.6f  %14.6f\n", 1e6 * *leading_jkr.zero_load_radius(),
              1e6 * *two_term_jkr.zero_load_radius());
  std::cout << "\nwrote " << dir << "/section4_curves.csv\n";

  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string script = dir + "/section4_curves.gp";
    std::ofstream gp(script);
    const std::string data = "'" + dir + "/section4_curves.csv' skip 1";
    const std::string curves =
        data + " u ($2*1e6):($3*1e3) w l lw 2 dt 2 lc rgb '#1f77b4' t 'leading, w = 0', \\\n"
        "  '' skip 1 u ($4*1e6):($5*1e3) w l lw 2 dt 2 lc rgb '#d62728' t 'two-term, w = 0', \\\n"
        "  '' skip 1 u ($6*1e6):($7*1e3) w l lw 2 lc rgb '#1f77b4' t 'leading, w = 0.05 J/m^2', \\\n"
        "  '' skip 1 u ($8*1e6):($9*1e3) w l lw 2 lc rgb '#d62728' t 'two-term, w = 0.05 J/m^2'\n";
    gp << "set terminal pngcairo size 1200,520 font 'DejaVu Sans,11'\n"
       << "set output '" << dir << "/section4_curves.png'\n"
       << "set datafile separator ','\nset grid\nset xzeroaxis lt -1\nset yzeroaxis lt -1\n"
       << "set multiplot layout 1,2 title 'Sphere R = 10 mm on a thin bonded layer "
          "(E = 3 MPa, nu = 0.3, h = 0.1 mm), a <= 1 mm'\n"
       << "set xlabel 'approach delta [um]'\nset ylabel 'force P [mN]'\nset key left top\n"
       << "set title 'whole curve'\nplot " << curves
       << "set title 'near contact: pull-off -2 pi w R = -3.14 mN'\n"
       << "set xrange [-2:6]\nset yrange [-4:25]\nset key right bottom\nplot " << curves
       << "unset multiplot\n";
    gp.close();
    if (std::system(("gnuplot '" + script + "'").c_str()) == 0)
      std::cout << "wrote " << dir << "/section4_curves.png\n";
  } else {
    std::cout << "gnuplot not found: no plot written\n";
  }
  return 0;
}
