#pragma once
/// @file
/// Rooms for learning to navigate (thesis §11.1, figures 11.5 and 11.13): a target object (a
/// red-orange cylinder standing for the fire extinguisher, 1 m tall so that it stays in view),
/// chairs as obstacles, an object of similar colour as a distractor, a person walking across,
/// all laid out at random from a seed, in a walled room with textured surfaces (block matching
/// needs texture, §3.1). The robot starts at the origin facing +x, the generator's world frame.
/// Part of walkgen::mujoco: it produces MujocoRobotSettings::objects and knows where everything is,
/// so a scripted expert can steer through it (walkgen::GoToTarget) and an evaluation can tell
/// success from collision. Its look (light, floor, colours, the target's size and shape) is a
/// SceneAppearance (walkgen/mujoco/scene_appearance.hpp): the same by default, drawn at random
/// or shifted on request.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/core/obstacle.hpp"
#include "walkgen/mujoco/mujoco_robot.hpp"
#include "walkgen/mujoco/scene_appearance.hpp"

namespace walkgen {

/// The tasks of §9.2 and §11.1.2 (figures 9.4–9.7, 11.13).
enum class NavigationTask : std::uint8_t {
  straight,  ///< the target ahead, 1.5–2.5 m
  curved,  ///< the target 14–24° to the left or right (in the cameras' ±29° view), 1.4–2.2 m
  obstacle,    ///< the target ahead and a chair on the straight way to it
  scan,        ///< the target behind the robot (150–210°): turn, then walk
  dynamic,     ///< the target ahead and a person crossing the way back and forth
  distractor,  ///< the target and an object of similar colour elsewhere in view
};

/// The enumerator's name ("straight", ...), as navigation_task_from_string() reads it; "unknown"
/// for a value out of range.
constexpr const char* to_string(NavigationTask t) noexcept {
  switch (t) {
    case NavigationTask::straight:
      return "straight";
    case NavigationTask::curved:
      return "curved";
    case NavigationTask::obstacle:
      return "obstacle";
    case NavigationTask::scan:
      return "scan";
    case NavigationTask::dynamic:
      return "dynamic";
    case NavigationTask::distractor:
      return "distractor";
  }
  return "unknown";
}

/// Every task, in enum order.
inline std::vector<NavigationTask> all_navigation_tasks() {
  return {NavigationTask::straight, NavigationTask::curved,  NavigationTask::obstacle,
          NavigationTask::scan,     NavigationTask::dynamic, NavigationTask::distractor};
}

/// @throws walkgen::invalid_argument for an unknown name.
inline NavigationTask navigation_task_from_string(const std::string& name) {
  for (NavigationTask t : all_navigation_tasks()) {
    if (name == to_string(t)) return t;
  }
  check_argument(false, "navigation_task_from_string",
                 "straight, curved, obstacle, scan, dynamic or distractor", "'" + name + "'");
  return NavigationTask::straight;
}

/// Tasks from a comma-separated list of names ("straight,scan").
/// @throws walkgen::invalid_argument for an unknown name or an empty list.
inline std::vector<NavigationTask> navigation_tasks_from_list(const std::string& list) {
  std::vector<NavigationTask> tasks;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    tasks.push_back(navigation_task_from_string(list.substr(start, comma - start)));
    start = comma + 1;
  }
  return tasks;
}

/// A person walking back and forth between two points at a constant speed.
struct WalkingPerson {
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();  ///< [m]
  double speed = 0.3;                                                            ///< [m/s]
  double radius = 0.2;                                                           ///< [m]
  double height = 1.7;                                                           ///< [m]

  /// Where the person is at time t [s] (t = 0 at `from`).
  Eigen::Vector2d position(double t) const {
    const double length = (to - from).norm();
    if (!(length > 0.0) || !(speed > 0.0)) return from;
    const double s = std::fmod(speed * std::max(0.0, t), 2.0 * length);
    const double along = s <= length ? s : 2.0 * length - s;
    return from + (to - from) * (along / length);
  }
};

/// One room layout. Lengths [m], world frame of the generator.
struct NavigationScene {
  NavigationTask task = NavigationTask::straight;
  std::uint32_t seed = 0;
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  ///< the target's centre
  std::vector<CircleObstacle<double>> chairs;  ///< static obstacles (radius around the centre)
  bool has_distractor = false;
  Eigen::Vector2d distractor = Eigen::Vector2d::Zero();
  bool has_person = false;
  WalkingPerson person;
  double room_half_size = 3.5;  ///< walls at ±room_half_size around (room_centre)
  Eigen::Vector2d room_centre = Eigen::Vector2d::Zero();
  /// How the room looks: objects() colours and shapes the target, distractor and walls with
  /// it; its `world` part is MujocoRobotSettings::appearance (NavigationEpisode sets both).
  SceneAppearance appearance;

  /// Static obstacles plus the person where it is at time t, each with `margin`, for the NMPC
  /// (eq. 2.79) and the expert.
  std::vector<CircleObstacle<double>> obstacles_at(double t, double margin) const {
    std::vector<CircleObstacle<double>> out;
    for (const auto& c : chairs) out.push_back({c.x, c.y, c.radius, margin});
    if (has_person) {
      const Eigen::Vector2d p = person.position(t);
      out.push_back({p.x(), p.y(), person.radius, margin});
    }
    return out;
  }

  /// The objects for MujocoRobotSettings::objects: four textured walls, the target (visible,
  /// not colliding, so that reaching it is judged by distance), textured chairs, the
  /// distractor, the person (movable), and two textured crates along the walls; the target,
  /// distractor and walls as `appearance` says.
  std::vector<SceneObject> objects() const {
    std::vector<SceneObject> out;
    const double h = room_half_size;
    for (int i = 0; i < 4; ++i) {
      SceneObject w;
      w.name = "wall_" + std::to_string(i);
      const bool along_x = i < 2;
      const double side = (i % 2 == 0) ? 1.0 : -1.0;
      w.position = Eigen::Vector3d(room_centre.x() + (along_x ? 0.0 : side * h),
                                   room_centre.y() + (along_x ? side * h : 0.0), 0.0);
      w.size = along_x ? Eigen::Vector3d(2.0 * h, 0.1, 1.2) : Eigen::Vector3d(0.1, 2.0 * h, 1.2);
      w.rgb = appearance.wall_rgb;
      w.textured = true;
      out.push_back(w);
    }
    SceneObject t;
    t.name = "target";
    t.shape = appearance.target_shape;
    const double r = appearance.target_radius;
    t.position = Eigen::Vector3d(target.x(), target.y(), 0.0);
    t.size = Eigen::Vector3d(r, r, appearance.target_height);
    if (t.shape == SceneShape::box) t.size.head<2>() *= 2.0;  // side, side, height
    if (t.shape == SceneShape::sphere) t.position.z() = appearance.target_height - 2.0 * r;
    t.rgb = appearance.target_rgb;
    t.collides = false;
    out.push_back(t);
    for (std::size_t i = 0; i < chairs.size(); ++i) {
      SceneObject c;
      c.name = "chair_" + std::to_string(i);
      c.position = Eigen::Vector3d(chairs[i].x, chairs[i].y, 0.0);
      const double side = chairs[i].radius * std::sqrt(2.0);
      c.size = Eigen::Vector3d(side, side, 0.45);
      c.rgb = Eigen::Vector3d(0.35, 0.25, 0.15);
      c.textured = true;
      out.push_back(c);
    }
    if (has_distractor) {
      SceneObject d;
      d.name = "distractor";
      d.position = Eigen::Vector3d(distractor.x(), distractor.y(), 0.0);
      d.size = Eigen::Vector3d(0.15, 0.15, 0.3);
      d.rgb = appearance.distractor_rgb;  // of similar colour, a box 0.3 m tall
      d.collides = false;
      out.push_back(d);
    }
    if (has_person) {
      SceneObject p;
      p.name = "person";
      p.shape = SceneShape::cylinder;
      p.position = Eigen::Vector3d(person.from.x(), person.from.y(), 0.0);
      p.size = Eigen::Vector3d(person.radius, person.radius, person.height);
      p.rgb = Eigen::Vector3d(0.2, 0.3, 0.7);
      p.textured = true;
      p.movable = true;
      out.push_back(p);
    }
    for (int i = 0; i < 2; ++i) {  // clutter near the walls, out of every task's way
      SceneObject b;
      b.name = "crate_" + std::to_string(i);
      b.position = Eigen::Vector3d(room_centre.x() + (i == 0 ? 0.6 : -0.4) * h,
                                   room_centre.y() + (i == 0 ? -0.85 : 0.85) * h, 0.0);
      b.size = Eigen::Vector3d(0.4, 0.4, 0.4);
      b.rgb = Eigen::Vector3d(0.3, 0.45, 0.6);
      b.textured = true;
      out.push_back(b);
    }
    return out;
  }
};

/// Margin [m] that the NMPC keeps the footsteps from the rooms' chairs and person (eq. 2.79),
/// for every program walking in them (navigation episodes, teleoperation, the dashboard).
inline constexpr double kNavigationObstacleMargin = 0.12;

/// Moves the scene's person (if it has one) to where it is at time t [s] since the walk began,
/// in the simulation and in the NMPC's obstacles (chairs and person, kNavigationObstacleMargin):
/// the NMPC avoids where the person is now. `Mpc` is a walkgen::WalkingMpc.
template <class Mpc>
void move_person(const NavigationScene& scene, double t, MujocoRobot& robot, Mpc& mpc) {
  if (!scene.has_person) return;
  const Eigen::Vector2d p = scene.person.position(t);
  robot.set_object_position("person", {p.x(), p.y(), 0.0});
  mpc.set_obstacles(scene.obstacles_at(t, kNavigationObstacleMargin));
}

/// A random layout of `task` from `seed` (the same seed gives the same room).
inline NavigationScene make_navigation_scene(NavigationTask task, std::uint32_t seed) {
  std::mt19937 rng(seed * 2654435761u + static_cast<std::uint32_t>(task));
  auto uniform = [&rng](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };
  auto polar = [](double r, double angle_deg) {
    const double a = angle_deg * kPi / 180.0;
    return Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
  };
  NavigationScene s;
  s.task = task;
  s.seed = seed;
  const double side = uniform(0.0, 1.0) < 0.5 ? 1.0 : -1.0;
  switch (task) {
    case NavigationTask::straight:
    case NavigationTask::dynamic:
    case NavigationTask::distractor:
      s.target = polar(uniform(1.5, 2.5), uniform(-8.0, 8.0));
      break;
    case NavigationTask::curved:
      s.target = polar(uniform(1.4, 2.2), side * uniform(14.0, 24.0));
      break;
    case NavigationTask::obstacle:
      s.target = polar(uniform(1.8, 2.5), uniform(-5.0, 5.0));
      break;
    case NavigationTask::scan:
      s.target = polar(uniform(1.2, 2.0), uniform(150.0, 210.0));
      break;
  }
  if (task == NavigationTask::obstacle) {  // on the way, a little off the straight line
    const Eigen::Vector2d mid = s.target * uniform(0.42, 0.55);
    const Eigen::Vector2d normal(-s.target.y(), s.target.x());
    const Eigen::Vector2d c = mid + normal.normalized() * uniform(-0.08, 0.08);
    s.chairs.push_back({c.x(), c.y(), uniform(0.13, 0.17), 0.0});
  }
  if (task == NavigationTask::dynamic) {  // crossing the way between robot and target
    const Eigen::Vector2d mid = s.target * uniform(0.45, 0.6);
    const Eigen::Vector2d across = Eigen::Vector2d(-s.target.y(), s.target.x()).normalized();
    s.has_person = true;
    s.person.from = mid + side * across * 1.2;
    s.person.to = mid - side * across * 1.2;
    s.person.speed = uniform(0.2, 0.35);
  }
  if (task == NavigationTask::distractor) {  // in view, on the other side, not in the way
    s.has_distractor = true;
    s.distractor = polar(uniform(1.3, 2.2), side * uniform(18.0, 30.0));
  }
  // The room around start and target, with at least 1.2 m to spare.
  s.room_centre = s.target / 2.0;
  s.room_half_size = std::max(2.2, s.target.norm() / 2.0 + 1.2);
  return s;
}

}  // namespace walkgen
