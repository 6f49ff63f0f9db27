#pragma once
/// @file
/// Constraint block (walkgen's own, capturability): the capture point at the end of the horizon,
/// ξ_N = c_N + ċ_N / ω with ω = √(g / c_z), lies in the shrunk sole of the last planned
/// footstep: a_eᵀ R(θ_{N_f})ᵀ (ξ_N − F_{N_f}) ≤ b_e. Without it a plan may leave the pendulum
/// diverging beyond the horizon while every QP solves (N = 8 walked off this way); with it an
/// unrecoverable state is a failed QP. ξ_N = ξ_s c_k + ξ_u U_c from the last rows of P_ps, P_vs,
/// P_pu, P_vu (eq. 2.33–2.36). Rows: E, fixed (ShiftRule::fixed).

#include <Eigen/Core>
#include <cmath>

#include "walkgen/mpc/constraints/rotated_polygon.hpp"
#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar, int N, int FootEdges>
class CapturePoint {
 public:
  using Tick = WalkingTick<Scalar, N>;
  static constexpr const char* kName = "terminal capture point";

  CapturePoint(const FootPolygons<Scalar, FootEdges>& soles, const LipmPreview<Scalar, N>& lipm)
      : soles_(soles) {
    const Eigen::Index n = lipm.horizon();
    const Scalar w = std::sqrt(lipm.gravity / lipm.com_height);
    xi_s_ = lipm.P_ps.row(n - 1) + lipm.P_vs.row(n - 1) / w;
    xi_u_ = lipm.P_pu.row(n - 1) + lipm.P_vu.row(n - 1) / w;
  }

  BlockShape shape(const WalkingDims&) const { return {1, 1, soles_.edges(), ShiftRule::fixed}; }

  template <typename T>
  void values(const Tick& t, const LayoutBlock& rows, const MpcVector<T>& U,
              MpcVector<T>& c) const {
    const WalkingLayout& L = t.layout;
    const Eigen::Index n = L.dims().N, nf = L.dims().nf;
    const T xx =
        T(xi_s_.dot(t.state.com_x)) + xi_u_.template cast<T>().dot(U.segment(L.jerk_x(), n));
    const T xy =
        T(xi_s_.dot(t.state.com_y)) + xi_u_.template cast<T>().dot(U.segment(L.jerk_y(), n));
    rotated_polygon_values(soles_.normals(t.foot_of_step(nf)), t.q(U, nf), xx - t.x(U, nf),
                           xy - t.y(U, nf), c, rows.offset);
  }

  void bounds(const Tick& t, const LayoutBlock& rows, MpcVector<Scalar>& lower,
              MpcVector<Scalar>& upper) const {
    rotated_polygon_bounds(soles_.offsets(t.foot_of_step(t.layout.dims().nf)), lower, upper,
                           rows.offset);
  }

  void linearise(const Tick& t, const LayoutBlock& rows, const MpcVector<Scalar>& U,
                 MpcRowMatrix<Scalar>& J, MpcVector<Scalar>& lower,
                 MpcVector<Scalar>& upper) const {
    const WalkingLayout& L = t.layout;
    const Eigen::Index n = L.dims().N, nf = L.dims().nf;
    const Foot foot = t.foot_of_step(nf);
    const Scalar ux = xi_u_.dot(U.segment(L.jerk_x(), n));  // the jerks' part, per axis
    const Scalar uy = xi_u_.dot(U.segment(L.jerk_y(), n));
    const Scalar xx = xi_s_.dot(t.state.com_x) + ux;
    const Scalar xy = xi_s_.dot(t.state.com_y) + uy;
    rotated_polygon_rows(soles_.normals(foot), soles_.offsets(foot), t.q(U, nf), xx - t.x(U, nf),
                         xy - t.y(U, nf), J, lower, upper, rows.offset,
                         [&](const auto& ed, auto& row) {
                           row.segment(L.jerk_x(), n) = ed.rx * xi_u_;
                           row.segment(L.jerk_y(), n) = ed.ry * xi_u_;
                           return ed.rx * ux + ed.ry * uy + footstep_columns(L, ed, nf, U, row);
                         });
  }

  /// ξ_N = ξ_s c_k + ξ_u U_c (per axis).
  const Eigen::Matrix<Scalar, 1, 3>& xi_s() const { return xi_s_; }
  const Eigen::Matrix<Scalar, 1, N>& xi_u() const { return xi_u_; }

 private:
  FootPolygons<Scalar, FootEdges> soles_;
  Eigen::Matrix<Scalar, 1, 3> xi_s_;
  Eigen::Matrix<Scalar, 1, N> xi_u_;
};

}  // namespace walkgen
