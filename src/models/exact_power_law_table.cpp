// Per-(nu, base, d) tables of the exact layer's power-law moments in ln(a/h).
#include "models/exact_power_law_table.hpp"
#include "models/stack_symbol.hpp"

#include <gsl/gsl_chebyshev.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>
#include <limits>
#include <string>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include "core/context_caches.hpp"
#include "core/disk_cache.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr int kOrder = 12;  // Chebyshev terms a piece (13 solves): 1e-10 against direct
                            // solves (16 terms: 1e-13, a third more solves; measured)
// Pieces in ln(a/h) - ln 0.01. Below a/h = 0.01 the normalised moments are constants plus
// O(a/h) (the half-space limit), so two pieces span [1e-6, 1e-4] and [1e-4, 0.01] (one
// piece there loses two digits with 13 points, measured); above, unit pieces (pieces
// twice as wide lose four digits below a/h = 1.5, measured), and half-unit pieces beyond
// a/h = 11, where a solve costs ~(a/h)^3 and a narrower piece spares the largest radii
// until a query needs them. The last ends at a/h = 220.
constexpr double kBreaks[] = {-9.210340371976183, -4.605170185988091, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0,
                              7.5, 8.0, 8.5, 9.0, 9.5, 10.0};
constexpr int kPieces = static_cast<int>(std::size(kBreaks)) - 1;

struct ChebFree {
  void operator()(gsl_cheb_series* s) const { gsl_cheb_free(s); }
};
using Cheb = std::unique_ptr<gsl_cheb_series, ChebFree>;

double x_min() { return std::log(0.01); }  // the origin of kBreaks

}  // namespace

struct ExactPowerLawTable::Pieces {
  struct Piece {
    std::array<Cheb, 4> series;  // int0/rho, end0, intf/(C rho^(d+1)), endf/(C rho^d)
  };
  std::array<std::once_flag, kPieces> built;
  std::array<Piece, kPieces> piece;
  std::once_flag kernel_made;
  std::unique_ptr<ExactLayerKernel> kernel;
};

double ExactPowerLawTable::max_rho() { return std::exp(x_min() + kBreaks[kPieces]); }
double ExactPowerLawTable::min_rho() { return std::exp(x_min() + kBreaks[0]); }

ExactPowerLawTable::ExactPowerLawTable(double nu, Base base, double d, const ExactLayerOptions& options)
    : ExactPowerLawTable(LayeredMedium::single(ElasticLayer{1.0, nu, 1.0, base}), d, options) {}

ExactPowerLawTable::ExactPowerLawTable(const LayeredMedium& unit_medium, double d, const ExactLayerOptions& options,
                                       std::shared_ptr<const DiskCache> disk, std::vector<double> disk_key)
    : d_(d),
      unit_profile_(make_power_law(1.0, d)),
      unit_medium_(unit_medium),
      options_(options),
      context_(options.context),
      disk_(std::move(disk)),
      disk_key_(std::move(disk_key)),
      pieces_(std::make_unique<Pieces>()) {
  C_ = unit_profile_->sneddon(1.0).I0;
  unit_medium_.validate("ExactPowerLawTable");
  options_.context = nullptr;
}

ExactPowerLawTable::~ExactPowerLawTable() = default;

const ExactLayerKernel& ExactPowerLawTable::unit_kernel() const {
  std::call_once(pieces_->kernel_made, [&] {
    ExactLayerOptions o = options_;
    o.context = context_.lock();  // null after the Context is gone: the global one's kernel (same numbers)
    pieces_->kernel = std::make_unique<ExactLayerKernel>(unit_medium_, o);
  });
  return *pieces_->kernel;
}

namespace {
constexpr const char* kPieceKind = "power-law-piece-1";  // a new revision whenever a piece's numbers change
}

// A piece from the disk cache (4 series of kOrder + 1 coefficients on the piece's interval),
// or solved and stored there.
void ExactPowerLawTable::build_piece(int k) const {
  Pieces::Piece& piece = pieces_->piece[static_cast<std::size_t>(k)];
  const bool disk = disk_ && disk_->enabled();
  std::vector<double> key;
  if (disk) {
    key = disk_key_;
    key.push_back(k);
    if (const std::optional<std::vector<double>> v = disk_->load(kPieceKind, key);
        v && v->size() == 4 * static_cast<std::size_t>(kOrder + 1)) {
      const double lo = x_min() + kBreaks[k], hi = x_min() + kBreaks[k + 1];
      for (std::size_t w = 0; w < 4; ++w) {
        Cheb c(gsl_cheb_alloc(kOrder));
        c->a = lo;
        c->b = hi;
        c->order_sp = kOrder;
        std::copy_n(v->begin() + static_cast<std::ptrdiff_t>(w * (kOrder + 1)), kOrder + 1, c->c);
        piece.series[w] = std::move(c);
      }
      return;
    }
  }
  solve_piece(k);
  if (disk) {
    std::vector<double> out;
    for (const Cheb& c : piece.series) out.insert(out.end(), c->c, c->c + kOrder + 1);
    disk_->store(kPieceKind, key, out);
  }
}

// The solves happen here, in C++, at the points where gsl_cheb_init will sample (its
// documented Chebyshev points); the sampler it calls only looks them up, so no exception
// crosses GSL's C frames.
void ExactPowerLawTable::solve_piece(int k) const {
  const double lo = x_min() + kBreaks[k], hi = x_min() + kBreaks[k + 1];
  std::vector<std::pair<double, std::array<double, 4>>> solved;
  for (int j = 0; j <= kOrder; ++j) {
    const double y = std::cos(boost::math::constants::pi<double>() * (j + 0.5) / (kOrder + 1.0));
    const double xs = y * 0.5 * (hi - lo) + 0.5 * (hi + lo), r = std::exp(xs);
    const ExactMoments m = exact_moments(unit_kernel(), *unit_profile_, r);
    solved.push_back({xs, {m.int0 / r, m.end0, m.intf / (C_ * std::pow(r, d_ + 1.0)),
                           m.endf / (C_ * std::pow(r, d_))}});
  }
  struct Sampler {
    const std::vector<std::pair<double, std::array<double, 4>>>* solved;
    std::size_t which;
    static double at(double xs, void* p) {
      const auto* s = static_cast<const Sampler*>(p);
      for (const auto& [x, v] : *s->solved)
        if (std::abs(x - xs) <= 1e-12 * (1.0 + std::abs(x))) return v[s->which];
      return std::numeric_limits<double>::quiet_NaN();  // checked below
    }
  };
  Pieces::Piece& piece = pieces_->piece[static_cast<std::size_t>(k)];
  for (std::size_t w = 0; w < 4; ++w) {
    Sampler sampler{&solved, w};
    gsl_function f{&Sampler::at, &sampler};
    Cheb c(gsl_cheb_alloc(kOrder));
    gsl_cheb_init(c.get(), &f, lo, hi);
    if (!std::isfinite(gsl_cheb_eval(c.get(), 0.5 * (lo + hi))))
      throw NumericalError("layerjkr exact layer: power-law table piece " + std::to_string(k) +
                           " is not finite");
    piece.series[w] = std::move(c);
  }
}

ExactMoments ExactPowerLawTable::at(double rho) const {
  if (!covers(rho))
    throw DomainError("ExactPowerLawTable::at", "a/h", rho,
                      "[" + format_double(min_rho()) + ", " + format_double(max_rho()) + "]");
  const double x = std::log(rho);
  const int k = std::clamp<int>(static_cast<int>(std::upper_bound(std::begin(kBreaks), std::end(kBreaks),
                                                                    x - x_min()) - std::begin(kBreaks)) - 1,
                                0, kPieces - 1);
  const Pieces::Piece& piece = pieces_->piece[static_cast<std::size_t>(k)];
  std::call_once(pieces_->built[static_cast<std::size_t>(k)], [&] { build_piece(k); });
  const double n0 = gsl_cheb_eval(piece.series[0].get(), x), e0 = gsl_cheb_eval(piece.series[1].get(), x);
  const double nf = gsl_cheb_eval(piece.series[2].get(), x), ef = gsl_cheb_eval(piece.series[3].get(), x);
  const double rd = std::pow(rho, d_);
  return {n0 * rho, nf * C_ * rd * rho, e0, ef * C_ * rd};
}

std::shared_ptr<const ExactPowerLawTable> shared_power_law_table(double nu, Base base, double d,
                                                                 const ExactLayerOptions& o) {
  return shared_power_law_table(LayeredMedium::single(ElasticLayer{1.0, nu, 1.0, base}), d, o);
}

std::shared_ptr<const ExactPowerLawTable> shared_power_law_table(const LayeredMedium& medium, double d,
                                                                 const ExactLayerOptions& o) {
  // In units of the top layer: E1 = h1 = 1, every other modulus and thickness a ratio.
  LayeredMedium unit = medium;
  const StackLayer top = medium.layers.at(0);
  for (StackLayer& l : unit.layers) {
    l.E /= top.E;
    l.h /= top.h;
  }
  if (unit.substrate) unit.substrate->E /= top.E;
  const PowerLawTableKey key{StackSymbol(unit, "exact_power_law_table").signature(), d, o.points_per_panel,
                             o.panel_width, o.min_panels};
  auto& caches = context_caches(o.context);
  return caches.power_law_tables.get(key, [&] {
    std::vector<double> disk_key = std::get<0>(key);
    disk_key.insert(disk_key.end(), {d, static_cast<double>(o.points_per_panel), o.panel_width,
                                     static_cast<double>(o.min_panels)});
    return std::make_shared<const ExactPowerLawTable>(unit, d, o, caches.disk, std::move(disk_key));
  });
}

}  // namespace layerjkr::detail
