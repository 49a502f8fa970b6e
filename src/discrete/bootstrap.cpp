// The residual bootstrap of the two-model and single-model reconstructions (discrete.hpp).
#include <cmath>
#include <map>
#include <optional>
#include <random>

#include "core/line_fit.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {

void BootstrapOptions::validate() const {
  if (replicates < 20 || replicates > 100000) throw DomainError("BootstrapOptions", "replicates", replicates, "20 .. 100000");
}

namespace {

using Rng = std::mt19937_64;

// Fitted values plus residuals drawn with replacement from `residuals`, inflated by
// sqrt(n / (n - p)) because least-squares residuals are smaller than the noise.
std::vector<double> resample(const std::vector<double>& fitted, const std::vector<double>& residuals, int p, Rng& rng) {
  const auto n = residuals.size();
  const double inflate = n > static_cast<std::size_t>(p) ? std::sqrt(double(n) / double(n - static_cast<std::size_t>(p))) : 1.0;
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::vector<double> out(fitted.size());
  for (std::size_t i = 0; i < fitted.size(); ++i) out[i] = fitted[i] + inflate * residuals[pick(rng)];
  return out;
}

// A flat-punch data set with the residuals of each radius's line reshuffled within that radius.
class FlatResampler {
 public:
  explicit FlatResampler(const FlatPunchData& flat) : flat_(flat) {
    std::map<double, std::vector<std::size_t>> steps;
    for (std::size_t i = 0; i < flat.a.size(); ++i) steps[flat.a[i]].push_back(i);
    for (auto& [a, idx] : steps) {
      const detail::LineFit line = detail::fit_line(flat.delta, flat.P, idx);
      Group g{idx, {}, {}};
      for (std::size_t i : idx) {
        const double fit = line.mean_y + line.slope * (flat.delta[i] - line.mean_x);
        g.fitted.push_back(fit);
        g.residuals.push_back(flat.P[i] - fit);
      }
      groups_.push_back(std::move(g));
    }
  }
  FlatPunchData draw(Rng& rng) const {
    FlatPunchData d = flat_;
    for (const Group& g : groups_) {
      const std::vector<double> P = resample(g.fitted, g.residuals, 2, rng);
      for (std::size_t k = 0; k < g.idx.size(); ++k) d.P[g.idx[k]] = P[k];
    }
    return d;
  }

 private:
  struct Group {
    std::vector<std::size_t> idx;
    std::vector<double> fitted, residuals;
  };
  const FlatPunchData& flat_;
  std::vector<Group> groups_;
};

// One column of the convex data resampled in ln y about its log-log fit (positive samples only;
// the zero row of first contact stays).
class LogColumnResampler {
 public:
  LogColumnResampler(const std::vector<double>& x, const std::vector<double>& y, const DiscreteOptions& o, const std::string& what)
      : y_(y) {
    const auto fit = fit_log_log(x, y, o.smoothing, o.max_degree, what);
    p_ = fit->parameters();
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i] > 0.0 && y[i] > 0.0) {
        idx_.push_back(i);
        fitted_.push_back(std::log(fit->value(x[i])));
        residuals_.push_back(std::log(y[i]) - fitted_.back());
      }
  }
  std::vector<double> draw(Rng& rng) const {
    std::vector<double> y = y_;
    const std::vector<double> ln_y = resample(fitted_, residuals_, p_, rng);
    for (std::size_t k = 0; k < idx_.size(); ++k) y[idx_[k]] = std::exp(ln_y[k]);
    return y;
  }

 private:
  std::vector<double> y_;
  std::vector<std::size_t> idx_;
  std::vector<double> fitted_, residuals_;
  int p_ = 1;
};

class RunningStd {
 public:
  void add(double x) {
    ++n_;
    const double d = x - mean_;
    mean_ += d / n_;
    m2_ += d * (x - mean_);
  }
  double std() const { return n_ > 1 ? std::sqrt(m2_ / (n_ - 1)) : NAN; }
  int count() const { return static_cast<int>(n_); }

 private:
  double n_ = 0.0, mean_ = 0.0, m2_ = 0.0;
};

}  // namespace

DiscreteUncertainty bootstrap_discrete(const FlatPunchData& flat, const ConvexData& convex, double w,
                                       const std::vector<double>& radii, DiscreteApproach approach,
                                       const DiscreteOptions& options, const BootstrapOptions& bootstrap) {
  options.validate();
  bootstrap.validate();
  if (static_cast<double>(bootstrap.replicates) * static_cast<double>(radii.size()) > kMaxBootstrapEvaluations)
    throw InputError("bootstrap: " + std::to_string(bootstrap.replicates) + " replicates x " +
                     std::to_string(radii.size()) + " radii exceed the limit of " + format_double(kMaxBootstrapEvaluations) +
                     " evaluations (200 x 100 000 take 14 s; docs/development.md, Limits): ask fewer replicates or radii");
  const bool two = approach == DiscreteApproach::two_models;
  // The data as given must make a model; replicates that do not are counted.
  const ContactModelPtr base = two ? make_discrete_model(flat, convex, options) : make_single_model(convex, options);
  JkrSolution(base, w).curve(radii);
  const FlatResampler flat_draws(flat);
  const LogColumnResampler P_draws(convex.delta, convex.P, options, convex.source);
  std::optional<LogColumnResampler> a_draws;
  if (!two) a_draws.emplace(convex.delta, convex.a, options, convex.source + " (a)");

  DiscreteUncertainty out;
  out.a = radii;
  out.replicates = bootstrap.replicates;
  std::vector<RunningStd> P_spread(radii.size()), delta_spread(radii.size());
  RunningStd pull_off, zero_load;
  Rng rng(bootstrap.seed);
  for (int r = 0; r < bootstrap.replicates; ++r) {
    ConvexData c = convex;
    c.P = P_draws.draw(rng);
    try {
      ContactModelPtr model;
      if (two) {
        model = make_discrete_model(flat_draws.draw(rng), c, options);
      } else {
        c.a = a_draws->draw(rng);
        model = make_single_model(c, options);
      }
      const JkrSolution jkr(model, w);
      for (std::size_t k = 0; k < radii.size(); ++k) {
        // A radius at the edge of the data may fall outside a replicate's range: skip it there.
        if (radii[k] < model->min_radius() || radii[k] > model->max_radius()) continue;
        const AdhesiveState s = jkr.at(radii[k]);
        P_spread[k].add(s.P), delta_spread[k].add(s.delta);
      }
      if (const auto po = jkr.pull_off()) pull_off.add(po->P);
      if (const auto a0 = jkr.zero_load_radius()) zero_load.add(*a0);
    } catch (const Error&) {
      ++out.failed;  // the resampled data made no model (e.g. the two sets no longer overlap)
    }
  }
  for (std::size_t k = 0; k < radii.size(); ++k) {
    out.P_err.push_back(P_spread[k].std());
    out.delta_err.push_back(delta_spread[k].std());
    out.used.push_back(P_spread[k].count());
  }
  out.pull_off_force_err = pull_off.std();
  out.zero_load_radius_err = zero_load.std();
  if (out.failed * 2 > out.replicates)
    throw NumericalError("bootstrap_discrete: " + std::to_string(out.failed) + " of " + std::to_string(out.replicates) +
                         " replicates made no model; the data's noise is too large for an error estimate");
  return out;
}

}  // namespace layerjkr
