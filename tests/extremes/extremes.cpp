// The extreme-value matrix (see extremes.hpp). References are closed forms evaluated in
// long double (with series where the closed form cancels), or limits the physics fixes.
#include "extremes/extremes.hpp"

#include <cmath>
#include <functional>
#include <random>
#include <sstream>
#include <utility>

#include "layerjkr/layerjkr.hpp"

namespace test {
namespace {

using namespace layerjkr;
using LD = long double;
constexpr double kPi = 3.14159265358979323846;

std::string sci(double v) {
  std::ostringstream o;
  o.precision(2);
  o << std::scientific << v;
  return o.str();
}

class Matrix {
 public:
  std::vector<ExtremeCheck> rows;
  std::string area;

  void rel(const std::string& cell, double value, double reference, double tol) {
    const double e = reference == 0.0 ? std::abs(value) : std::abs(value - reference) / std::abs(reference);
    add(cell, "rel. err <= " + sci(tol), std::isfinite(value) ? "rel. err " + sci(e) : "not finite",
        std::isfinite(value) && e <= tol);
  }
  void truth(const std::string& cell, bool ok, const std::string& expected, const std::string& outcome) {
    add(cell, expected, outcome, ok);
  }
  // The call must throw a layerjkr::Error whose message contains `text`.
  void error(const std::string& cell, const std::function<void()>& f, const std::string& text) {
    try {
      f();
      add(cell, "error naming " + text, "no error", false);
    } catch (const Error& e) {
      const std::string m = e.what();
      add(cell, "error naming " + text, "error: " + m.substr(0, 90), m.find(text) != std::string::npos);
    }
  }
  // Runs f; a thrown Error fails the cell with its message.
  void guarded(const std::string& cell, const std::string& expected, const std::function<void()>& f) {
    try {
      f();
    } catch (const std::exception& e) {
      add(cell, expected, std::string("exception: ") + e.what(), false);
    }
  }

 private:
  void add(const std::string& cell, const std::string& expected, const std::string& outcome, bool ok) {
    rows.push_back({area, cell, expected, outcome, ok});
  }
};

bool finite_state(const NonAdhesiveState& s) {
  return std::isfinite(s.P_H) && std::isfinite(s.delta_H) && std::isfinite(s.S) && std::isfinite(s.dS_da);
}

// Half-space sphere, Sneddon: delta = a atanh(x) R/R..., P = E* R^2 [(1+x^2) atanh x - x], x = a/R.
LD sphere_force_ld(LD E_star, LD R, LD a) {
  const LD x = a / R;
  LD bracket;
  if (x < 0.05L) {  // sum_k x^(2k+1) 4k / ((2k+1)(2k-1)): the closed form cancels
    bracket = 0.0L;
    LD p = x * x * x;
    for (int k = 1; k < 40; ++k, p *= x * x) bracket += p * 4.0L * k / ((2.0L * k + 1) * (2.0L * k - 1));
  } else {
    bracket = (1 + x * x) * std::atanh(x) - x;
  }
  return E_star * R * R * bracket;
}

// The matrix as groups: each group checks one cell (or, where a cell's check needs the
// previous one, a short sequence) and runs alone, so every cell is its own test. Running
// every group in order gives the rows of the whole matrix, as validity_table prints them.
struct Group {
  std::string area;
  std::string tag;
  std::string name;
  std::function<void(Matrix&)> run;
};

class Groups {
 public:
  std::vector<Group> list;

  void area(const std::string& heading, const std::string& tag) {
    area_ = heading;
    tag_ = tag;
  }
  void add(const std::string& name, std::function<void(Matrix&)> run) {
    list.push_back({area_, tag_, name, std::move(run)});
  }

 private:
  std::string area_, tag_;
};

void poisson(Groups& g) {
  g.area("Poisson ratio (bonded layer, paraboloid R = 1 mm, h = 10 um, a/h = 2)", "poisson");
  for (double nu : {-0.99, 0.0, 0.25, 0.45, 0.49, 0.499, 0.4999, 0.5}) {
    const std::string n = "nu = " + std::to_string(nu).substr(0, nu < 0 ? 5 : 6);
    g.add(n + ", thin-layer K, G", [nu, n](Matrix& m) {
      const ElasticLayer layer{1e6, nu, 1e-5, Base::bonded};
      if (nu < 0.5) {
        m.guarded(n + ", thin-layer K, G", "finite, warning above 0.45", [&] {
          const ThinLayerConstants c = thin_layer_constants(layer);
          const bool warned = !c.warnings.empty();
          m.truth(n + ", thin-layer K, G", std::isfinite(c.K) && c.K > 0 && std::isfinite(c.G) &&
                                              (nu == 0.25 ? c.G == 0.0 : true) && warned == (nu > 0.45),
                  nu > 0.45 ? "finite, warns (compressible expansion non-uniform)"
                            : nu == 0.25 ? "finite, G = 0 exactly" : "finite, no warning",
                  "K " + sci(c.K) + ", G " + sci(c.G) + (warned ? ", warns" : ""));
        });
      } else {
        m.error(n + ", thin-layer K, G", [&] { thin_layer_constants(layer); }, "singular at 0.5");
      }
    });
    g.add(n + ", exact layer", [nu, n](Matrix& m) {
      const ProfilePtr p = make_paraboloid(1e-3);
      const ElasticLayer layer{1e6, nu, 1e-5, Base::bonded};
      m.guarded(n + ", exact layer", "finite, S and P_H increasing", [&] {
        const ContactModelPtr ex = make_exact_layer(p, layer);
        const NonAdhesiveState s1 = ex->state(1e-5), s2 = ex->state(2e-5), s4 = ex->state(4e-5);
        const bool ok = finite_state(s1) && finite_state(s2) && finite_state(s4) && s1.P_H < s2.P_H &&
                        s2.P_H < s4.P_H && s1.S < s2.S && s2.S < s4.S && s2.dS_da > 0;
        m.truth(n + ", exact layer", ok, "finite, S and P_H increasing in a",
                "P_H(a/h = 2) = " + sci(s2.P_H) + " N");
      });
    });
  }
  g.add("nu = 0.4999 -> 0.5, exact layer", [](Matrix& m) {
    const ProfilePtr p = make_paraboloid(1e-3);
    m.guarded("nu = 0.4999 -> 0.5, exact layer", "continuous", [&] {
      const double near = make_exact_layer(p, {1e6, 0.4999, 1e-5, Base::bonded})->state(2e-5).P_H;
      const double at = make_exact_layer(p, {1e6, 0.5, 1e-5, Base::bonded})->state(2e-5).P_H;
      m.rel("nu = 0.4999 -> 0.5, exact layer P_H (continuity into the incompressible limit)", near, at, 2e-3);
    });
  });
  g.add("nu = 0.499, auto at tolerance 1 %", [](Matrix& m) {
    const ProfilePtr p = make_paraboloid(1e-3);
    m.guarded("nu = 0.499, auto at tolerance 1 %", "chooses exact", [&] {
      const ModelChoice c = choose_layer_model(p, {1e6, 0.499, 1e-5, Base::bonded}, 0.0, 0.01, {2e-5});
      m.truth("nu = 0.499, auto at tolerance 1 %", c.model == ModelKind::exact,
              "chooses exact (no reduced model within 1 % at a/h = 2)", std::string("chose ") + to_string(c.model));
    });
  });
}

void thickness(Groups& g) {
  g.area("Thickness h/a (bonded, nu = 0.3, paraboloid R = 1 m, a = 1 mm)", "thickness");
  constexpr double a = 1e-3, R = 1.0, nu = 0.3, Es = 1.0 / ((1 - nu) * (1 + nu));
  for (double ha : {1e4, 1e2, 1.0, 1e-2, 1e-3}) {
    const std::string cell = "h/a = " + sci(ha) + ", exact";
    g.add(cell, [ha, cell](Matrix& m) {
      const ProfilePtr p = make_paraboloid(R);
      const ElasticLayer layer{1.0, nu, ha * a, Base::bonded};
      m.guarded(cell, "limit", [&] {
        const NonAdhesiveState s = make_exact_layer(p, layer)->state(a);
        if (ha >= 1e2) {
          m.rel(cell + " vs half-space", s.P_H, 4 * Es * a * a * a / (3 * R), 3.0 / ha);
        } else if (ha <= 1e-2) {
          const double K = thin_layer_constants(layer).K;
          m.rel(cell + " vs Winkler", s.P_H, make_winkler(p, K)->state(a).P_H, 0.5 * ha + 1e-3);
        } else {
          m.truth(cell, finite_state(s) && s.S > 0, "finite", "P_H " + sci(s.P_H));
        }
      });
    });
  }
  g.add("h/a = " + sci(1e-4) + ", exact", [](Matrix& m) {
    const ProfilePtr p = make_paraboloid(R);
    const ElasticLayer layer{1.0, nu, 1e-4 * a, Base::bonded};  // beyond ExactLayerOptions' 1000
    m.error("h/a = " + sci(1e-4) + ", exact", [&] { make_exact_layer(p, layer)->state(a); }, "a/h");
  });
  for (double ha : {1e-3, 1e-4}) {
    const std::string cell = "h/a = " + sci(ha) + ", edge_corrected vs Winkler";
    g.add(cell, [ha, cell](Matrix& m) {
      const ProfilePtr p = make_paraboloid(R);
      const ElasticLayer layer{1.0, nu, ha * a, Base::bonded};
      m.guarded(cell, "O(h/a)", [&] {
        const double K = thin_layer_constants(layer).K;
        const double w = make_winkler(p, K)->state(a).P_H, e = make_edge_corrected(p, layer)->state(a).P_H;
        m.rel(cell, e, w, 4 * 0.2 * ha);
      });
    });
  }
  // One group: each h/a's check compares with the previous one's error.
  g.add("nu = 0.5, thin limit", [](Matrix& m) {
    m.guarded("nu = 0.5, thin limit", "incompressible law", [&] {
      // theory.md s.2: an incompressible bonded layer has S = 3 pi mu a^4 / (8 h^3), with an
      // O(h/a) edge correction; the exact solver must converge to it as h/a -> 0.
      const ExactLayerKernel k({1.0, 0.5, 1.0, Base::bonded});
      const double Es_inc = 4.0 / 3.0, mu = 1.0 / 3.0;  // E = 1, nu = 1/2
      double previous = INFINITY;
      for (double aoh : {20.0, 50.0, 100.0, 300.0, 1000.0}) {
        const double S = 2.0 * Es_inc * aoh * k.flat_punch_factor(aoh),
                     S_inc = 3.0 * kPi * mu * std::pow(aoh, 4) / 8.0;
        const double scaled = (S / S_inc - 1.0) * aoh;  // -> const: O(h/a) convergence
        m.truth("nu = 0.5, h/a = " + sci(1.0 / aoh) + ", exact S vs incompressible 3 pi mu a^4/(8 h^3)",
                scaled > 0.0 && scaled < previous && scaled < 7.0, "rel. err <= 7 h/a, shrinking as O(h/a)",
                "rel. err " + sci(S / S_inc - 1.0) + " = " + sci(scaled) + " h/a");
        previous = scaled;
      }
    });
  });
  g.add("h/a = 1e4, auto at tolerance 1 %", [](Matrix& m) {
    const ProfilePtr p = make_paraboloid(R);
    m.guarded("h/a = 1e4, auto at tolerance 1 %", "not a thin-layer model", [&] {
      const ModelChoice c = choose_layer_model(p, {1.0, nu, 1e4 * a, Base::bonded}, 0.0, 0.01, {a});
      m.truth("h/a = 1e4, auto at tolerance 1 %", c.model != ModelKind::winkler && c.model != ModelKind::two_term,
              "not a thin-layer model", std::string("chose ") + to_string(c.model));
    });
  });
}

void radius(Groups& g) {
  g.area("Contact radius (sphere R = 1 mm, half-space E* = 1 MPa; cone tip)", "radius");
  constexpr double R = 1e-3, Es = 1e6;
  for (double x : {1e-12, 1e-8, 1e-4, 0.1, 0.5, 0.9, 0.999}) {
    const std::string cell = "a/R = " + sci(x) + ", half-space P_H vs long double";
    g.add(cell, [x, cell](Matrix& m) {
      const ContactModelPtr hs = make_half_space(make_sphere(R), Es * (1 - 0.09), 0.3);
      const double a = x * R;
      m.rel(cell, hs->state(a).P_H, static_cast<double>(sphere_force_ld(Es, R, a)), 1e-13);
    });
  }
  g.add("a/R = 1e-12, Winkler sphere vs paraboloid", [](Matrix& m) {
    const ContactModelPtr wk = make_winkler(make_sphere(R), 1e12), wp = make_winkler(make_paraboloid(R), 1e12);
    m.rel("a/R = 1e-12, Winkler sphere vs paraboloid", wk->state(1e-15).P_H, wp->state(1e-15).P_H, 1e-13);
  });
  g.add("a/R = 0.999, Winkler sphere", [](Matrix& m) {
    const ContactModelPtr wk = make_winkler(make_sphere(R), 1e12);
    m.guarded("a/R = 0.999, Winkler sphere", "finite, increasing", [&] {
      const NonAdhesiveState a1 = wk->state(0.99 * R), a2 = wk->state(0.999 * R);
      m.truth("a/R = 0.999, Winkler sphere", finite_state(a2) && a2.P_H > a1.P_H, "finite, increasing",
              "P_H " + sci(a2.P_H));
    });
  });
  const double alpha = 70.0 * kPi / 180.0, cot = 1.0 / std::tan(alpha);
  for (double a : {1e-15, 1e-9, 1e-3}) {
    const std::string cell = "cone tip, a = " + sci(a) + ", half-space P_H";
    g.add(cell, [a, alpha, cot, cell](Matrix& m) {
      const ContactModelPtr cone = make_half_space(make_cone(alpha), Es * (1 - 0.09), 0.3);
      m.rel(cell, cone->state(a).P_H, 0.5 * kPi * Es * a * a * cot, 1e-13);
    });
  }
  g.add("cone tip, a = 1e-12, two-term JKR", [alpha](Matrix& m) {
    m.guarded("cone tip, a = 1e-12, two-term JKR", "finite", [&] {
      const AdhesiveState st = JkrSolution(make_two_term(make_cone(alpha), 1e12, -0.5), 0.05).at(1e-12);
      m.truth("cone tip, a = 1e-12, two-term (G < 0) JKR", std::isfinite(st.P) && std::isfinite(st.delta),
              "finite (delta_H ~ -(G/K) cot/a: the asymptotic model needs a >> |G|/(K f'))",
              "delta " + sci(st.delta) + " m");
    });
  });
}

void adhesion(Groups& g) {
  g.area("Work of adhesion (half-space paraboloid R = 1 mm, E* = 1 MPa)", "adhesion");
  constexpr double R = 1e-3, a = 1e-5;
  const auto half_space = [] { return make_half_space(make_paraboloid(R), 1e6 * 0.91, 0.3); };
  for (double w : {1e-12, 1e-3, 1e3}) {
    const std::string cell = "w = " + sci(w) + ", pull-off vs -3/2 pi w R";
    g.add(cell, [w, cell, half_space](Matrix& m) {
      const auto po = JkrSolution(half_space(), w).pull_off();
      m.rel(cell, po ? po->P : NAN, -1.5 * kPi * w * R, 1e-10);
    });
  }
  g.add("w = 0", [half_space](Matrix& m) {
    const ContactModelPtr hs = half_space();
    const NonAdhesiveState h = hs->state(a);
    const AdhesiveState zero = JkrSolution(hs, 0.0).at(a);
    m.truth("w = 0", zero.P == h.P_H && zero.delta == h.delta_H && !JkrSolution(hs, 0.0).pull_off(),
            "non-adhesive state bit for bit, no pull-off", zero.P == h.P_H ? "identical" : "differs");
  });
  g.add("w = 1e-12: P - P_H vs -sqrt(4 pi w a S^2/S')", [half_space](Matrix& m) {
    const ContactModelPtr hs = half_space();
    const NonAdhesiveState h = hs->state(a);
    const AdhesiveState tiny = JkrSolution(hs, 1e-12).at(a);
    m.rel("w = 1e-12: P - P_H vs -sqrt(4 pi w a S^2/S')", tiny.P - h.P_H,
          -std::sqrt(4 * kPi * 1e-12 * a * h.S * h.S / h.dS_da), 1e-6);
  });
}

void foundation(Groups& g) {
  g.area("Foundation constants (sphere R = 1 mm, a = 10 um)", "foundation");
  constexpr double a = 1e-5, K = 1e12;
  for (double G : {1e-12, -1e-12, 1e-30, -1e-30}) {
    const std::string cell = "two-term G = " + sci(G) + ": delta_H vs Winkler - (G/K)(f'' + f'/a)";
    g.add(cell, [G, cell](Matrix& m) {
      const ProfilePtr s = make_sphere(1e-3);
      const NonAdhesiveState w0 = make_winkler(s, K)->state(a);
      const NonAdhesiveState two = make_two_term(s, K, G)->state(a);
      const ProfileDerivatives d = s->derivatives(a);
      m.rel(cell, two.delta_H, w0.delta_H - (G / K) * (d.d2f + d.df / a), 1e-15);
    });
  }
  // One group: each T's check compares with the previous one's difference.
  g.add("Filonenko-Borodich T -> 0", [](Matrix& m) {
    const ProfilePtr s = make_sphere(1e-3);
    const NonAdhesiveState w0 = make_winkler(s, K)->state(a);
    double previous = INFINITY;
    bool decreasing = true;
    for (double T : {1e-3, 1e-9, 1e-15}) {
      const NonAdhesiveState f = make_full_foundation(s, K, T)->state(a);
      const double e = std::abs(f.P_H / w0.P_H - 1.0);
      decreasing = decreasing && e < previous;
      previous = e;
      m.truth("Filonenko-Borodich T = " + sci(T), finite_state(f) && decreasing,
              "finite, converging to Winkler as T -> 0", "rel. diff from Winkler " + sci(e));
    }
  });
  // The ODE route (solver "ode") on the same cells: it failed at tiny radii before.
  for (double G : {1e-12, -1e-12, 30.0, -30.0}) {
    const std::string cell = "ODE route, two-term G = " + sci(G) + ": pull-off and P_H(a) vs the closed form";
    g.add(cell, [G, cell](Matrix& m) {
      const ProfilePtr s = make_paraboloid(1e-3);
      const ContactModelPtr ode = make_ode_foundation(s, K, G, FoundationKind::asymptotic);
      const ContactModelPtr closed = make_two_term(s, K, G);
      m.guarded(cell, "finite", [&] {
        const auto po = JkrSolution(ode, 0.05).pull_off(), ref = JkrSolution(closed, 0.05).pull_off();
        m.rel(cell + ": pull-off", po ? po->P : NAN, ref ? ref->P : NAN, 1e-8);
        m.rel(cell + ": P_H(1e-9 m)", ode->state(1e-9).P_H, closed->state(1e-9).P_H, 1e-6);
      });
    });
  }
  for (double Kx : {1e3, 1e12, 1e20}) {
    const std::string cell = "ODE route, Winkler K = " + sci(Kx) + ", pull-off vs -2 pi w R";
    g.add(cell, [Kx, cell](Matrix& m) {
      m.guarded(cell, "finite", [&] {
        const auto po = JkrSolution(make_ode_foundation(make_paraboloid(1e-3), Kx, 0.0, FoundationKind::asymptotic), 0.05).pull_off();
        m.rel(cell, po ? po->P : NAN, -2 * kPi * 0.05 * 1e-3, 1e-8);
      });
    });
  }
  for (double Kx : {1e3, 1e8, 1e12, 1e16, 1e20}) {
    const std::string cell = "Winkler K = " + sci(Kx) + ", pull-off vs -2 pi w R";
    g.add(cell, [Kx, cell](Matrix& m) {
      const auto po = JkrSolution(make_winkler(make_paraboloid(1e-3), Kx), 0.05).pull_off();
      m.rel(cell, po ? po->P : NAN, -2 * kPi * 0.05 * 1e-3, 1e-10);
    });
  }
}

void scales(Groups& g) {
  g.area("Length and force scales (JKR half-space paraboloid, long double reference)", "scales");
  for (double R : {1e-9, 1e-6, 1e-3, 1.0})
    for (double Es : {1e3, 1e6, 1e11}) {
      const double w = R < 1e-6 ? 1e-3 : R < 1e-2 ? 0.05 : 1e3;
      const LD a_po = std::cbrt(9.0L * kPi * w * R * R / (8.0L * Es));
      const LD a = 2.0L * a_po;
      const LD P = 4.0L * Es * a * a * a / (3.0L * R) - std::sqrt(8.0L * kPi * w * Es * a * a * a);
      const std::string cell = "R = " + sci(R) + " m, E* = " + sci(Es) + " Pa";
      const auto solution = [R, Es, w] { return JkrSolution(make_half_space(make_paraboloid(R), Es * 0.75, 0.5), w); };
      g.add(cell + ": pull-off radius", [cell, a_po, solution](Matrix& m) {
        const auto po = solution().pull_off();
        m.rel(cell + ": pull-off radius", po ? po->a : NAN, static_cast<double>(a_po), 1e-10);
      });
      const std::string p_cell = cell + ": P(2 a_po) = " + sci(static_cast<double>(P)) + " N";
      g.add(p_cell, [p_cell, a, P, solution](Matrix& m) {
        m.rel(p_cell, solution().at(static_cast<double>(a)).P, static_cast<double>(P), 1e-14);
      });
    }
}

void tables(Groups& g) {
  g.area("Tabulated profiles (half-space E* = 1 MPa)", "tables");
  const auto check = [](Matrix& m, const std::string& cell, std::vector<double> r, std::vector<double> z) {
    try {
      const ProfilePtr p = make_table_profile(r, z);
      const ContactModelPtr hs = make_half_space(p, 0.91e6, 0.3);
      bool ok = true;
      double previous = 0.0;
      for (int k = 1; k <= 20; ++k) {
        const NonAdhesiveState s = hs->state(r.back() * k / 20.0);
        ok = ok && finite_state(s) && s.P_H > previous;
        previous = s.P_H;
      }
      m.truth(cell, ok, "accepted: finite, P_H increasing", ok ? "accepted, finite, increasing" : "bad state");
    } catch (const Error& e) {
      const std::string msg = e.what();
      m.truth(cell, msg.find("decreases") != std::string::npos, "or rejected: the spline would decrease",
              "rejected: " + msg.substr(0, 80));
    }
  };
  // A sphere sampled at 41 points, and the same with 1e-6 relative noise.
  const auto sphere = [](bool noisy) {
    std::vector<double> r, z, zn;
    std::mt19937_64 rng(5);
    std::normal_distribution<double> gauss(0.0, 1e-6);
    for (int i = 0; i <= 40; ++i) {
      r.push_back(5e-4 * i / 40);
      z.push_back(r.back() * r.back() / (1e-3 + std::sqrt(1e-6 - r.back() * r.back())));
      zn.push_back(z.back() * (1.0 + gauss(rng)));
    }
    zn[0] = 0.0;
    return std::make_pair(r, noisy ? zn : z);
  };
  g.add("sphere, 41 points", [check, sphere](Matrix& m) {
    const auto [r, z] = sphere(false);
    check(m, "sphere, 41 points", r, z);
  });
  g.add("sphere, 41 points, 1e-6 relative noise", [check, sphere](Matrix& m) {
    const auto [r, z] = sphere(true);
    check(m, "sphere, 41 points, 1e-6 relative noise", r, z);
  });
  g.add("3 points", [check](Matrix& m) { check(m, "3 points", {0.0, 1e-4, 2e-4}, {0.0, 1e-8, 4e-8}); });
  g.add("kink: parabolic apex into a steeper cone", [check](Matrix& m) {
    check(m, "kink: parabolic apex into a steeper cone", {0.0, 1e-4, 2e-4, 3e-4, 4e-4, 5e-4},
          {0.0, 5e-6, 2e-5, 6e-5, 1e-4, 1.4e-4});
  });
  g.add("kink: flat apex then a cone (the spline overshoots)", [check](Matrix& m) {
    check(m, "kink: flat apex then a cone (the spline overshoots)", {0.0, 1e-4, 2e-4, 3e-4, 4e-4},
          {0.0, 0.0, 1e-5, 2e-5, 3e-5});
  });
}

// Scenes at the edge of their valid ranges, through parse_scene and solve_summary as the
// CLI and Python see them: refused as input errors naming the key, value and range (exit
// 2), or answered finitely - never a failure (exit 1) or a non-finite number.
void input_ranges(Groups& g) {
  g.area("Input ranges (scenes: refused naming key and range, or answered finitely)", "ranges");
  const auto scene = [](const std::string& indenter, const std::string& w) {
    return R"({"indenter": )" + indenter +
           R"(, "medium": {"type": "layer", "E": 5e4, "nu": 0.3, "h": 2e-7, "base": "bonded"}, "model": "two_term", "w": )" +
           w + "}";
  };
  const std::string para = R"({"shape": "paraboloid", "R": 1e-5})";
  struct Refused {
    std::string cell, text, names;
  };
  for (const Refused& r : std::vector<Refused>{
           {"w = 1e308 (printed -inf and NaN)", scene(para, "1e308"), "w = 1e+308"},
           {"w = 1e-300", scene(para, "1e-300"), "valid range: [1e-30, 1e6]"},
           {"R = 5e-324 (failed, exit 1)", scene(R"({"shape": "paraboloid", "R": 5e-324})", "1e-3"), "L/h"},
           {"R = 1e300", scene(R"({"shape": "sphere", "R": 1e300})", "1e-3"), "valid range: [1e-9, 1e9]"},
           {"power law d = 1000 (failed, exit 1)", scene(R"({"shape": "power_law", "B": 1, "d": 1000})", "1e-3"),
            "d = 1000 is invalid; valid range: [1, 50]"}}) {
    g.add(r.cell, [r](Matrix& m) {
      try {
        solve_summary(parse_scene(r.text, "scene"));
        m.truth(r.cell, false, "input error naming " + r.names, "answered");
      } catch (const InputError& e) {
        const std::string msg = e.what();
        m.truth(r.cell, msg.find(r.names) != std::string::npos, "input error naming " + r.names,
                "input error: " + msg.substr(0, 90));
      }
    });
  }
  for (const auto& [cell, text] : std::vector<std::pair<std::string, std::string>>{
           {"w/(E* R) = 1e5, two_term", scene(para, "5.5e4")},
           {"w/(E* R) = 1e-29, two_term", scene(para, "5.5e-28")},
           {"power law d = 50, two_term", scene(R"({"shape": "power_law", "B": 1e3, "d": 50})", "1e-3")},
           {"power law d = 50, exact",
            R"({"indenter": {"shape": "power_law", "B": 1e3, "d": 50}, "medium": {"type": "layer", "E": 5e4, "nu": 0.3, "h": 0.1, "base": "bonded"}, "model": "exact", "w": 1e-3})"}}) {
    g.add(cell, [cell = cell, text = text](Matrix& m) {
      m.guarded(cell, "a finite answer", [&] {
        const SummaryAnswer s = solve_summary(parse_scene(text, "scene"));
        const bool ok = s.contact.pull_off && std::isfinite(s.contact.pull_off->P) &&
                        s.contact.zero_load_radius && std::isfinite(*s.contact.zero_load_radius);
        m.truth(cell, ok, "a finite pull-off and zero-load radius", ok ? "finite" : "missing or not finite");
      });
    });
  }
}

const std::vector<Group>& groups() {
  static const std::vector<Group> list = [] {
    Groups g;
    poisson(g);
    thickness(g);
    radius(g);
    adhesion(g);
    foundation(g);
    scales(g);
    tables(g);
    input_ranges(g);
    return g.list;
  }();
  return list;
}

}  // namespace

std::vector<ExtremeGroup> extreme_groups() {
  std::vector<ExtremeGroup> out;
  for (const Group& g : groups()) out.push_back({g.tag, g.name});
  return out;
}

std::vector<ExtremeCheck> run_extreme_group(std::size_t index) {
  const Group& g = groups().at(index);
  Matrix m;
  m.area = g.area;
  g.run(m);
  return m.rows;
}

std::vector<ExtremeCheck> run_extreme_matrix() {
  std::vector<ExtremeCheck> rows;
  for (std::size_t i = 0; i < groups().size(); ++i) {
    const std::vector<ExtremeCheck> cells = run_extreme_group(i);
    rows.insert(rows.end(), cells.begin(), cells.end());
  }
  return rows;
}

}  // namespace test
