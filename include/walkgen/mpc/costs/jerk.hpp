#pragma once
/// @file
/// Cost term: CoM jerk, thesis eq. 2.46 (weight γ = WalkingSettings::gamma):
///   γ/2 ‖U_c‖² per axis. Hessian γ I (constant; γ > 0 keeps the QP strictly convex), no
/// gradient.

#include <Eigen/Core>

#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class Jerk {
 public:
  static constexpr const char* kName = "jerk (eq. 2.46)";

  explicit Jerk(const WalkingSettings<Scalar>& s) : gamma_(s.gamma) {}

  template <typename Preview>
  void add_constant_hessian(const WalkingLayout& L, const Preview&, MpcMatrix<Scalar>& H) const {
    for (Eigen::Index u0 : {L.jerk_x(), L.jerk_y()}) {
      H.block(u0, u0, L.dims().N, L.dims().N).diagonal().array() += gamma_;
    }
  }

  template <typename Tick>
  void add(const Tick&, MpcMatrix<Scalar>&, MpcVector<Scalar>&, MpcVector<Scalar>&) const {}

  template <typename T, typename Tick>
  T value(const Tick& t, const MpcVector<T>& U) const {
    const Eigen::Index n = t.layout.dims().N;
    return T(gamma_ / Scalar(2)) * (U.segment(t.layout.jerk_x(), n).squaredNorm() +
                                    U.segment(t.layout.jerk_y(), n).squaredNorm());
  }

 private:
  Scalar gamma_;
};

}  // namespace walkgen
