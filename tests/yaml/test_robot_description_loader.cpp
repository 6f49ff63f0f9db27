// Robot description files (walkgen/yaml/robot_description_loader.hpp): the humanoid's file is the
// code preset, the G1's loads with its added frames and geometry, and every malformed file is
// refused with the key (and line) that is wrong.
#include "walkgen/yaml/robot_description_loader.hpp"

#include <gtest/gtest.h>

#include <string>

#include "support/expect_error.hpp"

namespace {

using walkgen::RobotDescription;
using walkgen_test::expect_invalid_argument;

const std::string kModels = std::string(WALKGEN_SOURCE_DIR) + "/models/";

// The smallest valid file, for the error cases to break.
const std::string kMinimal = R"(name: tiny
mjcf: tiny.xml
base_body: base
joints: [hip, knee]
sole_frames: [l_sole, r_sole]
)";

TEST(RobotDescriptionFile, HumanoidFileIsTheCodePreset) {
  const RobotDescription file =
      walkgen::load_robot_description(kModels + "walkgen_humanoid/robot.yaml");
  const RobotDescription code = walkgen::walkgen_humanoid_description();
  EXPECT_EQ(file.name, code.name);
  // The file's paths are relative to it; both name the same files.
  EXPECT_EQ(file.mjcf_path, kModels + "walkgen_humanoid/../walkgen_humanoid.xml");
  EXPECT_EQ(file.urdf_path, kModels + "walkgen_humanoid/../walkgen_humanoid.urdf");
  EXPECT_EQ(file.joint_names, code.joint_names);
  EXPECT_EQ(file.sole_frames, code.sole_frames);
  EXPECT_EQ(file.ft_sensor_frames, code.ft_sensor_frames);
  EXPECT_EQ(file.ft_sensor_height, code.ft_sensor_height);
  EXPECT_EQ(file.cameras, code.cameras);
  EXPECT_EQ(file.imu_site, code.imu_site);
  EXPECT_EQ(file.base_body, code.base_body);
  EXPECT_EQ(file.torso_body, code.torso_body);
  EXPECT_EQ(file.stand_keyframe, code.stand_keyframe);
  EXPECT_EQ(walkgen::stand_angles(file), walkgen::stand_angles(code));
  EXPECT_TRUE(file.frames.empty());
  EXPECT_EQ(file.walking.t_step, code.walking.t_step);
  EXPECT_EQ(file.walking.foot_distance, code.walking.foot_distance);
  EXPECT_EQ(file.walking.com_z, code.walking.com_z);
  EXPECT_EQ(file.walking.max_command, code.walking.max_command);
  EXPECT_TRUE(file.walking.left_foot_convex_hull.isApprox(code.walking.left_foot_convex_hull));
}

TEST(RobotDescriptionFile, G1FileLoadsWithItsFramesAndGeometry) {
  const RobotDescription g1 = walkgen::find_robot_description(kModels + "unitree_g1/robot.yaml");
  EXPECT_EQ(g1.name, "unitree_g1");
  EXPECT_EQ(g1.mjcf_path, kModels + "unitree_g1/scene_mujoco2.xml");
  EXPECT_TRUE(g1.urdf_path.empty());
  EXPECT_EQ(g1.joint_names.size(), 23u);
  ASSERT_EQ(g1.frames.size(), 2u);
  EXPECT_EQ(g1.frames[0].name, "l_sole");
  EXPECT_EQ(g1.frames[0].body, "left_ankle_roll_link");
  EXPECT_EQ(g1.frames[0].xyz, Eigen::Vector3d(0.035, 0.0, -0.035));
  EXPECT_TRUE(g1.ft_sensor_frames[0].empty());
  EXPECT_TRUE(g1.cameras[0].empty());
  EXPECT_EQ(g1.imu_site, "imu");
  // Every joint in one group; the legs' gains.
  const walkgen::JointGains gains = walkgen::joint_gains(g1);
  EXPECT_TRUE(gains.kp.allFinite() && gains.kd.allFinite());
  EXPECT_EQ(gains.kp[3], 200.0);  // left_knee_joint
  EXPECT_EQ(gains.kd[3], 7.0);
  EXPECT_EQ(gains.kp[13], 40.0);  // left_shoulder_pitch_joint
  // The contact region: the spheres' lowest points, wider at the toes.
  ASSERT_EQ(g1.sole_polygon.size(), 4u);
  EXPECT_EQ(g1.sole_polygon[0], Eigen::Vector2d(0.085, 0.03));
  EXPECT_EQ(walkgen::sole_corners(g1)[3], Eigen::Vector2d(-0.085, -0.025));
  // The balance section: the contact feed-forward with its gains, no NMPC restart.
  EXPECT_TRUE(g1.balance.contact_feedforward);
  EXPECT_EQ(g1.balance.com_kp, 20.0);
  EXPECT_EQ(g1.balance.com_kd, 8.0);
  EXPECT_FALSE(g1.balance.nmpc_feedback);
  // The arms are held at the stand pose (the IK leaves them out); legs and waist are not.
  for (const walkgen::JointGroup& group : g1.joint_groups) {
    EXPECT_EQ(group.held, group.name == "arms") << group.name;
  }
  // walking_preset hrp2 under the file's keys.
  EXPECT_EQ(g1.walking.t_step, walkgen::hrp2_settings().t_step);
  EXPECT_EQ(g1.walking.foot_length, 0.17);
  EXPECT_EQ(g1.walking.foot_distance, 0.237);
  EXPECT_EQ(g1.walking.foot_y, 0.1185);
}

TEST(RobotDescriptionFile, ANameFindsTheFileUnderTheDataDirectory) {
  EXPECT_EQ(walkgen::find_robot_description("unitree_g1").name, "unitree_g1");
  expect_invalid_argument([] { (void)walkgen::find_robot_description("no_such_robot"); },
                          {"models/no_such_robot/robot.yaml", "a readable YAML file"});
}

TEST(RobotDescriptionFile, MinimalFileGetsTheDefaults) {
  const RobotDescription d = walkgen::robot_description_from_yaml(kMinimal, "/models/tiny");
  EXPECT_EQ(d.mjcf_path, "/models/tiny/tiny.xml");
  EXPECT_TRUE(d.stand_pose.empty());
  EXPECT_EQ(d.walking.t_step, walkgen::heicub_settings().t_step);  // the default preset
}

TEST(RobotDescriptionFile, ErrorsNameTheKey) {
  const auto bad = [](const std::string& text, std::vector<std::string> parts) {
    expect_invalid_argument([&] { (void)walkgen::robot_description_from_yaml(text, "."); }, parts);
  };
  bad(kMinimal + "colour: red\n", {"key 'colour'", "unknown key", "known keys: name"});
  bad("name: tiny\nmjcf: tiny.xml\njoints: [hip]\nsole_frames: [l, r]\n",
      {"the key 'base_body'", "none"});
  bad(kMinimal + "cameras: [left]\n", {"key 'cameras'", "two names"});
  bad(kMinimal + "sole_polygon: [[0.1, 0.05], [0.1, -0.05]]\n", {"sole_polygon", "four corners"});
  bad(kMinimal + "sole_polygon: [[0.1, 0.05], [0.1, -0.04], [-0.1, 0.05], [-0.1, -0.05]]\n",
      {"RobotDescription.sole_polygon", "symmetric"});
  bad(kMinimal + "balance: {com_kp: -1}\n", {"RobotDescription.balance", "com_kp"});
  bad(kMinimal + "balance: {gain: 1}\n", {"com_kp, com_kd or nmpc_feedback", "unknown key"});
  bad(kMinimal + "ft_sensor_frames: [l_ft, r_ft]\n", {"the key 'ft_sensor_height'"});
  bad(kMinimal + "ft_sensor_height: 0.03\n", {"ft_sensor_height only with ft_sensor_frames"});
  bad(kMinimal + "stand_pose: {hip: .nan}\n", {"key 'stand_pose.hip'", "a finite number"});
  bad(kMinimal + "stand_pose: {ankle: 0.1}\n", {"RobotDescription.stand_pose", "'ankle'"});
  bad(kMinimal + "frames: {l_sole: {xyz: [0, 0, 0]}}\n", {"frames.l_sole", "the key body"});
  bad(kMinimal + "joint_groups: {legs: {joints: [hip], kp: 100}}\n",
      {"joint_groups.legs", "joints, kp and kd"});
  bad(kMinimal + "joint_groups: {legs: {joints: [hip], kp: 100, kd: 1, ki: 3}}\n",
      {"joint_groups.legs.ki", "joints, kp, kd or held"});
  bad(kMinimal + "joint_groups: {legs: {joints: [hip], kp: 100, kd: 1, held: maybe}}\n",
      {"joint_groups.legs.held", "true or false", "maybe"});
  bad(kMinimal + "joint_groups: {legs: {joints: [hip, ankle], kp: 100, kd: 1}}\n",
      {"joint_groups: 'legs'", "'ankle'"});
  bad(kMinimal +
          "joint_groups: {a: {joints: [hip], kp: 1, kd: 1}, b: {joints: [hip], kp: 1, kd: 1}}\n",
      {"each joint in one group only", "'hip' 2 times"});
  bad(kMinimal + "joint_groups: {legs: {joints: [hip], kp: -1, kd: 1}}\n", {"kp, kd >= 0"});
  bad(kMinimal + "frames: {l_sole: {body: foot, xyz: [0, 0]}}\n",
      {"frames.l_sole.xyz", "a list of 3 numbers"});
  bad(kMinimal + "frames: {l_sole: {body: foot, size: 1}}\n",
      {"frames.l_sole.size", "body, xyz or rpy"});
  bad(kMinimal + "walking_preset: asimo\n", {"walking_preset", "hrp2 or heicub", "'asimo'"});
  bad(kMinimal + "walking: {t_stepp: 1.0}\n", {"'t_stepp'", "did you mean 't_step'"});
  bad(kMinimal + "walking: {foot_width: -0.1}\n", {"WalkingSettings.foot_width"});
  bad(kMinimal + "joints: [hip, hip]\n", {"repeated", "joints"});
  bad("[1, 2]", {"a map of robot description keys"});
  bad("name: [", {"well-formed YAML"});
}

}  // namespace
