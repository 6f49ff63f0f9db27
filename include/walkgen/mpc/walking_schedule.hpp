#pragma once
/// @file
/// The NMPC's schedule: the generator's state, which step each horizon sample belongs to
/// (thesis eq. 2.47–2.50), which foot stands in each step, and the per-tick references that
/// the cost terms track (velocity eq. 2.43, yaw rate eq. 2.44, step velocity). WalkingTick is
/// what every constraint block and cost term reads at one tick.
///
/// Timing: a step of S = t_step / t samples begins with double support. With `phase` p samples
/// of the current step elapsed, horizon sample j (0-based, time t_k + (j+1)t) belongs to step
/// ⌊(p + j) / S⌋: step 0 is the current support foot, step i ≥ 1 the i-th planned footstep
/// (the selection v/V of eq. 2.47–2.49). The ZMP therefore moves onto a new foot during the
/// first interval of every step, inside double support (t_ds ≥ t is validated).

#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/core/obstacle.hpp"
#include "walkgen/interpolation/swing_foot.hpp"
#include "walkgen/model/lipm.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/mpc/walking_layout.hpp"

namespace walkgen {

/// The generator's state at a tick (section 6.3's PatternGeneratorState). Feedback may overwrite
/// it between ticks with WalkingMpc::set_state(), e.g. the CoM from forward kinematics.
template <typename Scalar = double>
struct WalkingState {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  Vector3 com_x = Vector3::Zero();  ///< CoM x, ẋ, ẍ [m, m/s, m/s²], world frame
  Vector3 com_y = Vector3::Zero();  ///< CoM y, ẏ, ÿ
  Foot support_foot = Foot::left;   ///< the foot on the ground in single support
  FootPose<Scalar> support;         ///< its pose
  FootPose<Scalar> swing_origin;    ///< where the swing foot lifts off (stands in double support)
  FootMotion<Scalar> swing;         ///< the swing foot's motion now
  int phase = 0;                    ///< samples of the current step elapsed, 0 ≤ phase < S
  Scalar time = Scalar(0);          ///< [s] since the start
  long step_count = 0;              ///< steps completed since the start

  /// Heading of the robot [rad]: the mean of the two feet's yaws.
  Scalar heading() const { return (support.q + swing.q.position) / Scalar(2); }
  /// Which foot stands in step i (0 = the current support; the feet alternate, eq. 2.50).
  Foot foot_of_step(Eigen::Index i) const {
    return i % 2 == 0 ? support_foot : other(support_foot);
  }

  /// The state of a settings set: CoM from com_x/com_y, support foot at (foot_x, foot_y,
  /// foot_q), the other foot foot_distance beside it, standing.
  static WalkingState initial(const WalkingSettings<Scalar>& s) {
    using std::cos;
    using std::sin;
    WalkingState st;
    st.com_x = s.com_x;
    st.com_y = s.com_y;
    st.support_foot = s.support_foot;
    st.support = {s.foot_x, s.foot_y, s.foot_q};
    // Beside the support foot, on the other foot's side.
    const Scalar side = s.support_foot == Foot::left ? Scalar(-1) : Scalar(1);
    const FootPose<Scalar>& p = st.support;
    st.swing_origin = {p.x - side * s.foot_distance * sin(p.q),
                       p.y + side * s.foot_distance * cos(p.q), p.q};
    st.swing = FootMotion<Scalar>::at_rest(st.swing_origin);
    return st;
  }

  /// Whether every value is finite.
  bool all_finite() const {
    using std::isfinite;
    auto pose_ok = [](const FootPose<Scalar>& p) {
      return isfinite(p.x) && isfinite(p.y) && isfinite(p.q);
    };
    auto s3_ok = [](const Sample3<Scalar>& s) {
      return isfinite(s.position) && isfinite(s.velocity) && isfinite(s.acceleration);
    };
    return com_x.allFinite() && com_y.allFinite() && pose_ok(support) && pose_ok(swing_origin) &&
           s3_ok(swing.x) && s3_ok(swing.y) && s3_ok(swing.q) && isfinite(time);
  }

  /// What makes a finite state implausible under the settings' limits (max_state_distance,
  /// max_com_speed, max_com_acceleration), or nullptr.
  const char* implausible(const WalkingSettings<Scalar>& s) const {
    const auto far = [&](Scalar x, Scalar y) {
      return std::hypot(x - support.x, y - support.y) > s.max_state_distance;
    };
    if (far(com_x[0], com_y[0])) return "the CoM farther than max_state_distance";
    if (far(swing.x.position, swing.y.position) || far(swing_origin.x, swing_origin.y)) {
      return "the swing foot farther than max_state_distance";
    }
    if (std::abs(com_x[1]) > s.max_com_speed || std::abs(com_y[1]) > s.max_com_speed) {
      return "a CoM speed above max_com_speed";
    }
    if (std::abs(com_x[2]) > s.max_com_acceleration ||
        std::abs(com_y[2]) > s.max_com_acceleration) {
      return "a CoM acceleration above max_com_acceleration";
    }
    return nullptr;
  }
};

/// @throws walkgen::invalid_argument naming `where` if a value of `st` is non-finite, its phase
///         is outside [0, samples_per_step()), or it is implausible under the settings' limits
///         (WalkingState::implausible(): a feedback glitch).
template <typename Scalar>
void check_walking_state(const char* where, const WalkingSettings<Scalar>& s,
                         const WalkingState<Scalar>& st) {
  const int S = s.samples_per_step();
  if (st.phase < 0 || st.phase >= S) {  // the message is built only on failure
    check_argument(false, (std::string(where) + ": phase").c_str(),
                   "0 <= phase < samples_per_step() = " + std::to_string(S), st.phase);
  }
  check_argument(st.all_finite(), where, "finite values", "NaN or inf",
                 "check the feedback (forward kinematics) that produced the state");
  if (const char* what = st.implausible(s)) {
    std::ostringstream got;
    got << what << " (CoM at (" << st.com_x[0] << ", " << st.com_y[0] << ") m, support foot at ("
        << st.support.x << ", " << st.support.y << ") m)";
    check_argument(false, where, "a plausible walking state", got.str(),
                   "check the feedback; the limits are WalkingSettings::max_state_distance, "
                   "max_com_speed and max_com_acceleration");
  }
}

/// The reference heading [rad] when planned step i ≥ 0 lands (i = 0: when the support foot
/// landed): `heading` is the reference now (WalkingMpc::reference_heading(), the commanded yaw
/// rate integrated), the command's yaw rate carries it along the step times.
template <typename Scalar>
Scalar heading_at_step(const WalkingSettings<Scalar>& s, const WalkingState<Scalar>& st,
                       Scalar yaw_rate, Scalar heading, Eigen::Index i) {
  return heading + yaw_rate * (Scalar(i) * s.t_step - Scalar(st.phase) * s.t);
}

/// The yaw planned step i's foot should have: the reference heading at the middle of its
/// support, half a step after it lands. Consecutive feet are then ω·t_step apart (eq. 2.44) and
/// the two feet's mean yaw is the reference heading when a step lands.
template <typename Scalar>
Scalar yaw_of_step(const WalkingSettings<Scalar>& s, const WalkingState<Scalar>& st,
                   Scalar yaw_rate, Scalar heading, Eigen::Index i) {
  return heading_at_step(s, st, yaw_rate, heading, i) + yaw_rate * s.t_step / Scalar(2);
}

/// Step velocity target of planned step i relative to step i − 1 (walkgen's own, see
/// costs/step_velocity.hpp): F_i − F_{i−1} = R(h_i) (t_step v + lateral), h_i the reference
/// heading when step i lands (heading_at_step()). The feet stand foot_distance apart measured
/// in the frame of the foot a step is planned from, as the feasibility polygons measure it:
/// foot_distance / cos(Δ/2) between centres when consecutive feet turn by Δ = ω t_step.
/// @param command (v_x, v_y [m/s], ω_z [rad/s]) in the robot's frame.
/// @param heading the reference heading now [rad] (WalkingMpc::reference_heading()).
template <typename Scalar>
void step_displacement(const WalkingSettings<Scalar>& s, const WalkingState<Scalar>& st,
                       const Eigen::Matrix<Scalar, 3, 1>& command, Scalar heading, Eigen::Index i,
                       Scalar& dx_world, Scalar& dy_world) {
  using std::cos;
  using std::sin;
  const Scalar turn = command[2] * s.t_step;
  const Scalar h = heading_at_step(s, st, command[2], heading, i);
  const Scalar side = st.foot_of_step(i) == Foot::left ? Scalar(1) : Scalar(-1);
  // Sideways, the leading foot steps 2 t_step v_y out and the trailing one closes up.
  const Scalar lateral =
      side * command[1] > Scalar(0) ? Scalar(2) * s.t_step * command[1] : Scalar(0);
  const Scalar dx = s.t_step * command[0];
  const Scalar dy = lateral + side * s.foot_distance / cos(turn / Scalar(2));
  dx_world = cos(h) * dx - sin(h) * dy;
  dy_world = sin(h) * dx + cos(h) * dy;
}

/// The per-tick schedule: step membership and the references the costs track. Sized once.
template <typename Scalar>
struct WalkingSchedule {
  using VectorX = MpcVector<Scalar>;
  Eigen::Matrix<int, Eigen::Dynamic, 1> step_of;  ///< step of each horizon sample (eq. 2.47)
  /// Velocity reference at samples 1..N [m/s], world frame: the command rotated along the
  /// reference heading, R(h + ω t (j + 1)) v (eq. 2.43; the thesis keeps the heading constant
  /// over the horizon, which makes curved walks lag).
  VectorX ref_x, ref_y;
  /// Step velocity targets of F_i − F_{i−1} [m] (step_displacement()), the support foot's
  /// position added to the first (F_0 is not a variable).
  VectorX step_x, step_y;
  /// Yaw targets of θ_i − θ_{i−1} [rad]: ω·t_step (eq. 2.44), the support yaw added to the first.
  VectorX yaw;
  /// Absolute yaw targets of θ_i [rad] (yaw_of_step(): the reference heading, costs/heading.hpp).
  VectorX heading;

  explicit WalkingSchedule(const WalkingDims& d)
      : step_of(Eigen::Matrix<int, Eigen::Dynamic, 1>::Zero(d.N)),
        ref_x(VectorX::Zero(d.N)),
        ref_y(VectorX::Zero(d.N)),
        step_x(VectorX::Zero(d.nf)),
        step_y(VectorX::Zero(d.nf)),
        yaw(VectorX::Zero(d.nf)),
        heading(VectorX::Zero(d.nf)) {}

  /// Fills the schedule of a tick planned from `st` under `command`, the reference heading now
  /// being `reference_heading` [rad]. Allocation-free.
  void update(const WalkingSettings<Scalar>& s, const WalkingState<Scalar>& st,
              const Eigen::Matrix<Scalar, 3, 1>& command, Scalar reference_heading) {
    using std::cos;
    using std::sin;
    const Eigen::Index N = step_of.size(), nf = yaw.size(), S = s.samples_per_step();
    for (Eigen::Index j = 0; j < N; ++j) step_of[j] = int((st.phase + j) / S);
    for (Eigen::Index j = 0; j < N; ++j) {
      const Scalar q = reference_heading + command[2] * s.t * Scalar(j + 1);
      ref_x[j] = command[0] * cos(q) - command[1] * sin(q);
      ref_y[j] = command[0] * sin(q) + command[1] * cos(q);
    }
    yaw.setConstant(command[2] * s.t_step);
    yaw[0] += st.support.q;
    for (Eigen::Index i = 1; i <= nf; ++i) {
      step_displacement(s, st, command, reference_heading, i, step_x[i - 1], step_y[i - 1]);
      heading[i - 1] = yaw_of_step(s, st, command[2], reference_heading, i);
    }
    step_x[0] += st.support.x;
    step_y[0] += st.support.y;
  }
};

/// What the constraint blocks and cost terms read at one tick (a view; build it per use).
template <typename Scalar, int N>
struct WalkingTick {
  using Index = Eigen::Index;

  const WalkingSettings<Scalar>& settings;
  const WalkingLayout& layout;
  const LipmPreview<Scalar, N>& preview;
  const WalkingState<Scalar>& state;  ///< the state planned from
  const std::vector<CircleObstacle<Scalar>>& obstacles;
  const WalkingSchedule<Scalar>& schedule;
  /// The iterate U: where the Gauss–Newton rows are linearised, the proximal term's centre.
  const MpcVector<Scalar>& iterate;

  /// Step of horizon sample j: ⌊(phase + j) / S⌋ (eq. 2.47–2.49).
  Index step_of(Index j) const { return (state.phase + j) / layout.dims().S; }
  Foot foot_of_step(Index i) const { return state.foot_of_step(i); }
  /// Footstep i's x, y and yaw in U; i = 0 is the support foot (a constant, eq. 2.47).
  template <typename T>
  T x(const MpcVector<T>& U, Index i) const {
    return i == 0 ? T(state.support.x) : U[layout.step_x() + i - 1];
  }
  template <typename T>
  T y(const MpcVector<T>& U, Index i) const {
    return i == 0 ? T(state.support.y) : U[layout.step_y() + i - 1];
  }
  template <typename T>
  T q(const MpcVector<T>& U, Index i) const {
    return i == 0 ? T(state.support.q) : U[layout.step_q() + i - 1];
  }
};

}  // namespace walkgen
