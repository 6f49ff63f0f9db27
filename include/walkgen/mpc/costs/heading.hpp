#pragma once
/// @file
/// Cost term (walkgen's own): heading. Each planned footstep's yaw tracks the reference heading
/// at the middle of its support (WalkingSchedule::heading, yaw_of_step() in
/// mpc/walking_schedule.hpp: the commanded yaw rate integrated since the last reset):
///   w/2 Σ_{i=1..N_f} (θ_i − θ*_i)²,  w = heading_weight · S / t_step²
/// (per rad², scaled like the yaw-rate term of eq. 2.44). The yaw-rate term sees differences of
/// consecutive yaws only; without this term a bias of every foot cost nothing, and the yaws
/// bought room in the rotated feasibility polygons, so straight walks veered.
/// Hessian w I on the yaws (constant), gradient −w θ*.

#include <Eigen/Core>

#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class Heading {
 public:
  static constexpr const char* kName = "heading";

  explicit Heading(const WalkingSettings<Scalar>& s)
      : w_(s.heading_weight * Scalar(s.samples_per_step()) / (s.t_step * s.t_step)) {}
  Scalar weight() const { return w_; }

  template <typename Preview>
  void add_constant_hessian(const WalkingLayout& L, const Preview&, MpcMatrix<Scalar>& H) const {
    for (Eigen::Index i = 0; i < L.dims().nf; ++i) H(L.step_q() + i, L.step_q() + i) += w_;
  }
  template <typename Tick>
  void add(const Tick& t, MpcMatrix<Scalar>&, MpcVector<Scalar>& g, MpcVector<Scalar>&) const {
    const auto& target = t.schedule.heading;
    for (Eigen::Index i = 0; i < target.size(); ++i) g[t.layout.step_q() + i] -= w_ * target[i];
  }
  /// The term's value at U, for any scalar T (Jets included).
  template <typename T, typename Tick>
  T value(const Tick& t, const MpcVector<T>& U) const {
    const auto& target = t.schedule.heading;
    T sum = T(0);
    for (Eigen::Index i = 0; i < target.size(); ++i) {
      const T d = U[t.layout.step_q() + i] - target[i];
      sum += d * d;
    }
    return T(w_ / Scalar(2)) * sum;
  }

 private:
  Scalar w_;
};

}  // namespace walkgen
