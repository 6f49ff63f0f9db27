#pragma once
/// @file
/// Constraint block (walkgen's own): the soles stay apart. Every planned footstep's two inner
/// sole corners, seen from the foot it is planned from, lie at least min_foot_separation beyond
/// that foot's inner edge. For planned step i = 1..N_f and corner c_k = (±l/2, −σ w/2) (l × w
/// the sole, σ = +1 when step i is a left foot, −1 when a right one):
///   σ e_yᵀ R(θ_{i−1})ᵀ (F_i + R(θ_i) c_k − F_{i−1}) ≥ w/2 + d,   d = min_foot_separation.
/// The previous sole lies within |y| ≤ w/2 of its own frame and the new one beyond w/2 + d
/// (convex: its corners bound it), so no two points of the soles are closer than d. The
/// feasibility polygons (eq. 2.70) bound only the foot centres: turned feet came within
/// 1.4 cm (issue 24). The swing foot travels between two such poses, beside its neighbour.
/// Rows: N_f · 2, step-major; they move with the landings (ShiftRule::per_step).
/// Jacobian: for F_i and θ_i, and for F_{i−1} and θ_{i−1} when it is a variable (i ≥ 2).

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class FootSeparation {
 public:
  static constexpr const char* kName = "foot separation";

  explicit FootSeparation(const WalkingSettings<Scalar>& s)
      : half_length_(s.foot_length / Scalar(2)),
        half_width_(s.foot_width / Scalar(2)),
        bound_(s.foot_width / Scalar(2) + s.min_foot_separation) {}

  BlockShape shape(const WalkingDims& d) const { return {1, d.nf, 2, ShiftRule::per_step}; }

  template <typename T, int N>
  void values(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, const MpcVector<T>& U,
              MpcVector<T>& c) const {
    for (Eigen::Index i = 1; i <= t.layout.dims().nf; ++i) {
      for (int k = 0; k < 2; ++k) c[row(rows, i, k)] = corner<T>(t, U, i, k).value;
    }
  }

  template <int N>
  void bounds(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, MpcVector<Scalar>& lower,
              MpcVector<Scalar>& upper) const {
    for (Eigen::Index i = 1; i <= t.layout.dims().nf; ++i) {
      for (int k = 0; k < 2; ++k) {
        lower[row(rows, i, k)] = bound_;
        upper[row(rows, i, k)] = std::numeric_limits<Scalar>::infinity();
      }
    }
  }

  template <int N>
  void linearise(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows,
                 const MpcVector<Scalar>& U, MpcRowMatrix<Scalar>& J, MpcVector<Scalar>& lower,
                 MpcVector<Scalar>& upper) const {
    const WalkingLayout& L = t.layout;
    bounds(t, rows, lower, upper);
    for (Eigen::Index i = 1; i <= L.dims().nf; ++i) {
      for (int k = 0; k < 2; ++k) {
        const Eigen::Index r = row(rows, i, k);
        const Corner<Scalar> e = corner<Scalar>(t, U, i, k);
        J(r, L.step_x() + i - 1) = e.dx;
        J(r, L.step_y() + i - 1) = e.dy;
        J(r, L.step_q() + i - 1) = e.dq;
        Scalar lin = e.dx * U[L.step_x() + i - 1] + e.dy * U[L.step_y() + i - 1] +
                     e.dq * U[L.step_q() + i - 1];
        if (i > 1) {  // the previous footstep is a variable too
          J(r, L.step_x() + i - 2) = -e.dx;
          J(r, L.step_y() + i - 2) = -e.dy;
          J(r, L.step_q() + i - 2) = e.dq_previous;
          lin += -e.dx * U[L.step_x() + i - 2] - e.dy * U[L.step_y() + i - 2] +
                 e.dq_previous * U[L.step_q() + i - 2];
        }
        lower[r] -= e.value - lin;  // J U' ≥ lb − (c(U) − J U)
      }
    }
  }

 private:
  /// A row's value and its derivatives by F_i (x, y), θ_i and θ_{i−1}.
  template <typename T>
  struct Corner {
    T value, dx, dy, dq, dq_previous;
  };

  static Eigen::Index row(const LayoutBlock& rows, Eigen::Index i, int k) {
    return rows.offset + (i - 1) * 2 + k;
  }

  /// Corner k (0 front, 1 back) of step i, for any scalar T.
  template <typename T, int N>
  Corner<T> corner(const WalkingTick<Scalar, N>& t, const MpcVector<T>& U, Eigen::Index i,
                   int k) const {
    using std::cos;
    using std::sin;
    const Scalar side = t.foot_of_step(i) == Foot::left ? Scalar(1) : Scalar(-1);
    const Scalar cx = k == 0 ? half_length_ : -half_length_, cy = -side * half_width_;
    const T q = t.q(U, i), qp = t.q(U, i - 1);
    const T cq = cos(q), sq = sin(q), cp = cos(qp), sp = sin(qp);
    // ρ = F_i + R(θ_i) c − F_{i−1}, world frame.
    const T rx = t.x(U, i) + cq * cx - sq * cy - t.x(U, i - 1);
    const T ry = t.y(U, i) + sq * cx + cq * cy - t.y(U, i - 1);
    Corner<T> e;
    e.value = side * (-sp * rx + cp * ry);  // σ · (R(θ_{i−1})ᵀ ρ)_y
    e.dx = -side * sp;
    e.dy = side * cp;
    e.dq = side * (-sp * (-sq * cx - cq * cy) + cp * (cq * cx - sq * cy));
    e.dq_previous = side * (-cp * rx - sp * ry);
    return e;
  }

  Scalar half_length_, half_width_, bound_;
};

}  // namespace walkgen
