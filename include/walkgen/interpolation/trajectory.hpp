#pragma once
/// @file
/// Interpolation of the generator's plan at the command period (thesis §2.3, §6.2.2): the CoM by
/// the LIPM with the tick's first jerk (eq. 2.29 at the finer period), the ZMP from it
/// (z = c − c_z/g c̈, eq. 2.6–2.7), the support foot standing, the swing foot on its polynomials
/// (interpolation/swing_foot.hpp). The CoM yaw is the mean of the feet's yaws.
///
/// Trajectories are stored in the thesis's CSV column order (§6.3), 21 columns:
///   com_x com_dx com_ddx com_y com_dy com_ddy com_z com_q com_dq com_ddq zmp_x zmp_y zmp_z
///   lf_x lf_y lf_z lf_q rf_x rf_y rf_z rf_q
/// (the thesis's listing omits com_q and names the ZMP columns ambiguously; its code writes these
/// 21). Row r is time r · command_period.

#include <Eigen/Core>
#include <ostream>
#include <vector>

#include "walkgen/core/foot.hpp"
#include "walkgen/interpolation/swing_foot.hpp"
#include "walkgen/mpc/settings.hpp"

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

/// Samples the plan of a WalkingMpc between two ticks. Stateless apart from its settings.
template <typename Scalar = double>
class WalkingInterpolator {
 public:
  explicit WalkingInterpolator(const WalkingSettings<Scalar>& settings)
      : dt_(settings.command_period),
        per_tick_(int(std::lround(settings.t / settings.command_period))),
        h_(settings.com_z / settings.gravity),
        com_z_(settings.com_z) {
    check_argument(per_tick_ >= 1, "WalkingInterpolator: command_period",
                   "a period <= t = " + std::to_string(settings.t), settings.command_period);
  }

  /// Samples per tick: t / command_period.
  int samples_per_tick() const { return per_tick_; }
  Scalar command_period() const { return dt_; }

  /// Writes samples_per_tick() samples at t_k + i·command_period, i = 0…, of the plan that
  /// mpc.solve() just made (call before mpc.advance()). `out` must hold that many samples.
  /// No allocation.
  template <typename Mpc>
  void interpolate(const Mpc& mpc, TrajectorySample<Scalar>* out) const {
    const auto& st = mpc.state();
    const auto& plan = mpc.plan();
    const StepTiming<Scalar> timing = mpc.step_timing();
    const Scalar tau0 = Scalar(st.phase) * mpc.settings().t;
    const FootPose<Scalar> target = plan.footstep(1);
    SwingSample<Scalar> support;
    support.motion = FootMotion<Scalar>::at_rest(st.support);
    for (int i = 0; i < per_tick_; ++i) {
      TrajectorySample<Scalar>& o = out[i];
      const Scalar t = Scalar(i) * dt_;
      o.time = st.time + t;
      o.com_x = lipm_at(st.com_x, plan.jerk_x(0), t);
      o.com_y = lipm_at(st.com_y, plan.jerk_y(0), t);
      o.com_z = com_z_;
      o.zmp_x = o.com_x[0] - h_ * o.com_x[2];
      o.zmp_y = o.com_y[0] - h_ * o.com_y[2];
      o.zmp_z = Scalar(0);
      const SwingSample<Scalar> swing = swing_foot_sample(timing, st.swing, tau0, target, tau0 + t);
      o.support_foot = st.support_foot;
      o.double_support = tau0 + t <= timing.t_ds;
      (st.support_foot == Foot::left ? o.left : o.right) = support;
      (st.support_foot == Foot::left ? o.right : o.left) = swing;
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
