// URDF adapter: a small robot loads with the URDF conventions (inertial frames, continuous and
// fixed joints, default axis, ignored elements), and every kind of malformed document throws
// walkgen::invalid_argument naming the line and the element, never crashes.

#include "walkgen/urdf/urdf_loader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

const std::string kRobot = R"(<?xml version="1.0"?>
<robot name="small">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
  <link name="base">
    <inertial>
      <origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>
    </inertial>
    <visual><geometry><box size="1 1 1"/></geometry></visual>
  </link>
  <link name="wheel"/>
  <link name="arm"><inertial><mass value="0.5"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="tool"/>
  <joint name="spin" type="continuous">
    <parent link="base"/><child link="wheel"/><axis xyz="0 0 2"/>
  </joint>
  <joint name="lift" type="revolute">
    <origin xyz="0 0 0.5" rpy="0.1 0.2 0.3"/>
    <parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1.5" effort="10" velocity="1"/>
    <dynamics damping="0.1"/>
  </joint>
  <joint name="tool_fixed" type="fixed">
    <parent link="arm"/><child link="tool"/><origin xyz="0.3 0 0"/>
  </joint>
  <gazebo reference="arm"/>
  <transmission name="t"/>
  <sensor name="camera" update_rate="60"><parent link="tool"/></sensor>
</robot>
)";

TEST(Urdf, ReadsLinksJointsAndConventions) {
  const walkgen::KinematicDescription d = walkgen::kinematic_description_from_urdf(kRobot);
  EXPECT_EQ(d.name, "small");
  ASSERT_EQ(d.links.size(), 4u);
  ASSERT_EQ(d.joints.size(), 3u);
  const auto& base = d.links[0];
  EXPECT_EQ(base.name, "base");
  EXPECT_EQ(base.mass, 2.0);
  EXPECT_TRUE(base.com.isApprox(Eigen::Vector3d(0.1, 0, 0)));
  // The inertial frame is turned by 90° about z: ixx and iyy swap in the link frame.
  EXPECT_TRUE(base.inertia.isApprox(Eigen::Vector3d(2, 1, 3).asDiagonal().toDenseMatrix(), 1e-12))
      << base.inertia;
  EXPECT_EQ(d.links[1].mass, 0.0);  // no <inertial>: massless

  const auto& spin = d.joints[0];
  EXPECT_EQ(spin.type, walkgen::JointType::revolute);  // continuous: revolute without limits
  EXPECT_TRUE(std::isinf(spin.lower) && spin.lower < 0 && std::isinf(spin.upper));
  EXPECT_EQ(spin.axis, Eigen::Vector3d(0, 0, 2));
  const auto& lift = d.joints[1];
  EXPECT_EQ(lift.parent, "base");
  EXPECT_EQ(lift.child, "arm");
  EXPECT_EQ(lift.axis, Eigen::Vector3d::UnitX());  // URDF default
  EXPECT_EQ(lift.xyz, Eigen::Vector3d(0, 0, 0.5));
  EXPECT_EQ(lift.rpy, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(lift.lower, -1.0);
  EXPECT_EQ(lift.upper, 1.5);
  EXPECT_EQ(d.joints[2].type, walkgen::JointType::fixed);

  const auto tree = walkgen::kinematic_tree_from_urdf(kRobot);
  EXPECT_EQ(tree.num_joints(), 2);
  EXPECT_EQ(tree.joint_names(), (std::vector<std::string>{"spin", "lift"}));
  EXPECT_DOUBLE_EQ(tree.mass(), 2.5);
}

// Replaces the first occurrence of `from` in kRobot by `to`.
std::string robot_with(const std::string& from, const std::string& to) {
  std::string s = kRobot;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

std::string load_error(const std::string& urdf) {
  try {
    (void)walkgen::kinematic_tree_from_urdf(urdf, "robot.urdf");  // only the error is wanted
  } catch (const walkgen::invalid_argument& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
  return "no exception";
}

struct Malformed {
  std::string urdf;
  std::vector<std::string> message_parts;
};

TEST(Urdf, MalformedDocumentsThrowNamingLineAndElement) {
  const std::string lift_limit = R"(<limit lower="-1" upper="1.5" effort="10" velocity="1"/>)";
  const std::vector<Malformed> cases = {
      {"", {"robot.urdf:", "well-formed XML"}},
      {"<robot><link name='a'>", {"robot.urdf:", "well-formed XML"}},
      {"<model name='x'/>", {"a <robot> root element", "got <model>"}},
      {"<robot name='x'/>", {"at least one <link>"}},
      {robot_with(R"(<link name="wheel"/>)", "<link/>"), {"robot.urdf:12: <link> name", "none"}},
      {robot_with(R"(<mass value="2"/>)", ""), {"<link name='base'> <inertial>", "<mass> element"}},
      {robot_with(R"(<mass value="2"/>)", R"(<mass value="two"/>)"),
       {"robot.urdf:7: <link name='base'> <mass> value", "a finite number, got 'two'"}},
      {robot_with(R"(<mass value="2"/>)", R"(<mass value="-2"/>)"),
       {"<link name='base'> <mass> value", "a mass of 0 kg or in [1e-9, 1e6] kg, got -2"}},
      {robot_with(R"(<mass value="2"/>)", R"(<mass value="2kg"/>)"), {"got '2kg'"}},
      {robot_with(R"( izz="3")", ""), {"<link name='base'> <inertia> izz", "none"}},
      {robot_with(R"(<origin xyz="0 0 0.5")", R"(<origin xyz="0 0")"),
       {"robot.urdf:20: <joint name='lift'> <origin> xyz", "3 finite numbers, got '0 0'"}},
      {robot_with(R"(<origin xyz="0 0 0.5")", R"(<origin xyz="0 0 0.5 1")"), {"got '0 0 0.5 1'"}},
      {robot_with(R"(<origin xyz="0 0 0.5")", R"(<origin xyz="0 nan 0.5")"), {"got '0 nan 0.5'"}},
      {robot_with(R"(rpy="0.1 0.2 0.3")", R"(rpy="0.1,0.2,0.3")"), {"<origin> rpy"}},
      {robot_with(R"(type="revolute")", ""), {"<joint name='lift'> type", "none"}},
      {robot_with(R"(type="revolute")", R"(type="prismatic")"),
       {"<joint name='lift'> type", "revolute, continuous or fixed, got 'prismatic'"}},
      {robot_with(R"(type="revolute")", R"(type="floating")"), {"got 'floating'"}},
      {robot_with(R"(type="revolute")", R"(type="planar")"), {"got 'planar'"}},
      {robot_with(R"(<parent link="base"/><child link="arm"/>)", R"(<child link="arm"/>)"),
       {"<joint name='lift'>", "<parent> element"}},
      {robot_with(R"(<child link="arm"/>)", R"(<child name="arm"/>)"),
       {"<joint name='lift'> <child> link", "none"}},
      {robot_with(lift_limit, ""), {"<joint name='lift'>", "<limit> element"}},
      {robot_with(lift_limit, R"(<limit lower="2" upper="1"/>)"),
       {"<joint name='lift'> <limit>", "lower <= upper"}},
      {robot_with(lift_limit, R"(<limit lower="low" upper="1"/>)"), {"<limit> lower", "'low'"}},
      {robot_with(R"(<axis xyz="0 0 2"/>)", R"(<axis xyz="0 0 0"/>)"),
       {"<joint name='spin'> <axis> xyz", "non-zero axis"}},
      {robot_with(R"(<parent link="base"/><child link="arm"/>)",
                  R"(<parent link="bsae"/><child link="arm"/>)"),
       {"robot.urdf: KinematicTree: joint 'lift'", "parent link", "got 'bsae'"}},
      {robot_with(R"(<child link="wheel"/>)", R"(<child link="arm"/>)"),
       {"joint 'lift'", "only joint whose child is 'arm'"}},
      {robot_with(R"(<link name="tool"/>)", R"(<link name="tool"/><link name="extra"/>)"),
       {"exactly one root", "got 'base', 'extra'"}},
      {robot_with(R"(<parent link="arm"/><child link="tool"/>)",
                  R"(<parent link="tool"/><child link="tool"/>)"),
       {"below the root 'base'", "cycle through 'tool'"}},
      {robot_with(R"(<parent link="base"/><child link="wheel"/>)",
                  R"(<parent link="base"/><child link="base"/>)"),
       {"below the root 'wheel'", "cycle through 'base', 'arm', 'tool'"}},
      {robot_with(R"(<link name="wheel"/>)", R"(<link name="arm"/>)"),
       {"robot.urdf:13: <link name='arm'> name", "a unique link name",
        "got link 'arm' again after line 12"}},
      {robot_with(R"(<joint name="lift")", R"(<joint name="spin")"),
       {"robot.urdf:19: <joint name='spin'> name", "a unique joint name",
        "got joint 'spin' again after line 16"}},
      {robot_with(R"(<link name="wheel"/>)", R"(<link name=""/>)"),
       {"robot.urdf:12: <link name=''> name", "a non-empty name, got ''"}},
      {robot_with(R"(<joint name="lift")", R"(<joint name="")"), {"<joint name=''> name"}},
      {robot_with(R"(<child link="arm"/>)", R"(<child link=""/>)"),
       {"<joint name='lift'> <child> link", "a non-empty name"}},
      // Bounds (walkgen::UrdfBounds): every number finite and physically plausible.
      {robot_with(R"(<mass value="2"/>)", R"(<mass value="2e6"/>)"),
       {"<link name='base'> <mass> value", "[1e-9, 1e6] kg, got 2e+06"}},
      {robot_with(R"(<mass value="2"/>)", R"(<mass value="1e-12"/>)"), {"got 1e-12"}},
      {robot_with(R"(<mass value="2"/>)", R"(<mass value="1e999"/>)"),
       {"<mass> value", "a finite number, got '1e999'"}},
      {robot_with(R"(iyy="2")", R"(iyy="1e13")"),
       {"<link name='base'> <inertia> iyy", "an inertia entry in [-1e12, 1e12] kg m^2",
        "got '1e13'"}},
      {robot_with(R"(ixx="1" ixy="0")", R"(ixx="1" ixy="5")"),
       {"<link name='base'> <inertia>", "a positive semidefinite inertia", "principal moments"}},
      {robot_with(R"(ixx="1")", R"(ixx="-1")"), {"a positive semidefinite inertia"}},
      {robot_with(R"(<origin xyz="0 0 0.5")", R"(<origin xyz="0 0 1e4")"),
       {"<joint name='lift'> <origin> xyz", "3 coordinates in [-1000, 1000] m, got '0 0 1e4'"}},
      {robot_with(R"(<origin xyz="0.1 0 0")", R"(<origin xyz="0.1 -2e3 0")"),
       {"<link name='base'> <origin> xyz", "got '0.1 -2e3 0'"}},
      {robot_with(R"(rpy="0.1 0.2 0.3")", R"(rpy="0.1 0.2 1e300")"),
       {"<joint name='lift'> <origin> rpy", "3 angles in [-1000, 1000] rad"}},
      {robot_with(R"(<axis xyz="0 0 2"/>)", R"(<axis xyz="0 0 1e-7"/>)"),
       {"<joint name='spin'> <axis> xyz", "length in [1e-6, 1e6]", "got '0 0 1e-7'"}},
      {robot_with(R"(<axis xyz="0 0 2"/>)", R"(<axis xyz="1e-200 1e-200 0"/>)"),
       {"length in [1e-6, 1e6]"}},
      {robot_with(R"(<axis xyz="0 0 2"/>)", R"(<axis xyz="0 0 inf"/>)"),
       {"<axis> xyz", "3 finite numbers"}},
      {robot_with(lift_limit, R"(<limit lower="-1e9" upper="1"/>)"),
       {"<joint name='lift'> <limit> lower", "a limit in [-1000, 1000] rad, got '-1e9'"}},
      // Tree shape, found when the description is read (not only when a tree is built).
      {robot_with(R"(<parent link="base"/><child link="arm"/>)",
                  R"(<parent link="arm"/><child link="arm"/>)"),
       {"robot.urdf: KinematicTree", "cycle through 'arm', 'tool'"}},
  };
  for (const auto& c : cases) {
    const std::string message = load_error(c.urdf);
    for (const auto& part : c.message_parts) {
      EXPECT_NE(message.find(part), std::string::npos)
          << "'" << part << "' not in: " << message << "\nfor:\n"
          << c.urdf;
    }
  }
}

// Issue 21 reproducers (tests/data/reliability/urdf): each used to abort a Debug build or to load
// silently wrong values; each must now throw walkgen::invalid_argument naming the link or joint.
const std::string kReliability = std::string(WALKGEN_SOURCE_DIR) + "/tests/data/reliability/urdf/";

// The message of the walkgen::invalid_argument that loading `file` throws, or a description of
// what happened instead.
std::string file_error(const std::string& file) {
  try {
    const auto tree = walkgen::kinematic_tree_from_urdf_file(kReliability + file);
    return "expected a throw, but it loaded (total mass " + std::to_string(tree.mass()) + " kg)";
  } catch (const walkgen::invalid_argument& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
}

void expect_file_error(const std::string& file, const std::vector<std::string>& parts) {
  const std::string message = file_error(file);
  for (const auto& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos)
        << "'" << part << "' not in: " << message << "\nfor " << file;
  }
}

TEST(UrdfReliability, MalformedInertiaThrowsInsteadOfAbortingADebugBuild) {
  expect_file_error("urdf_bad_iyy_aborts_debug.urdf",
                    {"urdf_bad_iyy_aborts_debug.urdf:1: <link name='a'> <inertia> iyy",
                     "a finite number, got 'oops'"});
}

TEST(UrdfReliability, FuzzedHumanoidThrowsInsteadOfAbortingADebugBuild) {
  // A fuzzed copy of models/walkgen_humanoid.urdf: l_hip_1's iyy attribute is garbled.
  expect_file_error("urdf_fuzz_crash_commainit.urdf",
                    {"<link name='l_hip_1'> <inertia> iyy", "the attribute, got none"});
}

TEST(UrdfReliability, HugeAxisIsRejected) {
  expect_file_error("urdf_huge_axis.urdf",
                    {"urdf_huge_axis.urdf:3: <joint name='j'> <axis> xyz",
                     "a non-zero axis of length in [1e-6, 1e6], got '1e200 0 0'"});
}

TEST(UrdfReliability, MassOverflowIsRejected) {
  expect_file_error("urdf_mass_overflow.urdf",
                    {"urdf_mass_overflow.urdf:1: <link name='a'> <mass> value",
                     "a mass of 0 kg or in [1e-9, 1e6] kg, got 1e+308"});
}

TEST(Urdf, DescriptionIsCheckedAsATree) {
  // kinematic_description_from_urdf() checks the tree's shape too, naming the joint.
  try {
    (void)walkgen::kinematic_description_from_urdf(
        robot_with(R"(<parent link="base"/><child link="arm"/>)",
                   R"(<parent link="nowhere"/><child link="arm"/>)"),
        "robot.urdf");
    FAIL() << "a joint with an unknown parent loaded";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("robot.urdf: KinematicTree: joint 'lift'"),
              std::string::npos)
        << e.what();
  }
}

TEST(Urdf, MissingFileThrows) {
  try {
    (void)walkgen::kinematic_tree_from_urdf_file("/nonexistent/robot.urdf");
    FAIL();
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("a readable URDF file, got '/nonexistent/robot.urdf'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)walkgen::kinematic_description_from_urdf_file("/nonexistent/robot.urdf"),
               walkgen::invalid_argument);
}

}  // namespace
