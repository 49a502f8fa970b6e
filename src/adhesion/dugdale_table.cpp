// Per-(medium, d) tables of the Dugdale states' linear parts (dugdale_table.hpp).
#include "adhesion/dugdale_table.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <string>

#include <boost/math/constants/constants.hpp>

#include "core/context_caches.hpp"
#include "core/disk_cache.hpp"
#include "core/parallel.hpp"
#include "layerjkr/error.hpp"
#include "models/stack_symbol.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr const char* kPieceKind = "dugdale-piece-4";  // a new revision whenever a piece's numbers change

// Pieces in x = ln(c/h): two decades a piece below c/h = 0.01 (the ratios are 1 + O(c/h)
// there), then half decades to 100, where the layer's effect grows fastest.
constexpr double kDecades[] = {-6.0, -4.0, -2.0, -1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0};
constexpr int kPieces = static_cast<int>(std::size(kDecades)) - 1;
constexpr int kNx = 12, kNt = 16;   // Chebyshev points a piece in x and a sub-piece in its coordinate
constexpr int kChecks = 6;          // direct solves between them, for the measured error
constexpr int kRatios = 4;          // D, P, G, F
constexpr double kLn10 = 2.302585092994046;

double x_at(int k) { return kDecades[k] * kLn10; }

// T_0..T_{n-1} at y in [-1, 1].
void chebyshev(double y, int n, double* t) {
  t[0] = 1.0;
  if (n > 1) t[1] = y;
  for (int j = 2; j < n; ++j) t[j] = 2.0 * y * t[j - 1] - t[j - 2];
}

double node(int i, int n) { return std::cos(kPi * (i + 0.5) / n); }  // Chebyshev points of the first kind

// The second coordinate, in kSub sub-pieces of [0, c]. The upper half a in [c/2, c] in
// y = ln(1 + sqrt(c - a)) / ln(1 + sqrt(c/2)), linear in theta = acos(a/c) near a = c (so the
// ratios stay smooth there) and logarithmic in the zone's width c - a beyond h, where a thin
// layer's ratios change most, in four quarters; the lower half a in [0, c/2] in
// v = ln(1 + a) / ln(1 + c/2), logarithmic in a beyond h, in two halves. (One Chebyshev series
// in theta over [0, pi/2] missed 1e-4 at c/h = 17; these reach 1e-7 at c/h = 90, measured.)
constexpr int kUpper = 4, kLower = 2, kSub = kUpper + kLower;

struct SubPoint {
  int sub;   // which sub-piece
  double u;  // its coordinate mapped to [-1, 1]
};

SubPoint sub_of(double a, double c) {
  if (a >= 0.5 * c) {
    const double y = std::log1p(std::sqrt(std::max(0.0, c - a))) / std::log1p(std::sqrt(0.5 * c));
    const int k = std::clamp(static_cast<int>(y * kUpper), 0, kUpper - 1);
    return {k, std::clamp(2.0 * (y * kUpper - k) - 1.0, -1.0, 1.0)};
  }
  const double v = std::log1p(a) / std::log1p(0.5 * c);
  const int k = std::clamp(static_cast<int>(v * kLower), 0, kLower - 1);
  return {kUpper + k, std::clamp(2.0 * (v * kLower - k) - 1.0, -1.0, 1.0)};
}

double a_of(int sub, double u, double c) {
  if (sub < kUpper) {
    const double y = (sub + 0.5 * (u + 1.0)) / kUpper;
    const double z = std::expm1(y * std::log1p(std::sqrt(0.5 * c)));
    return std::clamp(c - z * z, 0.5 * c, c);
  }
  const double v = (sub - kUpper + 0.5 * (u + 1.0)) / kLower;
  return std::clamp(std::expm1(v * std::log1p(0.5 * c)), 0.0, 0.5 * c);
}

}  // namespace

// One piece of x: for each sub-piece kRatios tensor series, coefficient (sub, ratio, jx, jt) at
// [((sub * kRatios + r) * kNx + jx) * kNt + jt].
struct DugdaleTable::Piece {
  std::vector<double> coef;
  double error = 0.0;
};

double DugdaleTable::min_c() { return std::pow(10.0, kDecades[0]); }
double DugdaleTable::max_c() { return std::pow(10.0, kDecades[kPieces]); }

DugdaleTable::DugdaleTable(const LayeredMedium& unit_medium, double d, const ExactLayerOptions& options,
                           std::shared_ptr<const DiskCache> disk, std::vector<double> disk_key)
    : d_(d),
      unit_medium_(unit_medium),
      options_(options),
      disk_(std::move(disk)),
      disk_key_(std::move(disk_key)),
      built_(std::make_unique<std::array<std::once_flag, 16>>()),
      pieces_(std::make_unique<std::array<std::unique_ptr<Piece>, 16>>()) {
  static_assert(kPieces <= 16, "the once flags");
  options_.context = nullptr;  // the table lives in a Context's cache: it must not keep it alive
  options_.max_a_over_h = std::max(options_.max_a_over_h, max_c());
  unit_medium_.validate("DugdaleTable");
}

DugdaleTable::~DugdaleTable() = default;

const DugdaleSolver& DugdaleTable::solver() const {
  std::call_once(solver_made_, [&] {
    auto kernel = std::make_shared<ExactLayerKernel>(unit_medium_, options_);
    solver_ = std::make_unique<DugdaleSolver>(make_power_law(1.0, d_), std::move(kernel));
  });
  return *solver_;
}

DugdaleTable::Parts DugdaleTable::half_space(double a, double c, double d) {
  const double theta = std::acos(std::clamp(a / c, 0.0, 1.0)), s = std::sin(theta), co = std::cos(theta);
  Parts p;
  p.D = -2.0 * c * s;
  p.P = -2.0 * c * c * (s * co + theta);
  // theta sin - 1 + cos without cancellation at small theta: theta sin - 2 sin^2(theta/2)
  const double half = std::sin(0.5 * theta);
  p.G = (4.0 * c / kPi) * (theta * s - 2.0 * half * half);
  // sin cos - theta cos 2theta = sin(2 theta)/2 - theta cos(2 theta); small theta: 4 theta^3 / 3
  const double t2 = 2.0 * theta;
  const double shape = theta < 1e-3 ? (4.0 / 3.0) * theta * theta * theta * (1.0 - 0.4 * theta * theta)
                                    : 0.5 * std::sin(t2) - theta * std::cos(t2);
  p.F = (2.0 * std::pow(c, d) / kPi) * shape;
  return p;
}

namespace {

std::size_t index(int sub, int q, int jx, int jt) {
  const auto at = [](int i) { return static_cast<std::size_t>(i); };
  return ((at(sub) * at(kRatios) + at(q)) * at(kNx) + at(jx)) * at(kNt) + at(jt);
}

// The series of one sub-piece at (ux, ut) in [-1, 1]^2, ratio q.
double series(const std::vector<double>& coef, int sub, int q, double ux, double ut) {
  double tx[kNx], tt[kNt];
  chebyshev(ux, kNx, tx);
  chebyshev(ut, kNt, tt);
  double v = 0.0;
  for (int jx = 0; jx < kNx; ++jx) {
    const double* row = &coef[index(sub, q, jx, 0)];
    double inner = 0.0;
    for (int jt = 0; jt < kNt; ++jt) inner += row[jt] * tt[jt];
    v += inner * tx[jx];
  }
  return v;
}

}  // namespace

void DugdaleTable::build(int k, Piece& piece) const {
  const std::size_t size = index(kSub, 0, 0, 0);  // one past the last point
  const bool disk = disk_ && disk_->enabled();
  std::vector<double> key;
  if (disk) {
    key = disk_key_;
    key.insert(key.end(), {static_cast<double>(k), kNx, kNt, kSub, kDecades[k], kDecades[k + 1]});
    if (const std::optional<std::vector<double>> v = disk_->load(kPieceKind, key); v && v->size() == size + 1) {
      piece.coef.assign(v->begin(), v->end() - 1);
      piece.error = v->back();
      return;
    }
  }
  const DugdaleSolver& s = solver();
  const int nodes = options_.points_per_panel;
  const double x0 = x_at(k), x1 = x_at(k + 1);
  const auto c_at = [&](double ux) { return std::exp(0.5 * (x0 + x1) + 0.5 * (x1 - x0) * ux); };
  // The ratios to the half-space (dugdale_table.hpp): signed, since on an incompressible layer
  // tension can push the indenter in (D > 0) where the half-space's pulls it out.
  const auto ratios = [&](double a, double c, double* out) {
    const DugdaleParts p = s.parts(a, c, nodes);
    const Parts hs = half_space(a, c, d_);
    out[0] = p.D / hs.D;
    out[1] = p.P / hs.P;
    out[2] = p.G / hs.G;
    out[3] = p.F / hs.F;
    for (int q = 0; q < kRatios; ++q)
      if (!std::isfinite(out[q]))
        throw NumericalError("layerjkr: a Dugdale part at a/h = " + format_double(a) + ", c/h = " + format_double(c) +
                             " is not finite");
  };
  std::vector<double> f(size);
  parallel_for(kSub * kNx * kNt, [&](int i) {
    const int sub = i / (kNx * kNt), ix = (i / kNt) % kNx, it = i % kNt;
    const double c = c_at(node(ix, kNx));
    double r[kRatios];
    ratios(a_of(sub, node(it, kNt), c), c, r);
    for (int q = 0; q < kRatios; ++q) f[index(sub, q, ix, it)] = r[q];
  });
  // Coefficients by the discrete orthogonality of T_j at the points (a DCT in each direction).
  piece.coef.assign(size, 0.0);
  double tx[kNx], tt[kNt];
  for (int ix = 0; ix < kNx; ++ix) {
    chebyshev(node(ix, kNx), kNx, tx);
    for (int it = 0; it < kNt; ++it) {
      chebyshev(node(it, kNt), kNt, tt);
      for (int sub = 0; sub < kSub; ++sub)
        for (int q = 0; q < kRatios; ++q) {
          const double v = f[index(sub, q, ix, it)] * (2.0 / kNx) * (2.0 / kNt);
          for (int jx = 0; jx < kNx; ++jx)
            for (int jt = 0; jt < kNt; ++jt)
              piece.coef[index(sub, q, jx, jt)] += v * tx[jx] * tt[jt] * (jx == 0 ? 0.5 : 1.0) * (jt == 0 ? 0.5 : 1.0);
        }
    }
  }
  // The measured error: direct solves at points between the Chebyshev points (deterministic,
  // spread over every sub-piece), against the series, relative to the larger of the ratio and 1
  // (the part and its half-space size).
  std::vector<double> errors(static_cast<std::size_t>(kSub * kChecks), 0.0);
  parallel_for(kSub * kChecks, [&](int i) {
    const int sub = i / kChecks, m = i % kChecks;
    const double ux = -0.9 + 1.8 * (m + 0.37) / kChecks, ut = 0.95 - 1.9 * std::fmod(0.618034 * (m + 1), 1.0);
    const double c = c_at(ux);
    double r[kRatios];
    ratios(a_of(sub, ut, c), c, r);
    for (int q = 0; q < kRatios; ++q)
      errors[static_cast<std::size_t>(i)] = std::max(errors[static_cast<std::size_t>(i)],
                                                     std::abs(series(piece.coef, sub, q, ux, ut) - r[q]) /
                                                         std::max(1.0, std::abs(r[q])));
  });
  piece.error = *std::max_element(errors.begin(), errors.end());
  if (!std::isfinite(piece.error))
    throw NumericalError("layerjkr: the Dugdale table's piece " + std::to_string(k) + " is not finite");
  if (disk) {
    std::vector<double> out = piece.coef;
    out.push_back(piece.error);
    disk_->store(kPieceKind, key, out);
  }
}

const DugdaleTable::Piece& DugdaleTable::piece(int k) const {
  std::call_once((*built_)[static_cast<std::size_t>(k)], [&] {
    auto p = std::make_unique<Piece>();
    build(k, *p);
    (*pieces_)[static_cast<std::size_t>(k)] = std::move(p);
  });
  return *(*pieces_)[static_cast<std::size_t>(k)];
}

DugdaleTable::Parts DugdaleTable::at(double a, double c) const {
  if (!(c >= min_c() && c <= max_c()))
    throw DomainError("DugdaleTable::at", "c/h", c, "[" + format_double(min_c()) + ", " + format_double(max_c()) + "]");
  if (!(a >= 0.0 && a <= c)) throw DomainError("DugdaleTable::at", "a/h", a, "[0, c/h = " + format_double(c) + "]");
  const double x = std::log(c);
  int k = static_cast<int>(std::upper_bound(std::begin(kDecades), std::end(kDecades), x / kLn10) - std::begin(kDecades)) - 1;
  k = std::clamp(k, 0, kPieces - 1);
  const Piece& p = piece(k);
  const double x0 = x_at(k), x1 = x_at(k + 1);
  const double ux = std::clamp((2.0 * x - x0 - x1) / (x1 - x0), -1.0, 1.0);
  const SubPoint sp = sub_of(a, c);
  const Parts hs = half_space(a, c, d_);
  Parts out;
  out.D = series(p.coef, sp.sub, 0, ux, sp.u) * hs.D;
  out.P = series(p.coef, sp.sub, 1, ux, sp.u) * hs.P;
  out.G = series(p.coef, sp.sub, 2, ux, sp.u) * hs.G;
  out.F = series(p.coef, sp.sub, 3, ux, sp.u) * hs.F;
  out.error = p.error;
  return out;
}

double DugdaleTable::measured_error() const {
  double e = 0.0;
  for (const auto& p : *pieces_)
    if (p) e = std::max(e, p->error);
  return e;
}

std::shared_ptr<const DugdaleTable> shared_dugdale_table(const LayeredMedium& medium, double d,
                                                         const ExactLayerOptions& o) {
  LayeredMedium unit = medium;  // in units of the top layer: E1 = h1 = 1
  const StackLayer top = medium.layers.at(0);
  for (StackLayer& l : unit.layers) {
    l.E /= top.E;
    l.h /= top.h;
  }
  if (unit.substrate) unit.substrate->E /= top.E;
  std::vector<double> key = StackSymbol(unit, "dugdale_table").signature();
  key.insert(key.end(), {d, static_cast<double>(o.points_per_panel), o.panel_width, static_cast<double>(o.min_panels)});
  auto& caches = context_caches(o.context);
  return caches.dugdale_tables.get(key, [&] {
    return std::make_shared<const DugdaleTable>(unit, d, o, caches.disk, key);
  });
}

}  // namespace layerjkr::detail
