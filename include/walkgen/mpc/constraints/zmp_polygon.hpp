#pragma once
/// @file
/// Constraint block: the ZMP in the rotated, margin-shrunk support polygon (thesis eq.
/// 2.65–2.69). For every horizon sample j, in step s = ⌊(phase + j)/S⌋ on the foot of pose
/// (F_s, θ_s) (F_0, θ_0: the support foot, constant),
///   a_eᵀ R(θ_s)ᵀ (z_j − F_s) ≤ b_e,  e = 1..E,  z_j = P_zs,j c_k + P_zu,j U_c   (eq. 2.39)
/// with the sole polygon of the foot standing in step s (unit normals: a value is a distance).
/// Rows: N · E, sample-major; they move with the samples (ShiftRule::per_sample).
/// Jacobian: ρ_e P_zu,j for the jerks, −ρ_e for F_s, and ∂/∂θ_s exact per row (the thesis code
/// used one derivative for all rows, docs/design.md §4).

#include <Eigen/Core>

#include "walkgen/mpc/constraints/rotated_polygon.hpp"
#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar, int N, int FootEdges>
class ZmpPolygon {
 public:
  using Tick = WalkingTick<Scalar, N>;
  static constexpr const char* kName = "ZMP polygon (eq. 2.65-2.69)";

  /// @param soles the shrunk sole polygons of the two feet, each in its own frame
  explicit ZmpPolygon(const FootPolygons<Scalar, FootEdges>& soles) : soles_(soles) {}

  BlockShape shape(const WalkingDims& d) const {
    return {1, d.N, soles_.edges(), ShiftRule::per_sample};
  }

  /// c(U) of the block's rows, for any scalar T of U (Jets included).
  template <typename T>
  void values(const Tick& t, const LayoutBlock& rows, const MpcVector<T>& U,
              MpcVector<T>& c) const {
    const WalkingLayout& L = t.layout;
    const Eigen::Index n = L.dims().N;
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::Index s = t.step_of(j);
      const T zx = T(t.preview.P_zs.row(j).dot(t.state.com_x)) +
                   t.preview.P_zu.row(j).template cast<T>().dot(U.segment(L.jerk_x(), n));
      const T zy = T(t.preview.P_zs.row(j).dot(t.state.com_y)) +
                   t.preview.P_zu.row(j).template cast<T>().dot(U.segment(L.jerk_y(), n));
      rotated_polygon_values(soles_.normals(t.foot_of_step(s)), t.q(U, s), zx - t.x(U, s),
                             zy - t.y(U, s), c, rows.offset + j * soles_.edges());
    }
  }

  /// Bounds of c(U): −∞ ≤ c ≤ b_e.
  void bounds(const Tick& t, const LayoutBlock& rows, MpcVector<Scalar>& lower,
              MpcVector<Scalar>& upper) const {
    for (Eigen::Index j = 0; j < t.layout.dims().N; ++j) {
      rotated_polygon_bounds(soles_.offsets(t.foot_of_step(t.step_of(j))), lower, upper,
                             rows.offset + j * soles_.edges());
    }
  }

  /// The Gauss–Newton rows J = ∂c/∂U at U (J zero outside them on entry), bounds shifted by
  /// c(U) − J U.
  void linearise(const Tick& t, const LayoutBlock& rows, const MpcVector<Scalar>& U,
                 MpcRowMatrix<Scalar>& J, MpcVector<Scalar>& lower,
                 MpcVector<Scalar>& upper) const {
    const WalkingLayout& L = t.layout;
    const auto& P = t.preview;
    const Eigen::Index n = L.dims().N;
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::Index s = t.step_of(j);
      const Foot foot = t.foot_of_step(s);
      const Scalar zx =
          P.P_zs.row(j).dot(t.state.com_x) + P.P_zu.row(j).dot(U.segment(L.jerk_x(), n));
      const Scalar zy =
          P.P_zs.row(j).dot(t.state.com_y) + P.P_zu.row(j).dot(U.segment(L.jerk_y(), n));
      const auto p = P.P_zu.row(j).head(j + 1);                // P_zu is lower triangular
      const Scalar pux = p.dot(U.segment(L.jerk_x(), j + 1));  // the jerks' part of J U, per axis
      const Scalar puy = p.dot(U.segment(L.jerk_y(), j + 1));
      rotated_polygon_rows(soles_.normals(foot), soles_.offsets(foot), t.q(U, s), zx - t.x(U, s),
                           zy - t.y(U, s), J, lower, upper, rows.offset + j * soles_.edges(),
                           [&](const auto& ed, auto& row) {
                             row.segment(L.jerk_x(), j + 1) = ed.rx * p;
                             row.segment(L.jerk_y(), j + 1) = ed.ry * p;
                             Scalar lin = ed.rx * pux + ed.ry * puy;
                             if (s > 0) lin += footstep_columns(L, ed, s, U, row);
                             return lin;
                           });
    }
  }

  const FootPolygons<Scalar, FootEdges>& soles() const { return soles_; }

 private:
  FootPolygons<Scalar, FootEdges> soles_;
};

}  // namespace walkgen
