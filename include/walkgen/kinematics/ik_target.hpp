#pragma once
/// @file
/// What a whole-body inverse kinematics is asked for and what it answers (thesis §2.4.2, §6.2.3):
/// the target of one sample of a walking pattern (CoM, both soles, held pelvis and torso
/// orientations) and the result of a solve. Core (Eigen only): the closed walking loop
/// (control/walking_loop.hpp) uses any solver with this interface; walkgen::ceres provides one.
/// A walking-pattern sample becomes a target in control/pattern_targets.hpp (the data path runs
/// one way: kinematics knows nothing of the pattern).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace walkgen {

/// A flat sole: its point (lf/rf_body_point) at position_W [m], turned by yaw [rad] about z.
struct SoleTarget {
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();
  double yaw = 0.0;
};

/// What the whole body should do: CoM, both soles, and the held orientations.
struct IkTarget {
  Eigen::Vector3d com_W = Eigen::Vector3d::Zero();  ///< [m]
  SoleTarget left_foot, right_foot;
  Eigen::Matrix3d base_rotation_W = Eigen::Matrix3d::Identity();   ///< root link (pelvis)
  Eigen::Matrix3d torso_rotation_W = Eigen::Matrix3d::Identity();  ///< settings.torso_link

  /// Upright pelvis and torso turned by `yaw` [rad], the walking posture.
  void hold_upright(double yaw) {
    base_rotation_W = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    torso_rotation_W = base_rotation_W;
  }

  bool all_finite() const {
    return com_W.allFinite() && left_foot.position_W.allFinite() &&
           right_foot.position_W.allFinite() && std::isfinite(left_foot.yaw) &&
           std::isfinite(right_foot.yaw) && base_rotation_W.allFinite() &&
           torso_rotation_W.allFinite();
  }
};

/// Outcome of a solve.
enum class IkStatus {
  converged,      ///< every error within the tolerances; the solution was updated
  not_converged,  ///< some error above its tolerance after all runs; previous solution kept
  invalid_input,  ///< a non-finite target; nothing was solved, previous solution kept
};

/// The enumerator's name ("converged", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(IkStatus status) noexcept {
  switch (status) {
    case IkStatus::converged:
      return "converged";
    case IkStatus::not_converged:
      return "not_converged";
    case IkStatus::invalid_input:
      return "invalid_input";
  }
  return "unknown";
}

/// Result of an inverse-kinematics solve (e.g. CeresInverseKinematics::solve()): status, work and
/// the unweighted errors of the final iterate (of the best run; infinity when nothing was solved).
struct IkResult {
  IkStatus status = IkStatus::invalid_input;
  /// Why it did not converge (a static string: solves run in the control loop); empty when
  /// converged.
  const char* message = "";
  bool applied = false;  ///< the solution was updated (only when converged)
  int iterations = 0;    ///< LM iterations (successful + unsuccessful steps), all runs
  int runs = 0;          ///< Ceres runs (up to n_init on a cold solve)
  double com_error = std::numeric_limits<double>::infinity();            ///< |c − c*| [m]
  double foot_position_error = std::numeric_limits<double>::infinity();  ///< max of feet [m]
  double foot_yaw_error = std::numeric_limits<double>::infinity();       ///< max of feet [rad]
  double foot_tilt_error = std::numeric_limits<double>::infinity();      ///< sole normal vs z [rad]
  double base_orientation_error = std::numeric_limits<double>::infinity();   ///< [rad]
  double torso_orientation_error = std::numeric_limits<double>::infinity();  ///< [rad]
  double cost = std::numeric_limits<double>::infinity();  ///< Ceres' ½|weighted residual|²
};

}  // namespace walkgen
