// Proves that DenseQp's init(), update() and solve() never touch the heap after construction
// (docs/design.md convention 6). Two independent checks: Eigen's EIGEN_RUNTIME_NO_MALLOC guard (any
// Eigen heap allocation aborts; this target keeps asserts on) and a counting operator new.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdlib>
#include <new>
#include <vector>

#include "support/count_allocations.hpp"
#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/scenarios/manufactured_qp.hpp"
#include "walkgen/scenarios/walking_qp_sequence.hpp"

namespace {

using walkgen::DenseQp;
using walkgen::QpStatus;
using walkgen_test::count_allocations;

TEST(DenseQpNoAlloc, GuardsAreArmed) {
  // Positive controls: both detectors see an allocation.
  static volatile int sink = 0;
  EXPECT_EQ(count_allocations([] {
              std::vector<int> v(static_cast<std::size_t>(4 + sink));
              v[0] = 1;
              sink = v[0];
            }),
            1);
  EXPECT_DEATH(
      {
        Eigen::internal::set_is_malloc_allowed(false);
        Eigen::VectorXd v(100);
        v.setZero();
      },
      "");
}

TEST(DenseQpNoAlloc, WalkingSequence) {
  walkgen::WalkingQpSequence seq;
  using Seq = walkgen::WalkingQpSequence;
  std::vector<walkgen::WalkingQp> problems;
  DenseQp<double> reference(Seq::kVars, Seq::kRows);
  for (int k = 0; k < 40; ++k) {
    problems.push_back(seq.build({0.1, 0.0, k > 20 ? 0.1 : 0.0}));
    const auto& p = problems.back();
    reference.init(p.H, p.g, p.A, p.lb, p.ub);
    ASSERT_EQ(reference.solve().status, QpStatus::solved);
    seq.advance(reference.result().x);
  }
  DenseQp<double> warm(Seq::kVars, Seq::kRows), cold(Seq::kVars, Seq::kRows);
  cold.settings().warm_start = false;
  int solved = 0;
  const long news = count_allocations([&] {
    for (const auto& p : problems) {
      warm.init(p.H, p.g, p.A, p.lb, p.ub);
      solved += warm.solve().status == QpStatus::solved;
      warm.update(p.g, p.lb, p.ub);  // factorisation reuse path
      solved += warm.solve().status == QpStatus::solved;
      cold.init(p.H, p.g, p.A, p.lb, p.ub);
      solved += cold.solve().status == QpStatus::solved;
    }
  });
  EXPECT_EQ(news, 0);
  EXPECT_EQ(solved, 3 * static_cast<int>(problems.size()));
}

TEST(DenseQpNoAlloc, DegenerateInfeasibleAndInvalidPaths) {
  walkgen::QpFactory f(11);
  const auto degenerate = f.make(60, 120, walkgen::QpKind::degenerate);
  const auto equalities = f.make(60, 120, walkgen::QpKind::equalities);
  const auto infeasible = f.make_infeasible(60, 120);
  Eigen::VectorXd bad_g = degenerate.g;
  bad_g[3] = std::numeric_limits<double>::quiet_NaN();
  DenseQp<double> qp(60, 120);
  QpStatus s[5];
  const long news = count_allocations([&] {
    for (const auto* p : {&degenerate, &equalities, &infeasible}) {
      qp.init(p->H, p->g, p->A, p->lb, p->ub, p->l, p->u);
      s[p == &degenerate ? 0 : p == &equalities ? 1 : 2] = qp.solve().status;
    }
    qp.init(degenerate.H, bad_g, degenerate.A, degenerate.lb, degenerate.ub);
    s[3] = qp.solve().status;
    qp.settings().max_iterations = 1;
    qp.init(equalities.H, equalities.g, equalities.A, equalities.lb, equalities.ub, equalities.l,
            equalities.u);
    s[4] = qp.solve().status;
  });
  EXPECT_EQ(news, 0);
  EXPECT_EQ(s[0], QpStatus::solved);
  EXPECT_EQ(s[1], QpStatus::solved);
  EXPECT_EQ(s[2], QpStatus::infeasible);
  EXPECT_EQ(s[3], QpStatus::invalid_input);
  EXPECT_EQ(s[4], QpStatus::max_iterations);
}

TEST(DenseQpNoAlloc, FixedSizes) {
  walkgen::QpFactory f(12);
  const auto p = f.make(8, 6, walkgen::QpKind::generic);
  const Eigen::Matrix<double, 8, 8> H = p.H;
  const Eigen::Matrix<double, 6, 8> A = p.A;
  const Eigen::Matrix<double, 8, 1> g = p.g, l = p.l, u = p.u;
  const Eigen::Matrix<double, 6, 1> lb = p.lb, ub = p.ub;
  QpStatus status = QpStatus::unsolved;
  const long news = count_allocations([&] {
    DenseQp<double, 8, 6> qp;  // even construction is allocation-free with fixed sizes
    qp.init(H, g, A, lb, ub, l, u);
    status = qp.solve().status;
  });
  EXPECT_EQ(news, 0);
  EXPECT_EQ(status, QpStatus::solved);
}

}  // namespace
