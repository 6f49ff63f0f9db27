// The NMPC's formulation block by block (include/walkgen/mpc/walking_model.hpp, constraints/,
// costs/): every constraint block's Gauss–Newton rows against central differences of its values
// and, where Ceres is on, against Jets pushed through the same values; every cost term's Hessian
// and gradient against its value; their sum against the QP the generator solved; the row
// layout's counting and warm-start renaming. Typed over (N, FootEdges, HullEdges).

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <tuple>

#include "support/derivatives.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

#ifdef WALKGEN_TEST_WITH_CERES
#include <ceres/jet.h>
#endif

namespace {

using walkgen::LayoutBlock;
using walkgen_test::Tolerance;
using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

template <int N_, int Foot_, int Hull_>
struct Config {
  static constexpr int N = N_, FootEdges = Foot_, HullEdges = Hull_;
};
using Configs = ::testing::Types<Config<16, 4, 5>, Config<Eigen::Dynamic, Eigen::Dynamic, 5>,
                                 Config<8, 4, Eigen::Dynamic>>;

// The columns of U, named as the layout names them.
walkgen_test::Blocks variable_blocks(const walkgen::WalkingLayout& L) {
  walkgen_test::Blocks blocks;
  for (const LayoutBlock& b : L.variables()) blocks.push_back({b.name, b.count()});
  return blocks;
}
// The rows of one constraint block, one named block per unit (sample or step).
walkgen_test::Blocks unit_blocks(const LayoutBlock& rows) {
  walkgen_test::Blocks blocks;
  for (Eigen::Index u = 0; u < rows.shape.repeats * rows.shape.units; ++u) {
    blocks.push_back({std::string(rows.name) + ", unit " + std::to_string(u), rows.shape.width});
  }
  return blocks;
}

template <typename C>
class WalkingBlocks : public ::testing::Test {
 protected:
  using Mpc = walkgen::WalkingMpc<double, C::N, C::FootEdges, C::HullEdges>;

  // Mid-step, turning and sidestepping, next to an obstacle: every block is nonlinear here.
  void SetUp() override {
    auto s = walkgen::hrp2_settings<double>();
    s.n = C::N == Eigen::Dynamic ? 24 : C::N;
    s.obstacles.push_back({1.0, 0.6, 0.3, 0.2});
    mpc_ = std::make_unique<Mpc>(s, /*obstacle_capacity=*/2);
    ASSERT_EQ(mpc_->set_command({0.1, 0.02, 0.15}), walkgen::CommandStatus::accepted);
    for (int k = 0; k < 13; ++k) {
      ASSERT_EQ(mpc_->solve().status, walkgen::MpcStatus::solved);
      mpc_->advance();
    }
    ASSERT_EQ(mpc_->solve().status, walkgen::MpcStatus::solved);
    U_ = mpc_->plan().U + 0.01 * Eigen::VectorXd::Random(mpc_->num_vars());  // a generic point
  }

  typename Mpc::Model::Tick tick(const Eigen::VectorXd& iterate) const {
    return mpc_->model().tick(mpc_->state(), mpc_->obstacles(), mpc_->workspace().schedule,
                              iterate);
  }

  std::unique_ptr<Mpc> mpc_;
  Eigen::VectorXd U_;
};
TYPED_TEST_SUITE(WalkingBlocks, Configs);

// Each block's rows: J against central differences of c(U) (and Jets of the same c(U)), zero
// outside the block's rows, and bounds shifted by c(U) − J U: lb ≤ J U' ≤ ub holds at U' = U
// exactly when lb_c ≤ c(U) ≤ ub_c does.
TYPED_TEST(WalkingBlocks, ConstraintRowsAreTheDerivativesOfTheirValues) {
  const auto& model = this->mpc_->model();
  const auto& L = model.layout();
  const Eigen::VectorXd& U = this->U_;
  const auto t = this->tick(U);
  const Eigen::Index m = L.num_rows(), n = L.num_vars();
  int blocks = 0;
  model.for_each_constraint([&](const auto& block, const LayoutBlock& rows) {
    ++blocks;
    SCOPED_TRACE(rows.name);
    ASSERT_GT(rows.count(), 0);
    RowMatrixXd J = RowMatrixXd::Zero(m, n);
    Eigen::VectorXd lo = Eigen::VectorXd::Constant(m, 7.0), up = lo, lc = lo, uc = lo;
    block.linearise(t, rows, U, J, lo, up);
    const auto values = [&](const Eigen::VectorXd& x) {
      Eigen::VectorXd c = Eigen::VectorXd::Zero(m);
      block.template values<double>(t, rows, x, c);
      return Eigen::VectorXd(c.segment(rows.offset, rows.count()));
    };
    const Eigen::MatrixXd analytic = J.middleRows(rows.offset, rows.count());
    const auto fd = walkgen_test::compare_jacobians(
        rows.name, analytic, walkgen_test::central_differences(values, U, 1e-6), {1e-7, 1e-6},
        unit_blocks(rows), variable_blocks(L));
    EXPECT_TRUE(fd.passed()) << fd.message();
    // Nothing outside the block's rows is written.
    EXPECT_EQ(J.topRows(rows.offset).cwiseAbs().sum(), 0.0);
    EXPECT_EQ(J.bottomRows(m - rows.offset - rows.count()).cwiseAbs().sum(), 0.0);
    EXPECT_TRUE((lo.head(rows.offset).array() == 7.0).all());
    block.bounds(t, rows, lc, uc);
    const Eigen::VectorXd c = values(U), JU = analytic * U;
    for (Eigen::Index k = 0; k < rows.count(); ++k) {
      const Eigen::Index r = rows.offset + k;
      if (std::isfinite(up[r])) {
        EXPECT_NEAR(up[r] - JU[k], uc[r] - c[k], 1e-9) << "row " << r;
      }
      if (std::isfinite(lo[r])) {
        EXPECT_NEAR(lo[r] - JU[k], lc[r] - c[k], 1e-9) << "row " << r;
      }
      EXPECT_EQ(std::isfinite(up[r]), std::isfinite(uc[r])) << "row " << r;
      EXPECT_EQ(std::isfinite(lo[r]), std::isfinite(lc[r])) << "row " << r;
    }
#ifdef WALKGEN_TEST_WITH_CERES
    using Jet = ceres::Jet<double, 8>;
    const Eigen::MatrixXd jets = walkgen_test::jet_jacobian<Jet>(
        [&](const Jet* x, Jet* y) {
          const Eigen::Matrix<Jet, Eigen::Dynamic, 1> Ux =
              Eigen::Map<const Eigen::Matrix<Jet, Eigen::Dynamic, 1>>(x, n);
          Eigen::Matrix<Jet, Eigen::Dynamic, 1> cx(m);
          cx.setConstant(Jet(0.0));
          block.template values<Jet>(t, rows, Ux, cx);
          for (Eigen::Index k = 0; k < rows.count(); ++k) y[k] = cx[rows.offset + k];
        },
        U, rows.count());
    const auto jet = walkgen_test::compare_jacobians(rows.name, analytic, jets, {1e-12, 1e-10},
                                                     unit_blocks(rows), variable_blocks(L), "Jets");
    EXPECT_TRUE(jet.passed()) << jet.message();
#endif
  });
  EXPECT_EQ(blocks, 6);
}

// The QP's rows are the blocks' rows, and its H and g the sum of the cost terms'.
TYPED_TEST(WalkingBlocks, TheQpIsTheSumOfTheBlocks) {
  const auto& model = this->mpc_->model();
  const auto& ws = this->mpc_->workspace();
  const auto& w = ws.qp.problem();  // the QP's data, owned by the solver
  const auto& L = model.layout();
  const auto t = this->tick(ws.iterate);
  RowMatrixXd J(L.num_rows(), L.num_vars());
  Eigen::VectorXd lb(L.num_rows()), ub(L.num_rows());
  model.linearise(t, ws.iterate, J, lb, ub);
  EXPECT_EQ(J, w.A);
  EXPECT_EQ(lb, w.lb);
  EXPECT_EQ(ub, w.ub);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(L.num_vars(), L.num_vars());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(L.num_vars()), scratch(L.dims().N);
  std::apply(
      [&](const auto&... cost) {
        (cost.add_constant_hessian(L, model.preview(), H), ...);
        (cost.add(t, H, g, scratch), ...);
      },
      model.costs());
  EXPECT_LE((H - w.H).cwiseAbs().maxCoeff(), 1e-14 * w.H.cwiseAbs().maxCoeff());
  EXPECT_LE((g - w.g).cwiseAbs().maxCoeff(), 1e-14 * (1.0 + w.g.cwiseAbs().maxCoeff()));
  EXPECT_EQ(H, H.transpose());
}

// Each cost term is the quadratic ½UᵀH_kU + g_kᵀU + const its Hessian and gradient say: both
// against differences of its value (exact for a quadratic, hence unit steps) and Jets.
TYPED_TEST(WalkingBlocks, EachCostTermIsTheQuadraticOfItsHessianAndGradient) {
  const auto& model = this->mpc_->model();
  const auto& L = model.layout();
  const Eigen::Index n = L.num_vars();
  const auto t = this->tick(this->mpc_->workspace().iterate);
  const Eigen::VectorXd& U = this->U_;
  std::apply(
      [&](const auto&... cost) {
        const auto check = [&](const auto& term) {
          SCOPED_TRACE(term.kName);
          Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
          Eigen::VectorXd g = Eigen::VectorXd::Zero(n), scratch(L.dims().N);
          term.add_constant_hessian(L, model.preview(), H);
          term.add(t, H, g, scratch);
          const auto phi = [&](const Eigen::VectorXd& x) {
            return Eigen::VectorXd::Constant(1, term.template value<double>(t, x));
          };
          const Eigen::MatrixXd gradient = (H * U + g).transpose();
          const double scale = 1.0 + std::abs(phi(U)[0]);
          const Tolerance tol{1e-9 * scale, 1e-9};
          const auto fd = walkgen_test::compare_jacobians(
              term.kName, gradient, walkgen_test::central_differences(phi, U, 1.0), tol, {},
              variable_blocks(L));
          EXPECT_TRUE(fd.passed()) << fd.message();
          Eigen::MatrixXd second(n, n);  // Φ(U + e_i + e_j) − Φ(U + e_i) − Φ(U + e_j) + Φ(U)
          for (Eigen::Index i = 0; i < n; ++i) {
            for (Eigen::Index j = 0; j < n; ++j) {
              const Eigen::VectorXd ei = Eigen::VectorXd::Unit(n, i),
                                    ej = Eigen::VectorXd::Unit(n, j);
              second(i, j) = phi(U + ei + ej)[0] - phi(U + ei)[0] - phi(U + ej)[0] + phi(U)[0];
            }
          }
          const auto hessian = walkgen_test::compare_jacobians(
              std::string(term.kName) + " Hessian", H, second, tol, variable_blocks(L),
              variable_blocks(L), "second differences");
          EXPECT_TRUE(hessian.passed()) << hessian.message();
#ifdef WALKGEN_TEST_WITH_CERES
          using Jet = ceres::Jet<double, 8>;
          const Eigen::MatrixXd jets = walkgen_test::jet_jacobian<Jet>(
              [&](const Jet* x, Jet* y) {
                y[0] = term.template value<Jet>(
                    t, Eigen::Matrix<Jet, Eigen::Dynamic, 1>(
                           Eigen::Map<const Eigen::Matrix<Jet, Eigen::Dynamic, 1>>(x, n)));
              },
              U, 1);
          const auto jet = walkgen_test::compare_jacobians(
              term.kName, gradient, jets, {1e-10 * scale, 1e-10}, {}, variable_blocks(L), "Jets");
          EXPECT_TRUE(jet.passed()) << jet.message();
#endif
        };
        (check(cost), ...);
      },
      model.costs());
}

// One layout: the blocks tile the rows in the model's order, and the warm-start renaming moves
// each row and bound by its block's rule.
TEST(WalkingLayout, BlocksTileTheRowsAndRenameByTheirShiftRule) {
  walkgen::WalkingMpc<double, 16> mpc(walkgen::hrp2_settings<double>(), /*obstacle_capacity=*/2);
  const auto& L = mpc.layout();
  const Eigen::Index N = 16, nf = mpc.planned_steps(), m = L.num_rows();
  ASSERT_EQ(L.num_row_blocks(), 6);
  Eigen::Index next = 0;
  for (int k = 0; k < L.num_row_blocks(); ++k) {
    EXPECT_EQ(L.rows(k).offset, next) << L.rows(k).name;
    next += L.rows(k).count();
  }
  EXPECT_EQ(next, m);
  EXPECT_EQ(m, N * 4 + nf * 5 + 2 * nf + 2 * nf + 2 * nf + 4);
  EXPECT_EQ(L.num_vars(), 2 * (N + nf) + nf);
  using Zmp = walkgen::ZmpPolygon<double, 16, 4>;
  using Capture = walkgen::CapturePoint<double, 16, 4>;
  EXPECT_STREQ(L.block_of_row(0), Zmp::kName);
  EXPECT_STREQ(L.block_of_row(m - 1), Capture::kName);
  const LayoutBlock &zmp = L.rows(0), &hull = L.rows(1), &yaw = L.rows(2), &separation = L.rows(3),
                    &obstacles = L.rows(4), &capture = L.rows(5);
  // One sample advanced, no landing: ZMP rows move back one sample, per-step rows stay.
  EXPECT_EQ(L.renamed(zmp.offset + 4 * 3 + 2, 1, 0), zmp.offset + 4 * 2 + 2);
  EXPECT_EQ(L.renamed(zmp.offset + 1, 1, 0), -1);  // sample 0 left the horizon
  EXPECT_EQ(L.renamed(hull.offset + 5 + 1, 1, 0), hull.offset + 5 + 1);
  EXPECT_EQ(L.renamed(capture.offset + 2, 1, 1), capture.offset + 2);
  // A landing: step i becomes i − 1 in every per-step block, step 1 leaves.
  EXPECT_EQ(L.renamed(hull.offset + 5 + 3, 1, 1), hull.offset + 3);
  EXPECT_EQ(L.renamed(hull.offset + 3, 1, 1), -1);
  EXPECT_EQ(L.renamed(yaw.offset + nf + 1, 1, 1), yaw.offset + nf);  // the rate row of step 2
  EXPECT_EQ(L.renamed(yaw.offset + nf, 1, 1), -1);
  EXPECT_EQ(L.renamed(separation.offset + 2 + 1, 1, 1), separation.offset + 1);  // step 2, back
  EXPECT_EQ(L.renamed(separation.offset + 1, 1, 1), -1);
  EXPECT_EQ(L.renamed(obstacles.offset + nf + 1, 1, 1), obstacles.offset + nf);  // obstacle 1
  // Bounds: jerks move by samples, footsteps by steps.
  EXPECT_EQ(L.renamed(m + L.jerk_y() + 5, 1, 0), m + L.jerk_y() + 4);
  EXPECT_EQ(L.renamed(m + L.jerk_x(), 1, 0), -1);
  EXPECT_EQ(L.renamed(m + L.step_q() + 1, 1, 1), m + L.step_q());
  EXPECT_EQ(L.renamed(m + L.step_x() + 1, 1, 0), m + L.step_x() + 1);
  EXPECT_EQ(L.renamed(m + L.num_vars(), 1, 0), -1);
}

}  // namespace
