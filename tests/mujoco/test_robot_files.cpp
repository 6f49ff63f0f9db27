// The robot description files against the models they name (walkgen/mujoco/robot_model.hpp):
// every name in the model, the soles flat and foot_distance apart in the stand pose, the CoM at
// com_z above them, the G1's soles where its contact spheres are; and errors that list what the
// model has.
#include "walkgen/mujoco/robot_model.hpp"

#include <gtest/gtest.h>

#include <string>

#include "support/expect_error.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

using walkgen::RobotDescription;
using walkgen_test::expect_invalid_argument;

const std::string kModels = std::string(WALKGEN_SOURCE_DIR) + "/models/";

struct Stance {
  Eigen::Vector3d left, right, com;
  double tilt = 0.0;  ///< largest angle of a sole's z axis from the vertical [rad]
};

// Forward kinematics of the stand pose with an upright base at the origin.
Stance stance(const RobotDescription& robot) {
  const walkgen::KinematicTree<double> tree = walkgen::robot_kinematic_tree_from_mjcf(robot);
  const Eigen::VectorXd q = walkgen::stand_configuration(tree, robot);
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q, ws);
  Stance s;
  const int l = tree.link_index(robot.sole_frames[0]), r = tree.link_index(robot.sole_frames[1]);
  s.left = ws.position_W(l);
  s.right = ws.position_W(r);
  s.com = tree.center_of_mass(ws);
  for (int f : {l, r}) {
    s.tilt = std::max(s.tilt, std::acos(std::min(1.0, ws.rotation_W(f)(2, 2))));
  }
  return s;
}

TEST(RobotFiles, HumanoidNamesAreInItsModelAndItStandsOnItsSoles) {
  const RobotDescription robot = walkgen::find_robot_description("walkgen_humanoid");
  const auto model = walkgen::detail::load_mjcf(robot.mjcf_path, "test");
  EXPECT_NO_THROW(walkgen::check_robot_against_model(robot, *model.m));
  const Stance s = stance(robot);
  EXPECT_LE(s.tilt, 1e-12);
  EXPECT_NEAR(s.left.z(), s.right.z(), 1e-12);
  EXPECT_NEAR(s.left.y() - s.right.y(), robot.walking.foot_distance, 1e-12);
  EXPECT_NEAR(s.left.x(), s.right.x(), 1e-12);
}

TEST(RobotFiles, G1NamesAreInItsModelAndItsGeometryIsTheModels) {
  const RobotDescription robot = walkgen::find_robot_description("unitree_g1");
  const auto model = walkgen::detail::load_mjcf(robot.mjcf_path, "test");
  const mjModel& m = *model.m;
  EXPECT_NO_THROW(walkgen::check_robot_against_model(robot, m));
  const Stance s = stance(robot);
  EXPECT_LE(s.tilt, 1e-12);  // hip pitch + knee + ankle pitch = 0: the soles are flat
  EXPECT_NEAR(s.left.z(), s.right.z(), 1e-12);
  EXPECT_NEAR(s.left.y() - s.right.y(), robot.walking.foot_distance, 1e-3);
  // The walk keeps the CoM 4.4 cm below the stance's (knees bent further: more reach).
  EXPECT_NEAR(s.com.z() - s.left.z(), 0.6944, 1e-3);
  EXPECT_NEAR(s.com.z() - s.left.z() - robot.walking.com_z, 0.044, 1e-3);
  RecordProperty("stance_foot_distance_m", std::to_string(s.left.y() - s.right.y()));
  RecordProperty("stance_com_height_m", std::to_string(s.com.z() - s.left.z()));
  // The contact spheres of each foot: their lowest points on the sole plane, their centres
  // spanning foot_length along the foot and within foot_width/2 + a radius across it.
  for (int side = 0; side < 2; ++side) {
    const walkgen::FrameDescription& sole = robot.frames[std::size_t(side)];
    const int body = mj_name2id(&m, mjOBJ_BODY, sole.body.c_str());
    double x_min = 1e9, x_max = -1e9;
    int spheres = 0;
    for (int g = 0; g < m.ngeom; ++g) {
      if (m.geom_bodyid[g] != body || m.geom_type[g] != mjGEOM_SPHERE) continue;
      ++spheres;
      const Eigen::Vector3d c(m.geom_pos[3 * g], m.geom_pos[3 * g + 1], m.geom_pos[3 * g + 2]);
      const double radius = m.geom_size[3 * g];
      EXPECT_NEAR(c.z() - radius, sole.xyz.z(), 1e-9) << sole.name;
      EXPECT_LE(std::abs(c.y() - sole.xyz.y()), robot.walking.foot_width / 2.0 + radius + 1e-9);
      x_min = std::min(x_min, c.x());
      x_max = std::max(x_max, c.x());
    }
    EXPECT_EQ(spheres, 4) << sole.body;
    EXPECT_NEAR(x_max - x_min, robot.walking.foot_length, 1e-9);
    EXPECT_NEAR((x_max + x_min) / 2.0, sole.xyz.x(), 1e-9);
  }
}

TEST(RobotFiles, MissingNamesAreListedWithWhatTheModelHas) {
  const RobotDescription g1 = walkgen::find_robot_description("unitree_g1");
  const auto model = walkgen::detail::load_mjcf(g1.mjcf_path, "test");
  const auto bad = [&](auto change, std::vector<std::string> parts) {
    RobotDescription d = g1;
    change(d);
    expect_invalid_argument([&] { walkgen::check_robot_against_model(d, *model.m); }, parts);
  };
  bad([](RobotDescription& d) { d.joint_names[3] = "left_knee"; },
      {"robot 'unitree_g1'", "joint", "'left_knee'", "'left_knee_joint'"});
  bad([](RobotDescription& d) { d.base_body = "torso"; }, {"base_body", "'torso_link'"});
  bad([](RobotDescription& d) { d.frames[0].body = "left_foot"; },
      {"body of frame 'l_sole'", "'left_ankle_roll_link'"});
  bad([](RobotDescription& d) { d.frames[0].name = "imu"; }, {"frame 'imu'", "a name no body"});
  bad([](RobotDescription& d) { d.sole_frames[1] = "right_sole"; },
      {"sole frame", "'right_sole'", "'imu'"});
  bad(
      [](RobotDescription& d) {
        d.cameras = {{"head_left", "head_right"}};
      },
      {"camera", "'head_left'", "none"});
  bad([](RobotDescription& d) { d.stand_keyframe = "stand"; }, {"stand_keyframe", "none"});
  bad([](RobotDescription& d) { d.imu_site = "head_imu"; }, {"IMU site", "'head_imu'", "'imu'"});
  {  // the G1's second IMU (in the torso) has the three sensors too; a site without them not
    RobotDescription d = g1;
    d.imu_site = "secondary_imu";
    EXPECT_NO_THROW(walkgen::check_robot_against_model(d, *model.m));
    const RobotDescription h = walkgen::find_robot_description("walkgen_humanoid");
    const auto humanoid = walkgen::detail::load_mjcf(h.mjcf_path, "test");
    RobotDescription sole = h;
    sole.imu_site = "l_sole";
    expect_invalid_argument([&] { walkgen::check_robot_against_model(sole, *humanoid.m); },
                            {"IMU sensor", "'l_sole_quat'", "'imu_quat'"});
  }
  bad(
      [](RobotDescription& d) {
        d.ft_sensor_frames = {{"imu", "secondary_imu"}};
        d.ft_sensor_height = 0.03;
      },
      {"sensor", "'imu_force'"});
}

}  // namespace
