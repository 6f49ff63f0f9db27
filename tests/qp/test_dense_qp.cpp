// Tests of walkgen::DenseQp: manufactured solutions with independent KKT checks, infeasibility,
// warm starts (refactorised from scratch or reused), fixed sizes, float, regularisation and bad
// input.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/scenarios/manufactured_qp.hpp"
#include "walkgen/scenarios/walking_qp_sequence.hpp"

namespace {

using walkgen::DenseQp;
using walkgen::kkt_residuals;
using walkgen::QpFactory;
using walkgen::QpKind;
using walkgen::QpProblem;
using walkgen::QpStatus;

constexpr double kInf = std::numeric_limits<double>::infinity();

const QpStatus& solve_problem(DenseQp<double>& qp, const QpProblem& p) {
  qp.init(p.H, p.g, p.A, p.lb, p.ub, p.l, p.u);
  return qp.solve().status;
}

// Problem sizes cycle through small, medium and the largest asked for (150 vars, 300 rows).
void problem_size(QpFactory& f, int k, int* n, int* m) {
  switch (k % 4) {
    case 0:
      *n = f.integer(5, 20);
      *m = f.integer(0, 40);
      break;
    case 1:
      *n = f.integer(20, 70);
      *m = f.integer(0, 140);
      break;
    case 2:
      *n = f.integer(70, 150);
      *m = f.integer(0, 300);
      break;
    default:
      *n = f.integer(5, 150);
      *m = f.integer(0, 300);
      break;
  }
}

TEST(DenseQp, ManufacturedSolutionsSatisfyKkt) {
  const QpKind kinds[] = {QpKind::generic, QpKind::degenerate, QpKind::equalities,
                          QpKind::many_bounds, QpKind::parallel};
  constexpr int kProblems = 1000;
  double worst_kkt = 0, worst_x = 0, worst_reported = 0;
  int largest_n = 0, largest_m = 0, max_active = 0;
  for (int k = 0; k < kProblems; ++k) {
    QpFactory f(1000u + static_cast<unsigned>(k));
    int n = 0, m = 0;
    problem_size(f, k, &n, &m);
    const QpKind kind = kinds[k % 5];
    const QpProblem p = f.make(n, m, kind);
    DenseQp<double> qp(n, m);
    ASSERT_EQ(solve_problem(qp, p), QpStatus::solved)
        << "problem " << k << " (" << p.kind << ", n=" << n << ", m=" << m
        << "): " << qp.result().message;
    const auto& r = qp.result();
    const auto kkt = kkt_residuals(p, r.x, r.y, r.z);
    EXPECT_LE(kkt.max(), 1e-9) << "problem " << k << " (" << p.kind << ", n=" << n << ", m=" << m
                               << "): stationarity " << kkt.stationarity << ", primal "
                               << kkt.primal << ", complementarity " << kkt.complementarity
                               << ", dual sign " << kkt.dual_sign;
    // H ≻ 0 makes the minimiser unique: it must be the manufactured one.
    const double x_err = (r.x - p.x_star).lpNorm<Eigen::Infinity>() /
                         std::max(1.0, p.x_star.lpNorm<Eigen::Infinity>());
    EXPECT_LE(x_err, 1e-7) << "problem " << k << " (" << p.kind << ")";
    // The solver's own residuals agree with the independent ones in magnitude.
    EXPECT_LE(r.primal_residual,
              1e-8 * std::max(1.0, m > 0 ? (p.A * r.x).lpNorm<Eigen::Infinity>() : 0.0));
    worst_kkt = std::max(worst_kkt, kkt.max());
    worst_x = std::max(worst_x, x_err);
    worst_reported = std::max(worst_reported, r.dual_residual);
    largest_n = std::max(largest_n, n);
    largest_m = std::max(largest_m, m);
    max_active = std::max(max_active, r.active_set_size);
  }
  EXPECT_EQ(largest_n, 150);
  EXPECT_GE(largest_m, 290);
  std::printf(
      "[ stats    ] %d problems, n <= %d, m <= %d, up to %d active: worst relative KKT "
      "residual %.2e, worst relative x error %.2e\n",
      kProblems, largest_n, largest_m, max_active, worst_kkt, worst_x);
}

TEST(DenseQp, InfeasibleProblemsAreReportedInfeasible) {
  for (int k = 0; k < 200; ++k) {
    QpFactory f(5000u + static_cast<unsigned>(k));
    int n = 0, m = 0;
    problem_size(f, k, &n, &m);
    const QpProblem p = f.make_infeasible(n, m);
    DenseQp<double> qp(n, p.A.rows());
    const QpStatus status = solve_problem(qp, p);
    EXPECT_EQ(status, QpStatus::infeasible) << "problem " << k << " n=" << n << " m=" << m;
    EXPECT_TRUE(qp.result().x.allFinite());
  }
}

TEST(DenseQp, WarmStartAfterUpdateMatchesColdSolve) {
  for (int k = 0; k < 100; ++k) {
    QpFactory f(9000u + static_cast<unsigned>(k));
    const int n = f.integer(5, 80), m = f.integer(1, 160);
    QpProblem p = f.make(n, m, k % 2 ? QpKind::generic : QpKind::degenerate);
    DenseQp<double> warm(n, m), cold(n, m);
    cold.settings().warm_start = false;
    ASSERT_EQ(solve_problem(warm, p), QpStatus::solved);
    for (int t = 0; t < 5; ++t) {
      // Perturb g, and move the feasible set by a small δx (bounds shift by A δx and δx), as
      // between two control ticks; shifting keeps degenerate structure feasible.
      Eigen::VectorXd dx(n);
      for (int j = 0; j < n; ++j) {
        p.g[j] += 0.01 * f.normal();
        dx[j] = 0.01 * f.normal();
      }
      const Eigen::VectorXd Adx = p.A * dx;
      p.lb += Adx;
      p.ub += Adx;
      p.l += dx;
      p.u += dx;
      ASSERT_EQ(warm.update(p.g, p.lb, p.ub, p.l, p.u), QpStatus::unsolved);
      const auto& rw = warm.solve();
      ASSERT_EQ(rw.status, QpStatus::solved);
      EXPECT_TRUE(rw.warm_started);
      EXPECT_TRUE(rw.reused_factorization);
      const Eigen::VectorXd xw = rw.x;
      ASSERT_EQ(solve_problem(cold, p), QpStatus::solved);
      EXPECT_FALSE(cold.result().warm_started);
      EXPECT_LE((xw - cold.result().x).lpNorm<Eigen::Infinity>(),
                1e-9 * std::max(1.0, xw.lpNorm<Eigen::Infinity>()));
      EXPECT_LE(kkt_residuals(p, rw.x, rw.y, rw.z).max(), 1e-9);
    }
  }
}

TEST(DenseQp, WarmStartAfterInitRebuildsTheActiveSet) {
  QpFactory f(77);
  QpProblem p = f.make(40, 60, QpKind::generic);
  DenseQp<double> qp(40, 60);
  ASSERT_EQ(solve_problem(qp, p), QpStatus::solved);
  const int cold_iterations = qp.result().iterations;
  ASSERT_GT(cold_iterations, 3);
  // Same problem again through init(): the previous active set is optimal at once.
  ASSERT_EQ(solve_problem(qp, p), QpStatus::solved);
  EXPECT_TRUE(qp.result().warm_started);
  EXPECT_FALSE(qp.result().reused_factorization);
  EXPECT_EQ(qp.result().iterations, 0);
  EXPECT_LE((qp.result().x - p.x_star).lpNorm<Eigen::Infinity>(), 1e-8);
}

// A receding horizon renames its constraints from one solve to the next. Here: the same problem
// with its rows and variables renamed cyclically by one. Renaming the previous active set along
// makes the warm start exact; without it the solver must repair it.
TEST(DenseQp, RenamedWarmStartFollowsAShiftedProblem) {
  QpFactory f(78);
  QpProblem p = f.make(30, 45, QpKind::generic);
  // Row r of the new problem is row r + 1 of the old one, variable j is old variable j + 1.
  const int n = 30, m = 45;
  QpProblem q = p;
  Eigen::VectorXi perm(n);
  for (int j = 0; j < n; ++j) perm[j] = (j + 1) % n;
  Eigen::MatrixXd H(n, n), A(m, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) H(i, j) = p.H(perm[i], perm[j]);
  }
  for (int r = 0; r < m; ++r) {
    for (int j = 0; j < n; ++j) A(r, j) = p.A((r + 1) % m, perm[j]);
    q.lb[r] = p.lb[(r + 1) % m];
    q.ub[r] = p.ub[(r + 1) % m];
  }
  for (int j = 0; j < n; ++j) {
    q.g[j] = p.g[perm[j]];
    q.l[j] = p.l[perm[j]];
    q.u[j] = p.u[perm[j]];
  }
  q.H = H;
  q.A = A;
  DenseQp<double> cold(n, m), plain(n, m), renamed(n, m);
  ASSERT_EQ(solve_problem(cold, q), QpStatus::solved);
  for (DenseQp<double>* qp : {&plain, &renamed}) ASSERT_EQ(solve_problem(*qp, p), QpStatus::solved);
  renamed.rename_warm_start([&](int c) {
    if (c < m) return (c + m - 1) % m;  // row r + 1 → r
    return m + (c - m + n - 1) % n;     // variable j + 1 → j
  });
  ASSERT_EQ(solve_problem(plain, q), QpStatus::solved);
  ASSERT_EQ(solve_problem(renamed, q), QpStatus::solved);
  EXPECT_EQ(renamed.result().iterations, 0);
  EXPECT_GT(plain.result().iterations, 0);
  EXPECT_LE((renamed.result().x - cold.result().x).lpNorm<Eigen::Infinity>(), 1e-8);
  EXPECT_LE((plain.result().x - cold.result().x).lpNorm<Eigen::Infinity>(), 1e-8);
  // Constraints renamed to −1 are left out; the result is still the optimum.
  renamed.rename_warm_start([](int) { return -1; });
  ASSERT_EQ(solve_problem(renamed, q), QpStatus::solved);
  EXPECT_LE((renamed.result().x - cold.result().x).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(DenseQp, EqualityConstrainedMatchesKktSystem) {
  QpFactory f(3);
  const int n = 12, m = 5;
  Eigen::MatrixXd H = f.spd(n, 100.0, 1.0), A = f.random_matrix(m, n);
  Eigen::VectorXd g = f.random_matrix(n, 1), b = f.random_matrix(m, 1);
  // [H Aᵀ; A 0] [x; -y] = [-g; b], solved by a dense LU independent of the QP solver.
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  K.topLeftCorner(n, n) = H;
  K.topRightCorner(n, m) = A.transpose();
  K.bottomLeftCorner(m, n) = A;
  Eigen::VectorXd rhs(n + m);
  rhs << -g, b;
  const Eigen::VectorXd sol = K.fullPivLu().solve(rhs);
  DenseQp<double> qp(n, m);
  ASSERT_EQ(qp.init(H, g, A, b, b), QpStatus::unsolved);
  const auto& r = qp.solve();
  ASSERT_EQ(r.status, QpStatus::solved);
  EXPECT_LE((r.x - sol.head(n)).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_LE((r.y - sol.tail(m)).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_EQ(r.active_set_size, m);
}

TEST(DenseQp, UnconstrainedIsNewtonStep) {
  QpFactory f(4);
  const int n = 30;
  Eigen::MatrixXd H = f.spd(n, 1e3, 2.0);
  Eigen::VectorXd g = f.random_matrix(n, 1);
  DenseQp<double> qp(n, 0);
  qp.init(H, g, Eigen::MatrixXd(0, n), Eigen::VectorXd(0), Eigen::VectorXd(0));
  const auto& r = qp.solve();
  ASSERT_EQ(r.status, QpStatus::solved);
  const Eigen::VectorXd expected = -H.ldlt().solve(g);
  EXPECT_LE((r.x - expected).lpNorm<Eigen::Infinity>(), 1e-10 * expected.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(r.objective, 0.5 * expected.dot(H * expected) + g.dot(expected), 1e-10);
  EXPECT_EQ(r.iterations, 0);
}

TEST(DenseQp, BlockDiagonalHessianMatchesDenseFactorisation) {
  // Block-diagonal H (factorised per block) and the same H densified by a rotation give the same
  // solution after mapping back.
  QpFactory f(5);
  const int n = 20, m = 15;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  H.block(0, 0, 7, 7) = f.spd(7, 10, 1);
  H.block(7, 7, 1, 1) = f.spd(1, 1, 3);
  H.block(8, 8, 12, 12) = f.spd(12, 100, 2);
  Eigen::MatrixXd A = f.random_matrix(m, n);
  Eigen::VectorXd g = f.random_matrix(n, 1);
  Eigen::VectorXd lb = Eigen::VectorXd::Constant(m, -1.0), ub = Eigen::VectorXd::Constant(m, 1.0);
  DenseQp<double> block(n, m);
  block.init(H, g, A, lb, ub);
  ASSERT_EQ(block.solve().status, QpStatus::solved);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(f.random_matrix(n, n));
  const Eigen::MatrixXd Q = qr.householderQ();  // x = Q w
  DenseQp<double> dense(n, m);
  Eigen::MatrixXd Hw = Q.transpose() * H * Q;
  Hw = 0.5 * (Hw + Hw.transpose()).eval();
  dense.init(Hw, Q.transpose() * g, A * Q, lb, ub);
  ASSERT_EQ(dense.solve().status, QpStatus::solved);
  EXPECT_LE((block.result().x - Q * dense.result().x).lpNorm<Eigen::Infinity>(), 1e-9);
}

// init() keeps the rows of L whose leading principal block of H is unchanged (as in the walking
// MPC, whose jerk blocks stay and whose footstep rows change): every kind of change below must
// give what a fresh solver gives.
TEST(DenseQp, CholeskyRowsAreReusedOnlyWhereHIsUnchanged) {
  QpFactory f(9);
  const int n = 20, m = 12;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  H.block(0, 0, 12, 12) = f.spd(12, 50, 1);
  H.block(12, 12, 8, 8) = f.spd(8, 10, 2);
  const Eigen::MatrixXd A = f.random_matrix(m, n);
  const Eigen::VectorXd g = f.random_matrix(n, 1);
  const Eigen::VectorXd lb = Eigen::VectorXd::Constant(m, -0.3);
  const Eigen::VectorXd ub = Eigen::VectorXd::Constant(m, 0.3);
  DenseQp<double> reusing(n, m);
  auto expect_fresh = [&](const Eigen::MatrixXd& Hk, double eps, const char* what) {
    reusing.settings().regularization = eps;
    ASSERT_EQ(reusing.init(Hk, g, A, lb, ub), QpStatus::unsolved) << what;
    DenseQp<double> fresh(n, m);
    fresh.settings().regularization = eps;
    ASSERT_EQ(fresh.init(Hk, g, A, lb, ub), QpStatus::unsolved) << what;
    ASSERT_EQ(reusing.solve().status, QpStatus::solved) << what;
    ASSERT_EQ(fresh.solve().status, QpStatus::solved) << what;
    EXPECT_LE((reusing.result().x - fresh.result().x).lpNorm<Eigen::Infinity>(), 1e-12) << what;
    EXPECT_LT(reusing.result().dual_residual, 1e-9) << what;
  };
  expect_fresh(H, 0.0, "first factorisation");
  // Adds δ to H_ij = H_ji and |δ| to H_ii, H_jj: H stays positive definite.
  auto perturb = [](Eigen::MatrixXd& M, int i, int j, double delta) {
    M(i, j) += delta;
    M(j, i) += delta;
    M(i, i) += std::abs(delta);
    M(j, j) += std::abs(delta);
  };
  Eigen::MatrixXd Hk = H;
  perturb(Hk, 10, 3, 0.7);  // the first block's trailing rows (10, 11) only
  perturb(Hk, 11, 10, -0.2);
  expect_fresh(Hk, 0.0, "trailing rows of a block changed");
  perturb(Hk, 1, 0, -0.4);  // a leading row: nothing of that block can be kept
  expect_fresh(Hk, 0.0, "leading row changed");
  perturb(Hk, 19, 15, 0.3);  // the second block only
  expect_fresh(Hk, 0.0, "second block changed");
  expect_fresh(Hk, 1e-3, "regularisation changed");
  Eigen::MatrixXd coupled = Hk;  // the blocks merge: the block structure changed
  perturb(coupled, 14, 2, 0.5);
  expect_fresh(coupled, 1e-3, "blocks merged");
  expect_fresh(Hk, 1e-3, "blocks split again");
  Eigen::MatrixXd indefinite = Hk;  // fails half-way through the first block
  indefinite(11, 11) = -5.0;
  reusing.settings().regularization = 1e-3;
  EXPECT_EQ(reusing.init(indefinite, g, A, lb, ub), QpStatus::invalid_input);
  expect_fresh(Hk, 1e-3, "after a failed factorisation");
}

TEST(DenseQp, FixedSizesMatchDynamicSizes) {
  QpFactory f(6);
  QpProblem p = f.make(6, 4, QpKind::generic);
  DenseQp<double, 6, 4> fixed;
  DenseQp<double> dynamic(6, 4);
  Eigen::Matrix<double, 6, 6> H = p.H;
  Eigen::Matrix<double, 4, 6> A = p.A;
  ASSERT_EQ(fixed.init(H, p.g, A, p.lb, p.ub, p.l, p.u), QpStatus::unsolved);
  ASSERT_EQ(fixed.solve().status, QpStatus::solved);
  ASSERT_EQ(solve_problem(dynamic, p), QpStatus::solved);
  EXPECT_LE((fixed.result().x - dynamic.result().x).lpNorm<Eigen::Infinity>(), 1e-13);
  EXPECT_LE((fixed.result().x - p.x_star).lpNorm<Eigen::Infinity>(), 1e-9);
  // Single variable, single row: the column-vector special case of the row-major A.
  DenseQp<double, 1, 1> tiny;
  Eigen::Matrix<double, 1, 1> h(2.0), g1(-4.0), a(1.0), lo(-kInf), hi(1.0);
  tiny.init(h, g1, a, lo, hi);
  ASSERT_EQ(tiny.solve().status, QpStatus::solved);
  EXPECT_NEAR(tiny.result().x[0], 1.0, 1e-15);
  EXPECT_NEAR(tiny.result().y[0], 2.0, 1e-14);  // 2·1 − 4 + y = 0
}

TEST(DenseQp, FloatScalar) {
  QpFactory f(7);
  QpProblem p = f.make(10, 8, QpKind::generic);
  DenseQp<float> qp(10, 8);
  Eigen::MatrixXf H = p.H.cast<float>(), A = p.A.cast<float>();
  ASSERT_EQ(qp.init(H, p.g.cast<float>(), A, p.lb.cast<float>(), p.ub.cast<float>(),
                    p.l.cast<float>(), p.u.cast<float>()),
            QpStatus::unsolved);
  ASSERT_EQ(qp.solve().status, QpStatus::solved);
  EXPECT_LE((qp.result().x.cast<double>() - p.x_star).lpNorm<Eigen::Infinity>(),
            1e-2 * std::max(1.0, p.x_star.lpNorm<Eigen::Infinity>()));
}

TEST(DenseQp, RegularisationSolvesSemidefiniteHessian) {
  // H = diag(1, 0): without regularisation invalid; with ε the regularised problem is solved.
  Eigen::Matrix2d H;
  H << 1, 0, 0, 0;
  Eigen::Vector2d g(-1, -1);
  Eigen::RowVector2d A(0, 1);
  Eigen::Matrix<double, 1, 1> lb(-kInf), ub(2.0);
  DenseQp<double> qp(2, 1);
  EXPECT_EQ(qp.init(H, g, A, lb, ub), QpStatus::invalid_input);
  EXPECT_NE(std::string(qp.result().message).find("positive definite"), std::string::npos);
  EXPECT_EQ(qp.solve().status, QpStatus::invalid_input);
  EXPECT_TRUE(qp.result().x.allFinite());
  qp.settings().regularization = 1e-8;
  ASSERT_EQ(qp.init(H, g, A, lb, ub), QpStatus::unsolved);
  const auto& r = qp.solve();
  ASSERT_EQ(r.status, QpStatus::solved);
  // Regularised optimum: x0 = 1/(1+ε), x1 = 2 (bound active, multiplier 1 − 2ε).
  EXPECT_NEAR(r.x[0], 1.0 / (1.0 + 1e-8), 1e-10);  // cond(H + εI) = 1e8
  EXPECT_NEAR(r.x[1], 2.0, 1e-14);
  EXPECT_NEAR(r.y[0], 1.0 - 2e-8, 1e-10);
}

// Issue 22: the solver owns its data. Writing them in place through problem() and calling
// init() / update() gives what the copying overloads give, bit for bit; init() twice with
// regularisation factorises H + εI both times (H itself is never changed); data resized
// through problem() throw.
TEST(DenseQp, ProblemWrittenInPlaceMatchesCopyingInit) {
  QpFactory f(21);
  for (int k = 0; k < 12; ++k) {
    const QpProblem p = f.make(30, 60, k % 2 == 0 ? QpKind::generic : QpKind::many_bounds);
    DenseQp<double> copying(30, 60), in_place(30, 60);
    copying.settings().regularization = in_place.settings().regularization = 1e-9 * (k % 3);
    ASSERT_EQ(solve_problem(copying, p), QpStatus::solved) << k;
    auto& d = in_place.problem();
    d.H = p.H;
    d.g = p.g;
    d.A = p.A;
    d.lb = p.lb;
    d.ub = p.ub;
    d.l = p.l;
    d.u = p.u;
    ASSERT_EQ(in_place.init(), QpStatus::unsolved) << k;
    ASSERT_EQ(in_place.init(), QpStatus::unsolved) << k;  // ε is added once, not twice
    EXPECT_EQ(in_place.problem().H, p.H) << k;
    ASSERT_EQ(in_place.solve().status, QpStatus::solved) << k;
    EXPECT_EQ(in_place.result().x, copying.result().x) << k;
    EXPECT_EQ(in_place.result().y, copying.result().y) << k;
    EXPECT_EQ(in_place.result().dual_residual, copying.result().dual_residual) << k;
    EXPECT_LT(in_place.result().dual_residual, 1e-8) << k;
    // A new gradient in place: update() reuses the factorisations, as update(g, lb, ub) does.
    const Eigen::VectorXd g2 = 0.5 * p.g + Eigen::VectorXd::Constant(30, 0.1);
    in_place.problem().g = g2;
    ASSERT_EQ(in_place.update(), QpStatus::unsolved) << k;
    ASSERT_EQ(copying.update(g2, p.lb, p.ub), QpStatus::unsolved) << k;
    EXPECT_EQ(in_place.solve().x, copying.solve().x) << k;
  }
  // The documented snippet: H, g and A written, bounds left as constructed (absent) = the
  // unconstrained minimum −H⁻¹g.
  DenseQp<double> fresh(3, 2);
  fresh.problem().H = Eigen::Vector3d(1.0, 2.0, 4.0).asDiagonal();
  fresh.problem().g = Eigen::Vector3d(-1.0, -1.0, -1.0);
  fresh.problem().A.setOnes();
  ASSERT_EQ(fresh.init(), QpStatus::unsolved);
  ASSERT_EQ(fresh.solve().status, QpStatus::solved);
  EXPECT_LT((fresh.result().x - Eigen::Vector3d(1.0, 0.5, 0.25)).norm(), 1e-15);
  // A failed init() leaves nothing for update() to reuse.
  fresh.problem().A(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fresh.init(), QpStatus::invalid_input);
  fresh.problem().A(0, 1) = 1.0;
  EXPECT_EQ(fresh.update(), QpStatus::invalid_input);
  EXPECT_EQ(fresh.solve().status, QpStatus::invalid_input);
  ASSERT_EQ(fresh.init(), QpStatus::unsolved);
  // Settings made invalid after init() are reported by update() too.
  fresh.settings().dependency_tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fresh.update(), QpStatus::invalid_input);
  EXPECT_NE(std::string(fresh.result().message).find("dependency_tolerance"), std::string::npos);
  DenseQp<double> qp(3, 2);
  qp.problem().H.resize(4, 4);
  EXPECT_THROW(qp.init(), walkgen::invalid_argument);
  qp.problem().H.setIdentity(3, 3);
  qp.problem().lb.resize(1);
  EXPECT_THROW(qp.init(), walkgen::invalid_argument);
}

// validate(QpSettings): the constructor throws naming the field, its range and the value; a bad
// value set later through settings() makes init() report invalid_input naming the field.
TEST(DenseQp, SettingsAreValidated) {
  walkgen::QpSettings<double> s;
  EXPECT_NO_THROW(walkgen::validate(s));
  const auto expect_rejected = [](walkgen::QpSettings<double> bad, const char* field) {
    try {
      DenseQp<double> qp(2, 1, bad);
      ADD_FAILURE() << field << " accepted";
    } catch (const walkgen::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  s.max_iterations = -1;
  expect_rejected(s, "QpSettings.max_iterations");
  s = {};
  s.regularization = std::numeric_limits<double>::quiet_NaN();
  expect_rejected(s, "QpSettings.regularization");
  s = {};
  s.primal_tolerance = 0.0;
  expect_rejected(s, "QpSettings.primal_tolerance");
  s = {};
  s.dependency_tolerance = 1.0;
  expect_rejected(s, "QpSettings.dependency_tolerance");
  DenseQp<double> qp(2, 1);
  qp.settings().primal_tolerance = -1.0;
  EXPECT_EQ(qp.init(Eigen::Matrix2d::Identity(), Eigen::Vector2d::Ones(), Eigen::RowVector2d(1, 0),
                    Eigen::Matrix<double, 1, 1>(-1.0), Eigen::Matrix<double, 1, 1>(1.0)),
            QpStatus::invalid_input);
  EXPECT_NE(std::string(qp.result().message).find("QpSettings.primal_tolerance"),
            std::string::npos);
}

TEST(DenseQp, IterationLimitIsReported) {
  QpFactory f(8);
  QpProblem p = f.make(40, 80, QpKind::generic);
  DenseQp<double> qp(40, 80);
  qp.settings().max_iterations = 2;
  qp.settings().warm_start = false;
  EXPECT_EQ(solve_problem(qp, p), QpStatus::max_iterations);
  EXPECT_TRUE(qp.result().x.allFinite());
  qp.settings().max_iterations = 0;
  EXPECT_EQ(solve_problem(qp, p), QpStatus::solved);
}

TEST(DenseQp, WrongSizesThrowWithExpectedGot) {
  DenseQp<double> qp(3, 2);
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(3, 3), A = Eigen::MatrixXd::Ones(2, 3);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3), lb = -Eigen::VectorXd::Ones(2),
                  ub = Eigen::VectorXd::Ones(2);
  try {
    qp.init(Eigen::MatrixXd::Identity(4, 4), g, A, lb, ub);
    FAIL() << "expected walkgen::invalid_argument";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected an n x n matrix, got 4 x 4"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(qp.init(H, Eigen::VectorXd::Zero(2), A, lb, ub), walkgen::invalid_argument);
  EXPECT_THROW(qp.init(H, g, Eigen::MatrixXd::Ones(3, 3), lb, ub), walkgen::invalid_argument);
  EXPECT_THROW(qp.init(H, g, A, lb, Eigen::VectorXd::Ones(3)), walkgen::invalid_argument);
  EXPECT_THROW(qp.init(H, g, A, lb, ub, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(3)),
               walkgen::invalid_argument);
  EXPECT_THROW((DenseQp<double>(0, 2)), walkgen::invalid_argument);
  EXPECT_THROW((DenseQp<double>(3, -1)), walkgen::invalid_argument);
  EXPECT_THROW((DenseQp<double, 3, 2>(3, 5)), walkgen::invalid_argument);
  // Mismatched sizes in update() too.
  ASSERT_EQ(qp.init(H, g, A, lb, ub), QpStatus::unsolved);
  EXPECT_THROW(qp.update(Eigen::VectorXd::Zero(4), lb, ub), walkgen::invalid_argument);
}

TEST(DenseQp, BadNumbersGiveInvalidInputNeverNan) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(3, 3), A = Eigen::MatrixXd::Ones(2, 3);
  Eigen::VectorXd g = Eigen::VectorXd::Ones(3), lb = -Eigen::VectorXd::Ones(2),
                  ub = Eigen::VectorXd::Ones(2);
  struct Case {
    const char* name;
    Eigen::MatrixXd H, A;
    Eigen::VectorXd g, lb, ub;
    const char* message_part;
  };
  std::vector<Case> cases;
  auto with = [&](const char* name, const char* part) {
    cases.push_back({name, H, A, g, lb, ub, part});
    return &cases.back();
  };
  with("NaN in g", "g has a NaN")->g[1] = nan;
  with("Inf in g", "g has a NaN or Inf")->g[0] = kInf;
  with("NaN in H", "H has a NaN")->H(1, 1) = nan;
  with("Inf in A", "A has a NaN or Inf")->A(0, 2) = -kInf;
  with("NaN in lb", "NaN")->lb[0] = nan;
  with("lb > ub", "lb > ub")->lb[1] = 2.0;
  with("lb = +inf", "lb = +inf")->lb[0] = kInf;
  Case* c = with("H not symmetric", "not symmetric");
  c->H(0, 1) = 0.5;
  c = with("H indefinite", "positive definite");
  c->H(2, 2) = -1.0;
  for (const Case& k : cases) {
    DenseQp<double> qp(3, 2);
    EXPECT_EQ(qp.init(k.H, k.g, k.A, k.lb, k.ub), QpStatus::invalid_input) << k.name;
    EXPECT_NE(std::string(qp.result().message).find(k.message_part), std::string::npos)
        << k.name << ": " << qp.result().message;
    const auto& r = qp.solve();
    EXPECT_EQ(r.status, QpStatus::invalid_input) << k.name;
    EXPECT_TRUE(r.x.allFinite() && r.y.allFinite() && r.z.allFinite()) << k.name;
  }
  // A valid init followed by a bad update: invalid until fixed, then solved again.
  DenseQp<double> qp(3, 2);
  ASSERT_EQ(qp.init(H, g, A, lb, ub), QpStatus::unsolved);
  ASSERT_EQ(qp.solve().status, QpStatus::solved);
  Eigen::VectorXd bad = g;
  bad[2] = nan;
  EXPECT_EQ(qp.update(bad, lb, ub), QpStatus::invalid_input);
  EXPECT_EQ(qp.solve().status, QpStatus::invalid_input);
  EXPECT_TRUE(qp.result().x.allFinite());
  EXPECT_EQ(qp.update(g, lb, ub), QpStatus::unsolved);
  EXPECT_EQ(qp.solve().status, QpStatus::solved);
  // update() before any init().
  DenseQp<double> fresh(3, 2);
  EXPECT_EQ(fresh.update(g, lb, ub), QpStatus::invalid_input);
}

// Issue 21, defect 2 (reproducer qp_tiny_hessian_fixed_vars.cpp of the reliability pass): with H
// tiny against g, −H⁻¹g is huge and the active-set step onto l = u = −2 cancelled away every
// digit, yet the status said solved (x = 5e182 at scale 1e-199, x = 0 for n = 1, h = 1e-17).
// Solved must mean every constraint, active ones included, holds within tolerance.
TEST(DenseQp, SolvedIsCheckedAgainstEveryConstraintWhenHIsTinyAgainstG) {
  Eigen::Matrix3d H0;
  H0 << 2.8, 2.7, 2.7, 2.7, 2.8, 2.7, 2.7, 2.7, 2.8;
  const Eigen::Vector3d g(-3, -3, -3), fixed(-2, -2, -2);
  int solved = 0;
  for (double scale : {1.0, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16, 1e-100, 1e-150, 1e-199}) {
    DenseQp<double> qp(3, 0);
    ASSERT_EQ(qp.init(H0 * scale, g, Eigen::MatrixXd(0, 3), Eigen::VectorXd(0), Eigen::VectorXd(0),
                      fixed, fixed),
              QpStatus::unsolved);
    const auto& r = qp.solve();
    ASSERT_TRUE(r.x.allFinite()) << "scale " << scale;
    if (r.status == QpStatus::solved) {
      ++solved;
      EXPECT_LE((r.x - fixed).lpNorm<Eigen::Infinity>(), 1e-9) << "scale " << scale;
      EXPECT_LE(r.primal_residual, 1e-9) << "scale " << scale;
    } else {
      EXPECT_EQ(r.status, QpStatus::inaccurate) << "scale " << scale;
      EXPECT_GT(std::string(r.message).size(), 0u);
    }
    // Iterative refinement on the active set recovers every scale down to 1e-16.
    if (scale >= 1e-16) {
      EXPECT_EQ(r.status, QpStatus::solved) << "scale " << scale;
    }
  }
  EXPECT_GE(solved, 7);
  // One variable: minimise ½hx² − 3x subject to x = −2.
  for (double h : {1.0, 1e-12, 1e-17, 1e-200}) {
    DenseQp<double> qp(1, 0);
    const Eigen::VectorXd x_fixed = Eigen::VectorXd::Constant(1, -2.0);
    ASSERT_EQ(
        qp.init(Eigen::MatrixXd::Constant(1, 1, h), Eigen::VectorXd::Constant(1, -3.0),
                Eigen::MatrixXd(0, 1), Eigen::VectorXd(0), Eigen::VectorXd(0), x_fixed, x_fixed),
        QpStatus::unsolved);
    const auto& r = qp.solve();
    EXPECT_EQ(r.status, QpStatus::solved) << "h = " << h;
    EXPECT_NEAR(r.x[0], -2.0, 1e-12) << "h = " << h;
  }
  // −H⁻¹g overflows (h = 1e-320, denormal): inaccurate with a finite x, never solved or inf.
  DenseQp<double> qp(1, 0);
  ASSERT_EQ(qp.init(Eigen::MatrixXd::Constant(1, 1, 1e-320), Eigen::VectorXd::Constant(1, -3.0),
                    Eigen::MatrixXd(0, 1), Eigen::VectorXd(0), Eigen::VectorXd(0),
                    Eigen::VectorXd::Constant(1, -2.0), Eigen::VectorXd::Constant(1, -2.0)),
            QpStatus::unsolved);
  EXPECT_EQ(qp.solve().status, QpStatus::inaccurate);
  EXPECT_TRUE(qp.result().x.allFinite());
}

// Issue 22: every solve after init() refactorises its warm start from scratch (H and A changed),
// by a left-looking Householder QR of L⁻¹N that keeps Q in product form (for n >= 32 and at
// least n/4 constraints; cold solves keep J explicitly, so these tests check one form against
// the other). It must take the same constraints as adding them one by one did and agree with a
// cold solve to rounding, also with nearly as many active constraints as variables (the walking
// MPC has q ≈ 0.8 n).
struct Agreement {
  double x = 0;               // max |x_a − x_b| / max(1, |x|∞)
  double multipliers = 0;     // max |(y,z)_a − (y,z)_b| / max(1, |(y,z)|∞)
  int active_mismatches = 0;  // constraints active in one solution only (beyond rounding)
};

Agreement agreement(const DenseQp<double>::Result& a, const DenseQp<double>::Result& b) {
  Agreement r;
  r.x = (a.x - b.x).lpNorm<Eigen::Infinity>() / std::max(1.0, a.x.lpNorm<Eigen::Infinity>());
  const double scale = std::max(
      {1.0, a.y.size() > 0 ? a.y.lpNorm<Eigen::Infinity>() : 0.0, a.z.lpNorm<Eigen::Infinity>()});
  const double dy = a.y.size() > 0 ? (a.y - b.y).lpNorm<Eigen::Infinity>() : 0.0;
  r.multipliers = std::max(dy, (a.z - b.z).lpNorm<Eigen::Infinity>()) / scale;
  // Active: a multiplier beyond rounding (weakly active constraints may go either way).
  const double tiny = 1e-7 * scale;
  for (Eigen::Index i = 0; i < a.y.size(); ++i) {
    r.active_mismatches += (std::abs(a.y[i]) > tiny) != (std::abs(b.y[i]) > tiny);
  }
  for (Eigen::Index j = 0; j < a.z.size(); ++j) {
    r.active_mismatches += (std::abs(a.z[j]) > tiny) != (std::abs(b.z[j]) > tiny);
  }
  return r;
}

TEST(DenseQp, RebuiltWarmStartMatchesColdSolveWithManyActiveConstraints) {
  const QpKind kinds[] = {QpKind::generic, QpKind::equalities, QpKind::many_bounds};
  double worst_x = 0, worst_multipliers = 0, worst_kkt = 0;
  int most_active = 0, most_n = 0;
  for (int k = 0; k < 36; ++k) {
    QpFactory f(22000u + static_cast<unsigned>(k));
    const int n = f.integer(40, 150), m = 3 * n;  // enough rows to use up n − 1 active ones
    QpProblem p = f.make(n, m, kinds[k % 3]);
    DenseQp<double> warm(n, m), cold(n, m);
    cold.settings().warm_start = false;
    ASSERT_EQ(solve_problem(warm, p), QpStatus::solved);
    // The next problem, as the next MPC tick: H and A change (rows rescaled with their bounds,
    // which keeps the feasible set), g moves and the bounds move along a small δx.
    p.H.diagonal().array() *= 1.0 + 0.05 * f.uniform(0.0, 1.0);
    Eigen::VectorXd dx(n);
    for (int j = 0; j < n; ++j) {
      p.g[j] += 0.01 * f.normal();
      dx[j] = 0.01 * f.normal();
    }
    const Eigen::VectorXd Adx = p.A * dx;
    for (int i = 0; i < m; ++i) {
      const double s = 1.0 + 0.1 * f.uniform(-1.0, 1.0);
      p.A.row(i) *= s;
      p.lb[i] = s * (p.lb[i] + Adx[i]);
      p.ub[i] = s * (p.ub[i] + Adx[i]);
    }
    p.l += dx;
    p.u += dx;
    const auto& rw = solve_problem(warm, p);
    ASSERT_EQ(rw, QpStatus::solved) << "problem " << k;
    const auto& w = warm.result();
    EXPECT_TRUE(w.warm_started);
    EXPECT_FALSE(w.reused_factorization);
    ASSERT_EQ(solve_problem(cold, p), QpStatus::solved) << "problem " << k;
    const auto& c = cold.result();
    const Agreement d = agreement(w, c);
    // cond(H) up to 1e4, rows scaled by 0.1 to 10 and q up to n: ~1e-9 is rounding here (the
    // one-by-one factorisation that the rebuild replaced differed from cold solves as much).
    EXPECT_LE(d.x, 1e-8) << "problem " << k << " (" << p.kind << ", n=" << n << ")";
    EXPECT_LE(d.multipliers, 1e-8) << "problem " << k << " (" << p.kind << ", n=" << n << ")";
    EXPECT_EQ(d.active_mismatches, 0) << "problem " << k << " (" << p.kind << ", n=" << n << ")";
    const double kkt =
        std::max(kkt_residuals(p, w.x, w.y, w.z).max(), kkt_residuals(p, c.x, c.y, c.z).max());
    EXPECT_LE(kkt, 1e-9) << "problem " << k;
    worst_x = std::max(worst_x, d.x);
    worst_multipliers = std::max(worst_multipliers, d.multipliers);
    worst_kkt = std::max(worst_kkt, kkt);
    if (w.active_set_size > most_active) {
      most_active = w.active_set_size;
      most_n = n;
    }
  }
  EXPECT_GE(most_active, 120);  // the rebuild took well over a hundred constraints
  std::printf(
      "[ stats    ] rebuilt vs cold: worst relative x difference %.2e, multipliers %.2e, KKT "
      "%.2e; up to %d active of n = %d\n",
      worst_x, worst_multipliers, worst_kkt, most_active, most_n);
}

TEST(DenseQp, RebuiltWarmStartMatchesColdSolveOnWalkingQps) {
  using Seq = walkgen::WalkingQpSequence;
  Seq seq;
  DenseQp<double> warm(Seq::kVars, Seq::kRows), cold(Seq::kVars, Seq::kRows);
  cold.settings().warm_start = false;
  double worst_x = 0, worst_multipliers = 0;
  int rebuilt = 0;
  for (int tick = 0; tick < 160; ++tick) {
    const auto w = seq.build(Seq::demo_command(tick));
    ASSERT_EQ(warm.init(w.H, w.g, w.A, w.lb, w.ub), QpStatus::unsolved);
    ASSERT_EQ(warm.solve().status, QpStatus::solved) << "tick " << tick;
    ASSERT_EQ(cold.init(w.H, w.g, w.A, w.lb, w.ub), QpStatus::unsolved);
    ASSERT_EQ(cold.solve().status, QpStatus::solved) << "tick " << tick;
    const Agreement d = agreement(warm.result(), cold.result());
    EXPECT_LE(d.x, 1e-9) << "tick " << tick;
    EXPECT_LE(d.multipliers, 1e-9) << "tick " << tick;
    EXPECT_EQ(d.active_mismatches, 0) << "tick " << tick;
    worst_x = std::max(worst_x, d.x);
    worst_multipliers = std::max(worst_multipliers, d.multipliers);
    rebuilt += warm.result().warm_started;
    seq.advance(cold.result().x);
  }
  EXPECT_GE(rebuilt, 159);
  std::printf("[ stats    ] walking QPs, rebuilt vs cold: worst x %.2e, multipliers %.2e\n",
              worst_x, worst_multipliers);
}

// A constraint of the warm start that became linearly dependent on those taken before it is
// left out of the rebuilt factorisation, as when they were added one by one: the later one in
// the previous solve's order goes, and the rebuilt active set is optimal at once. Small
// problems keep J explicitly, larger ones in product form (both are checked here).
TEST(DenseQp, DependentConstraintOfTheWarmStartIsLeftOut) {
  for (const int n : {4, 40}) {
    // H diagonal; rows x_i ≤ 1 for i < k, violated at x₀ = −H⁻¹g by k − i, so that a cold solve
    // adds them in the order 0, 1, …, k − 1.
    const int k = n == 4 ? 3 : 12;
    Eigen::VectorXd h(n), x0 = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) h[i] = 1.0 + 0.1 * i;
    for (int i = 0; i < k; ++i) x0[i] = 1.0 + (k - i);
    Eigen::MatrixXd H = h.asDiagonal(), A = Eigen::MatrixXd::Zero(k, n);
    for (int i = 0; i < k; ++i) A(i, i) = 1.0;
    Eigen::VectorXd lb = Eigen::VectorXd::Constant(k, -kInf), ub = Eigen::VectorXd::Ones(k);
    DenseQp<double> qp(n, k), cold(n, k);
    cold.settings().warm_start = false;
    ASSERT_EQ(qp.init(H, -H * x0, A, lb, ub), QpStatus::unsolved);
    ASSERT_EQ(qp.solve().status, QpStatus::solved);
    ASSERT_EQ(qp.result().active_set_size, k);
    // Next problem: H changes and row 0 becomes x_{k−2} + x_{k−1} ≤ 2, the sum of the last two.
    // Rebuilding in the order 0, …, k − 1 takes rows 0 … k − 2; row k − 1 = row 0 − row k − 2 is
    // dependent and left out.
    H(0, 0) *= 1.5;
    A.row(0).setZero();
    A(0, k - 2) = A(0, k - 1) = 1.0;
    ub[0] = 2.0;
    ASSERT_EQ(qp.init(H, -H * x0, A, lb, ub), QpStatus::unsolved);
    const auto& r = qp.solve();
    ASSERT_EQ(r.status, QpStatus::solved) << "n = " << n;
    EXPECT_TRUE(r.warm_started) << "n = " << n;
    EXPECT_EQ(r.iterations, 0) << "n = " << n;
    EXPECT_EQ(r.active_set_size, k - 1) << "n = " << n;
    // x_i = 1 for 0 < i < k; x₀ = x₀[0] (row 0 no longer bounds it) and the rest unconstrained.
    Eigen::VectorXd x = x0;
    for (int i = 1; i < k; ++i) x[i] = 1.0;
    EXPECT_LE((r.x - x).lpNorm<Eigen::Infinity>(), 1e-13) << "n = " << n;
    // Hx + g + Aᵀy = 0: row 0 takes h_{k−1}(x₀[k−1] − 1) from x_{k−1}, row k − 2 the rest of
    // h_{k−2}(x₀[k−2] − 1); row k − 1 carries nothing.
    EXPECT_EQ(r.y[k - 1], 0.0) << "n = " << n;
    EXPECT_NEAR(r.y[0], h[k - 1] * (x0[k - 1] - 1.0), 1e-13) << "n = " << n;
    EXPECT_NEAR(r.y[k - 2], h[k - 2] * (x0[k - 2] - 1.0) - r.y[0], 1e-13) << "n = " << n;
    // The same problem solved cold gives the same point and multipliers.
    ASSERT_EQ(cold.init(H, -H * x0, A, lb, ub), QpStatus::unsolved);
    ASSERT_EQ(cold.solve().status, QpStatus::solved) << "n = " << n;
    EXPECT_LE((cold.result().x - r.x).lpNorm<Eigen::Infinity>(), 1e-13) << "n = " << n;
    EXPECT_LE((cold.result().y - r.y).lpNorm<Eigen::Infinity>(), 1e-13) << "n = " << n;
  }
}

TEST(DenseQp, StatusNames) {
  EXPECT_STREQ(walkgen::to_string(QpStatus::solved), "solved");
  EXPECT_STREQ(walkgen::to_string(QpStatus::infeasible), "infeasible");
  EXPECT_STREQ(walkgen::to_string(QpStatus::max_iterations), "max_iterations");
  EXPECT_STREQ(walkgen::to_string(QpStatus::invalid_input), "invalid_input");
  EXPECT_STREQ(walkgen::to_string(QpStatus::unsolved), "unsolved");
  EXPECT_STREQ(walkgen::to_string(QpStatus::inaccurate), "inaccurate");
}

}  // namespace
