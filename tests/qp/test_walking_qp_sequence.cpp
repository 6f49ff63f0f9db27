// The walking-like QP sequence (tests/support/walking_qp.hpp, built from the LIPM preview
// matrices of thesis eq. 2.36–2.42): every QP solved with KKT residuals ≤ 1e-9, warm-started
// solves equal to cold solves to 1e-9, and the resulting walk follows the command.

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/scenarios/manufactured_qp.hpp"
#include "walkgen/scenarios/walking_qp_sequence.hpp"

namespace {

using walkgen::DenseQp;
using walkgen::QpStatus;
using Seq = walkgen::WalkingQpSequence;

walkgen::QpProblem as_problem(const walkgen::WalkingQp& w) {
  walkgen::QpProblem p;
  p.H = w.H;
  p.A = w.A;
  p.g = w.g;
  p.lb = w.lb;
  p.ub = w.ub;
  p.l = Eigen::VectorXd::Constant(w.g.size(), -std::numeric_limits<double>::infinity());
  p.u = -p.l;
  return p;
}

TEST(WalkingQpSequence, SizesAreThoseOfTheThesisProblem) {
  Seq seq;
  const auto qp = seq.build({0.1, 0, 0});
  EXPECT_EQ(qp.H.rows(), 68);
  EXPECT_EQ(qp.A.rows(), 106);
  EXPECT_EQ(qp.A.cols(), 68);
  // 64 ZMP + 10 feasibility rows are one-sided, 32 yaw rows two-sided: 138 inequalities.
  int one_sided = 0;
  for (int i = 0; i < qp.A.rows(); ++i) {
    one_sided += std::isfinite(qp.lb[i]) + std::isfinite(qp.ub[i]);
  }
  EXPECT_EQ(one_sided, 138);
}

TEST(WalkingQpSequence, WarmStartsAgreeWithColdSolves) {
  Seq seq;
  DenseQp<double> warm(Seq::kVars, Seq::kRows), cold(Seq::kVars, Seq::kRows),
      hot(Seq::kVars, Seq::kRows);
  cold.settings().warm_start = false;
  double worst_diff = 0, worst_kkt = 0;
  int warm_iterations = 0, cold_iterations = 0, hot_iterations = 0;
  constexpr int kTicks = 220;
  for (int tick = 0; tick < kTicks; ++tick) {
    const auto w = seq.build(Seq::demo_command(tick));
    const auto p = as_problem(w);
    ASSERT_EQ(cold.init(w.H, w.g, w.A, w.lb, w.ub), QpStatus::unsolved);
    const auto& rc = cold.solve();
    ASSERT_EQ(rc.status, QpStatus::solved) << "tick " << tick;
    ASSERT_EQ(warm.init(w.H, w.g, w.A, w.lb, w.ub), QpStatus::unsolved);
    const auto& rw = warm.solve();
    ASSERT_EQ(rw.status, QpStatus::solved) << "tick " << tick;
    if (tick > 0) {
      EXPECT_TRUE(rw.warm_started);
    }
    const double scale = std::max(1.0, rc.x.lpNorm<Eigen::Infinity>());
    worst_diff = std::max(worst_diff, (rw.x - rc.x).lpNorm<Eigen::Infinity>() / scale);
    worst_kkt = std::max({worst_kkt, walkgen::kkt_residuals(p, rc.x, rc.y, rc.z).max(),
                          walkgen::kkt_residuals(p, rw.x, rw.y, rw.z).max()});
    warm_iterations += rw.iterations;
    cold_iterations += rc.iterations;

    // Factorisation reuse: the same tick again with fresh state feedback (the CoM measured
    // 1 mm off), which changes only g and the bounds.
    Seq perturbed = seq;
    perturbed.set_com_offset(0.001, -0.001);
    const auto w2 = perturbed.build(Seq::demo_command(tick));
    ASSERT_TRUE(w2.H.isApprox(w.H) && w2.A.isApprox(w.A));
    hot.init(w.H, w.g, w.A, w.lb, w.ub);
    ASSERT_EQ(hot.solve().status, QpStatus::solved);
    ASSERT_EQ(hot.update(w2.g, w2.lb, w2.ub), QpStatus::unsolved);
    const auto& rh = hot.solve();
    ASSERT_EQ(rh.status, QpStatus::solved) << "tick " << tick;
    EXPECT_TRUE(rh.reused_factorization);
    hot_iterations += rh.iterations;
    const Eigen::VectorXd xh = rh.x;
    cold.init(w2.H, w2.g, w2.A, w2.lb, w2.ub);
    ASSERT_EQ(cold.solve().status, QpStatus::solved);
    worst_diff = std::max(worst_diff, (xh - cold.result().x).lpNorm<Eigen::Infinity>() /
                                          std::max(1.0, xh.lpNorm<Eigen::Infinity>()));
    seq.advance(rc.x);
  }
  EXPECT_LE(worst_diff, 1e-9);
  EXPECT_LE(worst_kkt, 1e-9);
  // Warm starts pay off: far fewer active-set changes than cold solves.
  EXPECT_LT(warm_iterations, cold_iterations / 2);
  EXPECT_LT(hot_iterations, cold_iterations / 4);
  std::printf(
      "[ stats    ] %d ticks: worst warm/cold difference %.2e, worst KKT %.2e; "
      "active-set changes per solve: cold %.1f, warm %.1f, after update() %.1f\n",
      kTicks, worst_diff, worst_kkt, double(cold_iterations) / kTicks,
      double(warm_iterations) / kTicks, double(hot_iterations) / kTicks);
}

TEST(WalkingQpSequence, TheWalkFollowsTheCommand) {
  // Physics check on the QP solutions: 8 s at 0.1 m/s forward moves the CoM about 0.8 m, the
  // first-sample ZMP stays inside the support rectangle, and feet alternate sides.
  Seq seq;
  DenseQp<double> qp(Seq::kVars, Seq::kRows);
  const double hx = 0.2172 / 2 - 0.09, hy = 0.1380 / 2 - 0.05;
  for (int tick = 0; tick < 80; ++tick) {
    const auto w = seq.build({0.1, 0.0, 0.0});
    qp.init(w.H, w.g, w.A, w.lb, w.ub);
    ASSERT_EQ(qp.solve().status, QpStatus::solved);
    const Eigen::VectorXd& u = qp.result().x;
    const auto& P = seq.lipm();
    const double zx = P.P_zs.row(0).dot(seq.com_x()) + P.P_zu(0, 0) * u[0];
    const double zy = P.P_zs.row(0).dot(seq.com_y()) + P.P_zu(0, 0) * u[Seq::kN + Seq::kSteps];
    // The first sample always lies in the current step (v₁ = 1, eq. 2.48).
    EXPECT_LE(std::abs(zx - seq.support()[0]), hx + 1e-9) << "tick " << tick;
    EXPECT_LE(std::abs(zy - seq.support()[1]), hy + 1e-9) << "tick " << tick;
    seq.advance(u);
  }
  EXPECT_NEAR(seq.com_x()[0], 0.8, 0.15);
  EXPECT_NEAR(seq.com_x()[1], 0.1, 0.03);
  EXPECT_LT(std::abs(seq.com_y()[0]), 0.12);
}

}  // namespace
