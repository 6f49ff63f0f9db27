#pragma once
/// @file
/// Constraint block: relative foot yaw (thesis eq. 2.73) and relative yaw rate (eq. 2.74–2.78).
/// For planned step i = 1..N_f, first the relative yaw, then the rate:
///   |θ_i − θ_{i−1}| ≤ max_relative_yaw,
///   15/8 · |θ_i − θ_{lift-off}| / (t_step − t_ds) ≤ max_relative_yaw_rate,
/// the latter the peak rate of the swing foot's quintic yaw, whose lift-off yaw is θ_{i−2}
/// (θ_0 the support foot, θ_{−1} the swing foot's origin). Linear in U, so its own
/// linearisation. Rows: 2 · N_f (yaw, then rate), each moving with the landings
/// (ShiftRule::per_step).

#include <Eigen/Core>
#include <limits>

#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class RelativeYaw {
 public:
  static constexpr const char* kName = "relative yaw and yaw rate (eq. 2.73-2.74)";

  explicit RelativeYaw(const WalkingSettings<Scalar>& s)
      : limit_{s.max_relative_yaw,
               Scalar(8) / Scalar(15) * s.max_relative_yaw_rate * (s.t_step - s.t_ds)} {}

  BlockShape shape(const WalkingDims& d) const { return {2, d.nf, 1, ShiftRule::per_step}; }

  template <typename T, int N>
  void values(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, const MpcVector<T>& U,
              MpcVector<T>& c) const {
    for_each_row(t, rows, [&](Eigen::Index r, int, Eigen::Index i, Eigen::Index o) {
      c[r] = U[t.layout.step_q() + i - 1] - origin(t, U, o);
    });
  }

  template <int N>
  void bounds(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, MpcVector<Scalar>& lower,
              MpcVector<Scalar>& upper) const {
    for_each_row(t, rows, [&](Eigen::Index r, int kind, Eigen::Index, Eigen::Index) {
      lower[r] = -limit_[kind];
      upper[r] = limit_[kind];
    });
  }

  template <int N>
  void linearise(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows,
                 const MpcVector<Scalar>& U, MpcRowMatrix<Scalar>& J, MpcVector<Scalar>& lower,
                 MpcVector<Scalar>& upper) const {
    const Eigen::Index q0 = t.layout.step_q();
    bounds(t, rows, lower, upper);
    for_each_row(t, rows, [&](Eigen::Index r, int, Eigen::Index i, Eigen::Index o) {
      J(r, q0 + i - 1) = Scalar(1);
      if (o >= 1) {
        J(r, q0 + o - 1) = Scalar(-1);
      } else {  // a constant origin moves the bounds
        const Scalar value = origin(t, U, o);
        lower[r] += value;
        upper[r] += value;
      }
    });
  }

 private:
  /// Calls f(row, kind, i, o) for every row: kind 0 relative yaw, 1 rate; o the origin step.
  template <int N, typename F>
  void for_each_row(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, F&& f) const {
    const Eigen::Index nf = t.layout.dims().nf;
    for (int kind = 0; kind < 2; ++kind) {
      for (Eigen::Index i = 1; i <= nf; ++i) {
        f(rows.offset + kind * nf + i - 1, kind, i, kind == 0 ? i - 1 : i - 2);
      }
    }
  }
  /// Yaw of origin step o: a variable for o ≥ 1, the support foot's for 0, the swing foot's
  /// origin for −1.
  template <typename T, int N>
  static T origin(const WalkingTick<Scalar, N>& t, const MpcVector<T>& U, Eigen::Index o) {
    return o >= 0 ? t.q(U, o) : T(t.state.swing_origin.q);
  }

  Scalar limit_[2];  ///< [rad] max_relative_yaw, and the yaw change the rate limit allows
};

}  // namespace walkgen
