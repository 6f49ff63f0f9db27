#pragma once
/// @file
/// Cost term (walkgen's own): a proximal weight ε = footstep_regularization on the footstep
/// variables (x, y, yaw) toward the iterate, ε/2 ‖F − F_iterate‖². It keeps the QP strictly
/// convex when the last planned step has no ZMP sample in the horizon (at the first sample of
/// every step); small enough not to move a step the cost determines. Hessian ε I (constant),
/// gradient −ε F_iterate (the Gauss–Newton gradient of docs/design.md §5, eq. 2.85).

#include <Eigen/Core>

#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class FootstepRegularization {
 public:
  static constexpr const char* kName = "footstep regularisation";

  explicit FootstepRegularization(const WalkingSettings<Scalar>& s)
      : eps_(s.footstep_regularization) {}

  template <typename Preview>
  void add_constant_hessian(const WalkingLayout& L, const Preview&, MpcMatrix<Scalar>& H) const {
    for (Eigen::Index f0 : {L.step_x(), L.step_y(), L.step_q()}) {
      for (Eigen::Index i = 0; i < L.dims().nf; ++i) H(f0 + i, f0 + i) += eps_;
    }
  }
  template <typename Tick>
  void add(const Tick& t, MpcMatrix<Scalar>&, MpcVector<Scalar>& g, MpcVector<Scalar>&) const {
    for (Eigen::Index f0 : {t.layout.step_x(), t.layout.step_y(), t.layout.step_q()}) {
      for (Eigen::Index i = 0; i < t.layout.dims().nf; ++i) g[f0 + i] -= eps_ * t.iterate[f0 + i];
    }
  }
  template <typename T, typename Tick>
  T value(const Tick& t, const MpcVector<T>& U) const {
    T sum = T(0);
    for (Eigen::Index f0 : {t.layout.step_x(), t.layout.step_y(), t.layout.step_q()}) {
      for (Eigen::Index i = 0; i < t.layout.dims().nf; ++i) {
        const T d = U[f0 + i] - t.iterate[f0 + i];
        sum += d * d;
      }
    }
    return T(eps_ / Scalar(2)) * sum;
  }

 private:
  Scalar eps_;
};

}  // namespace walkgen
