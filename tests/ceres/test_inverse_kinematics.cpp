// Whole-body inverse kinematics through Ceres (include/walkgen/ceres/inverse_kinematics.hpp) on
// walkgen's humanoid: round trips from random reachable targets, a Heicub walk of the NMPC
// sample by sample, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "support/humanoid_ik.hpp"
#include "support/kinematics.hpp"

namespace {

using walkgen::IkStatus;
using walkgen::IkTarget;
using walkgen_test::HumanoidIk;

const walkgen::KinematicTree<double>& tree() {
  static const walkgen::KinematicTree<double> t = walkgen_test::humanoid_tree();
  return t;
}

bool within_limits(const Eigen::VectorXd& q) {
  return (q.array() >= tree().lower_limits().array()).all() &&
         (q.array() <= tree().upper_limits().array()).all();
}

double max_error(const walkgen::IkResult& r) {
  return std::max({r.com_error, r.foot_position_error, r.foot_yaw_error, r.foot_tilt_error,
                   r.base_orientation_error, r.torso_orientation_error});
}

/// A random reachable target: a random in-limit configuration under a random base pose, with
/// the ankles turned so that both soles lie flat (rejected where that leaves the ankle limits).
/// Returns the target and writes the configuration's left sole position.
IkTarget random_reachable_target(std::mt19937& rng) {
  const auto& t = tree();
  auto ws = t.make_workspace();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    Eigen::VectorXd q = walkgen_test::random_configuration(t, rng);
    const Eigen::Vector3d tilt_axis(u(rng), u(rng), 0.0);
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(M_PI * u(rng), Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(0.3 * u(rng), tilt_axis.normalized()))
                                  .toRotationMatrix();
    const Eigen::Vector3d p(u(rng), u(rng), 0.5);
    t.forward_kinematics(p, R, q, ws);
    bool in_limits = true;
    for (const char* side : {"l_", "r_"}) {
      const std::string s(side);
      // sole = lower leg · Ry(ankle pitch) · Rx(ankle roll): flat when that maps z to z.
      const int shank = t.link_index(s + "lower_leg");
      const Eigen::Vector3d v = ws.rotation_W(shank).transpose() * Eigen::Vector3d::UnitZ();
      const int pitch = t.joint_index(s + "ankle_pitch"), roll = t.joint_index(s + "ankle_roll");
      q[pitch] = std::atan2(v.x(), v.z());
      q[roll] = -std::asin(v.y());
      for (int j : {pitch, roll}) {
        in_limits = in_limits && q[j] >= t.lower_limits()[j] && q[j] <= t.upper_limits()[j];
      }
    }
    if (!in_limits) continue;
    t.forward_kinematics(p, R, q, ws);
    IkTarget target;
    target.com_W = t.center_of_mass(ws);
    for (const char* side : {"l_", "r_"}) {
      const std::string s(side);
      const int sole = t.link_index(s + "sole");
      const Eigen::Matrix3d& Rs = ws.rotation_W(sole);
      EXPECT_LT(std::hypot(Rs(0, 2), Rs(1, 2)), 1e-12);  // flat
      (s == "l_" ? target.left_foot : target.right_foot) =
          walkgen::SoleTarget{ws.position_W(sole), std::atan2(Rs(1, 0), Rs(0, 0))};
    }
    target.base_rotation_W = R;
    target.torso_rotation_W = ws.rotation_W(t.link_index("chest"));
    return target;
  }
}

TEST(CeresInverseKinematics, RoundTripOfRandomReachableTargets) {
  HumanoidIk ik(tree());
  std::mt19937 rng(20240604);
  const int trials = 1000;
  int successes = 0, iterations = 0, runs = 0;
  double worst = 0.0;
  for (int i = 0; i < trials; ++i) {
    const IkTarget target = random_reachable_target(rng);
    walkgen_test::start_standing(
        ik, target.left_foot.position_W,
        std::atan2(target.base_rotation_W(1, 0), target.base_rotation_W(0, 0)));
    const Eigen::VectorXd before = ik.q();
    const walkgen::IkResult r = ik.solve(target);
    iterations += r.iterations;
    runs += r.runs;
    ASSERT_TRUE(ik.q().allFinite());
    ASSERT_TRUE(within_limits(ik.q()));
    if (r.status == IkStatus::converged) {
      ASSERT_TRUE(r.applied);
      EXPECT_LE(r.com_error, 1e-6);
      EXPECT_LE(r.foot_position_error, 1e-6);
      EXPECT_LE(r.foot_yaw_error, 1e-6);
      EXPECT_LE(r.foot_tilt_error, 1e-6);
      worst = std::max(worst, max_error(r));
      ++successes;
    } else {
      EXPECT_FALSE(r.applied);
      EXPECT_EQ(ik.q(), before);  // kept
    }
  }
  const double rate = double(successes) / trials;
  std::printf(
      "IK round trip: %d / %d converged (%.1f %%), worst error %.2e, %.1f iterations and "
      "%.2f runs per solve\n",
      successes, trials, 100.0 * rate, worst, double(iterations) / trials, double(runs) / trials);
  RecordProperty("success_rate", walkgen_test::scientific(rate));
  RecordProperty("worst_error", walkgen_test::scientific(worst));
  EXPECT_GE(rate, 0.995);
}

/// IK at every command sample of a Heicub walk: converges every time, smooth joint motion.
void walk_and_check(const Eigen::Vector3d& command, int ticks) {
  const auto samples = walkgen_test::heicub_walk(command, ticks);
  HumanoidIk ik(tree());
  walkgen_test::start_walk(ik, samples.front());
  const double dt = walkgen::heicub_settings().command_period;
  Eigen::VectorXd previous_q, previous_v;
  double max_speed = 0.0, max_jump = 0.0, worst = 0.0;
  int iterations = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const walkgen::IkResult r = ik.solve(walkgen::ik_target(samples[k]));
    ASSERT_EQ(r.status, IkStatus::converged)
        << "sample " << k << " t = " << samples[k].time << " com " << r.com_error << " foot "
        << r.foot_position_error << " yaw " << r.foot_yaw_error << " tilt " << r.foot_tilt_error
        << " base " << r.base_orientation_error << " torso " << r.torso_orientation_error << " it "
        << r.iterations << " q " << ik.q().transpose();
    ASSERT_TRUE(within_limits(ik.q()));
    worst = std::max(worst, max_error(r));
    if (k > 0) iterations += r.iterations;
    if (k > 0) {
      const Eigen::VectorXd v = (ik.q() - previous_q) / dt;
      max_speed = std::max(max_speed, v.cwiseAbs().maxCoeff());
      if (k > 1) max_jump = std::max(max_jump, (v - previous_v).cwiseAbs().maxCoeff());
      previous_v = v;
    }
    previous_q = ik.q();
  }
  std::printf(
      "walk (%.3f, %.3f, %.3f): %zu samples, worst error %.2e, %.2f iterations per warm "
      "solve, max joint speed %.3f rad/s, max jump of the joint speed %.4f rad/s\n",
      command.x(), command.y(), command.z(), samples.size(), worst,
      double(iterations) / double(samples.size() - 1), max_speed, max_jump);
  // Walking at these speeds, no joint turns faster than 2 rad/s, and its finite-difference speed
  // changes by less than 0.1 rad/s from one 10 ms sample to the next (10 rad/s², no jumps).
  EXPECT_LT(max_speed, 2.0);
  EXPECT_LT(max_jump, 0.1);
}

TEST(CeresInverseKinematics, HeicubWalkForwardHasSmoothJoints) {
  walk_and_check(Eigen::Vector3d(0.03, 0.0, 0.0), 32);
}

TEST(CeresInverseKinematics, HeicubWalkCurvedHasSmoothJoints) {
  walk_and_check(Eigen::Vector3d(0.02, 0.0, 0.05), 32);
}

TEST(CeresInverseKinematics, DynamicJointCountMatchesFixed) {
  walkgen::CeresInverseKinematics<Eigen::Dynamic> dynamic(tree());
  HumanoidIk fixed(tree());
  std::mt19937 rng(7);
  for (int i = 0; i < 5; ++i) {
    const IkTarget target = random_reachable_target(rng);
    walkgen_test::start_standing(dynamic, target.left_foot.position_W);
    walkgen_test::start_standing(fixed, target.left_foot.position_W);
    const auto a = dynamic.solve(target), b = fixed.solve(target);
    EXPECT_EQ(a.status, b.status);
    if (a.status == IkStatus::converged) {
      EXPECT_LE(max_error(a), 1e-6);
      EXPECT_TRUE(dynamic.q().isApprox(fixed.q(), 1e-6));
    }
  }
}

TEST(CeresInverseKinematics, NonFiniteTargetKeepsTheSolution) {
  HumanoidIk ik(tree());
  walkgen_test::start_standing(ik, Eigen::Vector3d(0, 0.07, 0));
  const Eigen::VectorXd q = ik.q();
  IkTarget target;
  target.com_W = Eigen::Vector3d(0.0, 0.0, std::nan(""));
  const walkgen::IkResult r = ik.solve(target);
  EXPECT_EQ(r.status, IkStatus::invalid_input);
  EXPECT_FALSE(r.applied);
  EXPECT_EQ(r.runs, 0);
  EXPECT_EQ(ik.q(), q);
}

TEST(CeresInverseKinematics, UnreachableTargetKeepsTheSolution) {
  walkgen::CeresIkSettings s;
  s.n_init = 2;
  s.num_steps = 100;
  HumanoidIk ik(tree(), s);
  walkgen_test::start_standing(ik, Eigen::Vector3d(0, 0.07, 0));
  const Eigen::VectorXd q = ik.q();
  IkTarget target;
  target.com_W = Eigen::Vector3d(0.0, 0.0, 0.45);
  target.left_foot.position_W = Eigen::Vector3d(0.0, 0.5, 0.0);  // legs 0.4 m long: too far
  target.right_foot.position_W = Eigen::Vector3d(0.0, -0.5, 0.0);
  const walkgen::IkResult r = ik.solve(target);
  EXPECT_EQ(r.status, IkStatus::not_converged);
  EXPECT_FALSE(r.applied);
  EXPECT_EQ(r.runs, 2);
  EXPECT_GT(r.foot_position_error, 1e-3);
  EXPECT_EQ(ik.q(), q);
  EXPECT_TRUE(ik.q().allFinite());
}

TEST(CeresInverseKinematics, BadInputThrows) {
  walkgen::CeresIkSettings s;
  s.left_foot_link = "no_such_link";
  EXPECT_THROW(HumanoidIk(tree(), s), walkgen::invalid_argument);
  s = walkgen::CeresIkSettings();
  s.lambda = 0.0;
  EXPECT_THROW(HumanoidIk(tree(), s), walkgen::invalid_argument);
  s = walkgen::CeresIkSettings();
  s.n_init = 0;
  EXPECT_THROW(HumanoidIk(tree(), s), walkgen::invalid_argument);
  EXPECT_THROW(walkgen::CeresInverseKinematics<3>{tree()}, walkgen::invalid_argument);

  HumanoidIk ik(tree());
  EXPECT_THROW(ik.set_initial_guess(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                    Eigen::VectorXd::Zero(3)),
               walkgen::invalid_argument);
  EXPECT_THROW(ik.set_initial_guess(Eigen::Vector3d::Zero(), 2.0 * Eigen::Matrix3d::Identity(),
                                    Eigen::VectorXd::Zero(15)),
               walkgen::invalid_argument);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(15);
  q[0] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ik.set_initial_guess(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q),
               walkgen::invalid_argument);
  // Out-of-limit guesses are clamped: the knee cannot bend backwards.
  q.setZero();
  q[tree().joint_index("l_knee")] = -1.0;
  ik.set_initial_guess(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q);
  EXPECT_EQ(ik.q()[tree().joint_index("l_knee")], 0.0);
}

}  // namespace
