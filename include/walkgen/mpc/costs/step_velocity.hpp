#pragma once
/// @file
/// Cost term (walkgen's own): step velocity. Each planned footstep's displacement from the
/// previous one tracks T_i = step_displacement() (mpc/walking_schedule.hpp: t_step·v rotated
/// along the reference heading, the feet foot_distance apart):
///   w/2 Σ_{i=1..N_f} ‖F_i − F_{i−1} − T_i‖²,  w = step_velocity_weight · S / t_step²
/// per axis (per (m/s)² and horizon sample, like α). It carries the mean walking velocity that
/// the instantaneous velocity cost cannot, as that also charges the sway (docs/tuning.md).
/// Hessian w DᵀD (constant), gradient −w DᵀT (costs/footstep_differences.hpp).

#include <Eigen/Core>

#include "walkgen/mpc/costs/footstep_differences.hpp"
#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class StepVelocity : public FootstepDifferences<Scalar> {
 public:
  static constexpr const char* kName = "step velocity";
  explicit StepVelocity(const WalkingSettings<Scalar>& s)
      : FootstepDifferences<Scalar>(
            s.step_velocity_weight * Scalar(s.samples_per_step()) / (s.t_step * s.t_step),
            FootstepDifferences<Scalar>::Group::positions) {}
};

}  // namespace walkgen
