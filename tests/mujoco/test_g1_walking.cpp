// The Unitree G1 walks under torque control (issue 23): the closed loop of figure 6.1 from its
// description file (models/unitree_g1/robot.yaml) with the balance feed-forward of its joint
// controller (MujocoRobot, JointFeedforward::balance: the contact forces under the CoM motion
// the pattern asks for, with CoM feedback). Without that feed-forward the same walk fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "walkgen/simulation/simulated_tasks.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

const walkgen::RobotDescription& g1() {
  static const walkgen::RobotDescription d = walkgen::find_robot_description("unitree_g1");
  return d;
}

/// The smallest support-polygon margin of the valid samples [m].
double worst_margin(const walkgen::TaskResult& r) {
  double worst = 1.0;
  for (const walkgen::TaskRow& row : r.rows) {
    if (row.zmp_valid) worst = std::min(worst, row.support_margin);
  }
  return worst;
}

TEST(G1Walking, TheFileAsksForTheBalanceFeedforwardWithoutRestartingTheNmpc) {
  EXPECT_TRUE(g1().balance.contact_feedforward);
  EXPECT_FALSE(g1().balance.nmpc_feedback);
  const walkgen::MujocoRobotSettings s = walkgen::mujoco_robot_settings(g1());
  EXPECT_EQ(s.feedforward, walkgen::JointFeedforward::balance);
  EXPECT_EQ(s.balance_kp, g1().balance.com_kp);
  EXPECT_FALSE(walkgen::loop_settings(g1()).com_feedback);
}

// The straight task of §9.2: 2 m to a target, torque-driven, steered by GoToTarget.
TEST(G1Walking, TheG1WalksTwoMetresStraightToTheTarget) {
  const walkgen::SimTask task = walkgen::section_9_2_tasks()[0];
  ASSERT_EQ(task.name, "straight");
  const walkgen::TaskResult r = walkgen::run_task(task, g1());
  double mean = 0.0, sd = 0.0;
  r.zmp_distance(mean, sd);
  std::printf(
      "G1 straight: %s after %.1f s, %.3f m from the target, mean speed %.3f m/s, ZMP error "
      "%.2f +- %.2f cm, true ZMP in the contact polygon %.1f %% (worst %.1f mm outside), lowest "
      "base %.3f m\n",
      r.reached ? "reached" : "NOT reached", r.time, r.final_distance, r.mean_speed(), 100.0 * mean,
      100.0 * sd, 100.0 * r.inside_fraction(), -1000.0 * worst_margin(r), r.min_base_height);
  EXPECT_TRUE(r.reached) << r.message;
  EXPECT_FALSE(r.fallen());
  EXPECT_EQ(r.qp_failures, 0);
  EXPECT_EQ(r.ik_failures, 0);
  EXPECT_GE(r.mean_speed(), 0.1);
  EXPECT_LE(mean, 0.05);
  // The support polygon is the feet's contact region (the file's sole_polygon: the spheres'
  // lowest points). The true ZMP never leaves it by more than the contacts' penetration; in
  // about a fifth of the samples it lies on its edge (a foot rolling on two spheres).
  EXPECT_GE(worst_margin(r), -0.0005);
  EXPECT_GE(r.inside_fraction(), 0.75);
  EXPECT_GE(r.min_base_height, 0.9 * 0.7634);
}

// Before: the same walk with the weight feed-forward alone (the contact forces at the measured
// CoM's projection, no CoM feedback) ends within seconds: the robot tips over a sole edge, its
// motors saturate and the loop stops it (or it falls).
TEST(G1Walking, WithTheWeightFeedforwardAloneTheSameWalkEndsWithinSeconds) {
  walkgen::RobotDescription weight_only = g1();
  weight_only.balance.contact_feedforward = false;
  walkgen::SimTask task = walkgen::section_9_2_tasks()[0];
  task.time_limit = 20.0;
  const walkgen::TaskResult r = walkgen::run_task(task, weight_only);
  std::printf("G1 straight, weight feed-forward only: %s after %.1f s (%s)\n",
              walkgen::to_string(r.status), r.time, r.message.c_str());
  EXPECT_FALSE(r.reached);
  EXPECT_NE(r.status, walkgen::LoopStatus::ok);
  EXPECT_LT(r.time, 10.0);
}

}  // namespace
