// The Maugis-Dugdale and DMT states a DugdaleSolver answers (dugdale_solver.hpp): from its table
// where it has one and the state lies on it, else solved at two resolutions for the error
// estimate; the non-adhesive state at w = 0 (docs/theory.md s.4b). dugdale_solver.cpp holds the
// numerical core these call.
#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/math/constants/constants.hpp>
#include <boost/math/tools/roots.hpp>

#include "adhesion/dugdale_parts.hpp"
#include "adhesion/dugdale_solver.hpp"
#include "adhesion/dugdale_table.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

// A state from the table: its zone radius from gap(c) = h0 on the tabulated parts, then delta
// and P in closed form; the errors from the pieces' measured errors (dugdale_table.hpp).
struct DugdaleSolver::TableState {
  AdhesiveState state;
  double P_error = 0.0, delta_error = 0.0, c_error = 0.0;
};

bool DugdaleSolver::from_table(double a, double w, double sigma0, bool md, TableState& out) const {
  const double rho = a / h_, h0 = w / sigma0, s0 = sigma0 / E_star_, scale = form_.B * std::pow(h_, form_.d);
  const double c_lo = DugdaleTable::min_c();
  const double c_hi = std::min({DugdaleTable::max_c(), options_.max_a_over_h, profile_->max_radius() / h_});
  // The parts at c/h: the table's, or the half-space's below its range (within c/h of them).
  auto parts = [&](double c) {
    if (c < c_lo) {
      DugdaleTable::Parts p = DugdaleTable::half_space(rho, c, form_.d);
      p.error = c_lo;
      return p;
    }
    return table_->at(rho, c);
  };
  auto gap = [&](double c) {
    const DugdaleTable::Parts p = parts(c);
    return (md ? s0 * h_ * p.G : 0.0) + scale * p.F - h0;
  };
  if (!(rho < c_hi)) return false;
  // Bracket outwards from c = a (gap 0): steps growing 4x, so only the pieces up to the root are built.
  double lo = rho, hi = rho > 0.0 ? rho * 1.01 : std::min(c_hi, std::max(c_lo, 0.5 * std::pow(h0 / scale, 1.0 / form_.d)));
  double f_lo = -h0, f_hi = 0.0;
  for (;;) {
    f_hi = gap(hi);
    if (f_hi >= 0.0) break;
    if (!(hi < c_hi)) return false;  // the zone passes the table: solved directly
    lo = hi;
    f_lo = f_hi;
    hi = std::min(c_hi, rho + 4.0 * (hi - rho));
  }
  double c = hi;
  if (f_hi > 0.0) {
    std::uintmax_t iterations = 100;
    const auto root = boost::math::tools::toms748_solve(gap, lo, hi, f_lo, f_hi,
                                                        boost::math::tools::eps_tolerance<double>(46), iterations);
    c = 0.5 * (root.first + root.second);
  }
  const DugdaleTable::Parts p = parts(c);
  const ExactMoments mo = moments(a);
  const NonAdhesiveState hz = a > 0.0 ? exact_state_from(mo, a, h_, E_star_) : NonAdhesiveState{};
  AdhesiveState& s = out.state;
  s.a = a;
  s.c = c * h_;
  if (md) {
    s.delta = mo.endf / mo.end0 + s0 * h_ * p.D;
    s.P = (a > 0.0 ? hz.P_H : 0.0) + sigma0 * h_ * h_ * p.P;
    s.hertz.a = a;
    s.hertz.P_H = s.hertz.delta_H = s.hertz.S = s.hertz.dS_da = kNaN;
  } else {
    s.hertz = a > 0.0 ? hz : NonAdhesiveState{};
    s.hertz.a = a;
    s.delta = s.hertz.delta_H;
    s.P = s.hertz.P_H - sigma0 * kPi * (s.c - a) * (s.c + a);
  }
  // Errors: each part within error x the larger of itself and its half-space size; c moves by the
  // gap's error over its slope.
  const DugdaleTable::Parts hs = DugdaleTable::half_space(rho, c, form_.d);
  const auto size = [](double part, double half_space) { return std::max(std::abs(part), std::abs(half_space)); };
  const double gap_error = p.error * ((md ? s0 * h_ * size(p.G, hs.G) : 0.0) + scale * size(p.F, hs.F));
  const double dc = 1e-6 * c, slope = (gap(std::min(c_hi, c + dc)) - gap(std::max(rho, c - dc))) /
                                       (std::min(c_hi, c + dc) - std::max(rho, c - dc));
  out.c_error = slope > 0.0 ? h_ * gap_error / slope : kNaN;
  const DugdaleTable::Parts up = parts(std::min(c_hi, c + dc));
  const double dP_dc = md ? sigma0 * h_ * h_ * (up.P - p.P) / dc : -2.0 * sigma0 * kPi * c * h_ * h_;
  const double ddelta_dc = md ? s0 * h_ * (up.D - p.D) / dc : 0.0;
  out.P_error = (md ? p.error * sigma0 * h_ * h_ * size(p.P, hs.P) : 0.0) + std::abs(dP_dc) * out.c_error / h_ +
                1e-9 * std::abs(hz.P_H);  // the power-law table's accuracy
  out.delta_error = (md ? p.error * s0 * h_ * size(p.D, hs.D) : 0.0) + std::abs(ddelta_dc) * out.c_error / h_;
  if (!std::isfinite(s.P) || !std::isfinite(s.delta)) return false;
  return true;
}

namespace {

// w = 0: no adhesive zone (c = a), the non-adhesive state for either law.
AdhesiveState non_adhesive(const ExactMoments& mo, double a, double h, double E_star) {
  AdhesiveState s;
  s.a = s.c = a;
  s.hertz = exact_state_from(mo, a, h, E_star);
  s.P = s.hertz.P_H;
  s.delta = s.hertz.delta_H;
  return s;
}

}  // namespace

AdhesiveState DugdaleSolver::solve_md(double a, double w, double sigma0, int nodes) const {
  if (table_ && w > 0.0) {
    TableState t;
    if (from_table(a, w, sigma0, true, t)) return t.state;
  }
  const Inner in = inner(a, nodes);
  if (w == 0.0) return non_adhesive(in.mo, a, h_, E_star_);
  const double h0 = w / sigma0;
  const double c = find_c(a, h0, "DugdaleSolver::maugis_dugdale", sigma0, [&](double cc) {
    return zone(in, cc, sigma0).gap_c;
  });
  const Zone z = zone(in, c, sigma0);
  AdhesiveState s;
  s.a = a;
  s.c = c;
  s.delta = z.delta;
  // 2 pi int_0^a g + 2 pi int_a^c g_D, the latter -2 sigma0 [c^2 acos(a/c) - a sqrt(c^2 - a^2)].
  const double zone_load = -2.0 * sigma0 * (c * c * std::acos(std::min(1.0, a / c)) - a * std::sqrt((c - a) * (c + a)));
  s.P = 2.0 * E_star_ * h_ * (z.delta * in.mo.int0 - in.mo.intf + z.intD) + zone_load;
  s.hertz.a = a;
  s.hertz.P_H = s.hertz.delta_H = s.hertz.S = s.hertz.dS_da = kNaN;
  if (!std::isfinite(s.P) || !std::isfinite(s.delta))
    throw NumericalError("layerjkr::DugdaleSolver::maugis_dugdale: the state is not finite at a = " + format_double(a));
  return s;
}

AdhesiveState DugdaleSolver::solve_dmt(double a, double w, double sigma0, int nodes) const {
  if (table_ && w > 0.0) {
    TableState t;
    if (from_table(a, w, sigma0, false, t)) return t.state;
  }
  const Inner in = inner(a, nodes);
  if (w == 0.0) return non_adhesive(in.mo, a, h_, E_star_);
  const double h0 = w / sigma0;
  const double c = find_c(a, h0, "DugdaleSolver::dmt", sigma0, [&](double cc) { return gap_at(in, nullptr, cc); });
  AdhesiveState s;
  s.a = a;
  s.c = c;
  s.hertz = exact_state_from(in.mo, a, h_, E_star_);
  s.delta = s.hertz.delta_H;
  s.P = s.hertz.P_H - sigma0 * kPi * (c - a) * (c + a);
  if (!std::isfinite(s.P) || !std::isfinite(s.delta))
    throw NumericalError("layerjkr::DugdaleSolver::dmt: the state is not finite at a = " + format_double(a));
  return s;
}

namespace {

int fine_nodes(const ExactLayerOptions& o) { return o.points_per_panel; }
int coarse_nodes(const ExactLayerOptions& o) { return std::max(2, 3 * o.points_per_panel / 4); }

DugdaleEstimate with_error(const AdhesiveState& fine, const AdhesiveState& coarse) {
  DugdaleEstimate e;
  e.state = fine;
  e.P_error = std::abs(fine.P - coarse.P);
  e.delta_error = std::abs(fine.delta - coarse.delta);
  e.c_error = std::abs(fine.c - coarse.c);
  return e;
}

}  // namespace

AdhesiveState DugdaleSolver::maugis_dugdale(double a, double w, double sigma0) const {
  check("DugdaleSolver::maugis_dugdale", a, w, sigma0);
  return solve_md(a, w, sigma0, fine_nodes(options_));
}

DugdaleEstimate DugdaleSolver::maugis_dugdale_estimate(double a, double w, double sigma0) const {
  check("DugdaleSolver::maugis_dugdale", a, w, sigma0);
  if (TableState t; table_ && w > 0.0 && from_table(a, w, sigma0, true, t))
    return DugdaleEstimate{t.state, t.P_error, t.delta_error, t.c_error};
  return with_error(solve_md(a, w, sigma0, fine_nodes(options_)), solve_md(a, w, sigma0, coarse_nodes(options_)));
}

AdhesiveState DugdaleSolver::dmt(double a, double w, double sigma0) const {
  check("DugdaleSolver::dmt", a, w, sigma0);
  return solve_dmt(a, w, sigma0, fine_nodes(options_));
}

DugdaleEstimate DugdaleSolver::dmt_estimate(double a, double w, double sigma0) const {
  check("DugdaleSolver::dmt", a, w, sigma0);
  if (TableState t; table_ && w > 0.0 && from_table(a, w, sigma0, false, t))
    return DugdaleEstimate{t.state, t.P_error, t.delta_error, t.c_error};
  return with_error(solve_dmt(a, w, sigma0, fine_nodes(options_)), solve_dmt(a, w, sigma0, coarse_nodes(options_)));
}

double DugdaleSolver::non_adhesive_gap(double a, double r) const {
  const char* fn = "DugdaleSolver::non_adhesive_gap";
  check(fn, a, 1.0, 1.0);
  if (!std::isfinite(r) || r < a) throw DomainError(fn, "r", r, "finite and >= a = " + format_double(a));
  if (r > 0.0) profile_->require_contact_radius(fn, r);
  const Inner in = inner(a, fine_nodes(options_));
  return gap_at(in, nullptr, r);
}

std::vector<double> DugdaleSolver::maugis_dugdale_gap(double a, double w, double sigma0,
                                                      const std::vector<double>& radii) const {
  const char* fn = "DugdaleSolver::maugis_dugdale_gap";
  check(fn, a, w, sigma0);
  for (double r : radii) {
    if (!std::isfinite(r) || r < a) throw DomainError(fn, "r", r, "finite and >= a = " + format_double(a));
    if (r > 0.0) profile_->require_contact_radius(fn, r);
  }
  const AdhesiveState s = solve_md(a, w, sigma0, fine_nodes(options_));
  const Inner in = inner(a, fine_nodes(options_));
  const Zone z = zone(in, s.c, sigma0);
  std::vector<double> out;
  out.reserve(radii.size());
  for (double r : radii) out.push_back(gap_at(in, &z, r));
  return out;
}

}  // namespace layerjkr::detail
