#pragma once
/// @file
/// Constraint block: every planned footstep in the feasibility polygon of the foot it is
/// planned from (thesis eq. 2.70–2.72). For planned step i = 1..N_f,
///   a_eᵀ R(θ_{i−1})ᵀ (F_i − F_{i−1}) ≤ b_e,  e = 1..E,
/// with the polygon of the *landing* foot (left_ or right_foot_convex_hull; the thesis code
/// checked the second step against the other foot's, docs/design.md §4).
/// Rows: N_f · E, step-major; they move with the landings (ShiftRule::per_step).
/// Jacobian: ρ_e for F_i, −ρ_e and ∂/∂θ_{i−1} for F_{i−1} when it is a variable (i ≥ 2).

#include <Eigen/Core>

#include "walkgen/mpc/constraints/rotated_polygon.hpp"
#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar, int HullEdges>
class FootstepFeasibility {
 public:
  static constexpr const char* kName = "footstep feasibility (eq. 2.70-2.72)";

  /// @param hulls where each foot may land, in the frame of the other (support) foot
  explicit FootstepFeasibility(const FootPolygons<Scalar, HullEdges>& hulls) : hulls_(hulls) {}

  BlockShape shape(const WalkingDims& d) const {
    return {1, d.nf, hulls_.edges(), ShiftRule::per_step};
  }

  template <typename T, int N>
  void values(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, const MpcVector<T>& U,
              MpcVector<T>& c) const {
    for (Eigen::Index i = 1; i <= t.layout.dims().nf; ++i) {
      rotated_polygon_values(hulls_.normals(t.foot_of_step(i)), t.q(U, i - 1),
                             t.x(U, i) - t.x(U, i - 1), t.y(U, i) - t.y(U, i - 1), c,
                             rows.offset + (i - 1) * hulls_.edges());
    }
  }

  template <int N>
  void bounds(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, MpcVector<Scalar>& lower,
              MpcVector<Scalar>& upper) const {
    for (Eigen::Index i = 1; i <= t.layout.dims().nf; ++i) {
      rotated_polygon_bounds(hulls_.offsets(t.foot_of_step(i)), lower, upper,
                             rows.offset + (i - 1) * hulls_.edges());
    }
  }

  template <int N>
  void linearise(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows,
                 const MpcVector<Scalar>& U, MpcRowMatrix<Scalar>& J, MpcVector<Scalar>& lower,
                 MpcVector<Scalar>& upper) const {
    const WalkingLayout& L = t.layout;
    for (Eigen::Index i = 1; i <= L.dims().nf; ++i) {
      const Foot landing = t.foot_of_step(i);
      rotated_polygon_rows(hulls_.normals(landing), hulls_.offsets(landing), t.q(U, i - 1),
                           t.x(U, i) - t.x(U, i - 1), t.y(U, i) - t.y(U, i - 1), J, lower, upper,
                           rows.offset + (i - 1) * hulls_.edges(), [&](const auto& ed, auto& row) {
                             row[L.step_x() + i - 1] = ed.rx;
                             row[L.step_y() + i - 1] = ed.ry;
                             Scalar lin =
                                 ed.rx * U[L.step_x() + i - 1] + ed.ry * U[L.step_y() + i - 1];
                             if (i > 1) lin += footstep_columns(L, ed, i - 1, U, row);
                             return lin;
                           });
    }
  }

 private:
  FootPolygons<Scalar, HullEdges> hulls_;
};

}  // namespace walkgen
