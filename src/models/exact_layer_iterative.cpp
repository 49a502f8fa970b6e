// The exact layer's Nystrom system by two-level preconditioned CG with FFT products.
#include "models/exact_layer_iterative.hpp"

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/legendre.hpp>
#include <unsupported/Eigen/FFT>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr int kCoarseDegree = 4;        // Legendre polynomials a panel in the coarse space
constexpr double kTolerance = 1e-14;    // relative residual
constexpr int kMaxIterations = 1000;

using Complex = std::complex<double>;
using Spectrum = std::vector<Complex>;
using Index = Eigen::Index;

std::size_t at(Index i) { return static_cast<std::size_t>(i); }

// y = B x with B = I - (1/pi) S (T + H) S, products by FFT over the panel index.
class FftOperator {
 public:
  FftOperator(const KernelBlocks& blocks, const Grid& g) : m_(g.panels), p_(g.p) {
    while (length_ < 3 * m_ - 2) length_ *= 2;
    fft_.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    scale_.resize(at(p_));
    for (Index i = 0; i < p_; ++i) scale_[at(i)] = std::sqrt(g.b * g.v[at(i)]);
    // Sequences over n = 0..2m-2: Toeplitz offset n - (m-1), Hankel index n.
    toeplitz_.resize(at(p_ * p_));
    hankel_.resize(at(p_ * p_));
    std::vector<double> seq(at(length_));
    for (Index i = 0; i < p_; ++i)
      for (Index j = 0; j < p_; ++j) {
        std::fill(seq.begin(), seq.end(), 0.0);
        for (Index d = -(m_ - 1); d <= m_ - 1; ++d)
          seq[at(d + m_ - 1)] = d >= 0 ? blocks.toeplitz[at(d)](i, j) : blocks.toeplitz[at(-d)](j, i);
        toeplitz_[index(i, j)] = forward(seq);
        std::fill(seq.begin(), seq.end(), 0.0);
        for (Index e = 0; e <= 2 * m_ - 2; ++e) seq[at(e)] = blocks.hankel[at(e)](i, j);
        hankel_[index(i, j)] = forward(seq);
      }
  }

  Eigen::VectorXd apply(const Eigen::VectorXd& x) {
    // u = S x per node column j; its spectrum and that of its reversal (for the Hankel part).
    std::vector<Spectrum> u(at(p_)), u_reversed(at(p_));
    std::vector<double> seq(at(length_));
    for (Index j = 0; j < p_; ++j) {
      std::fill(seq.begin(), seq.end(), 0.0);
      for (Index l = 0; l < m_; ++l) seq[at(l)] = scale(j) * x(l * p_ + j);
      u[at(j)] = forward(seq);
      std::fill(seq.begin(), seq.end(), 0.0);
      for (Index l = 0; l < m_; ++l) seq[at(m_ - 1 - l)] = scale(j) * x(l * p_ + j);
      u_reversed[at(j)] = forward(seq);
    }
    Eigen::VectorXd y = x;
    const std::size_t bins = at(length_ / 2 + 1);
    Spectrum acc(bins);
    std::vector<double> out(at(length_));
    for (Index i = 0; i < p_; ++i) {
      std::fill(acc.begin(), acc.end(), Complex(0.0, 0.0));
      for (Index j = 0; j < p_; ++j) {
        const Spectrum& t = toeplitz_[index(i, j)];
        const Spectrum& h = hankel_[index(i, j)];
        const Spectrum& a = u[at(j)];
        const Spectrum& b = u_reversed[at(j)];
        for (std::size_t f = 0; f < bins; ++f) acc[f] += t[f] * a[f] + h[f] * b[f];
      }
      fft_.inv(out.data(), acc.data(), length_);
      // Both convolutions put row k at index k + m - 1.
      for (Index k = 0; k < m_; ++k) y(k * p_ + i) -= (1.0 / kPi) * scale(i) * out[at(k + m_ - 1)];
    }
    return y;
  }

 private:
  std::size_t index(Index i, Index j) const { return at(i * p_ + j); }
  double scale(Index i) const { return scale_[at(i)]; }
  Spectrum forward(const std::vector<double>& seq) {
    Spectrum s(at(length_ / 2 + 1));
    fft_.fwd(s.data(), seq.data(), length_);
    return s;
  }

  Index m_, p_, length_ = 1;
  Eigen::FFT<double> fft_;
  std::vector<double> scale_;
  std::vector<Spectrum> toeplitz_, hankel_;  // spectra of the (i, j) sequences
};

// M^-1 = Z E^-1 Z^T + (I - Z Z^T), Z = orthonormal Legendre polynomials on every panel.
class TwoLevelPreconditioner {
 public:
  TwoLevelPreconditioner(const KernelBlocks& blocks, const Grid& g)
      : m_(g.panels), p_(g.p), q_(std::min<Index>(kCoarseDegree, g.p)) {
    // Zb(i, a) = sqrt(v_i) P~_a(s_i): orthonormal columns, because the Gauss rule integrates
    // the product of two polynomials of degree < q exactly (q <= p).
    zb_.resize(p_, q_);
    for (Index i = 0; i < p_; ++i)
      for (Index a = 0; a < q_; ++a)
        zb_(i, a) = std::sqrt(g.v[at(i)] * (2.0 * static_cast<double>(a) + 1.0)) *
                    boost::math::legendre_p(static_cast<int>(a), 2.0 * g.s[at(i)] - 1.0);
    // E = I - (1/pi) Z^T S (T + H) S Z, block (K, L) from the Toeplitz block K - L and the
    // Hankel block K + L, projected once each.
    Eigen::VectorXd s(p_);
    for (Index i = 0; i < p_; ++i) s(i) = std::sqrt(g.b * g.v[at(i)]);
    const Eigen::MatrixXd sz = s.asDiagonal() * zb_;
    std::vector<Eigen::MatrixXd> tq(at(m_)), hq(at(2 * m_ - 1));
    for (Index d = 0; d < m_; ++d) tq[at(d)] = sz.transpose() * blocks.toeplitz[at(d)] * sz;
    for (Index e = 0; e < 2 * m_ - 1; ++e) hq[at(e)] = sz.transpose() * blocks.hankel[at(e)] * sz;
    const Index nc = m_ * q_;
    Eigen::MatrixXd E(nc, nc);  // the lower triangle is all LLT reads
    for (Index K = 0; K < m_; ++K)
      for (Index L = 0; L <= K; ++L)
        E.block(K * q_, L * q_, q_, q_) = -(1.0 / kPi) * (tq[at(K - L)] + hq[at(K + L)]);
    E.diagonal().array() += 1.0;
    coarse_.compute(E);
    if (coarse_.info() != Eigen::Success)
      throw NumericalError("layerjkr::exact_layer: the coarse operator is not positive definite");
  }

  Eigen::VectorXd apply(const Eigen::VectorXd& r) const {
    Eigen::VectorXd c(m_ * q_);
    for (Index K = 0; K < m_; ++K) c.segment(K * q_, q_) = zb_.transpose() * r.segment(K * p_, p_);
    const Eigen::VectorXd e = coarse_.solve(c) - c;  // Z (E^-1 c - c) + r
    Eigen::VectorXd y = r;
    for (Index K = 0; K < m_; ++K) y.segment(K * p_, p_) += zb_ * e.segment(K * q_, q_);
    return y;
  }

 private:
  Index m_, p_, q_;
  Eigen::MatrixXd zb_;
  Eigen::LLT<Eigen::MatrixXd> coarse_;
};

}  // namespace

IterativeSolve solve_iteratively(const ExactLayerKernel& kernel, const Grid& grid, const Eigen::MatrixXd& rhs) {
  const KernelBlocks blocks = kernel_blocks(kernel, grid);
  FftOperator B(blocks, grid);
  const TwoLevelPreconditioner M(blocks, grid);
  IterativeSolve out;
  out.psi.resize(rhs.rows(), rhs.cols());
  for (Eigen::Index c = 0; c < rhs.cols(); ++c) {
    const Eigen::VectorXd b = rhs.col(c);
    const double target = kTolerance * b.norm();
    Eigen::VectorXd x = M.apply(b);  // the coarse solution is a good start
    Eigen::VectorXd r = b - B.apply(x), z = M.apply(r), d = z;
    double rz = r.dot(z);
    int it = 0;
    for (; it < kMaxIterations && r.norm() > target; ++it) {
      const Eigen::VectorXd Bd = B.apply(d);
      const double alpha = rz / d.dot(Bd);
      x += alpha * d;
      r -= alpha * Bd;
      z = M.apply(r);
      const double rz_next = r.dot(z);
      d = z + (rz_next / rz) * d;
      rz = rz_next;
    }
    if (!(r.norm() <= target))
      throw NumericalError("layerjkr::exact_layer: conjugate gradients did not converge in " +
                           std::to_string(kMaxIterations) + " iterations at a/h = " +
                           format_double(grid.b * grid.panels) + " (residual " +
                           format_double(r.norm() / b.norm()) + ")");
    out.psi.col(c) = x;
    out.iterations = std::max(out.iterations, it);
  }
  return out;
}

}  // namespace layerjkr::detail
