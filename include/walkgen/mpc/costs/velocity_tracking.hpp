#pragma once
/// @file
/// Cost term: CoM velocity tracking, thesis eq. 2.43 (weight α = WalkingSettings::alpha):
///   α/2 Σ_{j=1..N} ‖Ċ_{k+j} − v_ref,j‖²,  Ċ = P_vs c_k + P_vu U_c  (eq. 2.34, 2.37),
/// per axis, with the reference rotated along the commanded yaw rate over the horizon
/// (WalkingSchedule::ref_x/ref_y). Hessian α P_vuᵀP_vu (constant, eq. 2.56), gradient
/// α P_vuᵀ(P_vs c_k − v_ref) (eq. 2.57).

#include <Eigen/Core>

#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar, int N>
class VelocityTracking {
 public:
  using Tick = WalkingTick<Scalar, N>;
  static constexpr const char* kName = "velocity tracking (eq. 2.43)";

  explicit VelocityTracking(const WalkingSettings<Scalar>& s) : alpha_(s.alpha) {}

  /// H += the part that never changes.
  void add_constant_hessian(const WalkingLayout& L, const LipmPreview<Scalar, N>& P,
                            MpcMatrix<Scalar>& H) const {
    const Eigen::Index n = L.dims().N;
    for (Eigen::Index u0 : {L.jerk_x(), L.jerk_y()}) {
      H.block(u0, u0, n, n).noalias() += alpha_ * P.P_vu.transpose() * P.P_vu;
    }
  }

  /// H += the part of this tick (none), g += the gradient; `scratch` has N entries.
  void add(const Tick& t, MpcMatrix<Scalar>&, MpcVector<Scalar>& g,
           MpcVector<Scalar>& scratch) const {
    const Eigen::Index n = t.layout.dims().N;
    for (int axis = 0; axis < 2; ++axis) {
      scratch.noalias() = t.preview.P_vs * (axis == 0 ? t.state.com_x : t.state.com_y);
      scratch -= axis == 0 ? t.schedule.ref_x : t.schedule.ref_y;  // velocity error at U = 0
      g.segment(axis == 0 ? t.layout.jerk_x() : t.layout.jerk_y(), n).noalias() +=
          alpha_ * t.preview.P_vu.transpose() * scratch;
    }
  }

  /// The term's value at U, for any scalar T (Jets included).
  template <typename T>
  T value(const Tick& t, const MpcVector<T>& U) const {
    const Eigen::Index n = t.layout.dims().N;
    T sum = T(0);
    for (int axis = 0; axis < 2; ++axis) {
      const MpcVector<T> v = (t.preview.P_vs * (axis == 0 ? t.state.com_x : t.state.com_y) -
                              (axis == 0 ? t.schedule.ref_x : t.schedule.ref_y))
                                 .template cast<T>() +
                             t.preview.P_vu.template cast<T>() *
                                 U.segment(axis == 0 ? t.layout.jerk_x() : t.layout.jerk_y(), n);
      sum += v.squaredNorm();
    }
    return T(alpha_ / Scalar(2)) * sum;
  }

 private:
  Scalar alpha_;
};

}  // namespace walkgen
