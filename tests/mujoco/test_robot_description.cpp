// walkgen_humanoid_description(), the humanoid's identity in one value, checked entry by entry
// against the two files models/generate.py writes (the ctest model_generator_reproduces checks
// that the script reproduces them): the MJCF through MuJoCo, the URDF through walkgen's loader.
// Also validate(RobotDescription) and the WalkingSettings parts.
#include "walkgen/robot/robot_description.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "support/expect_error.hpp"
#include "walkgen/mujoco/mujoco_robot.hpp"
#include "walkgen/urdf/urdf_loader.hpp"

namespace {

using walkgen::RobotDescription;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

class HumanoidDescription : public ::testing::Test {
 protected:
  void SetUp() override {
    char error[1000] = "";
    model_.reset(mj_loadXML(robot_.mjcf_path.c_str(), nullptr, error, sizeof error));
    ASSERT_NE(model_, nullptr) << robot_.mjcf_path << ": " << error;
    data_.reset(mj_makeData(model_.get()));
  }
  int id(mjtObj type, const std::string& name) const {
    return mj_name2id(model_.get(), type, name.c_str());
  }
  /// MuJoCo's state at the stand keyframe, after forward kinematics.
  void stand() {
    const int key = id(mjOBJ_KEY, robot_.stand_keyframe);
    ASSERT_GE(key, 0) << "no keyframe " << robot_.stand_keyframe;
    mj_resetDataKeyframe(model_.get(), data_.get(), key);
    mj_forward(model_.get(), data_.get());
  }
  Eigen::Vector3d site(const std::string& name) const {
    const int s = id(mjOBJ_SITE, name);
    EXPECT_GE(s, 0) << "no site " << name;
    if (s < 0) return Eigen::Vector3d::Constant(NAN);
    return Eigen::Vector3d::Map(data_->site_xpos + 3 * s);
  }

  RobotDescription robot_ = walkgen::walkgen_humanoid_description();
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
};

TEST_F(HumanoidDescription, IsValidAndNamesTheModelFiles) {
  EXPECT_NO_THROW(walkgen::validate(robot_));
  EXPECT_EQ(robot_.mjcf_path, walkgen::humanoid_mjcf_path());
  EXPECT_EQ(robot_.urdf_path, walkgen::humanoid_urdf_path());
}

TEST_F(HumanoidDescription, JointsAreTheMjcfsActuatedJointsInOrder) {
  ASSERT_EQ(model_->nu, static_cast<int>(robot_.joint_names.size()));
  for (int i = 0; i < model_->nu; ++i) {
    const std::string& name = robot_.joint_names[static_cast<std::size_t>(i)];
    const int joint = id(mjOBJ_JOINT, name);
    ASSERT_GE(joint, 0) << name;
    EXPECT_EQ(model_->actuator_trnid[2 * i], joint) << "actuator " << i << " drives " << name;
    EXPECT_GE(id(mjOBJ_SENSOR, name + "_pos"), 0) << name;
  }
}

TEST_F(HumanoidDescription, FramesCamerasAndBaseExistInBothModels) {
  const walkgen::KinematicTree<double> tree =
      walkgen::kinematic_tree_from_urdf_file(robot_.urdf_path);
  for (int side = 0; side < 2; ++side) {
    for (const std::string& frame : {robot_.sole_frames[side], robot_.ft_sensor_frames[side]}) {
      EXPECT_GE(id(mjOBJ_SITE, frame), 0) << frame;
      EXPECT_NO_THROW(tree.link_index(frame)) << frame;
    }
    EXPECT_GE(id(mjOBJ_SENSOR, robot_.ft_sensor_frames[side] + "_force"), 0);
    EXPECT_GE(id(mjOBJ_SENSOR, robot_.ft_sensor_frames[side] + "_torque"), 0);
    EXPECT_GE(id(mjOBJ_CAMERA, robot_.cameras[side]), 0) << robot_.cameras[side];
  }
  for (const std::string& body : {robot_.base_body, robot_.torso_body}) {
    EXPECT_GE(id(mjOBJ_BODY, body), 0) << body;
    EXPECT_NO_THROW(tree.link_index(body)) << body;
  }
  for (const std::string& joint : robot_.joint_names) {
    EXPECT_NO_THROW(tree.joint_index(joint)) << joint;
  }
  EXPECT_EQ(tree.num_joints(), static_cast<int>(robot_.joint_names.size()));
}

TEST_F(HumanoidDescription, StandPoseIsTheKeyframe) {
  stand();
  const std::vector<double> angles = walkgen::stand_angles(robot_);
  for (std::size_t i = 0; i < robot_.joint_names.size(); ++i) {
    const int joint = id(mjOBJ_JOINT, robot_.joint_names[i]);
    EXPECT_DOUBLE_EQ(data_->qpos[model_->jnt_qposadr[joint]], angles[i]) << robot_.joint_names[i];
    // The position servos hold the pose: the keyframe's control targets are the same angles.
    EXPECT_DOUBLE_EQ(data_->ctrl[i], angles[i]) << robot_.joint_names[i];
  }
  // Standing, the soles are flat on the floor.
  for (const std::string& sole : robot_.sole_frames) {
    const int s = id(mjOBJ_SITE, sole);
    EXPECT_NEAR(data_->site_xmat[9 * s + 8], 1.0, 1e-12) << sole << " is not flat";
    // The keyframe's base height is written to 0.1 mm (0.5062 m).
    EXPECT_NEAR(site(sole).z(), 0.0, 1e-4) << sole;
  }
}

TEST_F(HumanoidDescription, FootGeometryIsTheModels) {
  stand();
  const auto& g = robot_.walking.geometry();
  // The sole: the foot body's box (half sizes in MuJoCo) under the sole site.
  for (const std::string& sole : robot_.sole_frames) {
    const int body = model_->site_bodyid[id(mjOBJ_SITE, sole)];
    int box = -1;
    for (int i = 0; i < model_->ngeom; ++i) {
      if (model_->geom_bodyid[i] == body && model_->geom_type[i] == mjGEOM_BOX) box = i;
    }
    ASSERT_GE(box, 0) << "no box geom on the body of " << sole;
    EXPECT_NEAR(2.0 * model_->geom_size[3 * box + 0], g.foot_length, 1e-12) << sole;
    EXPECT_NEAR(2.0 * model_->geom_size[3 * box + 1], g.foot_width, 1e-12) << sole;
  }
  const Eigen::Vector3d left = site(robot_.sole_frames[0]), right = site(robot_.sole_frames[1]);
  EXPECT_NEAR(left.y() - right.y(), g.foot_distance, 1e-9);
  EXPECT_NEAR(left.x() - right.x(), 0.0, 1e-9);
  for (int side = 0; side < 2; ++side) {
    EXPECT_NEAR((site(robot_.ft_sensor_frames[side]) - site(robot_.sole_frames[side])).z(),
                robot_.ft_sensor_height, 1e-12);
  }
  const int numeric = id(mjOBJ_NUMERIC, "ft_sensor_height");
  ASSERT_GE(numeric, 0);
  EXPECT_DOUBLE_EQ(model_->numeric_data[model_->numeric_adr[numeric]], robot_.ft_sensor_height);
  // The walk starts on the left sole, half the foot distance left of the middle.
  const auto& start = robot_.walking.initial_state();
  EXPECT_EQ(start.support_foot, walkgen::Foot::left);
  EXPECT_NEAR(start.foot_y, g.foot_distance / 2.0, 1e-12);
}

TEST_F(HumanoidDescription, MujocoAndLoopSettingsComeFromIt) {
  const walkgen::MujocoRobotSettings defaults;
  const walkgen::MujocoRobotSettings from = walkgen::mujoco_robot_settings(robot_);
  EXPECT_EQ(defaults.joint_names, from.joint_names);
  EXPECT_EQ(defaults.ft_sensor_sites, from.ft_sensor_sites);
  EXPECT_EQ(defaults.cameras, from.cameras);
  EXPECT_EQ(defaults.base_body, from.base_body);
  EXPECT_EQ(defaults.keyframe, from.keyframe);
  EXPECT_EQ(from.model_path, robot_.mjcf_path);
  walkgen::MujocoRobot robot(from);
  EXPECT_EQ(robot.info().ft_sensor_height, robot_.ft_sensor_height);
}

TEST(RobotDescription, ValidateNamesTheBadEntry) {
  const RobotDescription good = walkgen::walkgen_humanoid_description();
  auto expect_bad = [&](auto change, const char* needle) {
    RobotDescription d = good;
    change(d);
    walkgen_test::expect_invalid_argument([&] { walkgen::validate(d); }, {needle});
  };
  expect_bad([](RobotDescription& d) { d.name.clear(); }, "RobotDescription.name");
  expect_bad([](RobotDescription& d) { d.joint_names.push_back("l_knee"); }, "'l_knee' twice");
  expect_bad([](RobotDescription& d) { d.sole_frames[1] = d.sole_frames[0]; },
             "RobotDescription.sole_frames");
  expect_bad([](RobotDescription& d) { d.cameras[0].clear(); }, "RobotDescription.cameras");
  expect_bad([](RobotDescription& d) { d.stand_pose.push_back({"l_elbow", 0.3}); }, "'l_elbow'");
  expect_bad([](RobotDescription& d) { d.stand_pose[0].angle = NAN; }, "finite angles");
  expect_bad([](RobotDescription& d) { d.stand_pose.push_back(d.stand_pose[1]); },
             "'l_knee' twice");
  expect_bad([](RobotDescription& d) { d.ft_sensor_height = 0.0; },
             "RobotDescription.ft_sensor_height");
  expect_bad([](RobotDescription& d) { d.walking.foot_width = -1.0; }, "foot_width");
}

// The three parts of WalkingSettings are the flat keys' homes and validate on their own.
TEST(WalkingSettingsParts, AssembleAndValidateOnTheirOwn) {
  const walkgen::WalkingSettings<double> heicub = walkgen::heicub_settings();
  const walkgen::WalkingSettings<double> assembled = walkgen::walking_settings(
      heicub.geometry(), heicub.generator(), heicub.initial_state(), heicub.obstacles);
  EXPECT_EQ(assembled.t_step, heicub.t_step);
  EXPECT_EQ(assembled.foot_distance, heicub.foot_distance);
  EXPECT_EQ(assembled.com_y, heicub.com_y);
  EXPECT_TRUE(assembled.left_foot_convex_hull.isApprox(heicub.left_foot_convex_hull));

  // Heicub's generator on HRP-2's geometry: each part keeps its own values.
  const walkgen::WalkingSettings<double> mixed = walkgen::walking_settings(
      walkgen::hrp2_settings().geometry(), heicub.generator(), heicub.initial_state());
  EXPECT_EQ(mixed.foot_length, walkgen::hrp2_settings().foot_length);
  EXPECT_EQ(mixed.t_step, heicub.t_step);
  EXPECT_NO_THROW(walkgen::validate(mixed));

  walkgen::RobotGeometry<double> geometry = heicub.geometry();
  geometry.security_margin.x() = 0.2;  // more than half the 0.2 m foot
  walkgen_test::expect_invalid_argument([&] { walkgen::validate(geometry); },
                                        {"WalkingSettings.security_margin[0]"});
  walkgen::GeneratorSettings<double> generator = heicub.generator();
  generator.t_ds = generator.t_step;
  walkgen_test::expect_invalid_argument([&] { walkgen::validate(generator); },
                                        {"WalkingSettings.t_ds"});
  walkgen::InitialState<double> start = heicub.initial_state();
  start.foot_q = INFINITY;
  walkgen_test::expect_invalid_argument([&] { walkgen::validate(start); },
                                        {"WalkingSettings.foot_q"});
  // What ties the parts together: a start farther from its foot than the generator believes.
  walkgen::WalkingSettings<double> far = heicub;
  far.com_y[0] = far.foot_y + 3.0;
  walkgen_test::expect_invalid_argument([&] { walkgen::validate(far); }, {"max_state_distance"});
}

}  // namespace
