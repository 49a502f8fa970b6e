// The retract read from its samples alone (retract_reading.hpp): baseline, pull-off, contact
// flags, release and tail.
#include "fit/data/retract_reading.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/short_number.hpp"
#include "fit/run/fit_steps.hpp"

namespace layerjkr::detail {
namespace {

constexpr std::size_t kMinRestSamples = 3;
// The free part is the first (approach) or last (retract) tenth of a branch's samples.
constexpr std::size_t kRestFraction = 10;

// A baseline may drift by this fraction of the force span over its part and still be at rest:
// real free parts carry virtual deflection and slow noise the third differences do not see (an
// Asylum map: a trend of 1.7 nN over the retract's last tenth, 4 times the third-difference
// noise, 0.07 % of its 2.3 uN span), while a part still in contact changes by a good part of it.
constexpr double kRestDrift = 0.01;
// Samples whose mean says a gradual return has settled at the baseline (read_retract).
constexpr std::size_t kSettleWindow = 5;

// A candidate free part, measured once: its level (median), spread (MAD sigma) and linear trend
// over its span of delta, all [N]; `valid` false for fewer than kMinRestSamples samples.
struct Part {
  bool valid = false;
  double level = 0.0, spread = 0.0, trend = 0.0;
};

Part measure_part(const FitData& data, const std::vector<std::size_t>& idx) {
  Part part;
  if (idx.size() < kMinRestSamples) return part;
  std::vector<double> P;
  P.reserve(idx.size());
  for (std::size_t i : idx) P.push_back(data.P[i]);
  part.level = median(P);
  for (double& v : P) v = std::abs(v - part.level);
  part.spread = kMadToSigma * median(P);
  part.trend = linear_trend(data, idx);
  part.valid = true;
  return part;
}

// At rest: no trend beyond 3 noise sigmas (or the drift allowed, [N]) over its span of delta and
// a spread of at most twice the noise (or the drift allowed).
bool at_rest(const Part& part, double noise, double drift) {
  return part.valid && noise > 0.0 && part.spread <= std::max(2.0 * noise, drift) &&
         part.trend <= std::max(3.0 * noise, drift);
}

std::string samples(std::size_t n) { return std::to_string(n) + (n == 1 ? " sample" : " samples"); }

}  // namespace

PullOffMeasure measure_pull_off(const FitData& data, double force_span) {
  PullOffMeasure m;
  std::vector<std::size_t> retract, approach;
  for (std::size_t i = 0; i < data.P.size(); ++i) (data.retract[i] ? retract : approach).push_back(i);
  if (retract.empty()) return m;
  m.any_retract = true;
  const double floor = kSignificantForceFraction * force_span;
  m.noise = std::max(third_difference_noise(data.P, retract), floor);
  m.minimum = *std::min_element(retract.begin(), retract.end(), [&](auto i, auto j) { return data.P[i] < data.P[j]; });
  // The retract's own free part first (JPK's and Asylum's adhesion are measured against it), then
  // the approach's; either must lie wholly on its side of the contact.
  const std::size_t nr = std::max(kMinRestSamples, retract.size() / kRestFraction);
  std::vector<std::size_t> tail_part;
  if (retract.size() > nr) tail_part.assign(retract.end() - static_cast<std::ptrdiff_t>(nr), retract.end());
  const bool after_minimum = !tail_part.empty() && tail_part.front() > m.minimum;
  const std::size_t na = std::max(kMinRestSamples, approach.size() / kRestFraction);
  std::vector<std::size_t> head_part;
  if (approach.size() > na) head_part.assign(approach.begin(), approach.begin() + static_cast<std::ptrdiff_t>(na));
  // At rest strictly (noise alone), or within the drift allowed where both free parts are and
  // agree on their level: a curve in contact at its end (a rig near its grips limit) changes
  // slowly there too, but never sits at the level of the approach's start.
  const double drift = kRestDrift * force_span;
  const Part tail = after_minimum ? measure_part(data, tail_part) : Part{};
  const Part head = measure_part(data, head_part);
  const bool agree = at_rest(tail, m.noise, drift) && at_rest(head, m.noise, drift) &&
                     std::abs(tail.level - head.level) <= drift;
  const bool tail_rests = at_rest(tail, m.noise, 0.0) || agree;
  const bool head_rests = at_rest(head, m.noise, 0.0) || agree;
  const Part* rest = tail_rests ? &tail : head_rests ? &head : nullptr;
  if (rest) {
    const bool from_tail = rest == &tail;
    m.baseline = rest->level;
    m.has_baseline = true;
    m.baseline_source = "the median of the " + std::string(from_tail ? "last " : "first ") +
                        samples(from_tail ? tail_part.size() : head_part.size()) + " of the " +
                        (from_tail ? "retract" : "approach") + ", at rest";
    // Samples at rest measure the noise directly; a steep curve inflates its third differences.
    if (rest->spread > floor) m.noise = std::min(m.noise, rest->spread);
  } else {
    m.baseline_source = "the force's zero: neither the end of the retract nor the start of the approach is at rest";
  }
  m.pull_off = data.P[m.minimum] - m.baseline;
  m.adhesive = m.pull_off < -std::max(kSignificantSigmas * m.noise, floor);
  return m;
}

void record_pull_off(const PullOffMeasure& m, FitSummary* out) {
  out->pull_off_force = m.pull_off;
  out->pull_off_baseline = m.baseline;
  out->pull_off_baseline_source = m.baseline_source;
  out->pull_off_baseline_measured = m.has_baseline;
}

const char* to_string(Release r) {
  switch (r) {
    case Release::none: return "";
    case Release::at_end: return "none: the data end at the force minimum";
    case Release::at_minimum: return "a jump at the force minimum";
    case Release::held_then_jump: return "held past the force minimum, then a jump";
    case Release::held_to_end: return "held to the end";
    case Release::gradual: return "gradual: a tail, excluded";
    case Release::held_gradual: return "gradual: held in contact back to the baseline";
  }
  return "";
}

namespace {

// The first position k >= from (in ret) where the return has settled: the mean of the kSettleWindow
// samples from k lies within one of its standard errors of the baseline; ret.size() if none does.
std::size_t settled_from(const std::vector<double>& P, const std::vector<std::size_t>& ret, std::size_t from,
                         double baseline, double noise) {
  for (std::size_t k = from; k + kSettleWindow <= ret.size(); ++k) {
    double sum = 0.0;
    for (std::size_t j = k; j < k + kSettleWindow; ++j) sum += P[ret[j]];
    if (std::abs(sum / kSettleWindow - baseline) <= noise / std::sqrt(static_cast<double>(kSettleWindow))) return k;
  }
  return ret.size();
}

}  // namespace

RetractReading read_retract(const FitData& data, const FitOptions& options, double force_span, bool hold_gradual_rise) {
  RetractReading r;
  r.pull_off = measure_pull_off(data, force_span);
  const PullOffMeasure& m = r.pull_off;
  r.tail.assign(data.P.size(), false);
  if (!m.any_retract || !m.adhesive || data.radius_driven) return r;
  std::vector<std::size_t> ret;
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (data.retract[i]) ret.push_back(i);
  const std::size_t n = ret.size();
  const std::size_t lowest = static_cast<std::size_t>(std::find(ret.begin(), ret.end(), m.minimum) - ret.begin());
  const double dip = -m.pull_off, floor = kSignificantForceFraction * force_span;
  const double sigmas = options.exclusion_sigmas > 0.0 ? options.exclusion_sigmas : 3.0;
  const double back_band = std::max(sigmas * m.noise, floor);
  const auto P = [&](std::size_t k) { return data.P[ret[k]]; };
  std::size_t back = n;  // the first sample after the minimum back at the baseline
  for (std::size_t k = lowest + 1; k < n && back == n; ++k)
    if (std::abs(P(k) - m.baseline) <= back_band) back = k;
  // The largest rise in one sample after the minimum, up to and including the step back.
  std::size_t jump_at = n;
  double jump = 0.0;
  for (std::size_t k = lowest + 1; k <= std::min(back, n - 1); ++k)
    if (P(k) - P(k - 1) > jump) {
      jump = P(k) - P(k - 1);
      jump_at = k;
    }
  // A release is a discontinuity: a significant rise after which the force changes by far less per
  // sample (the baseline, or a slower tail). The branch before it may be steep (a lever lets go
  // where dP/d delta = -k), but a tail's steps shrink gradually (0.78 of the previous step for one
  // relaxing at 4 samples per e-fold), and the branch's own steps grow towards the grips limit.
  const double after_jump = jump_at + 1 < n ? std::max(P(jump_at + 1) - P(jump_at), 0.0) : jump;
  const double jump_threshold =
      std::max({kSignificantSigmas * std::sqrt(2.0) * m.noise, kReleaseStepRatio * after_jump, floor});
  std::size_t last_contact = lowest, tail_begin = n, tail_end = n;  // positions in ret
  const std::string dip_text = short_number(m.pull_off) + " N";
  if (lowest + 1 == n) {
    r.release = Release::at_end;
    r.rule = "the retract ends at its force minimum (" + dip_text + "): every retract sample in contact";
  } else if (jump_at < n && jump >= jump_threshold) {
    last_contact = jump_at - 1;
    r.jump = jump;
    r.held_past_minimum = last_contact - lowest;
    tail_begin = jump_at;
    tail_end = back;
    const std::string jump_text = "a jump of " + short_number(jump) + " N (" + short_number(jump / dip) + " of the pull-off)";
    double rise = 0.0;
    for (std::size_t k = lowest + 1; k <= last_contact; ++k) rise = std::max(rise, P(k) - P(lowest));
    if (rise > back_band) {
      r.release = Release::held_then_jump;
      r.rule = "the contact holds " + samples(r.held_past_minimum) + " past the force minimum (" + dip_text +
               "), the force rising " + short_number(rise) + " N, and is released by " + jump_text;
    } else {
      r.release = Release::at_minimum;
      r.rule = "the retract is released at its force minimum (" + dip_text + ") by " + jump_text;
    }
  } else if (back == n && P(n - 1) - m.baseline < -kHeldToEndFraction * dip) {
    r.release = Release::held_to_end;
    last_contact = n - 1;
    r.held_past_minimum = n - 1 - lowest;
    r.rule = "the force rises " + short_number(P(n - 1) - P(lowest)) + " N past its minimum (" + dip_text +
             ") and ends " + short_number(m.baseline - P(n - 1)) + " N below the baseline without a release: every "
             "retract sample in contact, as under displacement control";
  } else if (hold_gradual_rise) {
    r.release = Release::held_gradual;
    last_contact = back - 1;
    r.held_past_minimum = last_contact - lowest;
    // A branch returning gradually enters the noise band before it ends: the samples from there until
    // the return has settled are in contact near zero force or at rest, and the data cannot tell.
    // Counted at rest they pull the baseline towards the branch; they are excluded instead.
    tail_begin = back;
    tail_end = settled_from(data.P, ret, back, m.baseline, m.noise);
    // A return that never settles (a baseline that drifts within what the rest reading accepts), or
    // settles later than the held branch is long, is not this case: nothing more is excluded.
    if (tail_end == n || tail_end - back > std::max(kSettleWindow, r.held_past_minimum)) tail_end = back;
    r.rule = "the force returns from its minimum (" + dip_text + ") to the baseline without a jump; read as the "
             "contact's own branch, held for " + samples(r.held_past_minimum) + " past the minimum";
  } else {
    r.release = Release::gradual;
    tail_begin = lowest + 1;
    tail_end = back;
    r.rule = "the force returns from its minimum (" + dip_text + ") towards the baseline without a jump (the largest "
             "rise in one sample " + short_number(jump) + " N, below " + short_number(jump_threshold) + " N): a tail";
  }
  r.contact.assign(data.P.size(), -1);
  for (std::size_t k = 0; k < n; ++k) r.contact[ret[k]] = k <= last_contact ? 1 : 0;
  for (std::size_t k = tail_begin; k < tail_end && k < n; ++k) r.tail[ret[k]] = true;
  r.tail_count = static_cast<std::size_t>(std::count(r.tail.begin(), r.tail.end(), true));
  if (r.tail_count > 0 && r.release == Release::held_gradual)
    r.rule += "; the " + samples(r.tail_count) + " from there until the return settles (the mean of the next " +
              std::to_string(kSettleWindow) + " within one standard error of the baseline) " +
              (options.exclusion_sigmas > 0.0 ? "excluded" : "kept (exclusion_sigmas = 0)") +
              ": in contact near zero force or at rest, the data cannot tell";
  else if (r.tail_count > 0)
    r.rule += options.exclusion_sigmas > 0.0
                  ? "; " + samples(r.tail_count) + " after the release not yet back within " + short_number(sigmas) +
                        " noise sigmas of the baseline excluded (necking, peeling, a viscoelastic tail)"
                  : "; the " + samples(r.tail_count) + " after it not yet back at the baseline are kept "
                    "(exclusion_sigmas = 0)";
  r.rule += "; baseline " + short_number(m.baseline) + " N (" + m.baseline_source + "), noise " +
            short_number(m.noise) + " N";
  return r;
}

void trim_held_to_model(RetractReading& reading, const FitOptions& options, const std::vector<double>& weights,
                        FitData& data, CurveEvaluator& ev, const std::vector<double>& x,
                        const std::function<bool()>& resolve) {
  if (reading.release != Release::held_gradual) return;
  const std::size_t minimum = reading.pull_off.minimum;
  std::size_t trimmed = 0;
  for (int pass = 0; pass < 4; ++pass) {
    if (!ev.evaluate(x.data(), false)) return;
    std::size_t first = data.P.size();
    for (std::size_t i = minimum + 1; i < data.P.size() && first == data.P.size(); ++i)
      if (data.retract[i] && data.contact[i] == 1 && ev.clamped()[i]) first = i;
    if (first == data.P.size()) break;
    for (std::size_t i = first; i < data.P.size(); ++i)
      if (data.retract[i] && data.contact[i] == 1) {
        reading.contact[i] = 0;
        reading.tail[i] = true;
        --reading.held_past_minimum;
        ++trimmed;
      }
    data.sqrt_weight = weights;
    apply_reading(reading, options, data);
    ev.invalidate();
    if (!resolve()) break;
  }
  reading.tail_count = static_cast<std::size_t>(std::count(reading.tail.begin(), reading.tail.end(), true));
  if (trimmed > 0)
    reading.rule += "; the model's branch ends after " + samples(reading.held_past_minimum) + " of them, the " +
                    samples(trimmed) + " beyond excluded as a tail";
}

void apply_reading(const RetractReading& reading, const FitOptions& options, FitData& data) {
  data.contact = reading.contact;
  data.dip = reading.pull_off.any_retract ? reading.pull_off.pull_off : 0.0;
  data.adhesive = reading.pull_off.adhesive;
  if (options.exclusion_sigmas > 0.0)
    for (std::size_t i = 0; i < data.P.size(); ++i)
      if (reading.tail[i]) data.sqrt_weight[i] = 0.0;
}

}  // namespace layerjkr::detail
