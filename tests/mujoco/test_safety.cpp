// Issue 24 item 4, label safety: the closed loop's safety state machine (docs/safety.md) in
// MuJoCo, on both robots: walkgen's humanoid (position servos) and the Unitree G1 (torque
// motors, from its description file). Each fault (a QP failure streak, an IK failure streak, an
// unreachable CoM height, non-finite or out-of-range joint, force or IMU readings, torque
// saturation, a fall told by the IMU) ends in its documented safe state with its status and
// reason, never with an exception, never with a stale plan walked on; a requested stop finishes
// the step and stands the robot on both feet.
//
// The physics is MuJoCo's throughout. Where a fault cannot be produced physically (the
// humanoid's position servos never saturate; sensors do not fail) a FaultyRobot reports the
// MujocoRobot's measurement with the fault written into it, and a FailingIk stops converging on
// request: the loop sees exactly what a faulty robot or solver would hand it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "edited_robot.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#ifdef WALKGEN_TEST_ROBOT_FILES  // tests/CMakeLists.txt: with walkgen::yaml
#include "walkgen/yaml/robot_description_loader.hpp"
#endif

namespace {

using walkgen::LoopMode;
using walkgen::LoopStatus;
using walkgen::StopReason;

const double kNan = std::numeric_limits<double>::quiet_NaN();

/// A robot of the suite and the joints its sensor faults name.
struct RobotCase {
  const char* name;
  const char* left_knee;
  const char* right_hip_pitch;
};

const std::vector<RobotCase>& robot_cases() {
  static const std::vector<RobotCase> cases = {
      {"walkgen_humanoid", "l_knee", "r_hip_pitch"},
#ifdef WALKGEN_TEST_ROBOT_FILES
      {"unitree_g1", "left_knee_joint", "right_hip_pitch_joint"},
#endif
  };
  return cases;
}

/// The robots a test runs on where the G1 does not reach the safe state yet (docs/safety.md,
/// "The G1's safe states"): walkgen's humanoid.
std::vector<RobotCase> position_robot_cases() { return {robot_cases().front()}; }

walkgen::RobotDescription description(const std::string& robot) {
  if (robot == "walkgen_humanoid") return walkgen::walkgen_humanoid_description();
#ifdef WALKGEN_TEST_ROBOT_FILES
  return walkgen::find_robot_description(robot);
#else
  ADD_FAILURE() << "no robot description files in this build: " << robot;
  return walkgen::walkgen_humanoid_description();
#endif
}

/// `robot` in MuJoCo (`push_on` changes its MuJoCo settings) and its closed loop with
/// `wrap(mujoco)`'s robot (the MujocoRobot itself by default) and IK: calls
/// test(mujoco, loop, settings). The walking settings are the description's in MuJoCo's world
/// (settings_where_standing()), changed by `change`.
template <typename Test>
void with_loop(const std::string& robot, Test&& test,
               const std::function<void(walkgen::WalkingSettings<double>&)>& change = nullptr) {
  const walkgen::RobotDescription d = description(robot);
  walkgen::MujocoRobot mujoco(walkgen::mujoco_robot_settings(d));
  walkgen::WalkingSettings<double> settings = walkgen::settings_where_standing(d.walking, mujoco);
  if (change) change(settings);
  walkgen::with_robot_ik(d, [&](auto& ik) {
    walkgen::WalkingLoop<16, std::decay_t<decltype(ik)>> loop(settings, mujoco, ik,
                                                              walkgen::loop_settings(d));
    test(mujoco, loop, settings);
  });
}

std::string robot_name(const ::testing::TestParamInfo<RobotCase>& info) { return info.param.name; }

/// What FaultyRobot writes into the measurement from its fault time on.
enum class Fault {
  none,
  nan_joint,           ///< a knee angle reads NaN
  joint_out_of_range,  ///< a knee angle reads 10 rad
  nan_joint_velocity,  ///< a hip velocity reads NaN
  nan_force,           ///< the right force sensor's f_z reads NaN
  huge_force,          ///< the right force sensor reads 1 MN
  nan_imu,             ///< the IMU's gyroscope reads NaN about x
  imu_out_of_range,    ///< the IMU's accelerometer reads 100 g
  saturating,          ///< 7 more clamped motor torques every step
};

const char* name(Fault f) {
  switch (f) {
    case Fault::none:
      return "none";
    case Fault::nan_joint:
      return "nan_joint";
    case Fault::joint_out_of_range:
      return "joint_out_of_range";
    case Fault::nan_joint_velocity:
      return "nan_joint_velocity";
    case Fault::nan_force:
      return "nan_force";
    case Fault::huge_force:
      return "huge_force";
    case Fault::nan_imu:
      return "nan_imu";
    case Fault::imu_out_of_range:
      return "imu_out_of_range";
    case Fault::saturating:
      return "saturating";
  }
  return "unknown";
}

/// A MujocoRobot whose reported measurement carries a fault from `at` seconds on; commands,
/// physics and images are the MujocoRobot's.
class FaultyRobot final : public walkgen_test::EditedRobot {
 public:
  explicit FaultyRobot(walkgen::MujocoRobot& inner) : EditedRobot(inner) { refresh(); }

  void inject(Fault fault, double at) {
    fault_ = fault;
    at_ = at;
  }
  /// The joints the joint faults write into (by name).
  void set_joints(const std::string& knee, const std::string& hip) {
    knee_ = knee;
    hip_ = hip;
  }

  int joint(const std::string& joint_name) const {
    const auto& names = info().joint_names;
    for (std::size_t j = 0; j < names.size(); ++j) {
      if (names[j] == joint_name) return int(j);
    }
    ADD_FAILURE() << "no joint " << joint_name;
    return 0;
  }

 private:
  void on_reset() override { extra_saturations_ = 0; }
  void edit(walkgen::RobotOutput& out) override {
    if (fault_ == Fault::none || out.time < at_) return;
    switch (fault_) {
      case Fault::none:
        break;
      case Fault::nan_joint:
        out.q[joint(knee_)] = kNan;
        break;
      case Fault::joint_out_of_range:
        out.q[joint(knee_)] = 10.0;
        break;
      case Fault::nan_joint_velocity:
        out.dq[joint(hip_)] = kNan;
        break;
      case Fault::nan_force:
        out.ft[1].force_S.z() = kNan;
        break;
      case Fault::huge_force:
        out.ft[1].force_S.z() = 1e6;
        break;
      case Fault::nan_imu:
        out.imu.angular_velocity_I.x() = kNan;
        break;
      case Fault::imu_out_of_range:
        out.imu.acceleration_I.z() = 981.0;
        break;
      case Fault::saturating:
        extra_saturations_ += 7;
        break;
    }
    out.saturations += extra_saturations_;
  }

  Fault fault_ = Fault::none;
  double at_ = 0.0;
  std::string knee_ = "l_knee", hip_ = "r_hip_pitch";
  long extra_saturations_ = 0;
};

/// A robot's Ceres IK that stops converging while `failing` (nothing solved, the previous
/// solution kept: what CeresInverseKinematics does when it does not converge).
template <typename Ik>
struct FailingIk {
  explicit FailingIk(Ik& inner) : ik(inner) {}
  const walkgen::KinematicTree<double>& tree() const { return ik.tree(); }
  void set_initial_guess(const Eigen::Vector3d& p, const Eigen::Matrix3d& R,
                         const Eigen::VectorXd& q) {
    ik.set_initial_guess(p, R, q);
  }
  walkgen::IkResult solve(const walkgen::IkTarget& target) {
    if (!failing) return ik.solve(target);
    walkgen::IkResult r;
    r.status = walkgen::IkStatus::not_converged;
    r.message = "injected";
    return r;
  }
  const Eigen::VectorXd& q() const { return ik.q(); }

  Ik& ik;
  bool failing = false;
};

/// Every number a sample reports is finite.
bool finite(const walkgen::LoopSample& s) {
  const auto& p = s.plan;
  bool ok = p.com_x.allFinite() && p.com_y.allFinite() && p.com_q.allFinite() &&
            std::isfinite(p.com_z) && std::isfinite(p.zmp_x) && std::isfinite(p.zmp_y) &&
            s.zmp.zmp_W.allFinite() && std::isfinite(s.zmp.normal_force) &&
            s.com_measured_W.allFinite() && std::isfinite(s.base_height);
  for (const auto& f : s.ft) {
    ok = ok && f.force_S.allFinite() && f.torque_S.allFinite() && f.pose_W_S.matrix().allFinite();
  }
  return ok;
}

/// The true robot (MuJoCo) stands on both feet with its CoM over the middle of its soles.
void expect_standing_on_both_feet(walkgen::MujocoRobot& robot) {
  const walkgen::RobotOutput& m = robot.output();
  EXPECT_EQ(m.status, walkgen::RobotStatus::ok) << m.message;
  EXPECT_GT(m.base_height, 0.9 * robot.info().nominal_base_height);
  const walkgen::MeasuredZmp zmp = walkgen::measured_zmp(m.ft, robot.info().ft_sensor_height);
  EXPECT_TRUE(zmp.in_contact[0] && zmp.in_contact[1]) << "not on both feet";
  const Eigen::Vector2d middle =
      (m.ft[0].pose_W_S.translation() + m.ft[1].pose_W_S.translation()).head<2>() / 2.0;
  EXPECT_LT((walkgen::true_com(robot) - middle).norm(), 0.02)
      << "CoM " << walkgen::true_com(robot).transpose() << ", middle " << middle.transpose();
}

/// Ticks of `loop` in `seconds` of walking.
template <typename Loop>
int ticks_in(const Loop& loop, double seconds) {
  return int(std::lround(seconds / loop.mpc().settings().t));
}

/// The loop's samples per tick (t / command_period).
template <typename Loop>
std::size_t samples_per_tick(const Loop& loop) {
  const auto& s = loop.mpc().settings();
  return std::size_t(std::lround(s.t / s.command_period));
}

/// Walks `seconds` forward at 0.03 m/s; every tick must be ok.
template <typename Loop>
void walk(Loop& loop, double seconds) {
  ASSERT_EQ(loop.set_command({0.03, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  const int ticks = ticks_in(loop, seconds);
  for (int k = 0; k < ticks; ++k) {
    const walkgen::LoopTick& t = loop.tick();
    ASSERT_EQ(t.status, LoopStatus::ok) << "tick " << k << ": " << t.message;
    ASSERT_EQ(t.mode, LoopMode::walking);
  }
}

// walking → stopping → stopped: the step ends along the plan, the CoM moves between the feet in
// transfer_time, then the joints are held; start() walks on.
class Safety : public ::testing::TestWithParam<RobotCase> {};
/// Tests the G1 does not pass yet (position_robot_cases()).
class SafetyPositionDriven : public ::testing::TestWithParam<RobotCase> {};

TEST_P(SafetyPositionDriven, ARequestedStopFinishesTheStepAndStandsTheRobotOnBothFeet) {
  const RobotCase rc = GetParam();
  const std::array<Eigen::Vector2d, 4> sole = walkgen::sole_corners(description(rc.name));
  with_loop(rc.name, [&](walkgen::MujocoRobot& robot, auto& loop,
                         const walkgen::WalkingSettings<double>& settings) {
    ASSERT_EQ(loop.start().status, LoopStatus::ok);
    // Into the second step's single support.
    walk(loop, settings.t_step + 0.75 * (settings.t_step - settings.t_ds));
    EXPECT_EQ(loop.request_stop(), LoopMode::stopping);
    // At most the rest of a step, then transfer_time (2 s).
    const int bound = int(std::ceil((settings.t_step + 2.0) / settings.t)) + 1;
    int ticks = 0;
    double worst_margin = 1.0;
    while (loop.mode() != LoopMode::stopped && ticks < bound) {
      const walkgen::LoopTick& t = loop.tick();
      ++ticks;
      ASSERT_EQ(t.status, LoopStatus::ok) << t.message;
      EXPECT_EQ(t.reason, StopReason::requested);
      EXPECT_EQ(t.ik_failures, 0);
      for (const auto& s : loop.samples()) {
        const walkgen::MeasuredZmp truth =
            walkgen::measured_zmp(s.ft, robot.info().ft_sensor_height);
        if (!truth.valid) continue;
        worst_margin = std::min(
            worst_margin,
            walkgen::support_polygon_margin(truth, s.ft, robot.info().ft_sensor_height, sole));
      }
    }
    ASSERT_EQ(loop.mode(), LoopMode::stopped) << "not stopped after " << ticks << " ticks";
    std::printf("stopped after %d ticks; worst ZMP margin in the support polygon %.1f mm\n", ticks,
                1e3 * worst_margin);
    EXPECT_GE(worst_margin, 0.0) << "the measured ZMP left the support polygon while stopping";
    // Held: 4 s more on both feet, still.
    const Eigen::Vector2d com = walkgen::true_com(robot);
    for (int k = 0; k < ticks_in(loop, 4.0); ++k) {
      const walkgen::LoopTick& t = loop.tick();
      ASSERT_EQ(t.status, LoopStatus::ok) << t.message;
      EXPECT_EQ(t.mode, LoopMode::stopped);
      EXPECT_EQ(t.reason, StopReason::requested);
      EXPECT_EQ(loop.samples().size(), samples_per_tick(loop));
    }
    EXPECT_LT((walkgen::true_com(robot) - com).norm(), 0.002);
    expect_standing_on_both_feet(robot);
    // Walks on in the generator's frame: the support sole where the plan put it (not back at
    // the settings' start), the generator's CoM where MuJoCo's is.
    const walkgen::FootPose<double> support = loop.mpc().state().support;
    const walkgen::Foot support_foot = loop.mpc().state().support_foot;
    EXPECT_GT(support.x, settings.foot_x + 0.05);  // it had walked
    const walkgen::LoopTick& started = loop.start();
    ASSERT_EQ(started.status, LoopStatus::ok) << started.message;
    EXPECT_EQ(started.reason, StopReason::none);
    EXPECT_EQ(loop.mpc().state().support_foot, support_foot);
    EXPECT_EQ(loop.mpc().state().support.x, support.x);
    EXPECT_EQ(loop.mpc().state().support.y, support.y);
    EXPECT_EQ(loop.mpc().state().support.q, support.q);
    const Eigen::Vector2d planned_com(loop.mpc().state().com_x[0], loop.mpc().state().com_y[0]);
    EXPECT_LT((planned_com - walkgen::true_com(robot)).norm(), 0.03)
        << "generator CoM " << planned_com.transpose() << ", true "
        << walkgen::true_com(robot).transpose();
    walk(loop, 2.0);
  });
}

// Issue 24: "after a kick every later QP is infeasible; the loop keeps walking the last shifted
// plan". An obstacle dropped around the robot makes every QP infeasible: the loop walks the
// shifted plan for at most max_qp_failures - 1 ticks, then only to finish the step, and stands.
TEST_P(Safety, AQpFailureStreakStopsTheWalkWithoutWalkingOnAStalePlan) {
  with_loop(
      GetParam().name,
      [](walkgen::MujocoRobot& robot, auto& loop, const walkgen::WalkingSettings<double>&) {
        ASSERT_EQ(loop.start().status, LoopStatus::ok);
        walk(loop, 2.4);
        const Eigen::Vector2d at = walkgen::true_com(robot);
        const std::vector<walkgen::CircleObstacle<double>> trap = {{at.x(), at.y(), 0.6, 0.1}};
        loop.mpc().set_obstacles(trap);
        const int max_failures = loop.settings().max_qp_failures;
        const int limit = ticks_in(loop, 12.0);
        int stale_walking = 0, ticks = 0;
        while (loop.mode() != LoopMode::stopped && loop.mode() != LoopMode::fault &&
               ticks < limit) {
          const walkgen::LoopTick& t = loop.tick();
          ++ticks;
          if (t.mode == LoopMode::walking) {
            EXPECT_EQ(t.status, LoopStatus::qp_failed) << t.message;
            EXPECT_EQ(t.mpc, walkgen::MpcStatus::qp_failed);
            ++stale_walking;
          } else {
            EXPECT_EQ(t.status, LoopStatus::fault) << t.message;
            EXPECT_EQ(t.reason, StopReason::qp_failures);
            EXPECT_NE(t.message.find("QP failed"), std::string::npos) << t.message;
          }
          for (const auto& s : loop.samples()) EXPECT_TRUE(finite(s));
        }
        std::printf("QP failures: %d stale ticks walking, stopped after %d ticks\n", stale_walking,
                    ticks);
        EXPECT_EQ(stale_walking, max_failures - 1);
        ASSERT_EQ(loop.mode(), LoopMode::stopped) << loop.last_tick().message;
        EXPECT_EQ(loop.reason(), StopReason::qp_failures);
        for (int k = 0; k < ticks_in(loop, 2.0); ++k) {  // held: no NMPC runs
          const walkgen::LoopTick& t = loop.tick();
          EXPECT_EQ(t.status, LoopStatus::fault);
          EXPECT_EQ(t.mode, LoopMode::stopped);
          EXPECT_EQ(t.qp_failure_streak, 0);
        }
        expect_standing_on_both_feet(robot);
      },
      [](walkgen::WalkingSettings<double>& s) {
        s.obstacles.push_back({50.0, 50.0, 0.1, 0.1});  // far away: reserves a row
      });
}

// Issue 24: "160 IK failures → falls while reporting ok". A streak of max_ik_failures command
// periods without an IK solution holds the last solution (LoopMode::fault) and says so.
TEST_P(SafetyPositionDriven, AnIkFailureStreakHoldsTheLastSolution) {
  const walkgen::RobotDescription d = description(GetParam().name);
  walkgen::MujocoRobot robot(walkgen::mujoco_robot_settings(d));
  const walkgen::WalkingSettings<double> settings =
      walkgen::settings_where_standing(d.walking, robot);
  walkgen::with_robot_ik(d, [&](auto& inner) {
    FailingIk<std::decay_t<decltype(inner)>> ik(inner);
    walkgen::WalkingLoop<16, decltype(ik)> loop(settings, robot, ik, walkgen::loop_settings(d));
    ASSERT_EQ(loop.start().status, LoopStatus::ok);
    walk(loop, 2.0);
    ik.failing = true;
    // Exactly max_ik_failures samples try the IK (over one tick or more: the G1's tick has 10
    // samples), the rest of that tick holds.
    int tried = 0, ticks = 0;
    const walkgen::LoopTick* t = nullptr;
    do {
      t = &loop.tick();
      tried += t->ik_failures;
      ++ticks;
      if (t->mode == LoopMode::walking) EXPECT_EQ(t->ik_failures, int(samples_per_tick(loop)));
    } while (t->mode == LoopMode::walking && ticks < 10);
    EXPECT_EQ(t->status, LoopStatus::fault);
    EXPECT_EQ(t->mode, LoopMode::fault);
    EXPECT_EQ(t->reason, StopReason::ik_failures);
    EXPECT_NE(t->message.find("IK"), std::string::npos) << t->message;
    EXPECT_EQ(tried, loop.settings().max_ik_failures);
    const Eigen::VectorXd held = robot.output().q;
    for (int k = 0; k < ticks_in(loop, 4.0); ++k) {  // 4 s held
      const walkgen::LoopTick& h = loop.tick();
      EXPECT_EQ(h.status, LoopStatus::fault);
      EXPECT_EQ(h.mode, LoopMode::fault);
      EXPECT_EQ(h.ik_failures, 0);  // no IK is asked while holding
      for (const auto& s : loop.samples()) EXPECT_TRUE(finite(s));
    }
    EXPECT_EQ(robot.output().status, walkgen::RobotStatus::ok) << robot.output().message;
    EXPECT_GT(robot.output().base_height, 0.9 * robot.info().nominal_base_height);
    EXPECT_LT((robot.output().q - held).cwiseAbs().maxCoeff(), 0.02);  // the joints held
  });
}

// Issue 24: "an unreachable CoM height → stands still reporting ok". The CoM at 0.8 m (the
// standing CoM is at about 0.47 m; the legs are 0.46 m long): start() ends in a fault.
TEST_P(Safety, AnUnreachableComHeightIsAFaultNotAStandstillReportedOk) {
  with_loop(
      GetParam().name,
      [](walkgen::MujocoRobot& robot, auto& loop, const walkgen::WalkingSettings<double>&) {
        const walkgen::LoopTick& started = loop.start();
        EXPECT_EQ(started.status, LoopStatus::fault);
        EXPECT_EQ(started.mode, LoopMode::fault);
        EXPECT_EQ(started.reason, StopReason::ik_failures);
        EXPECT_NE(started.message.find("com_z"), std::string::npos) << started.message;
        EXPECT_LT(robot.output().time, 2.0);  // gave up before the end of the transfer
        for (int k = 0; k < 5; ++k) {
          const walkgen::LoopTick& t = loop.tick();
          EXPECT_EQ(t.status, LoopStatus::fault);
          EXPECT_EQ(t.mode, LoopMode::fault);
          EXPECT_EQ(t.mpc, walkgen::MpcStatus::solved);  // not run
          for (const auto& s : loop.samples()) EXPECT_TRUE(finite(s));
        }
        EXPECT_GT(robot.output().base_height, 0.95 * robot.info().nominal_base_height);
        EXPECT_EQ(loop.ticks(), 0);
      },
      // Far above what the legs reach: the humanoid stands its CoM at 0.47 m (legs 0.46 m
      // long), the G1 at 0.69 m (legs about 0.7 m).
      [](walkgen::WalkingSettings<double>& s) { s.com_z *= 1.8; });
}

/// `robot` in MuJoCo behind a FaultyRobot (no fault yet), walking forward for 1.6 s: calls
/// test(mujoco, faulty, loop).
template <typename Test>
void with_faulty_walk(const std::string& robot, Test&& test) {
  const walkgen::RobotDescription d = description(robot);
  walkgen::MujocoRobot mujoco(walkgen::mujoco_robot_settings(d));
  FaultyRobot faulty(mujoco);
  const walkgen::WalkingSettings<double> settings =
      walkgen::settings_where_standing(d.walking, mujoco);
  walkgen::with_robot_ik(d, [&](auto& ik) {
    walkgen::WalkingLoop<16, std::decay_t<decltype(ik)>> loop(settings, faulty, ik,
                                                              walkgen::loop_settings(d));
    ASSERT_EQ(loop.start().status, LoopStatus::ok);
    walk(loop, 1.6);
    test(mujoco, faulty, loop);
  });
}

class SensorFault : public ::testing::TestWithParam<std::tuple<RobotCase, Fault>> {};

// Issue 24: "NaN feedback → the tick throws on every retry". A non-finite or out-of-range
// measurement is a sensor fault: the joint targets are held, the samples report zeros instead of
// the faulty values, nothing throws, and the message names the reading.
TEST_P(SensorFault, HoldsTheJointTargetsAndNamesTheReading) {
  const RobotCase& rc = std::get<0>(GetParam());
  const Fault fault = std::get<1>(GetParam());
  with_faulty_walk(rc.name, [&](walkgen::MujocoRobot& mujoco, FaultyRobot& robot, auto& loop) {
    robot.set_joints(rc.left_knee, rc.right_hip_pitch);
    robot.inject(fault, robot.output().time + 0.5 * loop.mpc().settings().t);  // mid-tick
    const walkgen::LoopTick& t = loop.tick();
    EXPECT_EQ(t.status, LoopStatus::fault);
    EXPECT_EQ(t.mode, LoopMode::fault);
    EXPECT_EQ(t.reason, StopReason::sensor_fault);
    const std::string expected =
        fault == Fault::nan_joint || fault == Fault::joint_out_of_range ? rc.left_knee
        : fault == Fault::nan_joint_velocity                            ? rc.right_hip_pitch
        : fault == Fault::nan_imu || fault == Fault::imu_out_of_range   ? "IMU"
                                                                        : "right force sensor";
    EXPECT_NE(t.message.find(expected), std::string::npos) << t.message;
    const std::size_t n = samples_per_tick(loop);
    ASSERT_EQ(loop.samples().size(), n);
    std::size_t faulty = 0;
    for (const auto& s : loop.samples()) {
      EXPECT_TRUE(finite(s));
      faulty += !s.sensors_ok;
    }
    EXPECT_GE(faulty, n * 3 / 8);  // from the middle of the tick on
    EXPECT_LE(faulty, n * 5 / 8);
    for (int k = 0; k < ticks_in(loop, 2.0); ++k) {
      const walkgen::LoopTick& h = loop.tick();
      EXPECT_EQ(h.status, LoopStatus::fault);
      EXPECT_EQ(h.mode, LoopMode::fault);
      EXPECT_EQ(h.reason, StopReason::sensor_fault);
      for (const auto& s : loop.samples()) {
        EXPECT_TRUE(finite(s));
        EXPECT_FALSE(s.sensors_ok);
      }
    }
    EXPECT_EQ(mujoco.output().status, walkgen::RobotStatus::ok) << mujoco.output().message;
    EXPECT_GT(mujoco.output().base_height, 0.9 * mujoco.info().nominal_base_height);
    // start() refuses a faulty measurement before it moves anything.
    const double time = mujoco.output().time;
    const walkgen::LoopTick& restart = loop.start();
    EXPECT_EQ(restart.status, LoopStatus::fault);
    EXPECT_EQ(restart.reason, StopReason::sensor_fault);
    EXPECT_EQ(mujoco.output().time, time);
  });
}

INSTANTIATE_TEST_SUITE_P(
    Readings, SensorFault,
    ::testing::Combine(::testing::ValuesIn(robot_cases()),
                       ::testing::Values(Fault::nan_joint, Fault::joint_out_of_range,
                                         Fault::nan_joint_velocity, Fault::nan_force,
                                         Fault::huge_force, Fault::nan_imu,
                                         Fault::imu_out_of_range)),
    [](const ::testing::TestParamInfo<std::tuple<RobotCase, Fault>>& info) {
      return std::string(std::get<0>(info.param).name) + "_" + name(std::get<1>(info.param));
    });

// Torque saturation: max_saturated_periods command periods in a row in which the robot reports
// clamped motor torques stop the walk like a requested stop.
TEST_P(Safety, TorqueSaturationStreakStopsTheWalk) {
  with_faulty_walk(GetParam().name,
                   [](walkgen::MujocoRobot& mujoco, FaultyRobot& robot, auto& loop) {
                     robot.inject(Fault::saturating, robot.output().time);
                     const walkgen::LoopTick& t = loop.tick();
                     EXPECT_EQ(t.status, LoopStatus::fault);
                     EXPECT_EQ(t.reason, StopReason::torque_saturation);
                     EXPECT_NE(t.message.find("clamped"), std::string::npos) << t.message;
                     int ticks = 1;
                     const int limit = ticks_in(loop, 8.0);
                     while (loop.mode() == LoopMode::stopping && ticks < limit) {
                       EXPECT_EQ(loop.tick().status, LoopStatus::fault);
                       ++ticks;
                     }
                     EXPECT_EQ(loop.mode(), LoopMode::stopped);
                     EXPECT_EQ(loop.reason(), StopReason::torque_saturation);
                     expect_standing_on_both_feet(mujoco);
                   });
}

// A fall is a fault: the IMU's tilt tells it (max_tilt) before the base has sunk to the robot's
// own fall height; the loop stops at once, later ticks report the fall and run nothing, nothing
// throws.
TEST_P(SafetyPositionDriven, AFallIsDetectedByTheImuAndNothingRunsAfterIt) {
  with_loop(GetParam().name, [](walkgen::MujocoRobot& robot, auto& loop,
                                const walkgen::WalkingSettings<double>&) {
    ASSERT_EQ(loop.start().status, LoopStatus::ok);
    walk(loop, 2.0);
    // Kicked sideways: 2 m/s in 0.1 s.
    const double mass = mj_getTotalmass(robot.model());
    robot.push(Eigen::Vector3d(0.0, mass * 2.0 / 0.1, 0.0), robot.output().time, 0.1);
    LoopStatus status = LoopStatus::ok;
    for (int k = 0; k < ticks_in(loop, 8.0) && status == LoopStatus::ok; ++k) {
      status = loop.tick().status;
    }
    EXPECT_EQ(status, LoopStatus::fallen);
    EXPECT_EQ(loop.mode(), LoopMode::fault);
    EXPECT_EQ(loop.reason(), StopReason::fallen);
    const double time = robot.output().time;
    const double tilt = robot.output().imu.tilt();
    std::printf(
        "fall detected at t = %.3f s: tilt %.3f rad, base height %.3f m (fall height "
        "%.3f m)\n",
        time, tilt, robot.output().base_height, robot.info().fall_height);
    EXPECT_GT(tilt, loop.settings().max_tilt);
    EXPECT_LT(tilt, loop.settings().max_tilt + 0.05);  // caught within a command period
    EXPECT_GT(robot.output().base_height, robot.info().fall_height);  // before the robot's check
    EXPECT_EQ(robot.output().status, walkgen::RobotStatus::ok);
    for (int k = 0; k < 3; ++k) {
      const walkgen::LoopTick& t = loop.tick();
      EXPECT_EQ(t.status, LoopStatus::fallen);
      EXPECT_EQ(t.reason, StopReason::fallen);
      EXPECT_NE(t.message.find("IMU tilts"), std::string::npos) << t.message;
      EXPECT_TRUE(loop.samples().empty());
    }
    EXPECT_EQ(robot.output().time, time);  // nothing stepped
    EXPECT_EQ(loop.request_stop(), LoopMode::fault);
  });
}

#ifdef WALKGEN_TEST_ROBOT_FILES
// The G1's requested stop, as far as it gets (docs/safety.md): the step ends, the planned CoM
// moves between the soles' centres without overshooting one (its CoM swings fast toward a sole
// when the step ends: over the whole transfer_time it overshot that sole by 2.3 cm and the IK
// found no joints), no IK failure, stopped. Holding that posture it tips over a second later
// (its true CoM is ahead of the planned one: no NMPC feedback), which this test does not cover.
TEST(SafetyG1, ARequestedStopMovesThePlannedComBetweenTheSoles) {
  with_loop("unitree_g1", [](walkgen::MujocoRobot&, auto& loop,
                             const walkgen::WalkingSettings<double>& settings) {
    ASSERT_EQ(loop.start().status, LoopStatus::ok);
    walk(loop, settings.t_step + 0.75 * (settings.t_step - settings.t_ds));
    EXPECT_EQ(loop.request_stop(), LoopMode::stopping);
    const int bound = int(std::ceil((settings.t_step + 2.0) / settings.t)) + 1;
    double worst = 0.0;  // [m] how far the planned CoM went beyond the soles' centres
    int ticks = 0;
    while (loop.mode() == LoopMode::stopping && ticks < bound) {
      const walkgen::LoopTick& t = loop.tick();
      ++ticks;
      ASSERT_EQ(t.status, LoopStatus::ok) << t.message;
      EXPECT_EQ(t.ik_failures, 0);
      for (const auto& s : loop.samples()) {
        if (!s.plan.double_support) continue;
        const Eigen::Vector2d left(s.plan.left.motion.x.position, s.plan.left.motion.y.position);
        const Eigen::Vector2d right(s.plan.right.motion.x.position, s.plan.right.motion.y.position);
        const Eigen::Vector2d across = left - right;
        const double along =
            (Eigen::Vector2d(s.plan.com_x[0], s.plan.com_y[0]) - right).dot(across) /
            across.squaredNorm();
        worst = std::max({worst, -along * across.norm(), (along - 1.0) * across.norm()});
      }
    }
    std::printf("G1 stopped after %d ticks; planned CoM at most %.1f mm beyond a sole's centre\n",
                ticks, 1e3 * worst);
    EXPECT_EQ(loop.mode(), LoopMode::stopped) << loop.last_tick().message;
    EXPECT_LE(worst, 0.0);
  });
}
#endif

INSTANTIATE_TEST_SUITE_P(Robots, Safety, ::testing::ValuesIn(robot_cases()), robot_name);
INSTANTIATE_TEST_SUITE_P(Robots, SafetyPositionDriven, ::testing::ValuesIn(position_robot_cases()),
                         robot_name);

}  // namespace
