// The NMPC walking pattern generator (include/walkgen/mpc/walking_mpc.hpp) and its interpolation
// on the thesis's HRP-2 scenarios (§9.1): balance (ZMP in the support polygon at every command
// sample), footstep feasibility, relative foot yaw, obstacles, velocity tracking, continuity of
// the interpolated trajectories, Jacobians against finite differences, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "support/derivatives.hpp"
#include "support/expect_error.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

namespace {

using walkgen::Foot;
using walkgen::FootPose;
using walkgen::ScenarioRun;
using Poly = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// The shrunk sole of a foot at a pose, in world coordinates (counter-clockwise).
Poly sole_world(const walkgen::WalkingSettings<double>& s, const FootPose<double>& p) {
  const double hx = s.foot_length / 2 - s.security_margin[0];
  const double hy = s.foot_width / 2 - s.security_margin[1];
  Poly v(4, 2);
  v << hx, hy, -hx, hy, -hx, -hy, hx, -hy;
  const double c = std::cos(p.q), sn = std::sin(p.q);
  Poly w(4, 2);
  for (int i = 0; i < 4; ++i) {
    w(i, 0) = p.x + c * v(i, 0) - sn * v(i, 1);
    w(i, 1) = p.y + sn * v(i, 0) + c * v(i, 1);
  }
  return w;
}

// Convex hull (Andrew's monotone chain), counter-clockwise.
Poly convex_hull(Poly pts) {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < pts.rows(); ++i) p.push_back(pts.row(i).transpose());
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  Poly out(int(k - 1), 2);
  for (std::size_t i = 0; i + 1 < k; ++i) out.row(int(i)) = h[i].transpose();
  return out;
}

// Signed distance outside a counter-clockwise convex polygon (≤ 0 inside).
double outside(const Poly& v, double x, double y) {
  double worst = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < v.rows(); ++i) {
    const Eigen::Vector2d a = v.row(i), b = v.row((i + 1) % v.rows());
    const Eigen::Vector2d e = b - a;
    const double d = (e.x() * (y - a.y()) - e.y() * (x - a.x())) / e.norm();  // > 0: left side
    worst = std::max(worst, -d);
  }
  return worst;
}

const walkgen::WalkingSettings<double>& hrp2() {
  static const auto s = walkgen::hrp2_settings<double>();
  return s;
}

// The HRP-2 feet without security margin (the double-support polygon of the acceptance).
const walkgen::WalkingSettings<double>& full_feet() {
  static const auto s = [] {
    auto f = walkgen::hrp2_settings<double>();
    f.security_margin.setZero();
    return f;
  }();
  return s;
}

const ScenarioRun& run_of(const std::string& name) {
  static std::map<std::string, ScenarioRun> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    it = cache.emplace(name, walkgen::run_scenario<16>(walkgen::scenario(name), hrp2())).first;
  }
  return it->second;
}

class Scenario : public ::testing::TestWithParam<std::string> {};

TEST_P(Scenario, EveryQpSolvesAndTheZmpStaysInTheSupportPolygon) {
  const ScenarioRun& run = run_of(GetParam());
  ASSERT_EQ(run.results.size(), 200u);
  ASSERT_EQ(run.commands.size(), 200u);
  for (std::size_t k = 0; k < run.results.size(); ++k) {
    ASSERT_EQ(run.commands[k], walkgen::CommandStatus::accepted)
        << "tick " << k << ": " << walkgen::to_string(run.commands[k]);
    ASSERT_EQ(run.results[k].status, walkgen::MpcStatus::solved)
        << "tick " << k << ": " << walkgen::to_string(run.results[k].qp_status);
  }
  double worst_single = -1, worst_double = -1, worst_double_shrunk = -1;
  for (const auto& o : run.samples) {
    const FootPose<double> sup = o.foot(o.support_foot).motion.pose();
    const Poly sole = sole_world(hrp2(), sup);
    if (o.double_support) {
      const FootPose<double> oth = o.foot(walkgen::other(o.support_foot)).motion.pose();
      Poly both(8, 2);
      both << sole_world(full_feet(), sup), sole_world(full_feet(), oth);
      worst_double = std::max(worst_double, outside(convex_hull(both), o.zmp_x, o.zmp_y));
      both << sole, sole_world(hrp2(), oth);
      worst_double_shrunk =
          std::max(worst_double_shrunk, outside(convex_hull(both), o.zmp_x, o.zmp_y));
    } else {
      worst_single = std::max(worst_single, outside(sole, o.zmp_x, o.zmp_y));
    }
  }
  // The rows hold the ZMP at the preview samples; between two, with a constant jerk, it is a
  // cubic of time and bulges slightly (1.29 mm at most, in "sequence", at a sole corner; the
  // shrunk sole is 50 mm inside the real one).
  EXPECT_LE(worst_single, 1.5e-3) << "ZMP outside the shrunk support foot";
  EXPECT_LE(worst_double, 1e-3) << "ZMP outside the hull of both feet";
  EXPECT_LE(worst_double_shrunk, 2e-3) << "ZMP far outside the hull of both shrunk feet";
  RecordProperty("worst_double_support_shrunk_mm", std::to_string(worst_double_shrunk * 1e3));
  RecordProperty("worst_single_support_mm", std::to_string(worst_single * 1e3));
  RecordProperty("worst_double_support_mm", std::to_string(worst_double * 1e3));
}

TEST_P(Scenario, FootstepsAreFeasibleAndRelativeYawIsLimited) {
  const ScenarioRun& run = run_of(GetParam());
  walkgen::WalkingMpc<double, 16> mpc(hrp2());
  double worst_hull = -1;
  for (std::size_t k = 0; k < run.plans.size(); ++k) {
    const auto& st = run.states[k];
    const auto& plan = run.plans[k];
    FootPose<double> prev = st.support;
    Foot prev_foot = st.support_foot;
    for (int i = 1; i <= plan.nf; ++i) {
      const FootPose<double> f = plan.footstep(i);
      const Foot landing = walkgen::other(prev_foot);
      // The step in the frame of the foot it is planned from.
      const double c = std::cos(prev.q), s = std::sin(prev.q);
      const double lx = c * (f.x - prev.x) + s * (f.y - prev.y);
      const double ly = -s * (f.x - prev.x) + c * (f.y - prev.y);
      const Poly& hull =
          landing == Foot::left ? hrp2().left_foot_convex_hull : hrp2().right_foot_convex_hull;
      worst_hull = std::max(worst_hull, outside(convex_hull(hull), lx, ly));
      EXPECT_LE(std::abs(f.q - prev.q), hrp2().max_relative_yaw + 1e-9) << "tick " << k;
      for (const auto& ob : walkgen::scenario(GetParam()).obstacles) {
        EXPECT_GE(std::hypot(f.x - ob.x, f.y - ob.y), ob.radius + ob.margin - 1e-9)
            << "tick " << k << " footstep " << i;
      }
      prev = f;
      prev_foot = landing;
    }
  }
  EXPECT_LE(worst_hull, 1e-3) << "a planned footstep leaves its feasibility polygon";
  // The robot gets past every obstacle: its CoM ends beyond the far side of the margin circle.
  for (const auto& ob : walkgen::scenario(GetParam()).obstacles) {
    EXPECT_GT(run.states.back().com_x[0], ob.x + ob.radius + ob.margin);
  }
  // The interpolated feet: relative yaw and its rate within their limits at every sample.
  double worst_yaw = 0, worst_rate = 0;
  for (const auto& o : run.samples) {
    worst_yaw = std::max(worst_yaw, std::abs(o.left.motion.q.position - o.right.motion.q.position));
    worst_rate =
        std::max(worst_rate, std::abs(o.left.motion.q.velocity - o.right.motion.q.velocity));
  }
  EXPECT_LE(worst_yaw, hrp2().max_relative_yaw + 1e-9);
  EXPECT_LE(worst_rate, hrp2().max_relative_yaw_rate * 1.001);
}

TEST_P(Scenario, InterpolationIsContinuousAndFeetAreFlatInDoubleSupport) {
  const ScenarioRun& run = run_of(GetParam());
  const double dt = hrp2().command_period;
  double worst_p = 0, worst_v = 0;
  auto check = [&](const walkgen::Sample3<double>& a, const walkgen::Sample3<double>& b) {
    // Trapezoidal consistency between consecutive samples: a jump in position or velocity
    // shows up as a mismatch of the order of the jump. The acceleration may jump (the 4th-order
    // lift of eq. 2.101 does at lift-off and touch-down), which the velocity's trapezoid error
    // dt |Δa| / 2 allows for.
    worst_p =
        std::max(worst_p, std::abs(b.position - a.position - dt * (a.velocity + b.velocity) / 2));
    worst_v = std::max(
        worst_v, std::abs(b.velocity - a.velocity - dt * (a.acceleration + b.acceleration) / 2) -
                     dt * std::abs(b.acceleration - a.acceleration) / 2);
  };
  for (std::size_t i = 0; i + 1 < run.samples.size(); ++i) {
    const auto& a = run.samples[i];
    const auto& b = run.samples[i + 1];
    for (int axis = 0; axis < 2; ++axis) {
      const auto& ca = axis == 0 ? a.com_x : a.com_y;
      const auto& cb = axis == 0 ? b.com_x : b.com_y;
      check({ca[0], ca[1], ca[2]}, {cb[0], cb[1], cb[2]});
    }
    for (const Foot f : {Foot::left, Foot::right}) {
      check(a.foot(f).motion.x, b.foot(f).motion.x);
      check(a.foot(f).motion.y, b.foot(f).motion.y);
      check(a.foot(f).motion.q, b.foot(f).motion.q);
      check(a.foot(f).z, b.foot(f).z);
    }
    if (a.double_support) {
      for (const Foot f : {Foot::left, Foot::right}) {
        EXPECT_EQ(a.foot(f).z.position, 0.0);
        EXPECT_EQ(a.foot(f).motion.x.velocity, 0.0);
        EXPECT_EQ(a.foot(f).motion.y.velocity, 0.0);
      }
    }
  }
  EXPECT_LE(worst_p, 1e-4) << "position jump";
  EXPECT_LE(worst_v, 5e-3) << "velocity jump";
}

INSTANTIATE_TEST_SUITE_P(Hrp2, Scenario,
                         ::testing::Values("straight", "sideways", "curved", "turn", "sequence",
                                           "obstacle"));

// Steady state over the last 7 gait cycles (t = 8.8 s … 20 s, walkgen::mean_velocity): the
// CoM velocity in the robot frame and the yaw rate, each within 5 % of the command's size,
// |v − v_cmd| ≤ 0.05 |v_cmd| per component (x, y, yaw).
void expect_tracking(const std::string& name, const Eigen::Vector3d& command) {
  const ScenarioRun& run = run_of(name);
  ASSERT_EQ(run.states.size(), 200u);
  const Eigen::Vector3d mean = walkgen::mean_velocity(run, 88, 6, 16, hrp2().t);
  const double speed = command.head<2>().norm();
  for (int i = 0; i < 3; ++i) {
    const double size = i < 2 ? speed : std::abs(command[2]);
    const double tolerance = size > 0 ? 0.05 * size : (i < 2 ? 0.005 : 0.0025);
    EXPECT_NEAR(mean[i], command[i], tolerance) << name << " component " << i;
  }
  ::testing::Test::RecordProperty(
      name + "_velocity",
      std::to_string(mean[0]) + " " + std::to_string(mean[1]) + " " + std::to_string(mean[2]));
}

TEST(WalkingMpc, TracksStraightSidewaysCurvedAndTurningCommands) {
  expect_tracking("straight", {0.1, 0.0, 0.0});
  expect_tracking("sideways", {0.0, 0.1, 0.0});
  expect_tracking("curved", {0.1, 0.0, 0.1});
  expect_tracking("turn", {0.0, 0.0, 0.2});
}

// --- Issue 24's generator fixes: straight walks, small and combined commands, soles apart ----
// Both presets: HRP-2 (0.1 s ticks, 0.8 s steps) and Heicub (0.4 s ticks, 3.2 s steps).
walkgen::WalkingSettings<double> preset(bool heicub) {
  return heicub ? walkgen::heicub_settings<double>() : walkgen::hrp2_settings<double>();
}
const char* preset_name(bool heicub) { return heicub ? "heicub" : "hrp2"; }

// Steady state at a constant command: walkgen::mean_velocity over the last `cycles` gait cycles
// (after at least 3 cycles of warm-up), every tick solved.
Eigen::Vector3d steady_velocity(bool heicub, const Eigen::Vector3d& command) {
  const auto s = preset(heicub);
  const int S = s.samples_per_step(), cycles = 5, ticks = (cycles + 4) * 2 * S;
  const ScenarioRun run = walkgen::run_commands(
      s, [&](int) { return command; }, ticks);
  for (const auto& r : run.results) EXPECT_EQ(r.status, walkgen::MpcStatus::solved);
  return walkgen::mean_velocity(run, ticks - (cycles + 1) * 2 * S, cycles, 2 * S, s.t);
}

// A straight command walks straight (issue 24: Heicub's right foot turned -0.064 rad every step
// and the walk drifted 8 cm sideways over 2.56 m): over 2.5 m at the preset's largest forward
// command, the feet end within 1 cm of the line they started on and no foot turns more than
// 0.01 rad.
TEST(WalkingMpc, StraightCommandsWalkStraight) {
  for (const bool heicub : {false, true}) {
    const auto s = preset(heicub);
    const double v = s.max_command.x();
    const int ticks = int(std::ceil(2.5 / v / s.t)) + 2 * s.samples_per_step();
    const ScenarioRun run = walkgen::run_commands(
        s, [&](int) { return Eigen::Vector3d(v, 0, 0); }, ticks);
    const auto& a = run.landings[0].pose;
    const auto& b = run.landings[1].pose;
    const double y0 = (a.y + b.y) / 2;
    double worst_y = 0, worst_q = 0, reach = 0;
    for (const auto& l : run.landings) {
      const double side = l.foot == Foot::left ? 1.0 : -1.0;
      worst_y = std::max(worst_y, std::abs(l.pose.y - side * s.foot_distance / 2 - y0));
      worst_q = std::max(worst_q, std::abs(l.pose.q));
      reach = std::max(reach, l.pose.x);
    }
    EXPECT_GE(reach, 2.5) << preset_name(heicub);
    EXPECT_LE(worst_y, 0.01) << preset_name(heicub);
    EXPECT_LE(worst_q, 0.01) << preset_name(heicub);
    ::testing::Test::RecordProperty(std::string(preset_name(heicub)) + "_straight_drift",
                                    std::to_string(worst_y));
  }
}

// Sideways commands move the robot in proportion: at 25 %, 50 % and 100 % of the preset's
// largest v_y the steady sideways velocity grows with the command, each increment within 5 % of
// the command's, and HRP-2 walks within 5 % of every command. Heicub's feasibility polygon
// starts at its stance width, so the trailing foot rests on it while the ZMP-centring cost
// (beta = 100) pulls the leading one in: a constant shortfall of about 2.3e-4 m/s, 5 % of its
// largest v_y (before issue 24 2.3e-3 m/s, and below 0.002 m/s nothing moved).
TEST(WalkingMpc, SidewaysCommandsMoveTheRobotInProportion) {
  for (const bool heicub : {false, true}) {
    const double limit = preset(heicub).max_command.y();
    const std::vector<double> fractions = {0.25, 0.5, 1.0};
    std::vector<double> walked;
    for (const double fraction : fractions) {
      const double vy = fraction * limit;
      const Eigen::Vector3d v = steady_velocity(heicub, {0.0, vy, 0.0});
      walked.push_back(v.y());
      const double shortfall = heicub ? 0.075 * limit : 0.05 * vy;
      EXPECT_NEAR(v.y(), vy, shortfall) << preset_name(heicub) << " v_y " << vy;
      EXPECT_NEAR(v.x(), 0.0, 0.05 * vy) << preset_name(heicub) << " v_y " << vy;
      EXPECT_NEAR(v.z(), 0.0, 1e-3) << preset_name(heicub) << " v_y " << vy;
    }
    for (std::size_t i = 1; i < fractions.size(); ++i) {
      const double commanded = (fractions[i] - fractions[i - 1]) * limit;
      EXPECT_NEAR(walked[i] - walked[i - 1], commanded, 0.05 * commanded)
          << preset_name(heicub) << " from " << fractions[i - 1] << " to " << fractions[i];
    }
    ::testing::Test::RecordProperty(std::string(preset_name(heicub)) + "_sideways",
                                    std::to_string(walked[0]) + " " + std::to_string(walked[1]) +
                                        " " + std::to_string(walked[2]));
  }
}

// Combined commands track within 5 % of the command's speed (issue 24: HRP-2's (0.1, 0.1, 0.1)
// walked v_y 0.0875), the yaw rate within 5 % of its own.
TEST(WalkingMpc, CombinedCommandsTrackWithinFivePercent) {
  const std::vector<std::pair<bool, Eigen::Vector3d>> cases = {
      {false, {0.1, 0.1, 0.1}},    {false, {0.2, 0.05, 0.1}},   {false, {0.1, -0.05, -0.2}},
      {true, {0.02, 0.002, 0.04}}, {true, {0.03, 0.003, 0.02}}, {true, {0.017, -0.0022, -0.0375}}};
  for (const auto& [heicub, command] : cases) {
    const Eigen::Vector3d v = steady_velocity(heicub, command);
    const double speed = command.head<2>().norm();
    EXPECT_NEAR(v.x(), command.x(), 0.05 * speed)
        << preset_name(heicub) << " " << command.transpose();
    EXPECT_NEAR(v.y(), command.y(), 0.05 * speed)
        << preset_name(heicub) << " " << command.transpose();
    EXPECT_NEAR(v.z(), command.z(), 0.05 * std::abs(command.z()))
        << preset_name(heicub) << " " << command.transpose();
  }
}

// The soles stay min_foot_separation (2 cm) apart at every planned footstep and all along the
// interpolated swing, in every scenario of both presets (issue 24: turned feet came within
// 1.4 cm). The plans hold the separation to the Gauss–Newton tolerance (sqp_tolerance 1 mm).
TEST(WalkingMpc, TheSolesStayApart) {
  for (const bool heicub : {false, true}) {
    auto s = preset(heicub);
    for (const auto& sc : walkgen::walking_scenarios()) {
      ScenarioRun run;
      if (heicub) {
        s.obstacles = walkgen::heicub_obstacle(sc.name);
        run = walkgen::run_commands(
            s, [&](int k) { return walkgen::heicub_scenario_command(sc.name, k, 32); }, 160);
      } else {
        run = walkgen::run_scenario(sc, s);
      }
      const double l = s.foot_length, w = s.foot_width;
      double planned = 1e9, walked = 1e9;
      for (std::size_t k = 0; k < run.plans.size(); ++k) {
        FootPose<double> previous = run.states[k].support;
        for (int i = 1; i <= run.plans[k].nf; ++i) {
          const FootPose<double> step = run.plans[k].footstep(i);
          planned = std::min(planned, walkgen::sole_distance(previous, step, l, w));
          previous = step;
        }
      }
      for (const auto& o : run.samples) {
        const auto pose = [](const walkgen::SwingSample<double>& f) {
          return FootPose<double>{f.motion.x.position, f.motion.y.position, f.motion.q.position};
        };
        walked = std::min(walked, walkgen::sole_distance(pose(o.left), pose(o.right), l, w));
      }
      const std::string what = std::string(preset_name(heicub)) + " " + sc.name;
      EXPECT_GE(planned, s.min_foot_separation - s.sqp_tolerance) << what;
      EXPECT_GE(walked, s.min_foot_separation - s.sqp_tolerance) << what;
      ::testing::Test::RecordProperty(std::string(preset_name(heicub)) + "_" + sc.name + "_gap",
                                      std::to_string(walked));
    }
  }
}

// The heading is the commanded one: feedback that reports the feet turned (a push) does not
// turn the reference; the walk turns back to the commanded heading.
TEST(WalkingMpc, TheReferenceHeadingIntegratesTheCommandAndSurvivesFeedback) {
  walkgen::WalkingMpc<double, 16> mpc(hrp2());
  EXPECT_EQ(mpc.reference_heading(), 0.0);
  ASSERT_EQ(mpc.set_command({0.1, 0.0, 0.2}), walkgen::CommandStatus::accepted);
  for (int k = 0; k < 10; ++k) {
    ASSERT_EQ(mpc.solve().status, walkgen::MpcStatus::solved);
    mpc.advance();
  }
  EXPECT_NEAR(mpc.reference_heading(), 0.2, 1e-12);  // 10 ticks of 0.1 s at 0.2 rad/s
  ASSERT_EQ(mpc.set_command({0.1, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  auto st = mpc.state();
  st.support.q += 0.1;  // the support foot reported turned by 0.1 rad
  mpc.set_state(st);
  EXPECT_NEAR(mpc.reference_heading(), 0.2, 1e-12);
  for (int k = 0; k < 40; ++k) {
    ASSERT_EQ(mpc.solve().status, walkgen::MpcStatus::solved);
    mpc.advance();
  }
  EXPECT_NEAR(mpc.state().heading(), 0.2, 0.01);
  mpc.reset(st);  // a reset takes the state's own heading
  EXPECT_NEAR(mpc.reference_heading(), st.heading(), 1e-12);
}

// --- Capturability and the Gauss–Newton corrections -------------------------------------------
// Every plan ends with the capture point ξ = c + ċ/ω inside the shrunk sole of the last planned
// footstep: the pendulum could stop there, so no plan lets it diverge beyond the horizon.
TEST_P(Scenario, EveryPlanEndsCapturableOverItsLastFootstep) {
  const ScenarioRun& run = run_of(GetParam());
  walkgen::WalkingMpc<double, 16> mpc(hrp2());
  const auto& P = mpc.preview();
  const double w = std::sqrt(hrp2().gravity / hrp2().com_z);
  const int N = 16;
  double worst = -1;
  for (std::size_t k = 0; k < run.plans.size(); ++k) {
    const auto& st = run.states[k];
    const auto& plan = run.plans[k];
    const Eigen::VectorXd jx = plan.U.segment(0, N), jy = plan.U.segment(N + plan.nf, N);
    const double cx = P.P_ps.row(N - 1).dot(st.com_x) + P.P_pu.row(N - 1).dot(jx);
    const double vx = P.P_vs.row(N - 1).dot(st.com_x) + P.P_vu.row(N - 1).dot(jx);
    const double cy = P.P_ps.row(N - 1).dot(st.com_y) + P.P_pu.row(N - 1).dot(jy);
    const double vy = P.P_vs.row(N - 1).dot(st.com_y) + P.P_vu.row(N - 1).dot(jy);
    const double o = outside(sole_world(hrp2(), plan.footstep(plan.nf)), cx + vx / w, cy + vy / w);
    worst = std::max(worst, o);
  }
  EXPECT_LE(worst, hrp2().sqp_tolerance);
}

// A state the pendulum cannot recover from within the horizon (1.5 m/s sideways) is reported as
// a failed QP, never planned as a divergent walk with a "solved" status.
TEST(WalkingMpc, AnUnrecoverableStateFailsInsteadOfPlanningADivergentWalk) {
  walkgen::WalkingMpc<double, 16> mpc(hrp2());
  auto st = mpc.state();
  st.com_y[1] = 1.5;
  mpc.set_state(st);
  const Eigen::VectorXd before = mpc.plan().U;
  EXPECT_EQ(mpc.solve().status, walkgen::MpcStatus::qp_failed);
  EXPECT_EQ(mpc.plan().U, before);
  // A forward push it can absorb (0.1 m/s) is planned, and the robot steps to a stop.
  mpc.reset(decltype(mpc)::initial_state(hrp2()));
  st = mpc.state();
  st.com_x[1] = 0.1;
  mpc.set_state(st);
  for (int k = 0; k < 40; ++k) {
    ASSERT_EQ(mpc.solve().status, walkgen::MpcStatus::solved) << "tick " << k;
    mpc.advance();
  }
  EXPECT_LT(std::abs(mpc.state().com_x[1]), 0.02);
}

// The real-time iteration linearises the rotated polygons at the previous plan; when a large
// change of foot yaw leaves a violation above sqp_tolerance, correction iterations remove it.
TEST(WalkingMpc, CorrectionIterationsBoundTheLinearisationError) {
  // Solved is a promise (issue 21, defect 3): a plan beyond sqp_tolerance is not_converged.
  auto worst_of = [](const ScenarioRun& run) {
    double worst = 0;
    for (const auto& r : run.results) {
      EXPECT_EQ(r.status, r.constraint_violation <= hrp2().sqp_tolerance
                              ? walkgen::MpcStatus::solved
                              : walkgen::MpcStatus::not_converged);
      worst = std::max(worst, r.constraint_violation);
    }
    return worst;
  };
  auto plain = hrp2();
  plain.sqp_corrections = 0;
  for (const char* name : {"sequence", "obstacle"}) {
    const ScenarioRun& run = run_of(name);
    int corrected = 0;
    for (const auto& r : run.results) corrected += r.sqp_iterations > 1;
    EXPECT_LE(worst_of(run), hrp2().sqp_tolerance) << name;
    for (const auto& r : run.results) EXPECT_EQ(r.status, walkgen::MpcStatus::solved) << name;
    EXPECT_GE(corrected, 1) << name;
    EXPECT_LE(corrected, 30) << name << ": corrections are the exception (≤ 15 %), not the rule";
    const ScenarioRun without = walkgen::run_scenario<16>(walkgen::scenario(name), plain);
    for (const auto& r : without.results) EXPECT_EQ(r.sqp_iterations, 1);
    EXPECT_GT(worst_of(without), 10 * hrp2().sqp_tolerance) << name;
  }
}

// The QP's warm start follows the receding horizon (the active set shifted by one sample, and by
// one footstep at a landing): few active-set changes per tick. Without the shift the straight
// walk needed 9.8 per tick.
TEST_P(Scenario, TheWarmStartFollowsTheHorizon) {
  const ScenarioRun& run = run_of(GetParam());
  double changes = 0;
  for (const auto& r : run.results) changes += r.qp_iterations;
  changes /= double(run.results.size());
  EXPECT_LE(changes, 5.0);
  RecordProperty("active_set_changes_per_tick", std::to_string(changes));
}

// --- Jacobians of every constraint block against central differences, typed over sizes --------
template <int N_, int Foot_, int Hull_>
struct Config {
  static constexpr int N = N_, FootEdges = Foot_, HullEdges = Hull_;
};
template <typename C>
class Jacobian : public ::testing::Test {};
using Configs = ::testing::Types<Config<16, 4, 5>, Config<Eigen::Dynamic, Eigen::Dynamic, 5>,
                                 Config<8, 4, Eigen::Dynamic>>;
TYPED_TEST_SUITE(Jacobian, Configs);

TYPED_TEST(Jacobian, MatchesFiniteDifferences) {
  auto s = hrp2();
  s.n = TypeParam::N == Eigen::Dynamic ? 24 : TypeParam::N;
  s.obstacles.push_back({1.0, 0.6, 0.3, 0.2});
  walkgen::WalkingMpc<double, TypeParam::N, TypeParam::FootEdges, TypeParam::HullEdges> mpc(s);
  ASSERT_EQ(mpc.set_command({0.1, 0.02, 0.15}), walkgen::CommandStatus::accepted);
  for (int k = 0; k < 13; ++k) {  // mid-step, turning: every block is nonlinear here
    ASSERT_EQ(mpc.solve().status, walkgen::MpcStatus::solved);
    mpc.advance();
  }
  Eigen::VectorXd U = mpc.plan().U;
  U += 0.01 * Eigen::VectorXd::Random(U.size());  // a generic point
  const auto m = mpc.num_rows();
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(m, U.size());
  Eigen::VectorXd lo(m), up(m), cp(m), lc(m), uc(m);
  mpc.constraint_jacobian(U, J, lo, up);
  auto c_of = [&](const Eigen::VectorXd& u) {
    mpc.constraint_values(u, cp, lc, uc);
    return cp;
  };
  walkgen_test::Blocks rows, cols;  // named by the layout: "ZMP polygon (row 5 of 64)", "F_x"
  const walkgen::WalkingLayout& layout = mpc.layout();
  for (int k = 0; k < layout.num_row_blocks(); ++k) {
    rows.push_back({layout.rows(k).name, layout.rows(k).count()});
  }
  for (const auto& v : layout.variables()) cols.push_back({v.name, v.count()});
  const auto check = walkgen_test::compare_jacobians("NMPC constraint Jacobian", J,
                                                     walkgen_test::central_differences(c_of, U),
                                                     {1e-7}, rows, cols);
  EXPECT_TRUE(check.passed()) << check.message();
  // The QP's rows are this linearisation: lb ≤ J U' ≤ ub holds at U' = U exactly when
  // lb_c ≤ c(U) ≤ ub_c does (bounds shifted by c(U) − J U).
  Eigen::VectorXd c0(m);
  mpc.constraint_values(U, c0, lc, uc);
  const Eigen::VectorXd JU = J * U;
  for (Eigen::Index r = 0; r < m; ++r) {
    if (std::isfinite(up[r])) {
      EXPECT_NEAR(up[r] - JU[r], uc[r] - c0[r], 1e-9) << "row " << r;
    }
    if (std::isfinite(lo[r])) {
      EXPECT_NEAR(lo[r] - JU[r], lc[r] - c0[r], 1e-9) << "row " << r;
    }
  }
}

// --- Failures and bad input --------------------------------------------------------------------
TEST(WalkingMpc, AFailedQpIsNeverAppliedAndThePlanIsTheShiftedPrevious) {
  walkgen::WalkingMpc<double, 16> mpc(hrp2(), /*obstacle_capacity=*/1);
  ASSERT_EQ(mpc.set_command({0.1, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  for (int k = 0; k < 5; ++k) {
    ASSERT_EQ(mpc.solve().status, walkgen::MpcStatus::solved);
    mpc.advance();
  }
  const Eigen::VectorXd before = mpc.plan().U;
  // An obstacle over the robot: no footstep can keep 2 m from it within one step.
  const auto& st = mpc.state();
  mpc.set_obstacles(
      std::vector<walkgen::CircleObstacle<double>>{{st.com_x[0], st.com_y[0], 1.5, 0.5}});
  const auto& r = mpc.solve();
  EXPECT_EQ(r.status, walkgen::MpcStatus::qp_failed);
  EXPECT_EQ(r.qp_status, walkgen::QpStatus::infeasible);
  EXPECT_TRUE(mpc.plan().U.isApprox(before)) << "the failed QP's iterate was applied";
  mpc.advance();
  EXPECT_TRUE(mpc.state().com_x.allFinite() && mpc.state().com_y.allFinite());
  // Without the obstacle the generator recovers.
  mpc.set_obstacles(std::vector<walkgen::CircleObstacle<double>>{});
  EXPECT_EQ(mpc.solve().status, walkgen::MpcStatus::solved);
}

TEST(WalkingMpc, RejectsNonFiniteCommandsAndClampsOutOfRangeOnes) {
  walkgen::WalkingMpc<double, 16> mpc(hrp2());
  EXPECT_EQ(mpc.set_command({0.1, 0.0, 0.1}), walkgen::CommandStatus::accepted);
  EXPECT_EQ(mpc.set_command({std::nan(""), 0.0, 0.0}), walkgen::CommandStatus::non_finite);
  EXPECT_EQ(mpc.set_command({0.0, std::numeric_limits<double>::infinity(), 0.0}),
            walkgen::CommandStatus::non_finite);
  EXPECT_EQ(mpc.command(), Eigen::Vector3d(0.1, 0.0, 0.1));  // the previous one stays
  // Each component beyond max_command (0.35, 0.12, 0.3) is clamped to it, its sign kept.
  EXPECT_EQ(mpc.set_command({5.0, -0.05, -1e300}), walkgen::CommandStatus::clamped);
  EXPECT_EQ(mpc.command(), Eigen::Vector3d(0.35, -0.05, -0.3));
  EXPECT_EQ(mpc.solve().last_command, walkgen::CommandStatus::clamped);
  EXPECT_EQ(mpc.result().command, Eigen::Vector3d(0.35, -0.05, -0.3));
  EXPECT_EQ(mpc.result().status, walkgen::MpcStatus::solved);
  EXPECT_TRUE(mpc.plan().U.allFinite());
  // Exactly at the limit is accepted as given.
  EXPECT_EQ(mpc.set_command({-0.35, 0.12, 0.3}), walkgen::CommandStatus::accepted);
}

// A clamped command walks at the limit: 10 m/s forward walks as 0.35 m/s does.
TEST(WalkingMpc, AClampedCommandWalksAtTheLimit) {
  walkgen::WalkingMpc<double, 16> clamped(hrp2()), limit(hrp2());
  for (int k = 0; k < 40; ++k) {
    ASSERT_EQ(clamped.set_command({10.0, 0.0, 0.0}), walkgen::CommandStatus::clamped);
    ASSERT_EQ(limit.set_command({0.35, 0.0, 0.0}), walkgen::CommandStatus::accepted);
    ASSERT_EQ(clamped.solve().status, walkgen::MpcStatus::solved);
    ASSERT_EQ(limit.solve().status, walkgen::MpcStatus::solved);
    clamped.advance();
    limit.advance();
  }
  EXPECT_EQ(clamped.state().com_x, limit.state().com_x);
  EXPECT_GT(clamped.state().com_x[0], 1.0);  // 4 s at 0.35 m/s, less the start
}

// heicub_walk() stops at the first tick whose command is rejected: the walk is what was
// planned up to that tick, its status says why it ended.
TEST(WalkingMpc, APatternWalkStopsAtTheFirstRejectedCommand) {
  const walkgen::PatternWalk walk =
      walkgen::heicub_walk([](int k) { return Eigen::Vector3d(k < 3 ? 0.03 : 5.0, 0.0, 0.0); }, 8);
  EXPECT_FALSE(walk.ok());
  EXPECT_EQ(walk.status, walkgen::PatternWalkStatus::command_rejected);
  EXPECT_EQ(walk.command, walkgen::CommandStatus::clamped);
  EXPECT_EQ(walk.ticks, 3);
  EXPECT_NE(walk.message.find("tick 3"), std::string::npos) << walk.message;
  ASSERT_FALSE(walk.samples.empty());
  const walkgen::PatternWalk whole = walkgen::heicub_walk(Eigen::Vector3d(0.03, 0.0, 0.0), 3);
  ASSERT_TRUE(whole.ok()) << whole.message;
  EXPECT_EQ(whole.status, walkgen::PatternWalkStatus::ok);
  EXPECT_TRUE(whole.message.empty());
  ASSERT_EQ(whole.samples.size(), walk.samples.size());
  EXPECT_EQ(whole.samples.back().com_x, walk.samples.back().com_x);
}

// Issue 21, defect 3 (reproducer mpc_far_state.cpp): a finite but absurd state (com_y = −1e30,
// a feedback glitch) was accepted and the tick said solved with a violation of 1.2e38.
TEST(WalkingMpc, ImplausibleStatesAreRejectedNamingTheLimit) {
  for (const auto& settings : {hrp2(), walkgen::heicub_settings<double>()}) {
    walkgen::WalkingMpc<double, 16> mpc(settings);
    const auto start = mpc.state();
    auto st = start;
    for (double offset : {1e30, 1e6, 10.0, 2.5}) {
      st = start;
      st.com_y[0] -= offset;
      walkgen_test::expect_invalid_argument([&] { mpc.set_state(st); },
                                            {"WalkingMpc::set_state", "max_state_distance"});
    }
    st = start;
    st.swing.x.position += 3.0;
    walkgen_test::expect_invalid_argument([&] { mpc.set_state(st); }, {"swing foot"});
    st = start;
    st.com_x[1] = 6.0;
    walkgen_test::expect_invalid_argument([&] { mpc.set_state(st); }, {"max_com_speed"});
    st = start;
    st.com_y[2] = -60.0;
    walkgen_test::expect_invalid_argument([&] { mpc.set_state(st); }, {"max_com_acceleration"});
    EXPECT_EQ(mpc.state().com_y[0], start.com_y[0]);  // left unchanged
    // Within the limits, the honest outcome: an unrecoverable offset fails the QP, and a plan
    // is solved only within sqp_tolerance.
    st = start;
    st.com_y[0] -= 1.0;
    mpc.set_state(st);
    const auto& r = mpc.solve();
    EXPECT_NE(r.status, walkgen::MpcStatus::solved);
    EXPECT_TRUE(mpc.plan().U.allFinite());
  }
}

TEST(WalkingMpc, StateFeedbackIsCheckedAndUsed) {
  walkgen::WalkingMpc<double, 16> mpc(hrp2());
  auto st = mpc.state();
  st.com_x[0] = std::nan("");
  EXPECT_THROW(mpc.set_state(st), walkgen::invalid_argument);
  st = mpc.state();
  st.phase = 8;
  EXPECT_THROW(mpc.set_state(st), walkgen::invalid_argument);
  // A CoM pushed 2 cm forward: the plan starts from it.
  st = mpc.state();
  st.com_x[0] += 0.02;
  mpc.set_state(st);
  ASSERT_EQ(mpc.solve().status, walkgen::MpcStatus::solved);
  mpc.advance();
  EXPECT_GT(mpc.state().com_x[0], 0.019);
}

TEST(WalkingMpc, SizesThatContradictTheTemplateAreRejected) {
  auto s = hrp2();
  s.n = 12;
  EXPECT_THROW((walkgen::WalkingMpc<double, 16>(s)), walkgen::invalid_argument);
  EXPECT_THROW((walkgen::WalkingMpc<double, 12, 5>(s)), walkgen::invalid_argument);
  EXPECT_THROW((walkgen::WalkingMpc<double, 12, 4, 6>(s)), walkgen::invalid_argument);
  EXPECT_NO_THROW((walkgen::WalkingMpc<double, 12, 4, 5>(s)));
  walkgen::WalkingMpc<double, 12> mpc(s);
  EXPECT_THROW(mpc.set_obstacles(std::vector<walkgen::CircleObstacle<double>>(1)),
               walkgen::invalid_argument);  // capacity 0
}

}  // namespace
