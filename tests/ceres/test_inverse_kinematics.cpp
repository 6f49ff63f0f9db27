// Whole-body inverse kinematics through Ceres (include/walkgen/ceres/inverse_kinematics.hpp) on
// walkgen's humanoid: round trips from random reachable targets, a Heicub walk of the NMPC
// sample by sample, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "support/derivatives.hpp"
#include "support/enum_strings.hpp"
#include "support/expect_error.hpp"
#include "support/kinematics.hpp"
#include "walkgen/control/pattern_targets.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/humanoid/humanoid_ik.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

namespace {

using walkgen::HumanoidIk;
using walkgen::IkStatus;
using walkgen::IkTarget;

const walkgen::KinematicTree<double>& tree() {
  static const walkgen::KinematicTree<double> t = walkgen::humanoid_tree();
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
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(walkgen::kPi * u(rng), Eigen::Vector3d::UnitZ()) *
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
          walkgen::SoleTarget{ws.position_W(sole), walkgen::yaw_of(Rs)};
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
    walkgen::start_standing(ik, target.left_foot.position_W,
                            walkgen::yaw_of(target.base_rotation_W));
    const Eigen::VectorXd before = ik.q();
    const walkgen::IkResult r = ik.solve(target);
    iterations += r.iterations;
    runs += r.runs;
    ASSERT_TRUE(ik.q().allFinite());
    ASSERT_TRUE(within_limits(ik.q()));
    if (r.status == IkStatus::converged) {
      ASSERT_TRUE(r.applied);
      EXPECT_STREQ(r.message, "");
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

/// IK at every command sample of a Heicub walk (heicub_settings() unchanged: com_z = 0.45 m) of
/// scenario `name`: converges every time, smooth joint motion.
void walk_and_check(const std::string& name, int ticks, int phase = 8) {
  const walkgen::PatternWalk walk =
      walkgen::heicub_walk([&](int k) { return walkgen::heicub_scenario_command(name, k, phase); },
                           ticks, walkgen::heicub_obstacle(name));
  ASSERT_TRUE(walk.ok()) << walk.message;
  const auto& samples = walk.samples;
  HumanoidIk ik(tree());
  walkgen::start_walk(ik, samples.front());
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
      "walk %s: %zu samples, 0 failures, worst error %.2e, %.2f iterations per warm solve, max "
      "joint speed %.3f rad/s, max jump of the joint speed %.4f rad/s\n",
      name.c_str(), samples.size(), worst, double(iterations) / double(samples.size() - 1),
      max_speed, max_jump);
  ::testing::Test::RecordProperty("samples", int(samples.size()));
  ::testing::Test::RecordProperty("max_joint_speed", walkgen_test::scientific(max_speed));
  ::testing::Test::RecordProperty("max_joint_speed_jump", walkgen_test::scientific(max_jump));
  // Walking at these speeds, no joint turns faster than 2 rad/s, and its finite-difference speed
  // changes by less than 0.1 rad/s from one 10 ms sample to the next (10 rad/s², no jumps).
  EXPECT_LT(max_speed, 2.0);
  EXPECT_LT(max_jump, 0.1);
}

// The pattern generator's scenarios at Heicub's speeds (walkgen::heicub_scenario_command):
// two gait cycles (32 ticks of 0.4 s, 1280 samples) each; the sequence changes its command every
// step (8 ticks) for five steps.
TEST(CeresInverseKinematics, HeicubWalkStraightHasSmoothJoints) { walk_and_check("straight", 32); }

TEST(CeresInverseKinematics, HeicubWalkSidewaysHasSmoothJoints) { walk_and_check("sideways", 32); }

TEST(CeresInverseKinematics, HeicubWalkCurvedHasSmoothJoints) { walk_and_check("curved", 32); }

TEST(CeresInverseKinematics, HeicubTurnOnTheSpotHasSmoothJoints) { walk_and_check("turn", 32); }

TEST(CeresInverseKinematics, HeicubCommandSequenceHasSmoothJoints) {
  walk_and_check("sequence", 40, 8);
}

// Obstacle avoidance at Heicub's scale (walkgen::heicub_obstacle): four gait cycles, the
// footsteps keep radius + margin from the obstacle and the walk ends past it.
TEST(CeresInverseKinematics, HeicubObstacleAvoidanceHasSmoothJoints) {
  walk_and_check("obstacle", 64);
  const auto obstacle = walkgen::heicub_obstacle("obstacle").front();
  const walkgen::PatternWalk walk = walkgen::heicub_walk(
      [](int k) { return walkgen::heicub_scenario_command("obstacle", k, 8); }, 64, {obstacle});
  ASSERT_TRUE(walk.ok()) << walk.message;
  const auto& samples = walk.samples;
  for (const auto& o : samples) {
    if (!o.double_support) continue;  // both feet on the ground: where footsteps landed
    for (const auto* foot : {&o.left, &o.right}) {
      const auto p = foot->motion.pose();
      EXPECT_GE(std::hypot(p.x - obstacle.x, p.y - obstacle.y),
                obstacle.radius + obstacle.margin - 1e-9);
    }
  }
  EXPECT_GT(samples.back().com_x[0], obstacle.x + obstacle.radius + obstacle.margin);
}

/// The analytic residual Jacobian equals Ceres' automatic one over the FK in Jets (the solver's
/// cost functions, residual_and_jacobian()) and the checker's Jets through IkResidual::residual()
/// (8 derivatives per pass), with non-zero body points, base rotation vectors from 1e-5 to
/// 0.8 rad, and both joint counts. tests/kinematics/test_ik_residual.cpp checks it against
/// central differences.
template <int NumJoints>
void check_analytic_jacobian() {
  auto s = walkgen_test::offset_ik_settings<walkgen::CeresIkSettings>();
  walkgen::CeresInverseKinematics<NumJoints> analytic(tree(), s);
  s.derivatives = walkgen::IkDerivatives::automatic;
  walkgen::CeresInverseKinematics<NumJoints> automatic(tree(), s);
  using Jet = ceres::Jet<double, 8>;
  const walkgen::IkResidual<NumJoints>& residual = analytic.residual();
  const walkgen::KinematicTree<Jet> jet_tree = residual.tree().template cast<Jet>();
  auto jet_ws = jet_tree.make_workspace();
  walkgen_test::Blocks rows;
  for (const char* name : walkgen::IkResidual<>::kRowBlocks) rows.push_back({name, 3});
  const walkgen_test::Blocks cols = walkgen_test::velocity_blocks(tree());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  walkgen_test::JacobianCheck worst;
  for (int i = 0; i < 20; ++i) {
    const IkTarget target = random_reachable_target(rng);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(walkgen::kPi * u(rng),
                          Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())
            .toRotationMatrix();
    const Eigen::VectorXd q = walkgen_test::random_configuration(tree(), rng);
    for (auto* ik : {&analytic, &automatic}) ik->set_initial_guess(Eigen::Vector3d::Zero(), R, q);
    Eigen::VectorXd x(6 + q.size());
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    x << u(rng), u(rng), u(rng), std::pow(10.0, -5.0 + 4.9 * (i % 5) / 4.0) * axis, q;
    Eigen::VectorXd ra, rb;
    Eigen::MatrixXd Ja, Jb;
    analytic.residual_and_jacobian(target, x, ra, Ja);
    automatic.residual_and_jacobian(target, x, rb, Jb);
    ASSERT_EQ(Ja.rows(), 21);
    ASSERT_EQ(Ja.cols(), 21);
    EXPECT_LE((ra - rb).cwiseAbs().maxCoeff(), 1e-12);
    const std::string what = "analytic IK residual Jacobian (sample " + std::to_string(i) + ")";
    worst.merge(walkgen_test::compare_jacobians(what, Ja, Jb, {1e-9}, rows, cols,
                                                "Ceres' AutoDiffCostFunction"));
    const Eigen::Matrix3d start = analytic.base_rotation_W();
    auto f = [&](const Jet* xx, Jet* r) {
      residual.residual(target, start, xx, r, jet_tree, jet_ws);
    };
    worst.merge(walkgen_test::compare_jacobians(what, Ja, walkgen_test::jet_jacobian<Jet>(f, x, 21),
                                                {1e-9}, rows, cols,
                                                "ceres::Jet<double, 8> through IkResidual"));
  }
  std::printf("analytic vs Jet residual Jacobian (joints %d): worst difference %.2e\n", NumJoints,
              worst.max_error);
  EXPECT_TRUE(worst.passed()) << worst.message();
}

TEST(CeresInverseKinematics, AnalyticJacobianMatchesJets) {
  check_analytic_jacobian<walkgen::kHumanoidJoints>();
  check_analytic_jacobian<Eigen::Dynamic>();
}

/// Both joint counts and both kinds of derivatives find the same solutions.
TEST(CeresInverseKinematics, DynamicJointCountAndAutomaticDerivativesMatchFixed) {
  HumanoidIk fixed(tree());
  for (auto derivatives : {walkgen::IkDerivatives::analytic, walkgen::IkDerivatives::automatic}) {
    walkgen::CeresIkSettings s;
    s.derivatives = derivatives;
    walkgen::CeresInverseKinematics<Eigen::Dynamic> dynamic(tree(), s);
    HumanoidIk fixed_same(tree(), s);  // fixed joint count, these derivatives
    std::mt19937 rng(7);
    for (int i = 0; i < 5; ++i) {
      const IkTarget target = random_reachable_target(rng);
      walkgen::start_standing(dynamic, target.left_foot.position_W);
      walkgen::start_standing(fixed_same, target.left_foot.position_W);
      walkgen::start_standing(fixed, target.left_foot.position_W);
      const auto a = dynamic.solve(target), b = fixed.solve(target), c = fixed_same.solve(target);
      EXPECT_EQ(a.status, b.status);
      EXPECT_EQ(c.status, b.status);
      if (a.status == IkStatus::converged) {
        EXPECT_LE(max_error(a), 1e-6);
        EXPECT_TRUE(dynamic.q().isApprox(fixed.q(), 1e-6));
        EXPECT_TRUE(fixed_same.q().isApprox(fixed.q(), 1e-6));
      }
    }
  }
}

TEST(CeresInverseKinematics, NonFiniteTargetKeepsTheSolution) {
  HumanoidIk ik(tree());
  walkgen::start_standing(ik, Eigen::Vector3d(0, 0.07, 0));
  const Eigen::VectorXd q = ik.q();
  IkTarget target;
  target.com_W = Eigen::Vector3d(0.0, 0.0, std::nan(""));
  const walkgen::IkResult r = ik.solve(target);
  EXPECT_EQ(r.status, IkStatus::invalid_input);
  EXPECT_NE(std::string(r.message).find("non-finite target"), std::string::npos) << r.message;
  EXPECT_FALSE(r.applied);
  EXPECT_EQ(r.runs, 0);
  EXPECT_EQ(ik.q(), q);
}

TEST(CeresInverseKinematics, UnreachableTargetKeepsTheSolution) {
  walkgen::CeresIkSettings s;
  s.n_init = 2;
  s.num_steps = 100;
  HumanoidIk ik(tree(), s);
  walkgen::start_standing(ik, Eigen::Vector3d(0, 0.07, 0));
  const Eigen::VectorXd q = ik.q();
  IkTarget target;
  target.com_W = Eigen::Vector3d(0.0, 0.0, 0.45);
  target.left_foot.position_W = Eigen::Vector3d(0.0, 0.5, 0.0);  // legs 0.4 m long: too far
  target.right_foot.position_W = Eigen::Vector3d(0.0, -0.5, 0.0);
  const walkgen::IkResult r = ik.solve(target);
  EXPECT_EQ(r.status, IkStatus::not_converged);
  EXPECT_NE(std::string(r.message).find("tolerance"), std::string::npos) << r.message;
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
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  EXPECT_THROW(ik.residual_and_jacobian(IkTarget(), Eigen::VectorXd::Zero(20), r, J),
               walkgen::invalid_argument);
  // Out-of-limit guesses are clamped: the knee cannot bend backwards.
  q.setZero();
  q[tree().joint_index("l_knee")] = -1.0;
  ik.set_initial_guess(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q);
  EXPECT_EQ(ik.q()[tree().joint_index("l_knee")], 0.0);
}

// Held joints (CeresIkSettings::held_joints) keep their initial-guess angles exactly, through
// a cold multi-start solve whose restarts move every other joint, while the targets are met
// around them (the torso turned 0.1 rad on its held yaw joint, where a free solve would
// untwist it); a joint named twice is held once; every joint held leaves the base to move; an
// unknown name is an error naming the setting and the joint.
TEST(CeresInverseKinematics, HeldJointsKeepTheirGuess) {
  walkgen::CeresIkSettings s;
  s.held_joints = {"torso_pitch", "torso_roll", "torso_yaw", "torso_yaw"};
  s.num_steps = 7;  // too few from the far guess below: restarts follow
  HumanoidIk ik(tree(), s);
  walkgen::start_standing(ik, Eigen::Vector3d(0, 0.07, 0));
  const Eigen::VectorXd guess = ik.q();
  auto ws = tree().make_workspace();
  tree().forward_kinematics(ik.base_position_W(), ik.base_rotation_W(), guess, ws);
  IkTarget target;
  target.com_W = tree().center_of_mass(ws) + Eigen::Vector3d(0.02, 0.03, -0.02);
  target.left_foot = {ws.position_W(tree().link_index("l_sole")), 0.0};
  target.right_foot = {ws.position_W(tree().link_index("r_sole")) + Eigen::Vector3d(0.05, 0, 0.03),
                       0.0};
  target.hold_upright(0.0);
  target.torso_rotation_W = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // A guess far from the solution (one knee bent to 2.2 rad, the other straight), the torso
  // turned by the 0.1 rad its target asks.
  Eigen::VectorXd far = guess;
  far[tree().joint_index("torso_yaw")] = 0.1;
  for (const char* j : {"l_hip_pitch", "l_knee", "l_ankle_pitch", "r_knee"}) {
    far[tree().joint_index(j)] = 0.0;
  }
  far[tree().joint_index("l_knee")] = 2.2;
  ik.set_initial_guess(ik.base_position_W(), ik.base_rotation_W(), far);
  const walkgen::IkResult r = ik.solve(target);
  ASSERT_EQ(r.status, IkStatus::converged) << max_error(r);
  EXPECT_GE(r.runs, 2);  // restarts ran
  for (const std::string& j : s.held_joints) {
    EXPECT_EQ(ik.q()[tree().joint_index(j)], far[tree().joint_index(j)]) << j;
  }
  tree().forward_kinematics(ik.base_position_W(), ik.base_rotation_W(), ik.q(), ws);
  EXPECT_LE((tree().center_of_mass(ws) - target.com_W).norm(), 1e-6);
  EXPECT_LE((ws.position_W(tree().link_index("r_sole")) - target.right_foot.position_W).norm(),
            1e-6);

  // Every joint held: only the base moves; a CoM shift along x is reached by moving it.
  s.held_joints = tree().joint_names();
  HumanoidIk rigid(tree(), s);
  walkgen::start_standing(rigid, Eigen::Vector3d(0, 0.07, 0));
  const Eigen::VectorXd stand = rigid.q();
  tree().forward_kinematics(rigid.base_position_W(), rigid.base_rotation_W(), stand, ws);
  IkTarget shifted;
  shifted.com_W = tree().center_of_mass(ws) + Eigen::Vector3d(0.01, 0.0, 0.0);
  shifted.left_foot = {ws.position_W(tree().link_index("l_sole")) + Eigen::Vector3d(0.01, 0, 0),
                       0.0};
  shifted.right_foot = {ws.position_W(tree().link_index("r_sole")) + Eigen::Vector3d(0.01, 0, 0),
                        0.0};
  shifted.hold_upright(0.0);
  ASSERT_EQ(rigid.solve(shifted).status, IkStatus::converged);
  EXPECT_EQ(rigid.q(), stand);

  s.held_joints = {"l_knee", "elbow"};
  walkgen_test::expect_invalid_argument(
      [&] { HumanoidIk bad(tree(), s); },
      {"CeresIkSettings.held_joints", "elbow", "l_knee", "torso_yaw"});
}

// validate(CeresIkSettings) names each field of its own and of IkResidualSettings.
TEST(CeresInverseKinematics, SettingsAreValidatedNamingTheField) {
  using S = walkgen::CeresIkSettings;
  walkgen_test::expect_rejected<S>(
      S(), {{[](S& s) { s.n_init = 0; }, {"CeresIkSettings.n_init", "at least 1", "0"}},
            {[](S& s) { s.step_tol = -1.0; }, {"CeresIkSettings.step_tol", "> 0", "-1"}},
            {[](S& s) { s.lambda = std::nan(""); }, {"CeresIkSettings.lambda", "nan"}},
            {[](S& s) { s.num_steps = 0; }, {"CeresIkSettings.num_steps", "0"}},
            {[](S& s) { s.com_weight = 0.0; }, {"IkResidualSettings.com_weight", "> 0", "0"}},
            {[](S& s) { s.position_tolerance = 0.0; }, {"CeresIkSettings.position_tolerance"}},
            {[](S& s) { s.orientation_tolerance = -1e-6; },
             {"CeresIkSettings.orientation_tolerance", "-1e-06"}}});
}

TEST(CeresInverseKinematics, DerivativesStrings) {
  walkgen_test::expect_enum_strings(std::array<walkgen::IkDerivatives, 2>{
      walkgen::IkDerivatives::analytic, walkgen::IkDerivatives::automatic});
  static_assert(to_string(walkgen::IkDerivatives::automatic)[0] == 'a');
}

}  // namespace
