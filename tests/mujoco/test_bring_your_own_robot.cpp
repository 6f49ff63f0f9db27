// "Bring your own robot" (issue 23 item 6, docs/robots.md): a third biped, written here as an
// MJCF with its own leg lengths, masses, joint order and feet, walks in MuJoCo from a robot
// description file alone. The test does what the docs tell a user to do: write the MJCF, write
// robot.yaml with the names, measure the walking geometry from forward kinematics of the stance,
// and run the library's closed loop (walkgen::run_task) with the file. No C++ of the library
// knows this robot.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "support/files.hpp"
#include "walkgen/mujoco/robot_model.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

/// A biped unlike walkgen's humanoid and the G1: thigh and shank of different lengths, heavier
/// pelvis, the hip joints in yaw-roll-pitch order, box feet of its own size, no torso joint, no
/// ankle sensors (the contact forces at the soles are the readings), position servos.
struct Biped {
  double thigh = 0.20, shank = 0.25;  ///< [m] leg segments (walkgen's humanoid: 0.22, 0.22)
  double hip_y = 0.075;               ///< [m] hip joints off the pelvis centre
  double pelvis_mass = 7.0, thigh_mass = 1.8, shank_mass = 1.1, foot_mass = 0.6;  ///< [kg]
  double foot_length = 0.18, foot_width = 0.09;                                   ///< [m]
  double bend = 0.45;  ///< [rad] the thigh's pitch in the stance (knees bent)
};

/// Diagonal inertia of a solid box of `mass` and full sides a, b, c, as MuJoCo's diaginertia.
std::string box_inertia(double mass, double a, double b, double c) {
  std::ostringstream o;
  o << mass * (b * b + c * c) / 12.0 << ' ' << mass * (a * a + c * c) / 12.0 << ' '
    << mass * (a * a + b * b) / 12.0;
  return o.str();
}

std::string leg(const Biped& b, const std::string& s, double side) {
  std::ostringstream o;
  o << "      <body name=\"" << s << "_hip\" pos=\"0 " << side * b.hip_y << " -0.06\">\n"
    << "        <joint name=\"" << s << "_hip_yaw\" axis=\"0 0 1\" range=\"-0.8 0.8\"/>\n"
    << "        <inertial pos=\"0 0 0\" mass=\"0.4\" diaginertia=\"3e-4 3e-4 3e-4\"/>\n"
    << "        <body name=\"" << s << "_hip_2\">\n"
    << "          <joint name=\"" << s << "_hip_roll\" axis=\"1 0 0\" range=\"-0.6 0.6\"/>\n"
    << "          <inertial pos=\"0 0 0\" mass=\"0.4\" diaginertia=\"3e-4 3e-4 3e-4\"/>\n"
    << "          <body name=\"" << s << "_thigh\">\n"
    << "            <joint name=\"" << s << "_hip_pitch\" axis=\"0 1 0\" range=\"-1.8 0.8\"/>\n"
    << "            <inertial pos=\"0 0 " << -b.thigh / 2 << "\" mass=\"" << b.thigh_mass
    << "\" diaginertia=\"" << box_inertia(b.thigh_mass, 0.07, 0.07, b.thigh) << "\"/>\n"
    << "            <geom type=\"capsule\" fromto=\"0 0 -0.03 0 0 " << -b.thigh + 0.03
    << "\" size=\"0.035\"/>\n"
    << "            <body name=\"" << s << "_shank\" pos=\"0 0 " << -b.thigh << "\">\n"
    << "              <joint name=\"" << s << "_knee\" axis=\"0 1 0\" range=\"0 2.2\"/>\n"
    << "              <inertial pos=\"0 0 " << -b.shank / 2 << "\" mass=\"" << b.shank_mass
    << "\" diaginertia=\"" << box_inertia(b.shank_mass, 0.06, 0.06, b.shank) << "\"/>\n"
    << "              <geom type=\"capsule\" fromto=\"0 0 -0.03 0 0 " << -b.shank + 0.03
    << "\" size=\"0.03\"/>\n"
    << "              <body name=\"" << s << "_ankle\" pos=\"0 0 " << -b.shank << "\">\n"
    << "                <joint name=\"" << s << "_ankle_pitch\" axis=\"0 1 0\" range=\"-1 1\"/>\n"
    << "                <inertial pos=\"0 0 0\" mass=\"0.2\" diaginertia=\"1e-4 1e-4 1e-4\"/>\n"
    << "                <body name=\"" << s << "_foot\">\n"
    << "                  <joint name=\"" << s
    << "_ankle_roll\" axis=\"1 0 0\" range=\"-0.5 0.5\"/>\n"
    << "                  <inertial pos=\"0 0 -0.03\" mass=\"" << b.foot_mass << "\" diaginertia=\""
    << box_inertia(b.foot_mass, b.foot_length, b.foot_width, 0.02) << "\"/>\n"
    << "                  <geom type=\"box\" size=\"" << b.foot_length / 2 << ' '
    << b.foot_width / 2 << " 0.01\" pos=\"0 0 -0.03\"/>\n"
    << "                  <site name=\"" << s << "_sole\" pos=\"0 0 -0.04\"/>\n"
    << "                </body>\n              </body>\n            </body>\n          </body>\n"
    << "        </body>\n      </body>\n";
  return o.str();
}

std::string biped_mjcf(const Biped& b) {
  std::ostringstream o;
  o << "<mujoco model=\"byo_biped\">\n"
    << "  <compiler angle=\"radian\" autolimits=\"true\"/>\n"
    << "  <option timestep=\"0.002\"/>\n"
    << "  <default>\n"
    << "    <joint damping=\"8\" armature=\"0.01\"/>\n"
    << "    <geom contype=\"2\" conaffinity=\"1\" condim=\"3\" friction=\"1 0.005 0.0001\"/>\n"
    << "  </default>\n"
    << "  <worldbody>\n"
    << "    <light pos=\"0 0 4\" dir=\"0 0 -1\" directional=\"true\"/>\n"
    << "    <geom name=\"floor\" type=\"plane\" size=\"0 0 0.05\" contype=\"1\" "
       "conaffinity=\"1\"/>\n"
    << "    <body name=\"pelvis\" pos=\"0 0 0.6\">\n"
    << "      <freejoint name=\"root\"/>\n"
    << "      <site name=\"imu\"/>\n"
    << "      <inertial pos=\"0 0 0.04\" mass=\"" << b.pelvis_mass << "\" diaginertia=\""
    << box_inertia(b.pelvis_mass, 0.12, 0.2, 0.14) << "\"/>\n"
    << "      <geom type=\"box\" size=\"0.06 0.1 0.07\" pos=\"0 0 0.04\"/>\n"
    << leg(b, "left", 1.0) << leg(b, "right", -1.0) << "    </body>\n"
    << "  </worldbody>\n  <actuator>\n";
  for (const char* s : {"left", "right"}) {
    for (const char* j :
         {"hip_yaw", "hip_roll", "hip_pitch", "knee", "ankle_pitch", "ankle_roll"}) {
      o << "    <position name=\"" << s << '_' << j << "\" joint=\"" << s << '_' << j
        << "\" kp=\"1500\" forcerange=\"-120 120\"/>\n";
    }
  }
  o << "  </actuator>\n  <sensor>\n"
    << "    <framequat name=\"imu_quat\" objtype=\"site\" objname=\"imu\"/>\n"
    << "    <gyro name=\"imu_gyro\" site=\"imu\"/>\n"
    << "    <accelerometer name=\"imu_acc\" site=\"imu\"/>\n"
    << "  </sensor>\n</mujoco>\n";
  return o.str();
}

/// robot.yaml of the biped; `walking` is the file's walking section (may be empty).
std::string biped_yaml(const Biped& b, const std::string& walking) {
  // Feet flat (hip pitch + knee + ankle pitch = 0) with the ankle under the hip: the shank's
  // angle from the vertical follows from the thigh's by the segments' lengths.
  const double shank_angle = std::asin(b.thigh * std::sin(b.bend) / b.shank);
  std::ostringstream o;
  o.precision(17);
  o << "name: byo_biped\n"
    << "mjcf: byo_biped.xml\n"
    << "base_body: pelvis\n"
    << "imu_site: imu\n"
    << "joints: [left_hip_yaw, left_hip_roll, left_hip_pitch, left_knee, left_ankle_pitch,\n"
    << "         left_ankle_roll, right_hip_yaw, right_hip_roll, right_hip_pitch, right_knee,\n"
    << "         right_ankle_pitch, right_ankle_roll]\n"
    << "sole_frames: [left_sole, right_sole]\n"
    << "stand_pose: {";
  for (const char* s : {"left", "right"}) {
    o << s << "_hip_pitch: " << -b.bend << ", " << s << "_knee: " << b.bend + shank_angle << ", "
      << s << "_ankle_pitch: " << -shank_angle << (std::string(s) == "left" ? ", " : "}\n");
  }
  o << "walking_preset: heicub\n" << walking;
  return o.str();
}

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

TEST(BringYourOwnRobot, ASmallBipedWalksTenSecondsFromItsDescriptionFileAlone) {
  const Biped b;
  const std::filesystem::path folder = walkgen_test::fresh_folder("byo_biped");
  write(folder / "byo_biped.xml", biped_mjcf(b));
  write(folder / "robot.yaml", biped_yaml(b, ""));
  // docs/robots.md step 4: the walking geometry from forward kinematics of the stance.
  const walkgen::RobotDescription first =
      walkgen::find_robot_description((folder / "robot.yaml").string());
  const walkgen::KinematicTree<double> tree = walkgen::robot_kinematic_tree_from_mjcf(first);
  ASSERT_EQ(tree.num_joints(), 12);
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                          walkgen::stand_configuration(tree, first), ws);
  const Eigen::Vector3d left = ws.position_W(tree.link_index("left_sole"));
  const Eigen::Vector3d right = ws.position_W(tree.link_index("right_sole"));
  const Eigen::Vector3d com = tree.center_of_mass(ws);
  EXPECT_NEAR(left.x(), 0.0, 1e-9);  // the ankles are under the hips
  EXPECT_NEAR(left.z(), right.z(), 1e-12);
  const double foot_distance = left.y() - right.y(), com_z = com.z() - left.z();
  EXPECT_NEAR(foot_distance, 2.0 * b.hip_y, 1e-12);
  std::ostringstream walking;
  walking.precision(17);
  walking << "walking:\n  geometry: {foot_length: " << b.foot_length
          << ", foot_width: " << b.foot_width << ", foot_distance: " << foot_distance
          << ", com_z: " << com_z << "}\n  initial_state: {com_y: [" << foot_distance / 2
          << ", 0, 0], foot_y: " << foot_distance / 2 << "}\n";
  write(folder / "robot.yaml", biped_yaml(b, walking.str()));
  const walkgen::RobotDescription robot =
      walkgen::find_robot_description((folder / "robot.yaml").string());
  EXPECT_EQ(robot.name, "byo_biped");

  // Ten seconds of walking (after the weight transfer) towards a target 1 m ahead.
  walkgen::SimTask task{"straight", "walk ahead", {1.0, 0.0}, {}, 10.0};
  const walkgen::TaskResult r = walkgen::run_task(task, robot, 0.0);
  EXPECT_EQ(r.status, walkgen::LoopStatus::ok) << r.message;
  EXPECT_FALSE(r.fallen());
  EXPECT_NEAR(r.time, 10.0, 0.02);
  EXPECT_EQ(r.qp_failures, 0);
  EXPECT_EQ(r.ik_failures, 0);
  // The true ZMP stayed in the true support polygon, and the robot walked: the true CoM moved as
  // the plan asked (ahead, and sideways by the sway of the step it ends in).
  // At a few samples as a foot lands (10 of 1000 here) the true ZMP lies on a sole's edge, up
  // to 0.14 mm outside by the contacts' penetration: never further out than 0.5 mm.
  EXPECT_GE(r.inside_fraction(), 0.98);
  double worst = 1.0;
  for (const walkgen::TaskRow& row : r.rows) {
    if (row.zmp_valid) worst = std::min(worst, row.support_margin);
  }
  EXPECT_GE(worst, -5e-4);
  ASSERT_GE(r.rows.size(), 900u);
  const Eigen::Vector2d moved = r.rows.back().com_true - r.rows.front().com_true;
  const Eigen::Vector2d planned = r.rows.back().com_plan - r.rows.front().com_plan;
  std::printf(
      "byo_biped: 10 s walked, true CoM moved (%.3f, %.3f) m, planned (%.3f, %.3f) m; "
      "ZMP inside %.2f %% (worst margin %.2f mm); lowest base %.3f m\n",
      moved.x(), moved.y(), planned.x(), planned.y(), 100.0 * r.inside_fraction(), 1000.0 * worst,
      r.min_base_height);
  EXPECT_GE(planned.x(), 0.15);
  EXPECT_NEAR(moved.x(), planned.x(), 0.05 * planned.x() + 0.01);
  EXPECT_NEAR(moved.y(), planned.y(), 0.01);
  EXPECT_GE(r.min_base_height, 0.9 * r.rows.front().base_height);
}

}  // namespace
