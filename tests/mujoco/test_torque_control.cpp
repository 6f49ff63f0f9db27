// Torque control of the Unitree G1 in MuJoCo (issue 23 item 3): walkgen's joint controller (PD at
// the physics rate, feed-forward, clamp to the motors' limits) drives its 23 motors with the gains
// of models/unitree_g1/robot.yaml; the contact forces at its soles stand in for ankle sensors
// (item 4): their centre of pressure is the CoM's ground projection while it stands still.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "walkgen/mujoco/mujoco_robot.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

using walkgen::MujocoRobot;
using walkgen::MujocoRobotSettings;
using walkgen::RobotStatus;

const walkgen::RobotDescription& g1() {
  static const walkgen::RobotDescription d = walkgen::find_robot_description("unitree_g1");
  return d;
}

Eigen::Vector2d com_xy(MujocoRobot& robot) {
  const int base = mj_name2id(robot.model(), mjOBJ_BODY, g1().base_body.c_str());
  return {robot.data()->subtree_com[3 * base], robot.data()->subtree_com[3 * base + 1]};
}

TEST(TorqueControl, TheG1LoadsTorqueDrivenInItsStancePoseOnTheFloor) {
  MujocoRobot robot(walkgen::mujoco_robot_settings(g1()));
  const walkgen::RobotInfo& info = robot.info();
  EXPECT_EQ(info.drive, walkgen::JointDrive::torque);
  EXPECT_EQ(info.joint_names.size(), 23u);
  EXPECT_EQ(info.ft_sensor_height, 0.0);  // contact forces at the soles
  const walkgen::RobotOutput& out = robot.output();
  for (const auto& a : g1().stand_pose) {
    std::size_t i = 0;
    while (info.joint_names[i] != a.joint) ++i;
    EXPECT_DOUBLE_EQ(out.q[Eigen::Index(i)], a.angle) << a.joint;
  }
  for (int f = 0; f < 2; ++f)
    EXPECT_NEAR(out.ft[std::size_t(f)].pose_W_S.translation().z(), 0.0, 1e-6);
  EXPECT_NEAR(out.base_height, 0.7634, 0.002);  // SOURCE.txt: pelvis z at touch in this stance
  const walkgen::StereoImages& images = robot.render_cameras();
  EXPECT_EQ(images.status, walkgen::RenderStatus::unavailable);
  EXPECT_NE(images.message.find("no cameras"), std::string::npos) << images.message;
}

// Ten seconds standing: the weight feed-forward and the file's gains hold the stance to the
// millimetre, no torque reaches a limit, the feet carry m g and the contact forces' centre of
// pressure is the CoM's ground projection (statics) within 5 mm.
TEST(TorqueControl, TheG1StandsTenSecondsAndItsContactZmpIsTheComProjection) {
  MujocoRobot robot(walkgen::mujoco_robot_settings(g1()));
  const Eigen::VectorXd q0 = robot.output().q;
  ASSERT_EQ(robot.set_joint_targets(q0), walkgen::JointCommandStatus::accepted);
  ASSERT_EQ(robot.step(1.0), RobotStatus::ok) << robot.output().message;
  const double h1 = robot.output().base_height;
  double worst_zmp = 0.0, worst_joint = 0.0;
  for (int k = 0; k < 90; ++k) {
    ASSERT_EQ(robot.step(0.1), RobotStatus::ok) << robot.output().message;
    const walkgen::RobotOutput& out = robot.output();
    worst_joint = std::max(worst_joint, (out.q - q0).head(12).cwiseAbs().maxCoeff());
    const walkgen::MeasuredZmp zmp = walkgen::measured_zmp(out.ft, 0.0);
    ASSERT_TRUE(zmp.valid);
    EXPECT_TRUE(zmp.in_contact[0] && zmp.in_contact[1]);
    const double mg = robot.model()->body_subtreemass[1] * 9.81;
    EXPECT_NEAR(zmp.normal_force, mg, 0.01 * mg);
    worst_zmp = std::max(worst_zmp, (zmp.zmp_W.head<2>() - com_xy(robot)).norm());
  }
  const double drift = std::abs(robot.output().base_height - h1);
  std::printf(
      "G1 standing 10 s: base drift %.3f mm, worst leg joint error %.2f mrad, contact ZMP "
      "to CoM projection %.2f mm, saturations %ld\n",
      1e3 * drift, 1e3 * worst_joint, 1e3 * worst_zmp, robot.output().saturations);
  EXPECT_LT(drift, 0.001);
  EXPECT_LT(worst_joint, 0.005);
  EXPECT_LT(worst_zmp, 0.005);
  EXPECT_EQ(robot.output().saturations, 0);
}

// The feed-forward is what lets moderate gains stand (SOURCE.txt): at kp 100 the robot falls
// backwards with PD alone and stands with the weight feed-forward.
TEST(TorqueControl, TheWeightFeedforwardIsWhatLetsModerateGainsStand) {
  for (const auto ff : {walkgen::JointFeedforward::none, walkgen::JointFeedforward::weight}) {
    MujocoRobotSettings s = walkgen::mujoco_robot_settings(g1());
    s.kp.head(12).setConstant(100.0);
    s.feedforward = ff;
    MujocoRobot robot(s);
    const RobotStatus status = robot.step(5.0);
    std::printf("kp 100, feed-forward %s: %s at %.2f s\n", walkgen::to_string(ff),
                walkgen::to_string(status), robot.output().time);
    EXPECT_EQ(status,
              ff == walkgen::JointFeedforward::none ? RobotStatus::fallen : RobotStatus::ok);
  }
}

// The controller follows moving targets at the physics rate (the targets ramp over each command
// period): a 4 cm squat and back in 2 s, the knee within 20 mrad of its target.
TEST(TorqueControl, TheG1SquatsFollowingItsTargets) {
  MujocoRobot robot(walkgen::mujoco_robot_settings(g1()));
  const Eigen::VectorXd q0 = robot.output().q;
  const walkgen::RobotInfo& info = robot.info();
  auto index = [&](const std::string& name) {
    std::size_t i = 0;
    while (info.joint_names[i] != name) ++i;
    return Eigen::Index(i);
  };
  double worst = 0.0, low = 1.0;
  for (int k = 1; k <= 200; ++k) {                       // 10 ms command period
    const double a = 0.15 * std::sin(M_PI * k / 200.0);  // hip -a, knee +2a, ankle -a
    Eigen::VectorXd q = q0;
    for (const char* side : {"left_", "right_"}) {
      const std::string s(side);
      q[index(s + "hip_pitch_joint")] -= a;
      q[index(s + "knee_joint")] += 2 * a;
      q[index(s + "ankle_pitch_joint")] -= a;
    }
    ASSERT_EQ(robot.set_joint_targets(q), walkgen::JointCommandStatus::accepted);
    ASSERT_EQ(robot.step(0.01), RobotStatus::ok) << robot.output().message;
    const Eigen::Index knee = index("left_knee_joint");
    worst = std::max(worst, std::abs(robot.output().q[knee] - q[knee]));
    low = std::min(low, robot.output().base_height);
  }
  std::printf("squat: lowest base %.3f m, worst knee error %.1f mrad\n", low, 1e3 * worst);
  EXPECT_LT(worst, 0.02);
  EXPECT_LT(low, robot.info().nominal_base_height - 0.02);
}

// Targets far away with huge gains: every torque stays within the motors' ctrlrange and the
// clamped ones are counted.
TEST(TorqueControl, TorquesAreClampedToTheMotorLimitsAndCounted) {
  MujocoRobotSettings s = walkgen::mujoco_robot_settings(g1());
  s.kp.setConstant(1e5);
  MujocoRobot robot(s);
  Eigen::VectorXd q = robot.output().q;
  q.array() += 0.2;
  ASSERT_EQ(robot.set_joint_targets(q), walkgen::JointCommandStatus::accepted);
  (void)robot.step(0.01);
  EXPECT_GT(robot.output().saturations, 0);
  const mjModel* m = robot.model();
  for (Eigen::Index i = 0; i < robot.output().tau.size(); ++i) {
    const int joint = mj_name2id(m, mjOBJ_JOINT, robot.info().joint_names[std::size_t(i)].c_str());
    int actuator = 0;
    while (m->actuator_trnid[2 * actuator] != joint) ++actuator;
    EXPECT_LE(std::abs(robot.output().tau[i]), m->actuator_ctrlrange[2 * actuator + 1] + 1e-9);
  }
}

TEST(TorqueControl, MissingGainsAreAnErrorNamingTheJoints) {
  MujocoRobotSettings s = walkgen::mujoco_robot_settings(g1());
  s.kp[3] = std::nan("");
  try {
    MujocoRobot robot(s);
    FAIL() << "no error";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'left_knee_joint'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("joint_groups"), std::string::npos) << e.what();
  }
}

// Our humanoid has ankle sensors: the contact forces, reported at the sensor frames, give the
// sensors' ZMP while it stands (the feet's own weight is the difference).
TEST(TorqueControl, ContactForcesGiveTheAnkleSensorsZmp) {
  MujocoRobot robot;
  EXPECT_EQ(robot.info().drive, walkgen::JointDrive::position);
  ASSERT_EQ(robot.step(1.0), RobotStatus::ok);
  const double d = robot.info().ft_sensor_height;
  const walkgen::MeasuredZmp sensors = walkgen::measured_zmp(robot.output().ft, d);
  const walkgen::MeasuredZmp contacts = walkgen::measured_zmp(robot.contact_ft(), d);
  ASSERT_TRUE(sensors.valid && contacts.valid);
  std::printf("humanoid standing: sensor ZMP (%.4f, %.4f), contact ZMP (%.4f, %.4f) m\n",
              sensors.zmp_W.x(), sensors.zmp_W.y(), contacts.zmp_W.x(), contacts.zmp_W.y());
  EXPECT_LT((sensors.zmp_W - contacts.zmp_W).head<2>().norm(), 0.005);
  EXPECT_GT(robot.output().tau.cwiseAbs().maxCoeff(), 1.0);  // the servos' torques, reported
}

}  // namespace
