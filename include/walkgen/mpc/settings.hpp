#pragma once
/// @file
/// Settings of the walking pattern generator: every key of the thesis's configuration file
/// (Table 6.1), with units, plus the few limits the thesis's code hard-coded, in three parts:
/// RobotGeometry (the robot), GeneratorSettings (how it plans), InitialState (where it starts);
/// WalkingSettings is the three plus the obstacles. Two robots as code presets: hrp2_settings()
/// and heicub_settings(). validate() says what is wrong with a set or a part.
///
/// Key names follow Table 6.1 so that existing YAML files load unchanged (the YAML reader lives
/// in an adapter; the core needs Eigen only).

#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/core/obstacle.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/model/support_polygon.hpp"

namespace walkgen {

namespace detail {
/// HRP-2's footstep feasibility region of the left foot relative to the right one [m], from the
/// thesis's HRP-2 configuration (configs_hrp2.yaml of github.com/mhubii/nmpc_pattern_generator);
/// mirror_y() gives the right foot's.
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 2> hrp2_left_hull() {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 2> hull(5, 2);
  hull << -0.28, 0.2, -0.20, 0.3, 0.00, 0.4, 0.20, 0.3, 0.28, 0.2;
  return hull;
}
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 2> mirror_y(Eigen::Matrix<Scalar, Eigen::Dynamic, 2> hull) {
  hull.col(1) *= Scalar(-1);
  return hull;
}
}  // namespace detail

/// The robot and the world it walks in: its feet, where a foot may land, its CoM height, how it
/// may turn its feet, gravity. Part of WalkingSettings (a robot preset holds one); the flat keys
/// of Table 6.1 map onto it unchanged. In-class defaults: HRP-2.
template <typename Scalar = double>
struct RobotGeometry {
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;
  using Polygon = Eigen::Matrix<Scalar, Eigen::Dynamic, 2>;

  /// [m] how far the ZMP polygon is shrunk from the foot's edges in x and y (`security_margin`,
  /// fig. 6.4). Larger: more robust balance, less room for the ZMP, shorter feasible steps.
  Vector2 security_margin = Vector2(Scalar(0.09), Scalar(0.05));
  /// [m] vertices (E × 2) of the region where the left foot may land, in the frame of the right
  /// (support) foot (`left_foot_convex_hull`, fig. 2.5). Convex; any orientation.
  Polygon left_foot_convex_hull = detail::hrp2_left_hull<Scalar>();
  /// [m] the same for the right foot relative to the left one (`right_foot_convex_hull`).
  Polygon right_foot_convex_hull = detail::mirror_y<Scalar>(detail::hrp2_left_hull<Scalar>());
  Scalar foot_width = Scalar(0.1380);   ///< [m] sole size across the foot (y), `foot_width`
  Scalar foot_length = Scalar(0.2172);  ///< [m] sole size along the foot (x), `foot_length`
  Scalar foot_distance = Scalar(0.2);  ///< [m] lateral distance of the feet frames, `foot_distance`
  /// [m] the least distance between the two soles (foot_length × foot_width) at every planned
  /// footstep (walkgen's own, mpc/constraints/foot_separation.hpp): the feasibility polygons
  /// bound the foot centres only, and turned feet came within 1.4 cm. 0 lets the soles touch.
  Scalar min_foot_separation = Scalar(0.02);
  /// [m] optional ZMP support polygon of the left foot, in its foot frame (E × 2, convex); the
  /// right foot's is its mirror image. Empty: the foot_length × foot_width rectangle shrunk by
  /// security_margin (fig. 6.4). Its edge count must match the generator's FootEdges.
  Polygon zmp_polygon;
  Scalar step_height = Scalar(0.05);  ///< [m] apex height of the swing foot (eq. 2.95)
  Scalar com_z = Scalar(0.814);       ///< [m] CoM height c_z (eq. 2.40)
  /// [rad] |θ_L − θ_R| between the feet at every instant (eq. 2.73). A turn at ω needs
  /// ω·t_step between consecutive footsteps: 0.16 rad for the 0.2 rad/s turn at t_step 0.8 s,
  /// which the thesis code's 0.09 rad could never allow (its HRP-2 turned at half the command).
  Scalar max_relative_yaw = Scalar(0.25);
  /// [rad/s] peak |θ̇_L − θ̇_R| (eq. 2.74): the swing foot's yaw rate relative to the support
  /// foot on its 5th-order yaw polynomial, 15/8 · Δθ / (t_step − t_ds). The 0.2 rad/s turn at
  /// HRP-2's timing needs 1.5 rad/s (Δθ = 0.32 rad in 0.4 s).
  Scalar max_relative_yaw_rate = Scalar(2.0);
  Scalar gravity = Scalar(9.81);  ///< [m/s²]
};

/// Exact-penalty weights of the soft-constraint fallback, one per constraint block
/// (mpc/constraints/), per unit of a row's violation [1/m; 1/rad for the relative yaw]: 0 (hard)
/// or in [1e-6, 1e12]. When a tick's QP is infeasible or reaches nwsr, WalkingMpc solves it
/// again with every row r of each block whose weight w is > 0 relaxed by two slacks s⁺, s⁻ ≥ 0,
/// lb_r ≤ a_r U + s⁺ − s⁻ ≤ ub_r, at the cost w (s⁺ + s⁻ + (s⁺² + s⁻²)/2) (the quadratic keeps the
/// QP strictly convex): the plan that violates those blocks least under that penalty is walked,
/// reported as MpcStatus::relaxed while it needs the slacks. A block of weight 0 stays hard; all
/// 0 (the default) keeps the thesis's behaviour, an infeasible QP fails the tick. The fallback
/// changes no tick whose QP solves within nwsr; a tick that needs it solves up to
/// 1 + sqp_corrections elastic QPs of up to 10 nwsr active-set changes each (docs/walking.md,
/// "Soft constraints").
template <typename Scalar = double>
struct SoftConstraintWeights {
  Scalar zmp_polygon = Scalar(0);           ///< ZMP in the support polygon (eq. 2.65–2.69)
  Scalar footstep_feasibility = Scalar(0);  ///< footsteps in reach (eq. 2.70–2.72)
  Scalar relative_yaw = Scalar(0);          ///< relative yaw and its rate (eq. 2.73–2.74)
  Scalar foot_separation = Scalar(0);       ///< soles apart
  /// Footsteps outside obstacles' R + m (eq. 2.79–2.82): a plan that cannot keep the margin m
  /// enters it as little as it can instead of failing.
  Scalar obstacles = Scalar(0);
  Scalar capture_point = Scalar(0);  ///< terminal capture point
};

/// How the generator plans: timing, horizon, cost weights, solver limits, the commands it
/// accepts and the states it believes. Part of WalkingSettings. In-class defaults: HRP-2's.
template <typename Scalar = double>
struct GeneratorSettings {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;

  /// [s] duration of one step, single + double support (`t_step`). Longer: slower, calmer gait.
  Scalar t_step = Scalar(0.8);
  Scalar t_ds = Scalar(0.4);              ///< [s] double support time within each step, `t_ds`
  int n = 16;                             ///< preview intervals N (eq. 2.30)
  Scalar t = Scalar(0.1);                 ///< [s] preview sampling period T (eq. 2.31)
  Scalar t_feedback = Scalar(0.1);        ///< [s] CoM and feet feedback period, `t_feedback`
  Scalar command_period = Scalar(0.005);  ///< [s] period of the interpolated trajectories
  int n_still = 0;  ///< preview horizons to stand still at the start, `n_still`
  /// Cost weights (eq. 2.43–2.46): alpha tracks the velocity command, beta centres the ZMP in the
  /// foot, gamma penalises jerk. Raising beta trades command tracking for ZMP margin; gamma > 0
  /// keeps the QP strictly convex and smooths the CoM.
  Scalar alpha = Scalar(1), beta = Scalar(1e-6), gamma = Scalar(1e-5);
  /// Weight of the step velocity: each planned footstep's displacement from the previous one,
  /// divided by t_step, tracks the command (plus the lateral foot_distance), per (m/s)² and
  /// horizon sample like alpha. It carries the mean walking velocity that the instantaneous
  /// CoM velocity cost (alpha) cannot, as that cost also charges the sway (docs/tuning.md).
  Scalar step_velocity_weight = Scalar(100);
  /// Weight of the heading: each planned footstep's yaw tracks the reference heading (the
  /// commanded yaw rate integrated since the last reset, at the middle of that foot's support),
  /// per rad² like the yaw-rate term of alpha (S / t_step² per step). The yaw-rate term alone
  /// only sees differences between consecutive feet: a bias of both feet went uncorrected and
  /// the feet's yaws bought ZMP margin from the feasibility polygons, so straight commands
  /// veered (Heicub 7 cm over 2.35 m, issue 24).
  Scalar heading_weight = Scalar(10);
  /// [s] the thesis's qpOASES wall-clock limit (`cpu_time`). Accepted for compatibility and
  /// ignored: a wall-clock limit made the thesis's runs fail under load (docs/design.md §4);
  /// walkgen limits work by iterations (`nwsr`) instead.
  Scalar cpu_time = Scalar(0.01);
  /// Maximal active-set changes per QP solve (`nwsr`); reaching it fails the tick safely (with
  /// soft constraints, `soft`, the tick falls back to the elastic QP instead).
  int nwsr = 100;
  /// Largest velocity command walked (|v_x| [m/s], |v_y| [m/s], |ω_z| [rad/s]): a larger
  /// component is clamped to it (CommandStatus::clamped), a non-finite command rejected. The
  /// presets accept what their feasibility polygons and yaw limit can reach: HRP-2 steps at most
  /// 0.28 m forward per 0.8 s step (0.35 m/s); sideways, the leading foot at most 0.4 m from the
  /// other, 0.2 m beyond foot_distance per 1.6 s gait cycle (0.125 m/s); it turns at most
  /// max_relative_yaw per step (0.31 rad/s).
  Vector3 max_command = Vector3(Scalar(0.35), Scalar(0.12), Scalar(0.3));
  /// Proximal weight on the footstep variables (x, y, yaw) toward the previous plan. Keeps the
  /// QP strictly convex when the last planned step has no ZMP sample in the horizon (at the
  /// first sample of every step); small enough not to move a step that the cost determines.
  Scalar footstep_regularization = Scalar(1e-9);
  /// Gauss–Newton iterations per tick: 1 is the real-time iteration (eq. 2.83–2.89).
  int sqp_iterations = 1;
  /// Further Gauss–Newton iterations, at most, when the plan violates the nonlinear
  /// constraints (rotated polygons) by more than sqp_tolerance after sqp_iterations: the
  /// linearisation error of a large change of foot yaw. 0 keeps exactly sqp_iterations.
  /// Gauss–Newton converges linearly at first: a cold start after a 0.1 m/s push violates the
  /// polygons by 53, 14, 5.8, 2.7 and 0.14 mm after 1–5 iterations, hence 4 (issue 21).
  int sqp_corrections = 4;
  /// [m] largest tolerated violation of the nonlinear constraints (a distance beyond a
  /// polygon edge or inside an obstacle's margin) before a correction iteration.
  Scalar sqp_tolerance = Scalar(1e-3);
  /// Soft constraints: the exact-penalty weight of each block, 0 = hard (SoftConstraintWeights).
  SoftConstraintWeights<Scalar> soft;
  /// Plausibility limits of WalkingMpc::set_state(): a state beyond them is a feedback glitch,
  /// not a walking robot, and is rejected with an error. [m] the largest horizontal distance of
  /// the CoM, the swing foot and its origin from the support foot.
  Scalar max_state_distance = Scalar(2);
  /// [m/s] the largest CoM speed along x or y, and [m/s²] the largest CoM acceleration, that
  /// set_state() accepts.
  Scalar max_com_speed = Scalar(5), max_com_acceleration = Scalar(50);

  /// Samples of the preview horizon per step, t_step / t (an integer after validate(), which
  /// also bounds it by settings_limits::kMaxSamplesPerStep).
  int samples_per_step() const {
    const Scalar ratio = t_step / t;
    return ratio >= Scalar(0) && ratio <= Scalar(1 << 30) ? static_cast<int>(std::lround(ratio))
                                                          : 0;
  }
  /// Footsteps planned within the horizon (N_f in the thesis): the most steps after the current
  /// one that N samples can reach, ⌊(N + S − 2) / S⌋ with S = samples_per_step(); the thesis's
  /// ⌊N T / t_step⌋ for a whole number of steps.
  int planned_steps() const {
    const long long S = samples_per_step();
    return S > 0 ? static_cast<int>((static_cast<long long>(n) + S - 2) / S) : 0;
  }
};

/// Where the walk starts: the CoM's state and the support foot (Table 6.1's initial values).
/// Part of WalkingSettings. In-class defaults: HRP-2's.
template <typename Scalar = double>
struct InitialState {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;

  Vector3 com_x = Vector3(Scalar(0), Scalar(0), Scalar(0));    ///< CoM x, ẋ, ẍ [m, m/s, m/s²]
  Vector3 com_y = Vector3(Scalar(0.1), Scalar(0), Scalar(0));  ///< CoM y, ẏ, ÿ
  Vector3 com_q = Vector3(Scalar(0), Scalar(0), Scalar(0));  ///< CoM yaw θ, θ̇, θ̈ [rad, …]
  Foot support_foot = Foot::left;                            ///< initial support foot
  Scalar foot_x = Scalar(0);    ///< [m] initial support foot x (eq. 2.47)
  Scalar foot_y = Scalar(0.1);  ///< [m] initial support foot y
  Scalar foot_q = Scalar(0);    ///< [rad] initial support foot yaw
};

/// Pattern generator settings: every key of Table 6.1 plus walkgen's own, in three parts that
/// can be set and validated on their own (a robot's geometry, the generator's settings, the
/// initial state) and the obstacles. The members of the parts are members of WalkingSettings
/// (`s.t_step`, `s.foot_width`, the flat keys of the thesis's files); geometry(), generator()
/// and initial_state() give the parts. The in-class defaults are the HRP-2 set (hrp2_settings()).
template <typename Scalar = double>
struct WalkingSettings : RobotGeometry<Scalar>, GeneratorSettings<Scalar>, InitialState<Scalar> {
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Polygon = Eigen::Matrix<Scalar, Eigen::Dynamic, 2>;

  /// Circles the footsteps keep out of (Table 6.1 has one: `obstacle`, `x_pos`, `y_pos`,
  /// `radius`; walkgen any number).
  std::vector<CircleObstacle<Scalar>> obstacles;

  RobotGeometry<Scalar>& geometry() { return *this; }
  const RobotGeometry<Scalar>& geometry() const { return *this; }
  GeneratorSettings<Scalar>& generator() { return *this; }
  const GeneratorSettings<Scalar>& generator() const { return *this; }
  InitialState<Scalar>& initial_state() { return *this; }
  const InitialState<Scalar>& initial_state() const { return *this; }
};

/// Settings assembled from their parts (e.g. a robot preset's geometry with a generator tuned
/// for a task and a chosen start).
template <typename Scalar>
WalkingSettings<Scalar> walking_settings(const RobotGeometry<Scalar>& geometry,
                                         const GeneratorSettings<Scalar>& generator,
                                         const InitialState<Scalar>& initial,
                                         std::vector<CircleObstacle<Scalar>> obstacles = {}) {
  WalkingSettings<Scalar> s;
  s.geometry() = geometry;
  s.generator() = generator;
  s.initial_state() = initial;
  s.obstacles = std::move(obstacles);
  return s;
}

/// HRP-2 (thesis §9.1, figures 9.1–9.3): the in-class defaults.
template <typename Scalar = double>
WalkingSettings<Scalar> hrp2_settings() {
  return WalkingSettings<Scalar>();
}

/// Heicub (thesis Table 6.1). The feasibility hulls beyond Table 6.1's first vertex are those of
/// the thesis's Heicub configuration (configs.yaml of github.com/mhubii/nmpc_pattern_generator).
template <typename Scalar = double>
WalkingSettings<Scalar> heicub_settings() {
  WalkingSettings<Scalar> s;
  s.t_step = Scalar(3.2);
  s.security_margin << Scalar(0.02), Scalar(0.02);
  s.left_foot_convex_hull.resize(5, 2);
  s.left_foot_convex_hull << -0.11, 0.14, -0.10, 0.16, 0.00, 0.17, 0.10, 0.16, 0.11, 0.14;
  s.right_foot_convex_hull = detail::mirror_y<Scalar>(s.left_foot_convex_hull);
  s.foot_width = Scalar(0.1);
  s.foot_length = Scalar(0.2);
  s.foot_distance = Scalar(0.14);
  s.command_period = Scalar(0.01);
  s.n_still = 0;
  s.t_ds = Scalar(1.6);
  s.step_height = Scalar(0.03);
  s.com_x << Scalar(0), Scalar(0), Scalar(0);
  s.com_y << Scalar(0.05), Scalar(0), Scalar(0);
  s.com_z = Scalar(0.45);
  s.foot_x = Scalar(0);
  s.foot_y = Scalar(0.07);
  s.foot_q = Scalar(0);
  s.n = 16;
  s.t = Scalar(0.4);
  s.t_feedback = Scalar(0.4);
  s.alpha = Scalar(1);
  s.beta = Scalar(1e2);
  s.gamma = Scalar(1e-2);
  // beta = 1e2 centres the ZMP 10⁸ times harder than HRP-2's: the step velocity must weigh
  // comparably for the gait to follow the command (docs/tuning.md: forward 0.92 of the
  // command at 100, 0.99 at 1000; sideways at 100 nothing below 0.002 m/s).
  s.step_velocity_weight = Scalar(1000);
  // Reach (see max_command): 0.11 m per 3.2 s step forward, 0.03 m per 6.4 s cycle sideways,
  // 0.25 rad per step.
  s.max_command << Scalar(0.034), Scalar(0.0045), Scalar(0.075);
  return s;
}

/// Ranges that validate() enforces on the integer settings and on the magnitudes that the QP
/// squares or sums (beyond them int arithmetic would overflow or the QP lose every digit).
namespace settings_limits {
constexpr int kMaxHorizon = 1000;              ///< n: preview samples (the QP has ~2n variables)
constexpr int kMaxSamplesPerStep = 1000;       ///< t_step / t
constexpr int kMaxSqpIterations = 100;         ///< sqp_iterations, and sqp_corrections alike
constexpr int kMaxActiveSetChanges = 1000000;  ///< nwsr
constexpr int kMaxStillHorizons = 1000000;     ///< n_still
constexpr double kMaxPosition = 1e6;     ///< [m] |com|, |foot|, obstacle centres, radii, sizes
constexpr double kMinPeriod = 1e-4;      ///< [s] t, t_step, t_ds, t_feedback, command_period
constexpr double kMaxPeriod = 1e3;       ///< [s] the same
constexpr double kMaxWeight = 1e12;      ///< alpha, beta, gamma, step_velocity_weight, ...
constexpr double kMinGamma = 1e-12;      ///< gamma keeps H definite; smaller leaves it singular
constexpr double kMinSoftWeight = 1e-6;  ///< a soft constraint's weight, when not 0
}  // namespace settings_limits

namespace detail {
template <typename Scalar>
bool is_multiple(Scalar value, Scalar period) {
  const Scalar k = value / period;
  return std::abs(k - std::round(k)) <= Scalar(1e-6) * std::max(Scalar(1), std::abs(k));
}
}  // namespace detail

namespace detail {
/// The checks validate() shares: each names the key ("WalkingSettings.<key>", the flat key of
/// the YAML files) and builds its message only when it fails.
template <typename Scalar>
struct SettingsChecks {
  static void count(const char* where, int value, int lo, int hi) {
    check_argument(value >= lo && value <= hi, where,
                   "a count in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", value);
  }
  /// value in [lo, hi], or in (lo, hi] with lower_open.
  static void range(const char* where, Scalar value, double lo, double hi, bool lower_open) {
    const bool above = lower_open ? value > Scalar(lo) : value >= Scalar(lo);
    if (!(std::isfinite(value) && above && value <= Scalar(hi))) {
      std::ostringstream text;
      text << "a value in " << (lower_open ? "(" : "[") << lo << ", " << hi << "]";
      check_argument(false, where, text.str(), value);
    }
  }
  static void up_to(const char* where, Scalar value, double hi, bool zero_ok) {
    range(where, value, 0.0, hi, !zero_ok);
  }
  static void between(const char* where, Scalar value, double lo, double hi) {
    range(where, value, lo, hi, false);
  }
  static void position(const char* where, Scalar value) {
    check_argument(std::isfinite(value) && std::abs(value) <= Scalar(settings_limits::kMaxPosition),
                   where, "a finite value with |value| <= 1e6", value);
  }
  template <typename Vertices>
  static void polygon(const char* where, const Vertices& vertices) {
    check_argument(vertices.allFinite() &&
                       (vertices.array().abs() <= Scalar(settings_limits::kMaxPosition)).all(),
                   where, "vertices with |coordinate| <= 1e6 m", "NaN, inf or larger");
    check_convex_polygon(where, vertices);
  }
};
}  // namespace detail

/// Checks a robot's geometry on its own.
/// @throws walkgen::invalid_argument naming the first offending key, with expected and got.
template <typename Scalar>
void validate(const RobotGeometry<Scalar>& s) {
  namespace lim = settings_limits;
  using C = detail::SettingsChecks<Scalar>;
  C::up_to("WalkingSettings.step_height", s.step_height, lim::kMaxPosition, true);
  C::up_to("WalkingSettings.foot_width", s.foot_width, lim::kMaxPosition, false);
  C::up_to("WalkingSettings.foot_length", s.foot_length, lim::kMaxPosition, false);
  C::up_to("WalkingSettings.foot_distance", s.foot_distance, lim::kMaxPosition, false);
  C::up_to("WalkingSettings.security_margin[0]", s.security_margin[0], lim::kMaxPosition, true);
  C::up_to("WalkingSettings.security_margin[1]", s.security_margin[1], lim::kMaxPosition, true);
  check_argument(Scalar(2) * s.security_margin[0] < s.foot_length,
                 "WalkingSettings.security_margin[0]", "less than half the foot length",
                 s.security_margin[0], "the shrunk support polygon would be empty");
  check_argument(Scalar(2) * s.security_margin[1] < s.foot_width,
                 "WalkingSettings.security_margin[1]", "less than half the foot width",
                 s.security_margin[1], "the shrunk support polygon would be empty");
  C::polygon("WalkingSettings.left_foot_convex_hull", s.left_foot_convex_hull);
  C::polygon("WalkingSettings.right_foot_convex_hull", s.right_foot_convex_hull);
  C::between("WalkingSettings.com_z", s.com_z, 1e-3, lim::kMaxPosition);
  C::between("WalkingSettings.gravity", s.gravity, 1e-2, 1e3);
  C::up_to("WalkingSettings.max_relative_yaw", s.max_relative_yaw, 1e3, false);
  C::up_to("WalkingSettings.min_foot_separation", s.min_foot_separation, lim::kMaxPosition, true);
  C::up_to("WalkingSettings.max_relative_yaw_rate", s.max_relative_yaw_rate, 1e3, false);
  if (s.zmp_polygon.rows() > 0) C::polygon("WalkingSettings.zmp_polygon", s.zmp_polygon);
}

/// Checks the generator's settings on their own.
/// @throws walkgen::invalid_argument naming the first offending key, with expected and got.
template <typename Scalar>
void validate(const GeneratorSettings<Scalar>& s) {
  namespace lim = settings_limits;
  using C = detail::SettingsChecks<Scalar>;
  C::count("WalkingSettings.n", s.n, 1, lim::kMaxHorizon);
  C::between("WalkingSettings.t", s.t, lim::kMinPeriod, lim::kMaxPeriod);
  C::between("WalkingSettings.t_step", s.t_step, lim::kMinPeriod, lim::kMaxPeriod);
  check_argument(s.t_step / s.t <= Scalar(lim::kMaxSamplesPerStep), "WalkingSettings.t_step",
                 "at most 1000 samples of t = " + std::to_string(s.t) + " s per step", s.t_step);
  check_argument(s.t_step >= s.t && detail::is_multiple(s.t_step, s.t), "WalkingSettings.t_step",
                 "a whole multiple of t = " + std::to_string(s.t) + " s", s.t_step);
  check_argument(
      s.planned_steps() >= 1, "WalkingSettings.n",
      "a horizon n·t covering at least one step (t_step = " + std::to_string(s.t_step) + " s)", s.n,
      "increase n or shorten t_step");
  check_argument(std::isfinite(s.t_ds) && s.t_ds >= s.t * (Scalar(1) - Scalar(1e-9)),
                 "WalkingSettings.t_ds",
                 "a double support of at least t = " + std::to_string(s.t) + " s", s.t_ds,
                 "the ZMP moves to the new foot during the first interval of every step");
  check_argument(s.t_ds < s.t_step, "WalkingSettings.t_ds", "a double support shorter than t_step",
                 s.t_ds);
  C::between("WalkingSettings.t_ds", s.t_ds, lim::kMinPeriod, lim::kMaxPeriod);
  C::between("WalkingSettings.command_period", s.command_period, lim::kMinPeriod, lim::kMaxPeriod);
  check_argument(s.command_period <= s.t && detail::is_multiple(s.t, s.command_period),
                 "WalkingSettings.command_period", "a period that divides t evenly",
                 s.command_period);
  C::between("WalkingSettings.t_feedback", s.t_feedback, lim::kMinPeriod, lim::kMaxPeriod);
  C::count("WalkingSettings.n_still", s.n_still, 0, lim::kMaxStillHorizons);
  C::up_to("WalkingSettings.cpu_time", s.cpu_time, lim::kMaxPeriod, true);
  C::up_to("WalkingSettings.alpha", s.alpha, lim::kMaxWeight, true);
  C::up_to("WalkingSettings.beta", s.beta, lim::kMaxWeight, true);
  C::up_to("WalkingSettings.step_velocity_weight", s.step_velocity_weight, lim::kMaxWeight, true);
  C::up_to("WalkingSettings.heading_weight", s.heading_weight, lim::kMaxWeight, true);
  C::up_to("WalkingSettings.gamma", s.gamma, lim::kMaxWeight, false);
  check_argument(s.gamma >= Scalar(lim::kMinGamma), "WalkingSettings.gamma",
                 "a jerk weight >= 1e-12 (it keeps the QP strictly convex)", s.gamma);
  C::count("WalkingSettings.nwsr", s.nwsr, 1, lim::kMaxActiveSetChanges);
  C::count("WalkingSettings.sqp_iterations", s.sqp_iterations, 1, lim::kMaxSqpIterations);
  C::count("WalkingSettings.sqp_corrections", s.sqp_corrections, 0, lim::kMaxSqpIterations);
  C::between("WalkingSettings.sqp_tolerance", s.sqp_tolerance, 1e-9, lim::kMaxPosition);
  const std::pair<const char*, Scalar> soft[] = {
      {"WalkingSettings.soft.zmp_polygon", s.soft.zmp_polygon},
      {"WalkingSettings.soft.footstep_feasibility", s.soft.footstep_feasibility},
      {"WalkingSettings.soft.relative_yaw", s.soft.relative_yaw},
      {"WalkingSettings.soft.foot_separation", s.soft.foot_separation},
      {"WalkingSettings.soft.obstacles", s.soft.obstacles},
      {"WalkingSettings.soft.capture_point", s.soft.capture_point}};
  for (const auto& [key, w] : soft) {
    check_argument(w == Scalar(0) || (w >= Scalar(lim::kMinSoftWeight) && w <= lim::kMaxWeight),
                   key, "0 (hard) or a weight in [1e-6, 1e12]", w,
                   "a smaller weight leaves the elastic QP's slack Hessian singular");
  }
  check_argument(s.max_command.allFinite() && (s.max_command.array() >= Scalar(0)).all() &&
                     (s.max_command.array() <= Scalar(1e3)).all(),
                 "WalkingSettings.max_command", "finite limits in [0, 1e3]",
                 "NaN, inf, negative or larger");
  C::up_to("WalkingSettings.footstep_regularization", s.footstep_regularization, lim::kMaxWeight,
           true);
  C::up_to("WalkingSettings.max_state_distance", s.max_state_distance, lim::kMaxPosition, false);
  C::up_to("WalkingSettings.max_com_speed", s.max_com_speed, 1e3, false);
  C::up_to("WalkingSettings.max_com_acceleration", s.max_com_acceleration, 1e4, false);
}

/// Checks an initial state on its own (finite, within the position limits).
/// @throws walkgen::invalid_argument naming the first offending key, with expected and got.
template <typename Scalar>
void validate(const InitialState<Scalar>& s) {
  using C = detail::SettingsChecks<Scalar>;
  check_argument(s.com_x.allFinite() && s.com_y.allFinite() && s.com_q.allFinite(),
                 "WalkingSettings.com_x/com_y/com_q", "finite values", "NaN or inf");
  C::position("WalkingSettings.com_x[0]", s.com_x[0]);
  C::position("WalkingSettings.com_y[0]", s.com_y[0]);
  C::position("WalkingSettings.foot_x", s.foot_x);
  C::position("WalkingSettings.foot_y", s.foot_y);
  check_argument(std::isfinite(s.foot_q), "WalkingSettings.foot_q", "a finite yaw", s.foot_q);
}

/// Checks a settings set before a generator is built from it: each part, then what ties them
/// together (the initial state within the generator's plausibility limits) and the obstacles.
/// @throws walkgen::invalid_argument naming the first offending key, with expected and got.
template <typename Scalar>
void validate(const WalkingSettings<Scalar>& s) {
  using C = detail::SettingsChecks<Scalar>;
  validate(s.generator());
  validate(s.geometry());
  validate(s.initial_state());
  check_argument(std::hypot(s.com_x[0] - s.foot_x, s.com_y[0] - s.foot_y) <= s.max_state_distance &&
                     std::abs(s.com_x[1]) <= s.max_com_speed &&
                     std::abs(s.com_y[1]) <= s.max_com_speed &&
                     std::abs(s.com_x[2]) <= s.max_com_acceleration &&
                     std::abs(s.com_y[2]) <= s.max_com_acceleration,
                 "WalkingSettings.com_x/com_y",
                 "an initial CoM within max_state_distance of "
                 "(foot_x, foot_y), max_com_speed and max_com_acceleration",
                 "an implausible initial state");
  for (const auto& o : s.obstacles) {
    C::position("WalkingSettings.obstacles[].x", o.x);
    C::position("WalkingSettings.obstacles[].y", o.y);
    C::up_to("WalkingSettings.obstacles[].radius", o.radius, settings_limits::kMaxPosition, false);
    C::up_to("WalkingSettings.obstacles[].margin", o.margin, settings_limits::kMaxPosition, true);
  }
}

/// The interpolator's numbers of a settings set (interpolation/trajectory.hpp).
template <typename Scalar>
InterpolationSettings<Scalar> interpolation_settings(const WalkingSettings<Scalar>& s) {
  return {s.t, s.command_period, s.com_z, s.gravity};
}

}  // namespace walkgen
