#pragma once
// The one derivative checker of the tests (docs/design.md convention 15). compare_jacobians()
// checks an analytic Jacobian entry by entry against a reference, central_differences() (also
// at a point with the caller's own ⊕ and ⊖, e.g. rotations) or jet_jacobian() (a ceres::Jet
// type passed in: no Ceres here), and names the worst entry: row, column, the caller's named
// blocks they fall in, both values and the tolerance. Use:
//   EXPECT_TRUE(check.passed()) << check.message();

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace walkgen_test {

/// An entry passes when |analytic − reference| ≤ absolute + relative·|reference|.
struct Tolerance {
  double absolute = 0.0;
  double relative = 0.0;
};

/// A named run of `size` consecutive rows or columns ("CoM", 3; "joint r_knee", 1).
struct Block {
  std::string name;
  Eigen::Index size = 1;
};
using Blocks = std::vector<Block>;

/// Where index i falls in `blocks`: "name (row 2 of 3)", "" without blocks.
/// @throws std::invalid_argument for blocks that do not cover `total` indices.
inline std::string block_of(const Blocks& blocks, Eigen::Index i, Eigen::Index total,
                            const std::string& kind) {
  std::string found;
  Eigen::Index start = 0;
  for (const Block& b : blocks) {
    if (found.empty() && i < start + b.size) {
      found = b.size == 1 ? b.name
                          : b.name + " (" + kind + " " + std::to_string(i - start) + " of " +
                                std::to_string(b.size) + ")";
    }
    start += b.size;
  }
  if (!blocks.empty() && start != total) {
    throw std::invalid_argument("compare_jacobians: the " + kind + " blocks cover " +
                                std::to_string(start) + " of " + std::to_string(total));
  }
  return found;
}

/// The outcome of comparing an analytic Jacobian with a reference. merge() keeps the worst of
/// several checks (configurations, links) with the largest error and all failures.
struct JacobianCheck {
  std::string what, reference;  ///< the Jacobian (and where), how the reference was made
  Tolerance tolerance;
  Eigen::Index failures = 0;  ///< entries beyond the tolerance (NaN counts)
  double max_error = 0.0;     ///< largest |analytic − reference|
  /// The worst entry (largest |analytic − reference| / allowed) and its blocks.
  Eigen::Index row = -1, col = -1;
  double analytic = 0.0, expected = 0.0, ratio = 0.0;
  std::string row_block{}, col_block{};

  bool passed() const { return failures == 0; }

  std::string message() const {
    std::ostringstream os;
    os.precision(6);
    os << what << " vs " << reference << ": " << failures << (failures == 1 ? " entry" : " entries")
       << " beyond the tolerance " << tolerance.absolute;
    if (tolerance.relative != 0.0) os << " + " << tolerance.relative << "·|reference|";
    os << "; worst at row " << row << (row_block.empty() ? "" : " [" + row_block + "]")
       << ", column " << col << (col_block.empty() ? "" : " [" + col_block + "]") << ": analytic "
       << analytic << ", reference " << expected << ", |difference| "
       << std::abs(analytic - expected) << " (" << ratio << " x allowed); largest |difference| "
       << max_error;
    return os.str();
  }

  void merge(const JacobianCheck& other) {
    const double error =
        std::isnan(other.max_error) ? other.max_error : std::max(max_error, other.max_error);
    const Eigen::Index all = failures + other.failures;
    if (row < 0 || other.ratio > ratio) *this = other;
    max_error = error;
    failures = all;
  }
};

/// Compares `analytic` with `reference` entry by entry; the row and column blocks, where given,
/// must cover the matrix and name the worst entry's place.
/// @throws std::invalid_argument for different shapes or blocks that do not cover the matrix.
inline JacobianCheck compare_jacobians(const std::string& what, const Eigen::MatrixXd& analytic,
                                       const Eigen::MatrixXd& reference, Tolerance tolerance,
                                       const Blocks& row_blocks = {}, const Blocks& col_blocks = {},
                                       const std::string& reference_name = "central differences") {
  if (analytic.rows() != reference.rows() || analytic.cols() != reference.cols()) {
    throw std::invalid_argument("compare_jacobians: " + what + ": shapes differ");
  }
  JacobianCheck c{what, reference_name, tolerance};
  for (Eigen::Index j = 0; j < analytic.cols(); ++j) {
    for (Eigen::Index i = 0; i < analytic.rows(); ++i) {
      const double a = analytic(i, j), r = reference(i, j), error = std::abs(a - r);
      const double allowed = tolerance.absolute + tolerance.relative * std::abs(r);
      const bool ok = error <= allowed;  // false for NaN
      const double ratio = error == 0.0 ? 0.0 : std::isnan(error) ? HUGE_VAL : error / allowed;
      c.failures += ok ? 0 : 1;
      if (std::isnan(error) || error > c.max_error) c.max_error = error;
      if (c.row < 0 || ratio > c.ratio) {
        c.row = i, c.col = j, c.analytic = a, c.expected = r, c.ratio = ratio;
      }
    }
  }
  if (c.row >= 0) {
    c.row_block = block_of(row_blocks, c.row, analytic.rows(), "row");
    c.col_block = block_of(col_blocks, c.col, analytic.cols(), "column");
  }
  return c;
}

/// Central differences at a point p: column k = minus(f(+h e_k), f(−h e_k)) / 2h, where f(dx)
/// evaluates the function at p ⊕ dx (dx of size n) and minus(a, b) returns a ⊖ b as an Eigen
/// vector (e.g. log(R_a R_bᵀ) for rotations).
template <typename F, typename Minus>
Eigen::MatrixXd central_differences(Eigen::Index n, double h, F&& f, Minus&& minus) {
  Eigen::MatrixXd J;
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    dx[k] = h;
    const auto plus = f(dx);
    dx[k] = -h;
    const Eigen::VectorXd column = minus(plus, f(dx)) / (2 * h);
    dx[k] = 0.0;
    if (k == 0) J.resize(column.size(), n);
    J.col(k) = column;
  }
  return J;
}

/// Central differences of a vector function f(x) (returning an Eigen vector) at x.
template <typename F>
Eigen::MatrixXd central_differences(F&& f, const Eigen::VectorXd& x, double h = 1e-6) {
  return central_differences(
      x.size(), h, [&](const Eigen::VectorXd& dx) { return Eigen::VectorXd(f(x + dx)); },
      [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return Eigen::VectorXd(a - b); });
}

/// Forward-mode automatic differentiation of a scalar-generic f at x: f(const T* x, T* y) writes
/// m outputs, T a ceres::Jet<double, N> (members a and v); derivatives are taken N columns per
/// pass (as Ceres' DynamicAutoDiffCostFunction does). Returns the m × x.size() Jacobian.
template <typename Jet, typename F>
Eigen::MatrixXd jet_jacobian(F&& f, const Eigen::VectorXd& x, Eigen::Index m) {
  constexpr Eigen::Index kStride = decltype(Jet::v)::RowsAtCompileTime;
  const Eigen::Index n = x.size();
  Eigen::MatrixXd J(m, n);
  std::vector<Jet> xj(static_cast<std::size_t>(n)), yj(static_cast<std::size_t>(m));
  for (Eigen::Index first = 0; first < n; first += kStride) {
    for (Eigen::Index i = 0; i < n; ++i) {
      xj[std::size_t(i)] = Jet(x[i]);
      if (i >= first && i < first + kStride) xj[std::size_t(i)].v[i - first] = 1.0;
    }
    f(static_cast<const Jet*>(xj.data()), yj.data());
    for (Eigen::Index r = 0; r < m; ++r) {
      for (Eigen::Index k = first; k < std::min(n, first + kStride); ++k) {
        J(r, k) = yj[std::size_t(r)].v[k - first];
      }
    }
  }
  return J;
}

}  // namespace walkgen_test
