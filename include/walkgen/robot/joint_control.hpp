#pragma once
/// @file
/// The joint controller of a torque-controlled robot, between the IK's joint positions and the
/// motors: PD on joint positions and velocities plus a feed-forward torque, clamped to the
/// motors' limits, saturation counted. Eigen only and allocation-free after construction: it
/// runs at the physics rate inside a robot backend (walkgen/mujoco/mujoco_robot.hpp) or a real
/// robot's driver.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "walkgen/core/assert.hpp"
#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// What one evaluation of the controller did.
struct JointTorqueResult {
  int saturated = 0;   ///< joints whose torque was clamped to a limit
  bool finite = true;  ///< false: an input was not finite and every torque was set to 0
};

/// τ = clamp(τ_ff + kp (q_ref − q) + kd (dq_ref − dq), τ_min, τ_max), joint by joint.
class JointTorqueController {
 public:
  /// Gains [N m/rad], [N m s/rad] and torque limits [N m] per joint (equal sizes).
  /// @throws walkgen::invalid_argument for sizes that differ, a gain that is not finite and
  ///   >= 0 (naming the joint index), or a limit pair with τ_min > 0 or τ_max < 0 or NaN.
  JointTorqueController(Eigen::VectorXd kp, Eigen::VectorXd kd, Eigen::VectorXd tau_min,
                        Eigen::VectorXd tau_max)
      : kp_(std::move(kp)), kd_(std::move(kd)), lo_(std::move(tau_min)), hi_(std::move(tau_max)) {
    const Eigen::Index n = kp_.size();
    check_argument(n >= 1 && kd_.size() == n && lo_.size() == n && hi_.size() == n,
                   "JointTorqueController", "kp, kd, tau_min, tau_max of one size >= 1",
                   std::to_string(kp_.size()) + ", " + std::to_string(kd_.size()) + ", " +
                       std::to_string(lo_.size()) + ", " + std::to_string(hi_.size()));
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::string at = "JointTorqueController: joint " + std::to_string(i);
      check_argument(
          std::isfinite(kp_[i]) && std::isfinite(kd_[i]) && kp_[i] >= 0.0 && kd_[i] >= 0.0,
          at.c_str(), "gains kp, kd finite and >= 0",
          std::to_string(kp_[i]) + ", " + std::to_string(kd_[i]));
      check_argument(!std::isnan(lo_[i]) && !std::isnan(hi_[i]) && lo_[i] <= 0.0 && hi_[i] >= 0.0,
                     at.c_str(), "torque limits tau_min <= 0 <= tau_max",
                     std::to_string(lo_[i]) + ", " + std::to_string(hi_[i]));
    }
  }

  Eigen::Index size() const { return kp_.size(); }
  const Eigen::VectorXd& kp() const { return kp_; }
  const Eigen::VectorXd& kd() const { return kd_; }
  const Eigen::VectorXd& tau_min() const { return lo_; }
  const Eigen::VectorXd& tau_max() const { return hi_; }

  /// The torques for references q_ref, dq_ref, tau_ff and measurements q, dq (all of size()).
  /// A non-finite input gives zero torque (the motors go limp rather than jump) and finite
  /// false; wrong sizes are a programming error (assert).
  JointTorqueResult compute(const Eigen::Ref<const Eigen::VectorXd>& q_ref,
                            const Eigen::Ref<const Eigen::VectorXd>& dq_ref,
                            const Eigen::Ref<const Eigen::VectorXd>& tau_ff,
                            const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& dq,
                            Eigen::Ref<Eigen::VectorXd> tau) const noexcept {
    WALKGEN_ASSERT(q_ref.size() == size() && dq_ref.size() == size() && tau_ff.size() == size() &&
                   q.size() == size() && dq.size() == size() && tau.size() == size());
    JointTorqueResult result;
    for (Eigen::Index i = 0; i < size(); ++i) {
      const double t = tau_ff[i] + kp_[i] * (q_ref[i] - q[i]) + kd_[i] * (dq_ref[i] - dq[i]);
      if (!std::isfinite(t)) {
        tau.setZero();
        result.saturated = 0;
        result.finite = false;
        return result;
      }
      tau[i] = std::clamp(t, lo_[i], hi_[i]);
      result.saturated += tau[i] != t;
    }
    return result;
  }

 private:
  Eigen::VectorXd kp_, kd_, lo_, hi_;
};

}  // namespace walkgen
