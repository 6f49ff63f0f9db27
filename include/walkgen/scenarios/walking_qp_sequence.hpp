#pragma once
/// @file
/// A walking-like sequence of QPs for testing and benchmarking the dense QP solver (tests,
/// bench_qp, examples/qp_walking_sequence); docs/qp.md quotes its numbers.
///
/// Each QP is the linearised NMPC problem of thesis §2.2 (eq. 2.43–2.78) for an HRP-2-like robot:
/// N = 16 samples of T = 0.1 s, steps of 0.8 s (8 samples), 2 planned footsteps.
///   variables (68): CoM jerk x (16), footsteps x (2), CoM jerk y (16), footsteps y (2),
///                   yaw jerk of the left foot (16), of the right foot (16)       (eq. 2.52–2.54)
///   rows (106):     ZMP in the support foot's rotated, margin-shrunk rectangle: 4 × 16 (eq. 2.68)
///                   next footstep in the feasibility pentagon of the foot before it: 5 × 2 (2.71)
///                   relative foot yaw: 16 two-sided (2.75); relative yaw rate: 16 two-sided (2.77)
/// Foot yaws inside the ZMP/feasibility rows are frozen at the commanded yaw rate, which makes
/// every QP linear (the real generator, WalkingMpc, linearises them, eq. 2.86). The sequence
/// walks: each tick applies the first jerks, shifts the support schedule (eq. 2.49) and lands
/// planned footsteps, so consecutive QPs differ slightly, as in a control loop.
///
/// Small deviations from the thesis, needed for a strictly convex QP: the jerk weight γ also
/// applies to the yaw jerks, and footsteps carry a weak pull (1e-6) to the nominal step, so that a
/// footstep with no sample in the horizon (phase 0) still has a unique optimum.
///
/// Depends on the core only (Eigen).

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/model/lipm.hpp"
#include "walkgen/model/support_polygon.hpp"

namespace walkgen {

/// One QP of the sequence: minimise ½ xᵀ H x + gᵀ x subject to lb ≤ A x ≤ ub (no bounds on x).
struct WalkingQp {
  Eigen::MatrixXd H, A;       ///< 68 × 68, 106 × 68
  Eigen::VectorXd g, lb, ub;  ///< 68, 106, 106 (±infinity where a side is open)
  int phase = 0;              ///< samples elapsed in the current step
};

/// The QPs of a walk, one per tick: build() the current one, solve it, advance() with the
/// solution.

class WalkingQpSequence {
 public:
  static constexpr int kN = 16;
  static constexpr int kStepSamples = 8;
  static constexpr int kSteps = 2;
  static constexpr int kVars = 2 * (kN + kSteps) + 2 * kN;    // 68
  static constexpr int kRows = 4 * kN + 5 * kSteps + 2 * kN;  // 106

  /// A velocity command in the robot frame.
  struct Command {
    double vx, vy, wz;  ///< [m/s], [m/s], [rad/s]
  };

  /// The command schedule shared by the tests, the benchmark and the example: 8 s straight,
  /// 6 s curved, 4 s sideways, then turning on the spot (ticks of T = 0.1 s).
  static Command demo_command(int tick) {
    if (tick < 80) return {0.1, 0.0, 0.0};
    if (tick < 140) return {0.1, 0.0, 0.1};
    if (tick < 180) return {0.0, 0.1, 0.0};
    return {0.0, 0.0, 0.2};
  }

  WalkingQpSequence() : lipm_(0.1, 0.814, 9.81, kN), step_(0.1) {
    cx_.setZero();
    cy_.setZero();
    support_ << 0.0, 0.1, 0.0;  // left foot support at y = +0.1 (feet 0.2 apart)
    swing_ << 0.0, -0.1, 0.0;
    cy_[0] = 0.1;  // CoM starts over the support foot
    yaw_left_.setZero();
    yaw_right_.setZero();
    // Where the right foot may land relative to the left one; mirrored (y → −y) for the left.
    Eigen::Matrix<double, 5, 2> right_of_left;
    right_of_left << -0.25, -0.14, 0.25, -0.14, 0.30, -0.22, 0.0, -0.32, -0.30, -0.22;
    Eigen::Matrix<double, 5, 2> left_of_right = right_of_left;
    left_of_right.col(1) *= -1.0;
    polygon_halfplanes(right_of_left, hull_A_[0], hull_b_[0]);
    polygon_halfplanes(left_of_right, hull_A_[1], hull_b_[1]);
  }

  /// The QP of the current tick for command cmd.
  WalkingQp build(const Command& cmd) const {
    WalkingQp qp;
    qp.phase = phase_;
    const int nv = kVars;
    qp.H.setZero(nv, nv);
    qp.g.setZero(nv);
    qp.A.setZero(kRows, nv);
    qp.lb.setConstant(kRows, -kInf);
    qp.ub.setConstant(kRows, kInf);
    const double alpha = 1.0, beta = 1e-6, gamma = 1e-5, foot_pull = 1e-6;

    // Support schedule (eq. 2.47–2.49): v selects the current foot, V the planned ones.
    Eigen::VectorXd v = Eigen::VectorXd::Zero(kN);
    Eigen::MatrixXd V = Eigen::MatrixXd::Zero(kN, kSteps);
    for (int i = 0; i < kN; ++i) {
      const int step = (i + phase_) / kStepSamples;  // 0: current support, 1..: planned
      if (step == 0) {
        v[i] = 1.0;
      } else {
        V(i, step - 1) = 1.0;
      }
    }
    // Which foot supports each sample: the current one, then alternating.
    const bool left_support = left_support_;
    auto support_is_left = [&](int step) { return (step % 2 == 0) == left_support; };

    // World-frame yaw of the foot standing at each step (frozen at the commanded rate).
    const double yaw_now = support_[2];
    std::vector<double> step_yaw(kSteps + 1);
    for (int s = 0; s <= kSteps; ++s) {
      step_yaw[s] = yaw_now + cmd.wz * 0.8 * s;
    }
    const double c = std::cos(yaw_now), s = std::sin(yaw_now);
    const double vx_w = c * cmd.vx - s * cmd.vy, vy_w = s * cmd.vx + c * cmd.vy;

    // Cost, x and y blocks (eq. 2.56, 2.59) plus the weak footstep pull.
    const auto& P = lipm_;
    Eigen::MatrixXd Qj = alpha * P.P_vu.transpose() * P.P_vu + beta * P.P_zu.transpose() * P.P_zu +
                         gamma * Eigen::MatrixXd::Identity(kN, kN);
    Eigen::MatrixXd Qjf = -beta * P.P_zu.transpose() * V;
    Eigen::MatrixXd Qff =
        beta * V.transpose() * V + foot_pull * Eigen::MatrixXd::Identity(kSteps, kSteps);
    const Eigen::Vector3d* axis_state[2] = {&cx_, &cy_};
    const double vel_ref[2] = {vx_w, vy_w};
    for (int axis = 0; axis < 2; ++axis) {
      const int o = axis * (kN + kSteps);
      qp.H.block(o, o, kN, kN) = Qj;
      qp.H.block(o, o + kN, kN, kSteps) = Qjf;
      qp.H.block(o + kN, o, kSteps, kN) = Qjf.transpose();
      qp.H.block(o + kN, o + kN, kSteps, kSteps) = Qff;
      const Eigen::Vector3d& cs = *axis_state[axis];
      const double f = support_[axis];
      Eigen::VectorXd vel_err = P.P_vs * cs - Eigen::VectorXd::Constant(kN, vel_ref[axis]);
      Eigen::VectorXd zmp_err = P.P_zs * cs - v * f;
      qp.g.segment(o, kN) =
          alpha * P.P_vu.transpose() * vel_err + beta * P.P_zu.transpose() * zmp_err;
      qp.g.segment(o + kN, kSteps) = -beta * V.transpose() * zmp_err;
      // Nominal footsteps: along the command, alternating ±0.1 m sideways.
      for (int st = 0; st < kSteps; ++st) {
        const double t_land = 0.8 * (st + 1) - 0.1 * phase_;
        const double lateral = (support_is_left(st + 1) ? 0.1 : -0.1);
        const double yaw = step_yaw[st + 1];
        const double nominal = (axis == 0 ? cx_[0] + vx_w * t_land - std::sin(yaw) * lateral
                                          : cy_[0] + vy_w * t_land + std::cos(yaw) * lateral);
        qp.g[o + kN + st] -= foot_pull * nominal;
      }
    }
    // Yaw blocks (eq. 2.57, 2.60): each foot turns only while it swings.
    for (int foot = 0; foot < 2; ++foot) {
      const bool is_left = foot == 0;
      Eigen::VectorXd e(kN);
      for (int i = 0; i < kN; ++i) {
        const int step = (i + phase_) / kStepSamples;
        e[i] = support_is_left(step) == is_left ? 0.0 : 1.0;  // swing foot
      }
      const int o = 2 * (kN + kSteps) + foot * kN;
      const Eigen::Vector3d& ys = is_left ? yaw_left_ : yaw_right_;
      Eigen::MatrixXd EPvu = e.asDiagonal() * P.P_vu;
      qp.H.block(o, o, kN, kN) =
          alpha * EPvu.transpose() * EPvu + gamma * Eigen::MatrixXd::Identity(kN, kN);
      Eigen::VectorXd err = e.asDiagonal() * (P.P_vs * ys) - e * cmd.wz;
      qp.g.segment(o, kN) = alpha * EPvu.transpose() * err;
    }

    // ZMP rows (eq. 2.68): rectangle 0.2172 × 0.1380 shrunk by the margin (0.09, 0.05)... which
    // leaves half-extents (0.0186, 0.019) m: a tight polygon with many active rows.
    const double hx = 0.2172 / 2 - 0.09, hy = 0.1380 / 2 - 0.05;
    const double edge_n[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    const double edge_b[4] = {hx, hy, hx, hy};
    int row = 0;
    for (int i = 0; i < kN; ++i) {
      const int step = (i + phase_) / kStepSamples;
      const double yaw = step_yaw[step];
      const double cy = std::cos(yaw), sy = std::sin(yaw);
      for (int e = 0; e < 4; ++e) {
        // a · R(yaw)ᵀ (z − f) ≤ b, R(yaw)ᵀ maps world to foot frame (thesis R_z(f^θ)).
        const double ax = edge_n[e][0] * cy + edge_n[e][1] * sy;
        const double ay = -edge_n[e][0] * sy + edge_n[e][1] * cy;
        const int ox = 0, oy = kN + kSteps;
        qp.A.block(row, ox, 1, kN) = ax * P.P_zu.row(i);
        qp.A.block(row, oy, 1, kN) = ay * P.P_zu.row(i);
        qp.A.block(row, ox + kN, 1, kSteps) = -ax * V.row(i);
        qp.A.block(row, oy + kN, 1, kSteps) = -ay * V.row(i);
        const double zx0 = P.P_zs.row(i).dot(cx_) - v[i] * support_[0];
        const double zy0 = P.P_zs.row(i).dot(cy_) - v[i] * support_[1];
        qp.ub[row] = edge_b[e] - (ax * zx0 + ay * zy0);
        ++row;
      }
    }
    // Feasibility rows (eq. 2.71): footstep s relative to the foot before it, in that foot's frame.
    for (int st = 0; st < kSteps; ++st) {
      const bool prev_left = support_is_left(st);
      const double yaw = step_yaw[st];
      const double cy = std::cos(yaw), sy = std::sin(yaw);
      // Half-planes of the landing region in the previous foot's frame (eq. 2.62–2.64).
      const Eigen::Matrix<double, 5, 2>& hull_A = hull_A_[prev_left ? 0 : 1];
      const Eigen::Matrix<double, 5, 1>& hull_b = hull_b_[prev_left ? 0 : 1];
      for (int e = 0; e < 5; ++e) {
        const double nx = hull_A(e, 0), ny = hull_A(e, 1), b = hull_b[e];
        const double ax = nx * cy + ny * sy;
        const double ay = -nx * sy + ny * cy;
        const int fx = kN + st, fy = 2 * kN + kSteps + st;
        qp.A(row, fx) += ax;
        qp.A(row, fy) += ay;
        double rhs = b;
        if (st == 0) {
          rhs += ax * support_[0] + ay * support_[1];
        } else {
          qp.A(row, fx - 1) -= ax;
          qp.A(row, fy - 1) -= ay;
        }
        qp.ub[row] = rhs;
        ++row;
      }
    }
    // Relative yaw and yaw-rate rows (eq. 2.75, 2.77).
    const double yaw_max = 0.2, rate_max = 0.4;
    const int ol = 2 * (kN + kSteps), orr = ol + kN;
    const Eigen::Vector3d dyaw = yaw_left_ - yaw_right_;
    for (int i = 0; i < kN; ++i, ++row) {
      qp.A.block(row, ol, 1, kN) = P.P_pu.row(i);
      qp.A.block(row, orr, 1, kN) = -P.P_pu.row(i);
      const double off = P.P_ps.row(i).dot(dyaw);
      qp.lb[row] = -yaw_max - off;
      qp.ub[row] = yaw_max - off;
    }
    for (int i = 0; i < kN; ++i, ++row) {
      qp.A.block(row, ol, 1, kN) = P.P_vu.row(i);
      qp.A.block(row, orr, 1, kN) = -P.P_vu.row(i);
      const double off = P.P_vs.row(i).dot(dyaw);
      qp.lb[row] = -rate_max - off;
      qp.ub[row] = rate_max - off;
    }
    return qp;
  }

  /// Applies the first sample of solution u and advances one tick.
  /// @throws walkgen::invalid_argument unless u has kVars (68) entries.
  void advance(const Eigen::VectorXd& u) {
    check_argument(u.size() == kVars, "WalkingQpSequence::advance: u", "68 entries", u.size());
    const int oy = kN + kSteps, ol = 2 * (kN + kSteps), orr = ol + kN;
    cx_ = step_.advance(cx_, u[0]);
    cy_ = step_.advance(cy_, u[oy]);
    yaw_left_ = step_.advance(yaw_left_, u[ol]);
    yaw_right_ = step_.advance(yaw_right_, u[orr]);
    ++phase_;
    if (phase_ == kStepSamples) {
      // The swing foot lands on the first planned footstep.
      phase_ = 0;
      swing_ = support_;
      support_[0] = u[kN];
      support_[1] = u[oy + kN];
      support_[2] = left_support_ ? yaw_right_[0] : yaw_left_[0];
      left_support_ = !left_support_;
    }
  }

  /// State feedback: the measured CoM differs from the planned one by (dx, dy) metres.
  void set_com_offset(double dx, double dy) {
    cx_[0] += dx;
    cy_[0] += dy;
  }

  /// CoM state (position [m], velocity [m/s], acceleration [m/s²]) along x and y.
  const Eigen::Vector3d& com_x() const { return cx_; }
  const Eigen::Vector3d& com_y() const { return cy_; }
  /// The support foot (x [m], y [m], yaw [rad]) and whether it is the left one.
  const Eigen::Vector3d& support() const { return support_; }
  bool left_support() const { return left_support_; }
  /// The preview matrices (eq. 2.30–2.42) the QPs are built from.
  const LipmPreview<double>& lipm() const { return lipm_; }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  LipmPreview<double> lipm_;
  LipmStep<double> step_;
  Eigen::Vector3d cx_, cy_, yaw_left_, yaw_right_;
  Eigen::Vector3d support_, swing_;  // x, y, yaw
  // Landing-region half-planes: [0] after a left support foot, [1] after a right one.
  Eigen::Matrix<double, 5, 2> hull_A_[2];
  Eigen::Matrix<double, 5, 1> hull_b_[2];
  bool left_support_ = true;
  int phase_ = 0;
};

}  // namespace walkgen
