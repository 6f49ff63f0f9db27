#pragma once
/// @file
/// Random QPs with a known solution (manufactured from chosen KKT points) and a KKT checker
/// independent of any solver: the reference problems of walkgen::DenseQp's tests and of
/// bench_qp (docs/design.md convention 15).
///
/// A problem is built backwards: pick H ≻ 0, x*, which constraints are active on which side and
/// their multipliers; put the active bounds through x*, the inactive ones at a positive distance,
/// and set g = −(H x* + Aᵀ y* + z*). Then x* is the unique minimiser (H ≻ 0, KKT hold).
///
/// Depends on the core only (Eigen).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// min ½ xᵀ H x + gᵀ x subject to lb ≤ A x ≤ ub and l ≤ x ≤ u (±infinity where a side is
/// open), with its solution.
struct QpProblem {
  Eigen::MatrixXd H, A;             ///< n × n (positive definite), m × n
  Eigen::VectorXd g, lb, ub, l, u;  ///< n, m, m, n, n
  Eigen::VectorXd x_star;           ///< the solution (empty for infeasible problems)
  bool feasible = true;
  std::string kind;  ///< to_string(QpKind), or "infeasible"
};

/// What a manufactured problem stresses.

enum class QpKind {
  generic,      ///< random active set, positive multipliers
  degenerate,   ///< duplicated, scaled and combined active rows, weakly active rows
  equalities,   ///< a block of equality rows (multipliers of any sign) and fixed variables
  many_bounds,  ///< most variables at a bound
  parallel,     ///< pairs of parallel rows: ranges lb ≤ aᵀx ≤ ub and opposite copies −a
};

/// The enumerator's name; "unknown" out of range.
constexpr const char* to_string(QpKind k) noexcept {
  switch (k) {
    case QpKind::generic:
      return "generic";
    case QpKind::degenerate:
      return "degenerate";
    case QpKind::equalities:
      return "equalities";
    case QpKind::many_bounds:
      return "many_bounds";
    case QpKind::parallel:
      return "parallel";
  }
  return "unknown";
}

/// Makes manufactured problems from a seeded std::mt19937: the same seed gives the same problems
/// with the same standard library (its distributions are implementation-defined).
class QpFactory {
 public:
  explicit QpFactory(unsigned seed) : rng_(seed) {}

  /// Draws: uniform in [a, b), integer in [a, b], standard normal, true with probability p.
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }
  double normal() { return std::normal_distribution<double>(0.0, 1.0)(rng_); }
  bool coin(double p = 0.5) { return uniform(0.0, 1.0) < p; }

  /// A random r × c matrix of standard normal entries.
  Eigen::MatrixXd random_matrix(int r, int c) {
    Eigen::MatrixXd M(r, c);
    for (int i = 0; i < r; ++i)
      for (int j = 0; j < c; ++j) M(i, j) = normal();
    return M;
  }

  /// Symmetric positive definite with eigenvalues log-uniform in [1/cond, 1] · scale.
  Eigen::MatrixXd spd(int n, double cond, double scale) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(random_matrix(n, n));
    Eigen::MatrixXd Q = qr.householderQ();
    Eigen::VectorXd eig(n);
    for (int i = 0; i < n; ++i) eig[i] = scale * std::pow(cond, -uniform(0.0, 1.0));
    Eigen::MatrixXd H = Q * eig.asDiagonal() * Q.transpose();
    return 0.5 * (H + H.transpose());
  }

  /// A feasible problem of n variables and m rows of `kind`, with its solution x_star.
  /// @throws walkgen::invalid_argument unless n ≥ 1 and m ≥ 0.
  QpProblem make(int n, int m, QpKind kind) {
    check_argument(n >= 1 && m >= 0, "QpFactory::make", "n >= 1 variables and m >= 0 rows",
                   std::to_string(n) + " and " + std::to_string(m));
    const double inf = std::numeric_limits<double>::infinity();
    QpProblem p;
    p.kind = to_string(kind);
    p.H = spd(n, std::pow(10.0, uniform(0.0, 4.0)), std::pow(10.0, uniform(-1.0, 2.0)));
    p.x_star.resize(n);
    for (int j = 0; j < n; ++j) p.x_star[j] = 2.0 * normal();
    p.A = random_matrix(m, n);
    for (int i = 0; i < m; ++i) p.A.row(i) *= std::pow(10.0, uniform(-1.0, 1.0));
    p.lb.resize(m);
    p.ub.resize(m);
    p.l.resize(n);
    p.u.resize(n);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(m), z = Eigen::VectorXd::Zero(n);

    // How many constraints may carry a nonzero multiplier and be independent.
    int budget = std::max(0, n - 1);
    const int eq_rows =
        kind == QpKind::equalities ? std::min(m, integer(1, std::max(1, n / 3))) : 0;
    const double bound_active_p = kind == QpKind::many_bounds ? 0.8 : 0.15;

    // Variable bounds.
    for (int j = 0; j < n; ++j) {
      const double xj = p.x_star[j];
      const double r = uniform(0.0, 1.0);
      if (kind == QpKind::equalities && r < 0.1 && budget > 0) {
        p.l[j] = p.u[j] = xj;  // fixed variable
        z[j] = 3.0 * normal();
        --budget;
      } else if (r < bound_active_p && budget > 0) {
        const bool lower = coin();
        const double mult = coin(0.1) ? 0.0 : uniform(0.1, 10.0);
        if (lower) {
          p.l[j] = xj;
          p.u[j] = coin(0.3) ? inf : xj + uniform(0.1, 2.0);
          z[j] = -mult;
        } else {
          p.u[j] = xj;
          p.l[j] = coin(0.3) ? -inf : xj - uniform(0.1, 2.0);
          z[j] = mult;
        }
        --budget;
      } else {
        p.l[j] = coin(0.4) ? -inf : xj - uniform(0.1, 3.0);
        p.u[j] = coin(0.4) ? inf : xj + uniform(0.1, 3.0);
      }
    }

    // Rows.
    const Eigen::VectorXd Ax = p.A * p.x_star;
    const double active_p = kind == QpKind::many_bounds ? 0.1 : 0.35;
    std::vector<int> active_rows;
    for (int i = 0; i < m; ++i) {
      const double v = Ax[i];
      if (i < eq_rows && budget > 0) {
        p.lb[i] = p.ub[i] = v;
        y[i] = 3.0 * normal();
        active_rows.push_back(i);
        --budget;
      } else if (coin(active_p) && budget > 0) {
        const bool lower = coin();
        const double mult = coin(0.1) ? 0.0 : uniform(0.1, 10.0);
        if (lower) {
          p.lb[i] = v;
          p.ub[i] = coin(0.5) ? inf : v + uniform(0.1, 2.0);
          y[i] = -mult;
        } else {
          p.ub[i] = v;
          p.lb[i] = coin(0.5) ? -inf : v - uniform(0.1, 2.0);
          y[i] = mult;
        }
        active_rows.push_back(i);
        --budget;
      } else {
        p.lb[i] = coin(0.3) ? -inf : v - uniform(0.05, 3.0);
        p.ub[i] = coin(0.3) ? inf : v + uniform(0.05, 3.0);
      }
    }

    // Degenerate additions overwrite some inactive rows with rows that depend on active ones.
    if ((kind == QpKind::degenerate || kind == QpKind::parallel) && !active_rows.empty()) {
      for (int i = 0; i < m; ++i) {
        if (y[i] != 0.0 || (p.lb[i] == Ax[i] || p.ub[i] == Ax[i]) || !coin(0.4)) continue;
        const int a = active_rows[integer(0, static_cast<int>(active_rows.size()) - 1)];
        const int b = active_rows[integer(0, static_cast<int>(active_rows.size()) - 1)];
        const double ya = y[a];
        const bool a_lower = p.lb[a] == Ax[a] && (ya <= 0.0 || p.ub[a] != Ax[a]);
        const int choice = integer(0, kind == QpKind::parallel ? 1 : 3);
        if (choice == 0) {
          // exact or scaled duplicate of an active row, same side, zero multiplier
          const double s = coin() ? 1.0 : uniform(0.5, 4.0);
          p.A.row(i) = s * p.A.row(a);
          const double v = s * Ax[a];
          if (a_lower) {
            p.lb[i] = v;
            p.ub[i] = coin() ? inf : v + 1.0;
          } else {
            p.ub[i] = v;
            p.lb[i] = coin() ? -inf : v - 1.0;
          }
        } else if (choice == 1) {
          // opposite copy −a with the same (tight) bound, or a parallel row that is slack
          p.A.row(i) = -p.A.row(a);
          const double v = -Ax[a];
          if (coin()) {
            if (a_lower) {
              p.ub[i] = v;
              p.lb[i] = -inf;
            } else {
              p.lb[i] = v;
              p.ub[i] = inf;
            }
          } else {
            p.lb[i] = v - uniform(0.1, 1.0);
            p.ub[i] = v + uniform(0.1, 1.0);
          }
        } else if (choice == 2 && a != b) {
          // sum of two active rows on the same side as both (if they agree), tight
          const bool b_lower = p.lb[b] == Ax[b] && (y[b] <= 0.0 || p.ub[b] != Ax[b]);
          if (a_lower != b_lower || p.lb[a] == p.ub[a] || p.lb[b] == p.ub[b]) continue;
          p.A.row(i) = p.A.row(a) + p.A.row(b);
          const double v = Ax[a] + Ax[b];
          if (a_lower) {
            p.lb[i] = v;
            p.ub[i] = inf;
          } else {
            p.ub[i] = v;
            p.lb[i] = -inf;
          }
        } else {
          // weakly active: tight at x* with zero multiplier
          const double v = p.A.row(i).dot(p.x_star);
          if (coin()) {
            p.lb[i] = v;
          } else {
            p.ub[i] = v;
          }
        }
      }
    }

    p.g = -(p.H * p.x_star + p.A.transpose() * y + z);
    return p;
  }

  /// A problem of n variables and max(m, 3) rows that has no feasible point; the contradiction
  /// is one of several kinds.
  /// @throws walkgen::invalid_argument unless n ≥ 1.
  QpProblem make_infeasible(int n, int m) {
    check_argument(n >= 1, "QpFactory::make_infeasible: n", "n >= 1 variables", n);
    const double inf = std::numeric_limits<double>::infinity();
    QpProblem p = make(n, std::max(m, 3), QpKind::generic);
    p.kind = "infeasible";
    p.feasible = false;
    p.x_star.resize(0);
    const int rows = static_cast<int>(p.A.rows());
    const int i = integer(0, rows - 3);
    switch (integer(0, 3)) {
      case 0: {  // a1ᵀx ≥ 1, a2ᵀx ≥ 1, (a1 + a2)ᵀx ≤ 1
        p.A.row(i + 2) = p.A.row(i) + p.A.row(i + 1);
        p.lb[i] = p.lb[i + 1] = 1.0;
        p.ub[i] = p.ub[i + 1] = inf;
        p.lb[i + 2] = -inf;
        p.ub[i + 2] = 1.0;
        break;
      }
      case 1: {  // inconsistent equalities: a3 = a1 + a2 but b3 ≠ b1 + b2
        p.A.row(i + 2) = p.A.row(i) + p.A.row(i + 1);
        p.lb[i] = p.ub[i] = 0.5;
        p.lb[i + 1] = p.ub[i + 1] = -0.25;
        p.lb[i + 2] = p.ub[i + 2] = 1.0;
        break;
      }
      case 2: {  // a row against a variable bound: x_j ≥ 2 and x_j ≤ 1 via a row
        const int j = integer(0, n - 1);
        p.A.row(i).setZero();
        p.A(i, j) = 3.0;
        p.lb[i] = -inf;
        p.ub[i] = 3.0;
        p.l[j] = 2.0;
        p.u[j] = inf;
        break;
      }
      default: {  // a box in some direction that is empty: aᵀx ≥ 1 and (−2a)ᵀx ≥ 0
        p.A.row(i + 1) = -2.0 * p.A.row(i);
        p.lb[i] = 1.0;
        p.ub[i] = inf;
        p.lb[i + 1] = 0.0;
        p.ub[i + 1] = inf;
        break;
      }
    }
    return p;
  }

 private:
  std::mt19937 rng_;
};

/// Relative KKT residuals of (x, y, z) for a problem, computed independently of the solver.
struct KktResiduals {
  double stationarity = 0;  ///< |H x + g + Aᵀ y + z|∞ over the largest of its terms (≥ 1)
  double primal = 0;        ///< largest violation of a row or bound, over max(1, |A x|∞, |x|∞)
  double complementarity = 0;  ///< largest |multiplier × distance to its side|, scaled
  double dual_sign = 0;        ///< largest multiplier on a side that is open (±infinity)
  /// The largest of the four.
  double max() const { return std::max({stationarity, primal, complementarity, dual_sign}); }
};

/// The KKT residuals of primal x and multipliers y (rows) and z (bounds) for problem p, with
/// DenseQp's sign convention (y < 0 at an active lower side, y > 0 at an active upper side).
/// @throws walkgen::invalid_argument when the sizes do not match the problem.
inline KktResiduals kkt_residuals(const QpProblem& p, const Eigen::VectorXd& x,
                                  const Eigen::VectorXd& y, const Eigen::VectorXd& z) {
  check_argument(x.size() == p.H.rows(), "walkgen::kkt_residuals: x", "one entry per variable",
                 x.size());
  check_argument(y.size() == p.A.rows(), "walkgen::kkt_residuals: y", "one entry per row",
                 y.size());
  check_argument(z.size() == p.H.rows(), "walkgen::kkt_residuals: z", "one entry per variable",
                 z.size());
  KktResiduals r;
  const Eigen::VectorXd Hx = p.H * x;
  const Eigen::VectorXd Aty = p.A.transpose() * y;
  const Eigen::VectorXd Ax = p.A * x;
  const double stat_scale =
      std::max({1.0, Hx.lpNorm<Eigen::Infinity>(), p.g.lpNorm<Eigen::Infinity>(),
                Aty.lpNorm<Eigen::Infinity>(), z.lpNorm<Eigen::Infinity>()});
  r.stationarity = (Hx + p.g + Aty + z).lpNorm<Eigen::Infinity>() / stat_scale;
  const double x_scale =
      std::max({1.0, Ax.size() ? Ax.lpNorm<Eigen::Infinity>() : 0.0, x.lpNorm<Eigen::Infinity>()});
  const double y_scale =
      std::max({1.0, y.size() ? y.lpNorm<Eigen::Infinity>() : 0.0, z.lpNorm<Eigen::Infinity>()});
  auto side = [&](double v, double lo, double hi, double mult) {
    r.primal = std::max(r.primal, std::max(lo - v, v - hi) / x_scale);
    // y < 0 needs the lower side active, y > 0 the upper side.
    if (mult < 0) {
      if (!std::isfinite(lo)) {
        r.dual_sign = std::max(r.dual_sign, -mult / y_scale);
      } else {
        r.complementarity =
            std::max(r.complementarity, -mult * std::abs(v - lo) / (x_scale * y_scale));
      }
    } else if (mult > 0) {
      if (!std::isfinite(hi)) {
        r.dual_sign = std::max(r.dual_sign, mult / y_scale);
      } else {
        r.complementarity =
            std::max(r.complementarity, mult * std::abs(hi - v) / (x_scale * y_scale));
      }
    }
  };
  for (int i = 0; i < Ax.size(); ++i) side(Ax[i], p.lb[i], p.ub[i], y[i]);
  for (int j = 0; j < x.size(); ++j) side(x[j], p.l[j], p.u[j], z[j]);
  return r;
}

}  // namespace walkgen
