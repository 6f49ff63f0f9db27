// The closed loop of thesis figure 6.1 with walkgen's humanoid in MuJoCo (walkgen::WalkingLoop):
// the four tasks of §9.2 in full, a ten-minute walk with random commands, CoM feedback, the
// measured ZMP in the support polygon, and bad input. Heicub's settings (Table 6.1) unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "walkgen/simulation/simulated_tasks.hpp"

namespace {

using walkgen::LoopStatus;
using walkgen::SimTask;
using walkgen::TaskResult;

const walkgen::KinematicTree<double>& tree() {
  static const walkgen::KinematicTree<double> t = walkgen::humanoid_tree();
  return t;
}

/// A robot that only has a name list (for the loop's checks of its joints).
struct OtherRobot final : walkgen::Robot {
  explicit OtherRobot(std::vector<std::string> names) { info_.joint_names = std::move(names); }
  const walkgen::RobotInfo& info() const override { return info_; }
  walkgen::JointCommandStatus set_joint_targets(const Eigen::Ref<const Eigen::VectorXd>&) override {
    return walkgen::JointCommandStatus::accepted;
  }
  walkgen::RobotStatus step(double) override { return walkgen::RobotStatus::ok; }
  const walkgen::RobotOutput& output() const override { return output_; }
  const walkgen::StereoImages& render_cameras() override { return images_; }
  void reset() override {}
  walkgen::RobotInfo info_;
  walkgen::RobotOutput output_;
  walkgen::StereoImages images_;
};

// TaskResult::mean_speed(): the net displacement of the true CoM over the time between the
// first and the last row; 0 without two rows or without time between them.
TEST(TaskResult, MeanSpeedIsTheNetDisplacementOverTheTime) {
  TaskResult r;
  EXPECT_EQ(r.mean_speed(), 0.0);
  walkgen::TaskRow row;
  row.time = 1.0;
  r.rows.push_back(row);
  EXPECT_EQ(r.mean_speed(), 0.0);
  r.rows.push_back(row);  // no time between the rows
  EXPECT_EQ(r.mean_speed(), 0.0);
  row.time = 2.0;
  row.com_true = Eigen::Vector2d(0.5, -0.2);  // a sway in between does not count
  r.rows.push_back(row);
  row.time = 3.0;
  row.com_true = Eigen::Vector2d(0.3, 0.4);
  row.com_plan = Eigen::Vector2d(0.6, 0.8);
  r.rows.push_back(row);
  EXPECT_DOUBLE_EQ(r.mean_speed(), 0.25);
  EXPECT_DOUBLE_EQ(r.planned_mean_speed(), 0.5);
  EXPECT_FALSE(r.fallen());
  r.status = LoopStatus::fallen;
  EXPECT_TRUE(r.fallen());
}

class Section92Task : public ::testing::TestWithParam<int> {};

// Acceptance: each task reaches within 0.25 m of its target without a fall (base above 80 % of
// its nominal height: the robot reports anything lower as fallen), no QP or IK failure, and the
// measured ZMP inside the support polygon in at least 99 % of the samples.
TEST_P(Section92Task, ReachesTheTargetWithoutFallingAndKeepsTheZmpInTheSupportPolygon) {
  const SimTask task = walkgen::section_9_2_tasks()[std::size_t(GetParam())];
  const TaskResult r = walkgen::run_task(task);
  double mean = 0.0, sd = 0.0;
  r.zmp_distance(mean, sd);
  RecordProperty("final_distance_m", std::to_string(r.final_distance));
  RecordProperty("time_s", std::to_string(r.time));
  RecordProperty("zmp_distance_mean_cm", std::to_string(100.0 * mean));
  RecordProperty("zmp_distance_std_cm", std::to_string(100.0 * sd));
  RecordProperty("zmp_inside_fraction", std::to_string(r.inside_fraction()));
  RecordProperty("mean_speed_m_s", std::to_string(r.mean_speed()));
  std::printf(
      "%s: %.1f s, %.3f m from the target, ZMP distance %.2f ± %.2f cm, inside %.2f %%, mean speed "
      "%.4f m/s (planned %.4f)\n",
      task.name.c_str(), r.time, r.final_distance, 100.0 * mean, 100.0 * sd,
      100.0 * r.inside_fraction(), r.mean_speed(), r.planned_mean_speed());
  EXPECT_EQ(r.status, LoopStatus::ok) << r.message;
  EXPECT_FALSE(r.fallen());
  // The robot made the plan's progress: the true CoM's net speed is the planned CoM's.
  EXPECT_GT(r.planned_mean_speed(), 0.005);
  EXPECT_NEAR(r.mean_speed(), r.planned_mean_speed(), 0.05 * r.planned_mean_speed());
  EXPECT_TRUE(r.stopped) << "the steering never reported the target reached in " << task.time_limit
                         << " s";
  EXPECT_LE(r.final_distance, walkgen::kTaskReachDistance);
  EXPECT_TRUE(r.reached);
  EXPECT_GT(r.min_base_height, 0.9 * 0.5062);  // never near the fall threshold (80 %)
  EXPECT_EQ(r.rejected_commands, 0);
  EXPECT_EQ(r.qp_failures, 0);
  EXPECT_EQ(r.ik_failures, 0);
  EXPECT_GE(r.inside_fraction(), 0.99);
  // The NMPC's ZMP and the measured one: the thesis measured 3.24 ± 1.99 cm on Heicub.
  EXPECT_LT(mean, 0.05);
  if (!task.obstacles.empty()) {
    const auto& o = task.obstacles.front();
    // Every sole on the ground kept the footstep clearance (radius + margin) from the chair's
    // centre, up to the landing error of the soles (a centimetre).
    EXPECT_GE(r.min_obstacle_distance, o.radius + o.margin - 0.01);
  }
  // The true CoM stays with the plan's: the walk went where the generator planned it.
  double worst = 0.0;
  for (std::size_t k = 39; k < r.rows.size(); k += 40) {  // the last sample of each tick
    worst = std::max(worst, (r.rows[k].com_true - r.rows[k].com_plan).norm());
  }
  EXPECT_LT(worst, 0.03);
}

INSTANTIATE_TEST_SUITE_P(Tasks, Section92Task, ::testing::Range(0, 4),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return walkgen::section_9_2_tasks()[std::size_t(info.param)].name;
                         });

// Acceptance: ten minutes with a random command every 5 s: no fall, no QP failure, no IK drift
// (torso and hip angles stay bounded), and the measured ZMP in the support polygon.
TEST(WalkingLoop, TenMinutesOfRandomCommandsWithoutFallOrDrift) {
  walkgen::MujocoRobot robot;
  walkgen::HumanoidIk ik(tree());
  const walkgen::WalkingSettings<double> settings = walkgen::heicub_settings();
  walkgen::SimLoop loop(settings, robot, ik);
  ASSERT_EQ(loop.start().status, LoopStatus::ok);
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Vector3d limit = 0.95 * settings.max_command;
  const int ticks_per_command = int(std::lround(5.0 / settings.t));
  const int ticks = int(std::lround(600.0 / settings.t));
  const auto& names = robot.info().joint_names;
  std::vector<int> watched;  // torso and hip joints
  for (std::size_t j = 0; j < names.size(); ++j) {
    if (names[j].find("torso") == 0 || names[j].find("hip") != std::string::npos) {
      watched.push_back(int(j));
    }
  }
  // Deviation of each watched joint from the standing posture, over the first and the last
  // two minutes: drift would grow it.
  const Eigen::VectorXd stand = robot.output().q;
  Eigen::VectorXd early = Eigen::VectorXd::Zero(Eigen::Index(names.size())), late = early;
  long samples = 0, inside = 0, qp_failures = 0, ik_failures = 0;
  double max_torso = 0.0;
  for (int k = 0; k < ticks; ++k) {
    if (k % ticks_per_command == 0) {
      const Eigen::Vector3d command(limit.x() * unit(rng), limit.y() * unit(rng),
                                    limit.z() * unit(rng));
      ASSERT_EQ(loop.set_command(command), walkgen::CommandStatus::accepted);
    }
    const walkgen::LoopTick& tick = loop.tick();
    ASSERT_TRUE(tick.status == LoopStatus::ok || tick.status == LoopStatus::qp_failed)
        << "tick " << k << ": " << walkgen::to_string(tick.status) << " " << tick.message;
    qp_failures += tick.mpc != walkgen::MpcStatus::solved;
    ik_failures += tick.ik_failures;
    for (const auto& s : loop.samples()) {
      const walkgen::MeasuredZmp truth = walkgen::measured_zmp(s.ft, robot.info().ft_sensor_height);
      if (!truth.valid) continue;
      ++samples;
      inside += walkgen::support_polygon_margin(truth, s.ft, robot.info().ft_sensor_height,
                                                settings.foot_length, settings.foot_width) >= 0.0;
    }
    const Eigen::VectorXd& q = robot.output().q;
    Eigen::VectorXd& worst = k < ticks / 5 ? early : late;
    if (k < ticks / 5 || k >= ticks - ticks / 5) {
      for (int j : watched) worst[j] = std::max(worst[j], std::abs(q[j] - stand[j]));
    }
    for (const char* torso : {"torso_pitch", "torso_roll", "torso_yaw"}) {
      max_torso = std::max(max_torso, std::abs(q[tree().joint_index(torso)]));
    }
  }
  const double fraction = double(inside) / double(samples);
  RecordProperty("zmp_inside_fraction", std::to_string(fraction));
  RecordProperty("max_torso_angle_rad", std::to_string(max_torso));
  std::printf("10 min: %ld samples, ZMP inside %.3f %%, max |torso joint| %.4f rad\n", samples,
              100.0 * fraction, max_torso);
  EXPECT_EQ(qp_failures, 0);
  EXPECT_EQ(ik_failures, 0);
  EXPECT_GE(fraction, 0.99);
  // The IK holds pelvis and torso upright: the torso joints stay near zero, the hips within
  // what stepping needs (yaw for turning, roll for sideways steps) of the standing posture, and
  // no worse in the last two minutes than in the first two.
  EXPECT_LT(max_torso, 0.02);
  for (int j : watched) {
    EXPECT_LT(late[j], 0.6) << names[std::size_t(j)];
    EXPECT_LT(late[j], early[j] + 0.1) << names[std::size_t(j)] << " drifts";
  }
  EXPECT_GT(robot.output().base_height, 0.95 * 0.5062 - 0.02);
}

// §6.3: the measured CoM (forward kinematics of the measured joints from the planned support
// sole) is fed back every t_feedback; the plan follows the robot, which stays within millimetres.
TEST(WalkingLoop, FeedsTheMeasuredComBackEveryFeedbackPeriod) {
  walkgen::MujocoRobot robot;
  walkgen::HumanoidIk ik(tree());
  walkgen::WalkingSettings<double> settings = walkgen::heicub_settings();
  settings.t_feedback = 2.0 * settings.t;  // every second tick
  walkgen::SimLoop loop(settings, robot, ik);
  ASSERT_EQ(loop.start().status, LoopStatus::ok);
  ASSERT_EQ(loop.set_command({0.03, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  int fed = 0;
  double worst = 0.0;
  for (int k = 0; k < 100; ++k) {
    const walkgen::LoopTick& tick = loop.tick();
    ASSERT_EQ(tick.status, LoopStatus::ok);
    EXPECT_EQ(tick.fed_back, k > 0 && k % 2 == 0) << "tick " << k;
    // the NMPC ran and was timed (monitoring, e.g. the dashboard's plot): a real duration
    EXPECT_GT(tick.mpc_seconds, 0.0) << "tick " << k;
    EXPECT_LT(tick.mpc_seconds, 1.0) << "tick " << k;
    fed += tick.fed_back;
    if (tick.fed_back) worst = std::max(worst, tick.com_error.norm());
    // The measured CoM of every sample next to the planned one.
    for (const auto& s : loop.samples()) {
      EXPECT_LT(
          (s.com_measured_W.head<2>() - Eigen::Vector2d(s.plan.com_x[0], s.plan.com_y[0])).norm(),
          0.015);
    }
  }
  EXPECT_EQ(fed, 49);
  EXPECT_GT(worst, 0.0);   // a real measurement, not the plan itself
  EXPECT_LT(worst, 0.01);  // [m]: the servos track the IK to millimetres
  // The fed-back state moved the plan: the generator's CoM is the measured one after feedback.
  EXPECT_NEAR(loop.mpc().state().com_x[0], loop.samples().back().plan.com_x[0], 0.05);
}

// Issue 23 item 4: the ZMP from the contact forces (what a robot without ankle sensors reports)
// against the ankle sensors' ZMP while walking. The sensors also feel the foot's own weight and
// inertia (largest as a foot lands): measured mean 4.4 mm, worst 11 mm over 100 tick ends.
TEST(WalkingLoop, TheContactForcesGiveTheAnkleSensorsZmpWhileWalking) {
  walkgen::MujocoRobot robot;
  walkgen::HumanoidIk ik(tree());
  walkgen::SimLoop loop(walkgen::heicub_settings(), robot, ik);
  ASSERT_EQ(loop.start().status, LoopStatus::ok);
  ASSERT_EQ(loop.set_command({0.03, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  const double d = robot.info().ft_sensor_height;
  double worst = 0.0, sum = 0.0;
  int n = 0;
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(loop.tick().status, LoopStatus::ok);
    // A swinging foot's ankle sensor reads the foot's weight and inertia (up to 5.2 N at
    // mid-swing): contacts count from 10 N, 4 % of the robot's weight.
    const walkgen::MeasuredZmp sensors = walkgen::measured_zmp(robot.output().ft, d, 10.0);
    const walkgen::MeasuredZmp contacts = walkgen::measured_zmp(robot.contact_ft(), d, 10.0);
    ASSERT_TRUE(sensors.valid && contacts.valid) << "tick " << k;
    EXPECT_EQ(sensors.in_contact, contacts.in_contact) << "tick " << k;
    const double e = (sensors.zmp_W - contacts.zmp_W).head<2>().norm();
    worst = std::max(worst, e);
    sum += e;
    ++n;
  }
  std::printf("walking 100 ticks: contact ZMP to sensor ZMP mean %.2f mm, worst %.2f mm\n",
              1e3 * sum / n, 1e3 * worst);
  EXPECT_LT(sum / n, 0.006);
  EXPECT_LT(worst, 0.015);
}

// Without the transfer to one foot the generator, whose ZMP must be in the support sole from the
// first sample, cannot start from standing on both feet: start() moves the CoM over it first.
TEST(WalkingLoop, StartMovesTheComOverTheSupportFootAndTheStateFollowsTheRobot) {
  walkgen::MujocoRobot robot;
  walkgen::HumanoidIk ik(tree());
  const walkgen::WalkingSettings<double> settings = walkgen::heicub_settings();
  walkgen::SimLoop loop(settings, robot, ik);
  EXPECT_EQ(loop.tick().status, LoopStatus::not_started);
  EXPECT_EQ(loop.last_tick().mode, walkgen::LoopMode::idle);
  ASSERT_EQ(loop.start().status, LoopStatus::ok);
  const auto& st = loop.mpc().state();
  EXPECT_NEAR(st.com_x[0], settings.com_x[0], 0.005);
  EXPECT_NEAR(st.com_y[0], settings.com_y[0], 0.005);
  EXPECT_NEAR(st.swing_origin.y, settings.foot_y - settings.foot_distance, 0.005);
  EXPECT_NEAR(robot.output().time, 2.0, 0.02);  // the transfer time
  ASSERT_EQ(loop.set_command({0.0, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  EXPECT_EQ(loop.tick().status, LoopStatus::ok);
}

TEST(WalkingLoop, BadInputGetsClearErrorsAndNonFiniteCommandsAreRejected) {
  walkgen::MujocoRobot robot;
  walkgen::HumanoidIk ik(tree());
  walkgen::WalkingSettings<double> settings = walkgen::heicub_settings();
  {
    walkgen::WalkingLoopSettings bad;
    bad.feedback_gain = 1.5;
    EXPECT_THROW(walkgen::SimLoop(settings, robot, ik, bad), walkgen::invalid_argument);
    bad = walkgen::WalkingLoopSettings();
    bad.left_sole_link = "no_such_link";
    EXPECT_THROW(walkgen::SimLoop(settings, robot, ik, bad), walkgen::invalid_argument);
  }
  settings.t_feedback = 0.5;  // not a multiple of t = 0.4
  try {
    walkgen::SimLoop loop(settings, robot, ik);
    ADD_FAILURE() << "nothing thrown";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t_feedback"), std::string::npos) << e.what();
  }
  // Robots whose joints are not the tree's: one unknown name, one joint too few.
  OtherRobot unknown(robot.info().joint_names);
  unknown.info_.joint_names[3] = "bogus_knee";
  try {
    walkgen::SimLoop loop(walkgen::heicub_settings(), unknown, ik);
    ADD_FAILURE() << "nothing thrown";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bogus_knee"), std::string::npos) << e.what();
  }
  OtherRobot fewer(robot.info().joint_names);
  fewer.info_.joint_names.pop_back();
  EXPECT_THROW(walkgen::SimLoop(walkgen::heicub_settings(), fewer, ik), walkgen::invalid_argument);

  walkgen::SimLoop loop(walkgen::heicub_settings(), robot, ik);
  ASSERT_EQ(loop.start().status, LoopStatus::ok);
  ASSERT_EQ(loop.set_command({0.02, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  EXPECT_EQ(loop.set_command({std::nan(""), 0.0, 0.0}), walkgen::CommandStatus::non_finite);
  EXPECT_NEAR(loop.mpc().command().x(), 0.02, 1e-12);  // the last accepted one
  EXPECT_EQ(loop.set_command({1.0, 0.0, 0.0}), walkgen::CommandStatus::clamped);
  EXPECT_EQ(loop.mpc().command().x(), walkgen::heicub_settings().max_command.x());
  for (int k = 0; k < 20; ++k) ASSERT_EQ(loop.tick().status, LoopStatus::ok);
}

// A fall is reported and stops the loop: the robot is pushed hard sideways mid-walk.
TEST(WalkingLoop, AFallIsReportedAndStopsTheLoop) {
  walkgen::MujocoRobot robot;
  walkgen::HumanoidIk ik(tree());
  walkgen::SimLoop loop(walkgen::heicub_settings(), robot, ik);
  ASSERT_EQ(loop.start().status, LoopStatus::ok);
  ASSERT_EQ(loop.set_command({0.03, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  for (int k = 0; k < 5; ++k) ASSERT_EQ(loop.tick().status, LoopStatus::ok);
  robot.data()->qvel[1] = 2.0;  // base velocity y [m/s]
  LoopStatus status = LoopStatus::ok;
  for (int k = 0; k < 20 && status == LoopStatus::ok; ++k) status = loop.tick().status;
  EXPECT_EQ(status, LoopStatus::fallen);
  EXPECT_NE(loop.last_tick().message.find("IMU tilts"), std::string::npos)
      << loop.last_tick().message;
  EXPECT_LT(loop.samples().size(), 40u);  // the samples up to the fall
  EXPECT_EQ(loop.last_tick().mode, walkgen::LoopMode::fault);
  EXPECT_EQ(loop.last_tick().reason, walkgen::StopReason::fallen);
  // Stopped until the robot's reset() and start(): later ticks report the fall, run nothing.
  const walkgen::LoopTick& again = loop.tick();
  EXPECT_EQ(again.status, LoopStatus::fallen);
  EXPECT_EQ(again.mode, walkgen::LoopMode::fault);
  EXPECT_TRUE(loop.samples().empty());
  EXPECT_EQ(loop.start().status, LoopStatus::fallen);  // the robot still tilts
  robot.reset();
  EXPECT_EQ(loop.start().status, LoopStatus::ok);
  EXPECT_EQ(loop.last_tick().mode, walkgen::LoopMode::walking);
}

}  // namespace
