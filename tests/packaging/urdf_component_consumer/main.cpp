// Packaging check of the URDF adapter: a program built against walkgen::urdf must compile, link
// against tinyxml2, load a robot and compute its forward kinematics.
#include <cstdio>

#include <walkgen/urdf/urdf_loader.hpp>

int main() {
  const char* urdf =
      "<robot name='pendulum'><link name='base'/>"
      "<link name='bob'><inertial><origin xyz='0 0 -1'/><mass value='2'/>"
      "<inertia ixx='0' ixy='0' ixz='0' iyy='0' iyz='0' izz='0'/></inertial></link>"
      "<joint name='swing' type='continuous'><parent link='base'/><child link='bob'/>"
      "<axis xyz='0 1 0'/></joint></robot>";
  const auto tree = walkgen::kinematic_tree_from_urdf(urdf);
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                          Eigen::VectorXd::Zero(1), ws);
  const Eigen::Vector3d com = tree.center_of_mass(ws);
  std::printf("%d joint, mass %g kg, CoM z = %g m\n", tree.num_joints(), tree.mass(), com.z());
  if (tree.num_joints() != 1 || com.z() != -1.0) {
    std::fprintf(stderr, "wrong answer: expected 1 joint and the CoM at z = -1\n");
    return 1;
  }
  try {
    (void)walkgen::kinematic_tree_from_urdf("<robot><link name='a'><inertial/></link></robot>");
  } catch (const walkgen::invalid_argument& e) {
    std::printf("malformed URDF rejected: %s\n", e.what());
    return 0;
  }
  std::fprintf(stderr, "a malformed URDF was accepted\n");
  return 1;
}
