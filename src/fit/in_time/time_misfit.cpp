// Where a fit in time misses, named and measured (time_fit.hpp): the residuals' share per piece of
// the history, the dwell's unfollowed relaxation and its time scale, a baseline step, adhesion.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/short_number.hpp"
#include "fit/in_time/time_fit.hpp"

namespace layerjkr::detail {
namespace {

// A run of samples of one segment, in acquisition order.
struct Piece {
  std::size_t begin, end;  // [begin, end)
  int segment;
};

std::vector<Piece> pieces_of(const std::vector<int>& segment) {
  std::vector<Piece> out;
  for (std::size_t i = 0; i < segment.size(); ++i)
    if (out.empty() || segment[i] != out.back().segment) out.push_back({i, i + 1, segment[i]});
    else out.back().end = i + 1;
  return out;
}

std::string name_of(const Piece& p, std::size_t k, const std::vector<Piece>& all) {
  if (p.segment == 0) return "the approach";
  if (p.segment == 1) return "the retract";
  bool approach_before = false, retract_before = false;
  for (std::size_t j = 0; j < k; ++j) {
    approach_before = approach_before || all[j].segment == 0;
    retract_before = retract_before || all[j].segment == 1;
  }
  if (!approach_before) return "the pause before the approach";
  if (retract_before) return "the pause after the retract";
  return "the dwell";
}

std::string percent(double x) { return std::to_string(static_cast<int>(std::lround(100.0 * x))) + " %"; }

double mean_of(const std::vector<double>& r, std::size_t begin, std::size_t end) {
  double s = 0.0;
  for (std::size_t i = begin; i < end; ++i) s += r[i];
  return end > begin ? s / static_cast<double>(end - begin) : 0.0;
}

// The share of a dwell's residual sum of squares that a + b exp(-(t - t_begin)/tau2) takes, at the
// best tau2 on a log grid from the sample step to ten times the dwell: a relaxation the law lacks.
struct SecondScale {
  double tau2 = 0.0, amplitude = 0.0, share = 0.0;
};

SecondScale second_scale(const std::vector<double>& t, const std::vector<double>& r, std::size_t begin, std::size_t end) {
  SecondScale best;
  const std::size_t n = end - begin;
  if (n < 20) return best;
  const double t0 = t[begin], span = t[end - 1] - t0, step = span / static_cast<double>(n - 1);
  double ss = 0.0;
  for (std::size_t i = begin; i < end; ++i) ss += r[i] * r[i];
  if (!(ss > 0.0) || !(step > 0.0)) return best;
  constexpr int kGrid = 48;
  for (int g = 0; g <= kGrid; ++g) {
    const double tau2 = step * std::pow(10.0 * span / step, static_cast<double>(g) / kGrid);
    double s1 = 0.0, se = 0.0, see = 0.0, sr = 0.0, ser = 0.0;  // least squares in (a, b)
    for (std::size_t i = begin; i < end; ++i) {
      const double e = std::exp(-(t[i] - t0) / tau2);
      s1 += 1.0, se += e, see += e * e, sr += r[i], ser += e * r[i];
    }
    const double det = s1 * see - se * se;
    if (!(det > 1e-12 * s1 * see)) continue;
    const double a = (see * sr - se * ser) / det, b = (s1 * ser - se * sr) / det;
    double sse = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      const double d = r[i] - a - b * std::exp(-(t[i] - t0) / tau2);
      sse += d * d;
    }
    const double share = 1.0 - sse / ss;
    if (share > best.share) best = {tau2, b, share};
  }
  return best;
}

}  // namespace

void name_misfit_in_time(const FitData& data, double drag, FitSummary* out) {
  const std::size_t n = out->P.size();
  if (n < 2 || data.t.size() != n || data.segment.size() != n || !(out->noise > 0.0)) return;
  // The shares count the samples the fit weighed (not the history-only or excluded ones); the
  // dwell's trend, adhesion and the baseline step read every sample, as the data show them.
  std::vector<double> r(n);
  std::vector<bool> counted(n);
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = out->P[i] - out->P_fit[i];
    counted[i] = data.sqrt_weight[i] > 0.0 && !(i < out->excluded.size() && out->excluded[i]);
    if (counted[i]) total += r[i] * r[i];
  }
  if (!(total > 0.0)) return;
  const double noise = out->noise;
  const std::vector<Piece> pieces = pieces_of(data.segment);
  struct Share {
    double share;
    std::string text;
  };
  std::vector<Share> shares;
  std::string dwell_note, retract_note;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& p = pieces[k];
    double ss = 0.0;
    std::size_t m = 0;
    for (std::size_t i = p.begin; i < p.end; ++i)
      if (counted[i]) ss += r[i] * r[i], ++m;
    const std::string name = name_of(p, k, pieces);
    if (m > 0) {
      const double rms = std::sqrt(ss / static_cast<double>(m));
      const std::size_t left_out = p.end - p.begin - m;
      shares.push_back({ss / total, name + " " + percent(ss / total) + " (rms " + short_number(rms) + " N, " +
                                        short_number(rms / noise) + " x noise" +
                                        (left_out ? ", over " + std::to_string(m) + " of its samples" : std::string()) +
                                        ")"});
    }
    if (name == "the dwell" && p.end - p.begin >= 20) {
      // The unfollowed relaxation: the residual's change over the dwell, its first tenth to its last.
      const std::size_t tenth = std::max<std::size_t>(1, (p.end - p.begin) / 10);
      const double change = mean_of(r, p.end - tenth, p.end) - mean_of(r, p.begin, p.begin + tenth);
      if (std::abs(change) > 3.0 * noise) {
        dwell_note = "over the dwell the data's force falls " + short_number(std::abs(change)) + " N " +
                     (change < 0.0 ? "further" : "less") + " than the law's (" + short_number(std::abs(change) / noise) +
                     " x noise)";
        const SecondScale s = second_scale(data.t, r, p.begin, p.end);
        if (s.share > 0.5)
          dwell_note += "; one exponential of tau2 = " + short_number(s.tau2) + " s and " + short_number(std::abs(s.amplitude)) +
                        " N takes " + percent(s.share) + " of the dwell's misfit: a second time scale the law lacks";
      }
    }
    if (name == "the retract") {
      double lowest_data = out->P[p.begin], lowest_fit = out->P_fit[p.begin];
      for (std::size_t i = p.begin; i < p.end; ++i) {
        lowest_data = std::min(lowest_data, out->P[i]);
        lowest_fit = std::min(lowest_fit, out->P_fit[i]);
      }
      if (lowest_fit - lowest_data > 5.0 * noise)
        retract_note = "the retract's lowest force lies " + short_number(lowest_fit - lowest_data) + " N (" +
                       short_number((lowest_fit - lowest_data) / noise) +
                       " x noise) below the fit's lowest: adhesion, which this fit does not model (a relaxing half-space "
                       "models it with adhesion.model maugis_dugdale and w)";
    }
  }
  std::stable_sort(shares.begin(), shares.end(), [](const Share& a, const Share& b) { return a.share > b.share; });
  std::string where;
  for (const Share& s : shares)
    if (s.share >= 0.01) where += (where.empty() ? "" : ", ") + s.text;
  // A baseline step: the model's force off contact is its baseline plus the drag; where the data
  // are off contact at both ends, their mean residuals there should agree.
  const double base = out->P_fit[0] - drag * (data.velocity.empty() ? 0.0 : data.velocity[0]);
  const auto off = [&](std::size_t i) {
    const double v = data.velocity.empty() ? 0.0 : data.velocity[i];
    return std::abs(out->P_fit[i] - drag * v - base) <= 1e-12 * std::max(1.0, std::abs(base)) + 1e-3 * noise;
  };
  std::size_t head = 0, tail = n;
  while (head < n && off(head)) ++head;
  while (tail > head && off(tail - 1)) --tail;
  std::string step_note, open_end;  // open_end: said only beside a misfit, never alone
  if (head >= 10 && n - tail >= 10) {
    const double step = mean_of(r, tail, n) - mean_of(r, 0, head);
    const double se = noise * std::sqrt(1.0 / static_cast<double>(head) + 1.0 / static_cast<double>(n - tail));
    if (std::abs(step) > 3.0 * noise && std::abs(step) > 5.0 * se)
      step_note = "the baseline steps by " + short_number(step) + " N (" + short_number(std::abs(step) / noise) +
                  " x noise) from the curve's start to its end, both off contact in the fit: drift, or a contact that "
                  "has not let go";
  } else if (n - tail < 10) {
    open_end = "; the fit is still in contact at the curve's end, so a baseline step cannot be told from it";
  }
  // Residuals that are noise overall can still hide a local feature (a drift of a few noise
  // sigmas, a short adhesive dip): it is named alone.
  std::string notes;
  for (const std::string* note : {&dwell_note, &retract_note, &step_note})
    if (!note->empty()) notes += "; " + *note;
  if (out->residual_structure)
    out->warnings.push_back("where the law misses (share of the residuals' sum of squares): " + where + notes + open_end);
  else if (!notes.empty())
    out->warnings.push_back("where the law misses, though its residuals are noise overall: " + notes.substr(2));
}

}  // namespace layerjkr::detail
