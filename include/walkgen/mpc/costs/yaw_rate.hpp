#pragma once
/// @file
/// Cost term: yaw-rate tracking, thesis eq. 2.44. Consecutive footstep yaws ω·t_step apart:
///   w/2 Σ_{i=1..N_f} (θ_i − θ_{i−1} − ω t_step)²,  w = α · S / t_step²
/// (eq. 2.44 sums the rate error over the S samples of a step, divided by t_step² to turn yaw
/// steps into rates; footstep yaws are the variables instead of the thesis's foot-yaw jerks,
/// docs/walking.md). θ_0 is the support foot's yaw. Hessian w DᵀD (constant), gradient −w DᵀT
/// (costs/footstep_differences.hpp).

#include <Eigen/Core>

#include "walkgen/mpc/costs/footstep_differences.hpp"
#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class YawRate : public FootstepDifferences<Scalar> {
 public:
  static constexpr const char* kName = "yaw-rate tracking (eq. 2.44)";
  explicit YawRate(const WalkingSettings<Scalar>& s)
      : FootstepDifferences<Scalar>(s.alpha * Scalar(s.samples_per_step()) / (s.t_step * s.t_step),
                                    FootstepDifferences<Scalar>::Group::yaws) {}
};

}  // namespace walkgen
