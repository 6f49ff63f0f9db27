#pragma once
/// @file
/// The swing foot within one step (thesis §2.3.1, §6.2.2). A step of duration t_step begins
/// with double support [0, t_ds): both feet stand, the ZMP moves onto the new support foot. In
/// single support [t_ds, t_step) the swing foot flies to its planned footstep: x, y and yaw on
/// 5th-order polynomials (eq. 2.111) that end at rest on the target, z on the 4th-order lift
/// (eq. 2.101) with apex step_height at mid single support.
///
/// The target may change from one NMPC tick to the next (real-time iteration), so x, y and yaw
/// are re-planned at every tick from the foot's current position, velocity and acceleration to
/// the new target over the remaining flight time: the trajectory stays continuous in position,
/// velocity and acceleration. The generator (state update) and the interpolator (command
/// samples) both evaluate this one function, so they cannot disagree.

#include <algorithm>

#include "walkgen/core/foot.hpp"
#include "walkgen/interpolation/polynomial.hpp"

namespace walkgen {

/// A foot's horizontal motion: x, y [m] and yaw q [rad], each with its two derivatives.
template <typename Scalar>
struct FootMotion {
  Sample3<Scalar> x{}, y{}, q{};

  /// A foot standing still at pose p.
  static FootMotion at_rest(const FootPose<Scalar>& p) {
    FootMotion m;
    m.x = {p.x, Scalar(0), Scalar(0)};
    m.y = {p.y, Scalar(0), Scalar(0)};
    m.q = {p.q, Scalar(0), Scalar(0)};
    return m;
  }
  FootPose<Scalar> pose() const { return {x.position, y.position, q.position}; }
};

/// The swing foot's horizontal motion plus its height z [m] (with derivatives).
template <typename Scalar>
struct SwingSample {
  FootMotion<Scalar> motion;
  Sample3<Scalar> z{};
};

/// The swing foot at step time tau, given its motion `from` at step time tau0 ≤ tau (a tick)
/// and its target footstep. Before t_ds the foot stands at from's position; from max(tau0, t_ds)
/// it follows the quintic to the target, reached at rest at t_step. Times beyond t_step hold
/// the target. No allocation; scalar-generic.
template <typename Scalar>
SwingSample<Scalar> swing_foot_sample(const StepTiming<Scalar>& timing,
                                      const FootMotion<Scalar>& from, Scalar tau0,
                                      const FootPose<Scalar>& target, Scalar tau) {
  using std::max;
  SwingSample<Scalar> out;
  const Scalar t_ss = timing.t_step - timing.t_ds;
  if (tau <= timing.t_ds) {  // double support: flat on the ground where it stands
    out.motion = FootMotion<Scalar>::at_rest(from.pose());
    out.z = {Scalar(0), Scalar(0), Scalar(0)};
    return out;
  }
  // The quintic starts at the tick if the foot already flies, else at lift-off from rest.
  const bool flying = tau0 > timing.t_ds;
  const Scalar start = flying ? tau0 : timing.t_ds;
  const FootMotion<Scalar> s = flying ? from : FootMotion<Scalar>::at_rest(from.pose());
  const Scalar remaining = timing.t_step - start;
  const Scalar t = tau - start;
  auto axis = [&](const Sample3<Scalar>& a, Scalar goal) {
    return quintic(remaining, a, Sample3<Scalar>{goal, Scalar(0), Scalar(0)}).evaluate(t);
  };
  out.motion.x = axis(s.x, target.x);
  out.motion.y = axis(s.y, target.y);
  out.motion.q = axis(s.q, target.q);
  out.z = quartic_lift(t_ss, Scalar(0), Scalar(0), timing.step_height, Scalar(0), Scalar(0))
              .evaluate(tau - timing.t_ds);
  return out;
}

}  // namespace walkgen
