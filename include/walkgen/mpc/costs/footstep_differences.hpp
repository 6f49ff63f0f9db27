#pragma once
/// @file
/// What the cost terms on consecutive footsteps share (StepVelocity, YawRate):
/// w/2 Σ_{i=1..N_f} ‖(D F)_i − T_i‖² per footstep group F (positions x and y, or yaws), with the
/// difference operator (D F)_i = F_i − F_{i−1} (F_0 the support foot, a constant folded into the
/// target T_1 by WalkingSchedule). Hessian w DᵀD (constant), gradient −w DᵀT (eq. 2.56–2.57).

#include <Eigen/Core>
#include <cstdint>

#include "walkgen/mpc/walking_layout.hpp"
#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

/// Which footstep variables a FootstepDifferences term acts on.
enum class FootstepGroup : std::uint8_t {
  positions,  ///< x and y (StepVelocity)
  yaws,       ///< θ (YawRate)
};

/// The enumerator's name ("positions", "yaws"), e.g. for logs; "unknown" out of range.
constexpr const char* to_string(FootstepGroup group) noexcept {
  switch (group) {
    case FootstepGroup::positions:
      return "positions";
    case FootstepGroup::yaws:
      return "yaws";
  }
  return "unknown";
}

/// The difference-operator term on the footstep positions (targets WalkingSchedule::step_x,
/// step_y) or on the footstep yaws (target WalkingSchedule::yaw).
template <typename Scalar>
class FootstepDifferences {
 public:
  using Group = FootstepGroup;

  FootstepDifferences(Scalar weight, Group group) : w_(weight), group_(group) {}
  Scalar weight() const { return w_; }

  /// H += w DᵀD on each group's N_f × N_f block.
  template <typename Preview>
  void add_constant_hessian(const WalkingLayout& L, const Preview&, MpcMatrix<Scalar>& H) const {
    const Eigen::Index nf = L.dims().nf;
    for_each_group(L, nullptr, [&](Eigen::Index f0, const MpcVector<Scalar>*) {
      for (Eigen::Index i = 0; i < nf; ++i) {
        H(f0 + i, f0 + i) += w_ * (i + 1 < nf ? Scalar(2) : Scalar(1));
        if (i + 1 < nf) {
          H(f0 + i, f0 + i + 1) += -w_;
          H(f0 + i + 1, f0 + i) += -w_;
        }
      }
    });
  }
  /// g −= w DᵀT per group, (DᵀT)_i = T_i − T_{i+1}; no Hessian part per tick.
  template <typename Tick>
  void add(const Tick& t, MpcMatrix<Scalar>&, MpcVector<Scalar>& g, MpcVector<Scalar>&) const {
    for_each_group(t.layout, &t.schedule, [&](Eigen::Index f0, const MpcVector<Scalar>* target) {
      const Eigen::Index nf = target->size();
      for (Eigen::Index i = 0; i < nf; ++i) {
        g[f0 + i] -= w_ * ((*target)[i] - (i + 1 < nf ? (*target)[i + 1] : Scalar(0)));
      }
    });
  }
  /// The term's value at U, for any scalar T (Jets included).
  template <typename T, typename Tick>
  T value(const Tick& t, const MpcVector<T>& U) const {
    T sum = T(0);
    for_each_group(t.layout, &t.schedule, [&](Eigen::Index f0, const MpcVector<Scalar>* target) {
      for (Eigen::Index i = 0; i < target->size(); ++i) {
        const T d = U[f0 + i] - (i > 0 ? U[f0 + i - 1] : T(0)) - (*target)[i];
        sum += d * d;
      }
    });
    return T(w_ / Scalar(2)) * sum;
  }

 private:
  /// f(offset of the group in U, its targets or nullptr without a schedule) per group.
  template <typename F>
  void for_each_group(const WalkingLayout& L, const WalkingSchedule<Scalar>* s, F&& f) const {
    if (group_ == Group::yaws) {
      f(L.step_q(), s != nullptr ? &s->yaw : nullptr);
      return;
    }
    f(L.step_x(), s != nullptr ? &s->step_x : nullptr);
    f(L.step_y(), s != nullptr ? &s->step_y : nullptr);
  }

  Scalar w_;
  Group group_;
};

}  // namespace walkgen
