#pragma once
/// @file
/// What a tick of the walking pattern generator (mpc/walking_mpc.hpp) reports: MpcStatus, the
/// fate of a velocity command (CommandStatus) and MpcResult.

#include <Eigen/Core>
#include <cstdint>

#include "walkgen/qp/dense_qp.hpp"

namespace walkgen {

/// Outcome of one generator tick.
enum class MpcStatus : std::uint8_t {
  /// Every SQP iteration's QP solved and the plan meets the nonlinear constraints within
  /// sqp_tolerance (Result::constraint_violation); the plan is the new solution.
  solved,
  qp_failed,  ///< a QP failed (see Result::qp_status); the plan is the previous one, shifted
  /// Every QP solved, but after sqp_iterations + sqp_corrections Gauss–Newton iterations the
  /// plan still violates the nonlinear constraints (rotated polygons, obstacle margins) by
  /// Result::constraint_violation > sqp_tolerance. The plan is that last iterate: the best
  /// available and executable, but outside its constraints by that much.
  not_converged,
  /// The QP was infeasible (or hit nwsr), and the soft-constraint fallback
  /// (GeneratorSettings::soft) found the plan that violates the soft blocks least:
  /// Result::relaxed_blocks names those it violates beyond sqp_tolerance,
  /// Result::constraint_violation says by how much; the hard blocks hold as in solved.
  relaxed,
};

/// What happened to a velocity command.
enum class CommandStatus : std::uint8_t {
  accepted,    ///< in use from the next solve()
  non_finite,  ///< NaN or inf: rejected, the previous command stays
  /// beyond WalkingSettings::max_command: each component beyond its limit clamped to it
  /// (sign kept), in use from the next solve() (WalkingMpc::command() is what walks)
  clamped,
};

/// The enumerator's name ("solved", ...), e.g. for logs; "unknown" out of range.
constexpr const char* to_string(MpcStatus s) noexcept {
  switch (s) {
    case MpcStatus::solved:
      return "solved";
    case MpcStatus::qp_failed:
      return "qp_failed";
    case MpcStatus::not_converged:
      return "not_converged";
    case MpcStatus::relaxed:
      return "relaxed";
  }
  return "unknown";
}

/// The enumerator's name ("accepted", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(CommandStatus s) noexcept {
  switch (s) {
    case CommandStatus::accepted:
      return "accepted";
    case CommandStatus::non_finite:
      return "non_finite";
    case CommandStatus::clamped:
      return "clamped";
  }
  return "unknown";
}

/// Result of solve().
template <typename Scalar = double>
struct MpcResult {
  MpcStatus status = MpcStatus::solved;
  QpStatus qp_status = QpStatus::unsolved;  ///< status of the last QP solved in this tick
  const char* message = "";                 ///< the QP's message when it failed
  int sqp_iterations = 0;                   ///< Gauss–Newton iterations done
  int qp_iterations = 0;                    ///< active-set changes, summed over the iterations
  Scalar primal_residual = Scalar(0);       ///< of the last QP (linearised constraints)
  /// Largest violation of the nonlinear constraints (eq. 2.65–2.82) by the plan [m or rad]:
  /// the linearisation error that sqp_corrections iterations bring below sqp_tolerance.
  Scalar constraint_violation = Scalar(0);
  /// MpcStatus::relaxed: the soft blocks whose slacks exceed sqp_tolerance (bit k = row block k
  /// of WalkingMpc::layout(); WalkingMpc::block_names() spells them). 0 otherwise.
  std::uint32_t relaxed_blocks = 0;
  /// A QP of this tick was infeasible (or hit nwsr) and the soft-constraint fallback solved it
  /// (GeneratorSettings::soft). With a plan that needs no slack after the Gauss–Newton
  /// corrections (the conflict was the linearisation's: the obstacle rows' tangents at a poor
  /// iterate) the status is solved; otherwise relaxed.
  bool soft_fallback = false;
  CommandStatus last_command = CommandStatus::accepted;  ///< the last set_command() outcome
  Eigen::Matrix<Scalar, 3, 1> command = Eigen::Matrix<Scalar, 3, 1>::Zero();  ///< in use
};

}  // namespace walkgen
