// KinematicTree from an mjModel (walkgen/mujoco/mujoco_kinematics.hpp) against MuJoCo's own
// kinematics: every body and site frame and the centre of mass for random floating-base poses
// and joint configurations, on walkgen's humanoid, on the Unitree G1 (converted for MuJoCo 2.2.2)
// and on a small biped written here with what neither has (joint anchors off the body origin, a
// reference angle, two hinges in one body, a body without joints); and the errors.
#include "walkgen/mujoco/mujoco_kinematics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "support/expect_error.hpp"
#include "support/kinematics.hpp"
#include "walkgen/urdf/urdf_loader.hpp"

namespace {

using walkgen_test::Tree;

const std::string kModels = std::string(WALKGEN_SOURCE_DIR) + "/models/";

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

struct Loaded {
  std::unique_ptr<mjModel, void (*)(mjModel*)> m{nullptr, mj_deleteModel};
  std::unique_ptr<mjData, void (*)(mjData*)> d{nullptr, mj_deleteData};
};

Loaded load(const std::string& path) {
  Loaded l;
  char error[1000] = "";
  l.m.reset(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  EXPECT_NE(l.m, nullptr) << path << ": " << error;
  if (l.m) l.d.reset(mj_makeData(l.m.get()));
  return l;
}

struct Agreement {
  double position = 0.0, rotation = 0.0, com = 0.0;
  int frames = 0;  ///< tree links compared (bodies and sites)
};

// Random poses and configurations in both: the largest disagreement.
Agreement compare(const std::string& path, int trials) {
  Agreement worst;
  Loaded mj = load(path);
  if (!mj.m) return worst;
  const mjModel& m = *mj.m;
  const Tree tree(walkgen::kinematic_description_from_mujoco(m));
  int base = -1;
  for (int b = 1; b < m.nbody && base < 0; ++b) {
    if (m.body_parentid[b] == 0 && m.body_jntnum[b] == 1 &&
        m.jnt_type[m.body_jntadr[b]] == mjJNT_FREE) {
      base = b;
    }
  }
  // Each tree link's MuJoCo body or site (the massless "<body>/<joint>" links have neither).
  std::vector<std::pair<int, int>> frames;  // (link, body) or (link, -1 - site)
  for (int i = 0; i < tree.num_links(); ++i) {
    const std::string& name = tree.link(i).name;
    const int b = mj_name2id(&m, mjOBJ_BODY, name.c_str());
    const int s = mj_name2id(&m, mjOBJ_SITE, name.c_str());
    if (b >= 0)
      frames.push_back({i, b});
    else if (s >= 0)
      frames.push_back({i, -1 - s});
  }
  worst.frames = static_cast<int>(frames.size());
  std::mt19937 rng(7);
  auto ws = tree.make_workspace();
  for (int trial = 0; trial < trials; ++trial) {
    const auto pose = walkgen_test::random_base_pose(rng, 2.0);
    const Eigen::VectorXd q = walkgen_test::random_configuration(tree, rng);
    tree.forward_kinematics(pose.position, pose.rotation, q, ws);
    mj_resetData(&m, mj.d.get());
    const int free = m.jnt_qposadr[m.body_jntadr[base]];
    const Eigen::Quaterniond quat(pose.rotation);
    for (int k = 0; k < 3; ++k) mj.d->qpos[free + k] = pose.position[k];
    mj.d->qpos[free + 3] = quat.w();
    mj.d->qpos[free + 4] = quat.x();
    mj.d->qpos[free + 5] = quat.y();
    mj.d->qpos[free + 6] = quat.z();
    for (int i = 0; i < tree.num_joints(); ++i) {
      const int j = mj_name2id(&m, mjOBJ_JOINT, tree.joint_names()[std::size_t(i)].c_str());
      mj.d->qpos[m.jnt_qposadr[j]] = q[i];
    }
    mj_kinematics(&m, mj.d.get());
    mj_comPos(&m, mj.d.get());
    for (const auto& [link, id] : frames) {
      const mjtNum* p = id >= 0 ? mj.d->xpos + 3 * id : mj.d->site_xpos + 3 * (-1 - id);
      const mjtNum* R = id >= 0 ? mj.d->xmat + 9 * id : mj.d->site_xmat + 9 * (-1 - id);
      const Eigen::Matrix3d R_mj =
          Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R);
      worst.position = std::max(
          worst.position, (ws.position_W(link) - Eigen::Map<const Eigen::Vector3d>(p)).norm());
      worst.rotation = std::max(worst.rotation,
                                Eigen::AngleAxisd(ws.rotation_W(link).transpose() * R_mj).angle());
    }
    worst.com = std::max(
        worst.com,
        (tree.center_of_mass(ws) - Eigen::Map<const Eigen::Vector3d>(mj.d->subtree_com + 3 * base))
            .norm());
  }
  return worst;
}

void expect_agreement(const std::string& path, int expected_frames) {
  const Agreement a = compare(path, 300);
  EXPECT_EQ(a.frames, expected_frames);
  EXPECT_LE(a.position, 1e-9);
  EXPECT_LE(a.rotation, 1e-9);
  EXPECT_LE(a.com, 1e-9);
  ::testing::Test::RecordProperty("max_position_error_m", walkgen_test::scientific(a.position));
  ::testing::Test::RecordProperty("max_rotation_error_rad", walkgen_test::scientific(a.rotation));
  ::testing::Test::RecordProperty("max_com_error_m", walkgen_test::scientific(a.com));
}

TEST(MujocoKinematics, HumanoidAgreesWithMujoco) {
  // 19 bodies below the world, and the sites that are not a body's own frame (soles, ankle
  // sensors): every frame walkgen_humanoid.urdf has.
  const Tree tree = walkgen::kinematic_tree_from_mjcf_file(kModels + "walkgen_humanoid.xml");
  const Tree urdf_tree =
      walkgen::kinematic_tree_from_urdf_file<double>(kModels + "walkgen_humanoid.urdf");
  EXPECT_EQ(tree.joint_names(), urdf_tree.joint_names());
  EXPECT_NEAR(tree.mass(), urdf_tree.mass(), 1e-12);
  for (const auto& link : urdf_tree.links()) EXPECT_NO_THROW(tree.link_index(link.name));
  expect_agreement(kModels + "walkgen_humanoid.xml", tree.num_links());
}

TEST(MujocoKinematics, UnitreeG1AgreesWithMujoco) {
  const std::string path = kModels + "unitree_g1/scene_mujoco2.xml";
  const Tree tree = walkgen::kinematic_tree_from_mjcf_file(path);
  // 23 hinges; the six phantom bodies hang from the world, not from the pelvis.
  EXPECT_EQ(tree.num_joints(), 23);
  EXPECT_EQ(tree.link(0).name, "pelvis");
  EXPECT_NEAR(tree.mass(), 34.131, 5e-4);
  expect_agreement(path, tree.num_links());
}

// What neither robot has: anchors off the body origin, a reference angle, two hinges in one
// body, a body without joints, a rotated site, different leg lengths and masses.
const char* kBiped = R"(<mujoco model="small_biped">
  <compiler angle="radian" autolimits="true"/>
  <worldbody>
    <body name="base" pos="0 0 0.6">
      <freejoint name="root"/>
      <inertial pos="0.01 0 0.02" mass="4" diaginertia="0.05 0.04 0.03"/>
      <body name="l_thigh" pos="0 0.08 -0.05" quat="0.99 0.05 0.1 0">
        <joint name="l_hip" axis="0 1 0" pos="0 0 0.02" range="-1 1"/>
        <inertial pos="0 0 -0.12" quat="0.9 0.1 0.3 0.2" mass="1.2" diaginertia="0.02 0.018 0.004"/>
        <body name="l_shank" pos="0 0 -0.25">
          <joint name="l_knee" axis="0 1 0" ref="0.3" range="0 2"/>
          <joint name="l_twist" axis="0.2 0 1" pos="0.01 0 -0.03"/>
          <inertial pos="0 0 -0.1" mass="0.7" diaginertia="0.01 0.01 0.002"/>
          <body name="l_foot" pos="0 0 -0.22">
            <inertial pos="0.03 0 -0.02" mass="0.3" diaginertia="0.001 0.002 0.002"/>
            <site name="l_sole" pos="0.02 0 -0.04" euler="0 0.1 0.2"/>
          </body>
        </body>
      </body>
      <body name="r_thigh" pos="0 -0.09 -0.05">
        <joint name="r_hip" axis="0 1 0"/>
        <inertial pos="0 0 -0.15" mass="1.5" diaginertia="0.03 0.03 0.005"/>
        <body name="r_shank" pos="0 0 -0.3" euler="0 1.5707963267948966 0">
          <joint name="r_knee" axis="0 1 0" range="0 2"/>
          <inertial pos="0 0 -0.1" mass="0.8" diaginertia="0.01 0.01 0.002"/>
          <site name="r_sole" pos="0 0 -0.25"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>)";

TEST(MujocoKinematics, SmallBipedWithAnchorsReferencesAndTwoHingesInABody) {
  const std::string path = write_temp("small_biped.xml", kBiped);
  const Tree tree = walkgen::kinematic_tree_from_mjcf_file(path);
  EXPECT_EQ(tree.num_joints(), 5);
  EXPECT_NEAR(tree.mass(), 4 + 1.2 + 0.7 + 0.3 + 1.5 + 0.8, 1e-12);
  // Six bodies and two sites; the joint links "l_thigh/l_hip", "l_shank/l_knee" and
  // "l_shank/l_twist" have no MuJoCo frame of their own.
  expect_agreement(path, 8);
}

// A random robot: up to 12 bodies on random parents, random positions and orientations (some
// exactly at pitch ±90°, where roll-pitch-yaw would lose digits), 0 to 3 hinges per body with
// random anchors, axes, reference angles and ranges, random sites.
std::string random_mjcf(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto vec = [&](double scale) {
    return std::to_string(scale * u(rng)) + " " + std::to_string(scale * u(rng)) + " " +
           std::to_string(scale * u(rng));
  };
  const auto quat = [&]() -> std::string {
    if (u(rng) > 0.6) return "0.7071067811865476 0 0.7071067811865476 0";  // pitch 90°
    return std::to_string(u(rng)) + " " + vec(1.0);
  };
  const int bodies = 1 + int((u(rng) + 1.0) * 6.0);
  std::vector<std::vector<int>> children(static_cast<std::size_t>(bodies));
  for (int b = 1; b < bodies; ++b) {
    children[std::size_t(std::uniform_int_distribution<int>(0, b - 1)(rng))].push_back(b);
  }
  int joints = 0, sites = 0;
  std::function<std::string(int)> body = [&](int b) {
    std::string xml = "<body name=\"b" + std::to_string(b) + "\" pos=\"" + vec(0.3) + "\" quat=\"" +
                      quat() + "\">";
    if (b == 0) {
      xml += "<freejoint/>";
    } else {
      const int hinges = std::uniform_int_distribution<int>(0, 3)(rng);
      for (int j = 0; j < hinges; ++j) {
        xml += "<joint name=\"j" + std::to_string(joints++) + "\" type=\"hinge\" pos=\"" +
               vec(0.1) + "\" axis=\"" + vec(1.0) + "\" ref=\"" + std::to_string(u(rng)) + "\"" +
               (u(rng) > 0.0 ? " range=\"-1 1.5\"" : "") + "/>";
      }
    }
    xml += "<inertial pos=\"" + vec(0.1) + "\" quat=\"" + quat() + "\" mass=\"" +
           std::to_string(1.5 + u(rng)) + "\" diaginertia=\"0.02 0.03 0.04\"/>";
    if (u(rng) > 0.3) {
      xml += "<site name=\"s" + std::to_string(sites++) + "\" pos=\"" + vec(0.2) + "\" quat=\"" +
             quat() + "\"/>";
    }
    for (int c : children[std::size_t(b)]) xml += body(c);
    return xml + "</body>";
  };
  return "<mujoco><compiler angle=\"radian\" autolimits=\"true\"/><worldbody>" + body(0) +
         "</worldbody></mujoco>";
}

TEST(MujocoKinematics, RandomRobotsAgreeWithMujoco) {
  std::mt19937 rng(11);
  Agreement worst;
  for (int robot = 0; robot < 100; ++robot) {
    const std::string path = write_temp("random_robot.xml", random_mjcf(rng));
    const Agreement a = compare(path, 20);
    ASSERT_GE(a.frames, 1) << "robot " << robot << " did not load";
    worst.position = std::max(worst.position, a.position);
    worst.rotation = std::max(worst.rotation, a.rotation);
    worst.com = std::max(worst.com, a.com);
  }
  EXPECT_LE(worst.position, 1e-9);
  EXPECT_LE(worst.rotation, 1e-9);
  EXPECT_LE(worst.com, 1e-9);
  RecordProperty("max_position_error_m", walkgen_test::scientific(worst.position));
  RecordProperty("max_rotation_error_rad", walkgen_test::scientific(worst.rotation));
  RecordProperty("max_com_error_m", walkgen_test::scientific(worst.com));
}

TEST(MujocoKinematics, ErrorsNameWhatIsWrong) {
  using walkgen_test::expect_invalid_argument;
  expect_invalid_argument(
      [] { (void)walkgen::kinematic_tree_from_mjcf_file("/nonexistent/robot.xml"); },
      {"/nonexistent/robot.xml", "an MJCF file MuJoCo loads"});
  const std::string biped = write_temp("small_biped.xml", kBiped);
  expect_invalid_argument([&] { (void)walkgen::kinematic_tree_from_mjcf_file(biped, "pelvis"); },
                          {"'pelvis'", "'base'", "'l_thigh'"});
  std::string slide = kBiped;
  slide.replace(slide.find(R"(<joint name="r_hip" axis="0 1 0"/>)"),
                std::string(R"(<joint name="r_hip" axis="0 1 0"/>)").size(),
                R"(<joint name="r_hip" type="slide" axis="0 0 1"/>)");
  expect_invalid_argument(
      [&] { (void)walkgen::kinematic_tree_from_mjcf_file(write_temp("slide.xml", slide)); },
      {"joint 'r_hip' of body 'r_thigh'", "hinge joints"});
  std::string two = kBiped;
  two.replace(
      two.find("</worldbody>"), 12,
      R"(<body name="box" pos="1 0 0.1"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body></worldbody>)");
  expect_invalid_argument(
      [&] { (void)walkgen::kinematic_tree_from_mjcf_file(write_temp("two.xml", two)); },
      {"one body below the world with a free joint", "'base', 'box'"});
  // Naming the base picks one of the two.
  EXPECT_EQ(walkgen::kinematic_tree_from_mjcf_file(write_temp("two.xml", two), "base").num_joints(),
            5);
}

}  // namespace
