// Packaging check of the Ceres adapter: a program built against walkgen::ceres must compile,
// link against Ceres and solve a small inverse-kinematics problem.
#include <cmath>
#include <cstdio>
#include <string>

#include <walkgen/ceres/inverse_kinematics.hpp>

int main() {
  // A root with two feet and a torso that turns about z.
  walkgen::KinematicDescription d;
  for (const char* name : {"root", "lf", "rf", "torso"}) {
    walkgen::LinkDescription l;
    l.name = name;
    l.mass = 1.0;
    d.links.push_back(l);
  }
  for (const char* foot : {"lf", "rf"}) {
    walkgen::JointDescription j;
    j.name = std::string(foot) + "_fixed";
    j.parent = "root";
    j.child = foot;
    j.xyz = Eigen::Vector3d(0.0, foot[0] == 'l' ? 0.1 : -0.1, -0.5);
    d.joints.push_back(j);
  }
  walkgen::JointDescription spin;
  spin.name = "spin";
  spin.type = walkgen::JointType::revolute;
  spin.parent = "root";
  spin.child = "torso";
  spin.axis = Eigen::Vector3d::UnitZ();
  spin.lower = -1.0;
  spin.upper = 1.0;
  d.joints.push_back(spin);
  walkgen::CeresIkSettings s;
  s.left_foot_link = "lf";
  s.right_foot_link = "rf";
  s.torso_link = "torso";
  walkgen::CeresInverseKinematics<1> ik(walkgen::KinematicTree<double>(d), s);

  walkgen::IkTarget t;  // stand 0.5 m above the feet, torso turned by 0.3 rad
  t.com_W = Eigen::Vector3d(0.0, 0.0, 0.25);
  t.left_foot.position_W = Eigen::Vector3d(0.0, 0.1, 0.0);
  t.right_foot.position_W = Eigen::Vector3d(0.0, -0.1, 0.0);
  t.torso_rotation_W = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const walkgen::IkResult r = ik.solve(t);
  std::printf("status %d after %d iterations, spin = %g rad, base z = %g m\n", int(r.status),
              r.iterations, ik.q()[0], ik.base_position_W().z());
  if (r.status != walkgen::IkStatus::converged || std::abs(ik.q()[0] - 0.3) > 1e-6) {
    std::fprintf(stderr, "wrong answer: expected convergence and spin = 0.3 rad\n");
    return 1;
  }
  return 0;
}
