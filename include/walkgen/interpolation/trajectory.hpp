#pragma once
/// @file
/// Interpolation of the generator's plan at the command period (thesis §2.3, §6.2.2): the CoM by
/// the LIPM with the tick's first jerk (eq. 2.29 at the finer period), the ZMP from it
/// (z = c − c_z/g c̈, eq. 2.6–2.7), the support foot standing, the swing foot on its polynomials
/// (interpolation/swing_foot.hpp). The CoM yaw is the mean of the feet's yaws.
///
/// The data path runs one way: the generator emits a TickPlan value (WalkingMpc::tick_plan()),
/// the interpolator consumes that value and its own few numbers (InterpolationSettings, e.g.
/// walkgen::interpolation_settings(walking_settings)). Nothing here knows the generator.
///
/// Trajectories are stored in the thesis's CSV column order (§6.3), 21 columns:
///   com_x com_dx com_ddx com_y com_dy com_ddy com_z com_q com_dq com_ddq zmp_x zmp_y zmp_z
///   lf_x lf_y lf_z lf_q rf_x rf_y rf_z rf_q
/// (the thesis's listing omits com_q and names the ZMP columns ambiguously; its code writes these
/// 21). Row r is time r · command_period.

#include <Eigen/Core>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/interpolation/swing_foot.hpp"

namespace walkgen {

/// One command-period sample of the walking pattern. World frame; metres, radians, seconds.
template <typename Scalar = double>
struct TrajectorySample {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  Scalar time = Scalar(0);
  Vector3 com_x = Vector3::Zero(), com_y = Vector3::Zero();  ///< position, velocity, accel.
  Vector3 com_q = Vector3::Zero();                           ///< CoM yaw, rate, acceleration
  Scalar com_z = Scalar(0);
  Scalar zmp_x = Scalar(0), zmp_y = Scalar(0), zmp_z = Scalar(0);
  SwingSample<Scalar> left, right;  ///< feet: x, y, yaw and height with derivatives
  Foot support_foot = Foot::left;   ///< the foot that supports the current step
  bool double_support = true;       ///< both feet on the ground

  const SwingSample<Scalar>& foot(Foot f) const { return f == Foot::left ? left : right; }
};

/// The interpolator's own numbers. No defaults: they must match the generator's settings
/// (walkgen::interpolation_settings() copies them from WalkingSettings).
template <typename Scalar = double>
struct InterpolationSettings {
  Scalar t;               ///< [s] generator period: one tick, sampled by command_period
  Scalar command_period;  ///< [s] period of the samples; divides t
  Scalar com_z;           ///< [m] CoM height of the inverted pendulum
  Scalar gravity;         ///< [m/s²]
};

namespace detail {
/// t / command_period when it is a whole number in [1, 1e6), else 0.
template <typename Scalar>
int interpolation_samples_per_tick(const InterpolationSettings<Scalar>& s) {
  using std::abs;
  const Scalar ratio = s.t / s.command_period;
  const int per_tick = ratio < Scalar(1e6) ? int(std::lround(ratio)) : 0;
  return per_tick >= 1 && abs(Scalar(per_tick) - ratio) <= Scalar(1e-6) * ratio ? per_tick : 0;
}
}  // namespace detail

/// Checks the interpolator's numbers (WalkingInterpolator's constructor calls it).
/// @throws walkgen::invalid_argument naming the first bad field, unless every number is finite
///   and positive and command_period divides t.
template <typename Scalar>
void validate(const InterpolationSettings<Scalar>& s) {
  check_positive("InterpolationSettings.t", s.t);
  check_positive("InterpolationSettings.command_period", s.command_period);
  check_positive("InterpolationSettings.com_z", s.com_z);
  check_positive("InterpolationSettings.gravity", s.gravity);
  check_argument(
      detail::interpolation_samples_per_tick(s) >= 1, "InterpolationSettings.command_period",
      "a period that divides t = " + std::to_string(s.t) + " s evenly", s.command_period);
}

/// What one generator tick hands on: the state it planned from and the part of the plan that the
/// next t seconds follow. A value (no reference into the generator), allocation-free.
template <typename Scalar = double>
struct TickPlan {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  Scalar time = Scalar(0);       ///< [s] of the tick
  Scalar step_time = Scalar(0);  ///< [s] elapsed in the current step (phase · t)
  Vector3 com_x = Vector3::Zero(), com_y = Vector3::Zero();  ///< CoM x, ẋ, ẍ and y, ẏ, ÿ
  Scalar jerk_x = Scalar(0), jerk_y = Scalar(0);  ///< the plan's first jerks, held over the tick
  Foot support_foot = Foot::left;                 ///< the foot on the ground
  FootPose<Scalar> support;                       ///< its pose
  FootMotion<Scalar> swing;                       ///< the other foot's motion now
  FootPose<Scalar> landing;                       ///< the next planned footstep (swing target)
  StepTiming<Scalar> timing{};                    ///< of the current step
};

/// Samples a TickPlan at the command period. Stateless apart from its settings.
template <typename Scalar = double>
class WalkingInterpolator {
 public:
  /// @throws walkgen::invalid_argument for invalid settings (validate()).
  explicit WalkingInterpolator(const InterpolationSettings<Scalar>& settings)
      : dt_(settings.command_period),
        per_tick_(checked_samples_per_tick(settings)),
        h_(settings.com_z / settings.gravity),
        com_z_(settings.com_z) {}

  /// Samples per tick: t / command_period.
  int samples_per_tick() const { return per_tick_; }
  Scalar command_period() const { return dt_; }

  /// Writes samples_per_tick() samples of `plan` at plan.time + i·command_period, i = 0…
  /// `out` must hold that many samples. No allocation.
  void interpolate(const TickPlan<Scalar>& plan, TrajectorySample<Scalar>* out) const {
    SwingSample<Scalar> support;
    support.motion = FootMotion<Scalar>::at_rest(plan.support);
    const Scalar tau0 = plan.step_time;
    for (int i = 0; i < per_tick_; ++i) {
      TrajectorySample<Scalar>& o = out[i];
      const Scalar t = Scalar(i) * dt_;
      o.time = plan.time + t;
      o.com_x = lipm_at(plan.com_x, plan.jerk_x, t);
      o.com_y = lipm_at(plan.com_y, plan.jerk_y, t);
      o.com_z = com_z_;
      o.zmp_x = o.com_x[0] - h_ * o.com_x[2];
      o.zmp_y = o.com_y[0] - h_ * o.com_y[2];
      o.zmp_z = Scalar(0);
      const SwingSample<Scalar> swing =
          swing_foot_sample(plan.timing, plan.swing, tau0, plan.landing, tau0 + t);
      o.support_foot = plan.support_foot;
      o.double_support = tau0 + t <= plan.timing.t_ds;
      (plan.support_foot == Foot::left ? o.left : o.right) = support;
      (plan.support_foot == Foot::left ? o.right : o.left) = swing;
      const auto& lq = o.left.motion.q;
      const auto& rq = o.right.motion.q;
      o.com_q << (lq.position + rq.position) / Scalar(2), (lq.velocity + rq.velocity) / Scalar(2),
          (lq.acceleration + rq.acceleration) / Scalar(2);
    }
  }

 private:
  /// LIPM state after time t with constant jerk (eq. 2.25–2.27 at period t).
  static Eigen::Matrix<Scalar, 3, 1> lipm_at(const Eigen::Matrix<Scalar, 3, 1>& c, Scalar jerk,
                                             Scalar t) {
    const Scalar t2 = t * t;
    return {c[0] + c[1] * t + c[2] * t2 / Scalar(2) + jerk * t2 * t / Scalar(6),
            c[1] + c[2] * t + jerk * t2 / Scalar(2), c[2] + jerk * t};
  }

  static int checked_samples_per_tick(const InterpolationSettings<Scalar>& s) {
    validate(s);
    return detail::interpolation_samples_per_tick(s);
  }

  Scalar dt_;
  int per_tick_;
  Scalar h_, com_z_;
};

/// Column names of the trajectory CSV, in the thesis's order.
inline const char* trajectory_csv_header() {
  return "com_x,com_dx,com_ddx,com_y,com_dy,com_ddy,com_z,com_q,com_dq,com_ddq,zmp_x,zmp_y,zmp_z,"
         "lf_x,lf_y,lf_z,lf_q,rf_x,rf_y,rf_z,rf_q";
}

/// Writes samples as CSV with a header line (thesis column order). For logs, not the loop.
template <typename Scalar>
void write_trajectory_csv(std::ostream& os, const std::vector<TrajectorySample<Scalar>>& samples) {
  os << trajectory_csv_header() << '\n';
  const auto prec = os.precision(10);
  for (const auto& s : samples) {
    os << s.com_x[0] << ',' << s.com_x[1] << ',' << s.com_x[2] << ',' << s.com_y[0] << ','
       << s.com_y[1] << ',' << s.com_y[2] << ',' << s.com_z << ',' << s.com_q[0] << ','
       << s.com_q[1] << ',' << s.com_q[2] << ',' << s.zmp_x << ',' << s.zmp_y << ',' << s.zmp_z;
    for (const auto* f : {&s.left, &s.right}) {
      os << ',' << f->motion.x.position << ',' << f->motion.y.position << ',' << f->z.position
         << ',' << f->motion.q.position;
    }
    os << '\n';
  }
  os.precision(prec);
}

}  // namespace walkgen
