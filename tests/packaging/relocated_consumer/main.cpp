// A consumer of a moved walkgen installation (ctest install_relocated): walkgen::data_dir() is the
// moved prefix's share/walkgen, the default MujocoRobot loads walkgen's humanoid from there, and
// the library's closed loop (walkgen::SimLoop: NMPC, interpolation, Ceres IK, MuJoCo) walks it
// for three NMPC ticks (1.2 s).
#include <cmath>
#include <cstdio>
#include <string>

#include <walkgen/core/data_dir.hpp>
#include <walkgen/simulation/humanoid_loop.hpp>
#include <walkgen/walkgen.hpp>

int main() {
  const std::string dir = walkgen::data_dir();
  std::printf("walkgen::data_dir() = %s\n", dir.c_str());
  if (dir != EXPECTED_DATA_DIR) {
    std::fprintf(stderr, "FAIL: data_dir() is '%s', expected the moved prefix's '%s'\n",
                 dir.c_str(), EXPECTED_DATA_DIR);
    return 1;
  }
  try {
    walkgen::MujocoRobot robot;  // the default model: data_dir()/models/walkgen_humanoid.xml
    const auto tree = walkgen::humanoid_tree();  // data_dir()/models/walkgen_humanoid.urdf
    walkgen::HumanoidIk ik(tree);
    walkgen::SimLoop loop(walkgen::heicub_settings(), robot, ik);
    if (loop.start().status != walkgen::LoopStatus::ok) {
      std::fprintf(stderr, "FAIL: start() did not succeed\n");
      return 1;
    }
    const Eigen::Vector2d c0 = walkgen::true_com(robot);  // MuJoCo's CoM (ground truth)
    const auto command_status = loop.set_command({0.03, 0.0, 0.0});
    if (command_status != walkgen::CommandStatus::accepted) {
      std::fprintf(stderr, "FAIL: the command was not accepted: %s\n",
                   walkgen::to_string(command_status));
      return 1;
    }
    double t = 0.0;
    while (t < 1.0 - 1e-9) {
      const walkgen::LoopTick& tick = loop.tick();
      if (tick.status != walkgen::LoopStatus::ok) {
        std::fprintf(stderr, "FAIL: tick at t = %.1f s: %s\n", t, walkgen::to_string(tick.status));
        return 1;
      }
      t += loop.mpc().settings().t;
    }
    const Eigen::Vector2d c1 = walkgen::true_com(robot);
    const auto& state = loop.mpc().state();
    const double tracking = (c1 - Eigen::Vector2d(state.com_x[0], state.com_y[0])).norm();
    std::printf(
        "walked %.1f s: CoM (%.4f, %.4f) -> (%.4f, %.4f) m, %.4f m from the plan, base "
        "height %.3f m\n",
        t, c0.x(), c0.y(), c1.x(), c1.y(), tracking, robot.output().base_height);
    if (!(c1.allFinite() && robot.output().status == walkgen::RobotStatus::ok)) {
      std::fprintf(stderr, "FAIL: the robot is not standing after one second\n");
      return 1;
    }
    // Walking starts by shifting the CoM over the support foot: it moves by centimetres and
    // follows the NMPC's plan to millimetres.
    if (!((c1 - c0).norm() > 0.005 && tracking < 0.02)) {
      std::fprintf(stderr,
                   "FAIL: the CoM moved %.4f m (expected > 0.005) and is %.4f m from the "
                   "plan (expected < 0.02)\n",
                   (c1 - c0).norm(), tracking);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FAIL: %s\n", e.what());
    return 1;
  }
  return 0;
}
