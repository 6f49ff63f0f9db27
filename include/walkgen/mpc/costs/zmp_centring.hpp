#pragma once
/// @file
/// Cost term: ZMP centring, thesis eq. 2.45 (weight β = WalkingSettings::beta):
///   β/2 Σ_{j=1..N} ‖Z_{k+j} − F_{s(j)}‖²,  Z = P_zs c_k + P_zu U_c  (eq. 2.39, 2.42),
/// per axis, F_{s(j)} the foot of sample j's step (F_0 the support foot, a constant; the
/// selection v/V of eq. 2.47–2.49). Hessian (eq. 2.56): β P_zuᵀP_zu (constant), −β P_zuᵀV and
/// β VᵀV (by step membership, per tick); gradient (eq. 2.57): β P_zuᵀ(P_zs c_k − v f_0) for
/// the jerks and −β Vᵀ(P_zs c_k − v f_0) for the footsteps.

#include <Eigen/Core>

#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar, int N>
class ZmpCentring {
 public:
  using Tick = WalkingTick<Scalar, N>;
  static constexpr const char* kName = "ZMP centring (eq. 2.45)";

  explicit ZmpCentring(const WalkingSettings<Scalar>& s) : beta_(s.beta) {}

  void add_constant_hessian(const WalkingLayout& L, const LipmPreview<Scalar, N>& P,
                            MpcMatrix<Scalar>& H) const {
    const Eigen::Index n = L.dims().N;
    for (Eigen::Index u0 : {L.jerk_x(), L.jerk_y()}) {
      H.block(u0, u0, n, n).noalias() += beta_ * P.P_zu.transpose() * P.P_zu;
    }
  }

  /// H += the footstep blocks of this tick's step membership, g += the gradient.
  void add(const Tick& t, MpcMatrix<Scalar>& H, MpcVector<Scalar>& g,
           MpcVector<Scalar>& scratch) const {
    const Eigen::Index n = t.layout.dims().N;
    const auto& step_of = t.schedule.step_of;
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Index u0 = axis == 0 ? t.layout.jerk_x() : t.layout.jerk_y();
      const Eigen::Index f0 = axis == 0 ? t.layout.step_x() : t.layout.step_y();
      for (Eigen::Index j = 0; j < n; ++j) {
        const int s = step_of[j];
        if (s == 0) continue;
        for (Eigen::Index c = 0; c <= j; ++c) {
          const Scalar v = -beta_ * t.preview.P_zu(j, c);
          H(u0 + c, f0 + s - 1) += v;
          H(f0 + s - 1, u0 + c) += v;
        }
        H(f0 + s - 1, f0 + s - 1) += beta_;
      }
      // scratch: P_zs c − v f_0, the ZMP's distance from the support foot at U = 0.
      scratch.noalias() = t.preview.P_zs * (axis == 0 ? t.state.com_x : t.state.com_y);
      const Scalar f = axis == 0 ? t.state.support.x : t.state.support.y;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (step_of[j] == 0) scratch[j] -= f;
      }
      g.segment(u0, n).noalias() += beta_ * t.preview.P_zu.transpose() * scratch;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (step_of[j] > 0) g[f0 + step_of[j] - 1] -= beta_ * scratch[j];
      }
    }
  }

  template <typename T>
  T value(const Tick& t, const MpcVector<T>& U) const {
    const Eigen::Index n = t.layout.dims().N;
    T sum = T(0);
    for (int axis = 0; axis < 2; ++axis) {
      const MpcVector<T> z =
          (t.preview.P_zs * (axis == 0 ? t.state.com_x : t.state.com_y)).template cast<T>() +
          t.preview.P_zu.template cast<T>() *
              U.segment(axis == 0 ? t.layout.jerk_x() : t.layout.jerk_y(), n);
      for (Eigen::Index j = 0; j < n; ++j) {
        const T f = axis == 0 ? t.x(U, t.step_of(j)) : t.y(U, t.step_of(j));
        sum += (z[j] - f) * (z[j] - f);
      }
    }
    return T(beta_ / Scalar(2)) * sum;
  }

 private:
  Scalar beta_;
};

}  // namespace walkgen
