// walkgen::NavigationScene (thesis §11.1, figures 11.5, 11.13): layouts per task from a seed,
// reproducible, with the geometry each task promises, loadable into MuJoCo with a moving person.
#include "walkgen/mujoco/navigation_scene.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>

#include "support/enum_strings.hpp"
#include "walkgen/core/math.hpp"

namespace {

using walkgen::NavigationTask;

double bearing_deg(const Eigen::Vector2d& p) {
  return std::atan2(p.y(), p.x()) * 180.0 / walkgen::kPi;
}

TEST(NavigationScene, EachTaskHasItsGeometryAndTheSameSeedGivesTheSameRoom) {
  for (std::uint32_t seed = 0; seed < 50; ++seed) {
    const auto straight = walkgen::make_navigation_scene(NavigationTask::straight, seed);
    EXPECT_GE(straight.target.norm(), 1.5);
    EXPECT_LE(straight.target.norm(), 2.5);
    EXPECT_LE(std::abs(bearing_deg(straight.target)), 8.0);
    const auto curved = walkgen::make_navigation_scene(NavigationTask::curved, seed);
    EXPECT_GE(std::abs(bearing_deg(curved.target)), 14.0);
    EXPECT_LE(std::abs(bearing_deg(curved.target)), 24.0);
    const auto scan = walkgen::make_navigation_scene(NavigationTask::scan, seed);
    EXPECT_GE(std::abs(bearing_deg(scan.target)), 150.0);  // behind the robot
    const auto obstacle = walkgen::make_navigation_scene(NavigationTask::obstacle, seed);
    ASSERT_EQ(obstacle.chairs.size(), 1u);
    const Eigen::Vector2d c(obstacle.chairs[0].x, obstacle.chairs[0].y);
    const Eigen::Vector2d d = obstacle.target.normalized();
    const double across = std::abs(d.x() * c.y() - d.y() * c.x());
    EXPECT_LT(across, obstacle.chairs[0].radius);  // it blocks the straight way
    const auto dynamic = walkgen::make_navigation_scene(NavigationTask::dynamic, seed);
    ASSERT_TRUE(dynamic.has_person);
    const auto distractor = walkgen::make_navigation_scene(NavigationTask::distractor, seed);
    ASSERT_TRUE(distractor.has_distractor);
    EXPECT_GT((distractor.distractor - distractor.target).norm(), 0.3);
    // Everything inside the walls.
    for (const auto* s : {&straight, &curved, &scan, &obstacle, &dynamic, &distractor}) {
      EXPECT_LT((s->target - s->room_centre).cwiseAbs().maxCoeff(), s->room_half_size - 0.5);
      EXPECT_LT(s->room_centre.cwiseAbs().maxCoeff(), s->room_half_size - 0.5);  // the start
    }
  }
  const auto a = walkgen::make_navigation_scene(NavigationTask::obstacle, 7);
  const auto b = walkgen::make_navigation_scene(NavigationTask::obstacle, 7);
  const auto c = walkgen::make_navigation_scene(NavigationTask::obstacle, 8);
  EXPECT_EQ(a.target, b.target);
  EXPECT_EQ(a.chairs[0].x, b.chairs[0].x);
  EXPECT_NE(a.target, c.target);
  EXPECT_EQ(walkgen::navigation_task_from_string("scan"), NavigationTask::scan);
  EXPECT_THROW(walkgen::navigation_task_from_string("dance"), walkgen::invalid_argument);
  const auto list = walkgen::navigation_tasks_from_list("scan,obstacle");
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[1], NavigationTask::obstacle);
  EXPECT_THROW(walkgen::navigation_tasks_from_list("scan,,obstacle"), walkgen::invalid_argument);
}

TEST(NavigationScene, TaskNamesFollowTheToStringConvention) {
  const auto all = walkgen::all_navigation_tasks();
  ASSERT_EQ(all.size(), 6u);
  walkgen_test::expect_enum_strings(
      std::array<NavigationTask, 6>{all[0], all[1], all[2], all[3], all[4], all[5]});
  for (NavigationTask t : all) EXPECT_EQ(walkgen::navigation_task_from_string(to_string(t)), t);
}

TEST(NavigationScene, ThePersonWalksBackAndForthAtItsSpeed) {
  walkgen::WalkingPerson p;
  p.from = Eigen::Vector2d(0.0, 1.0);
  p.to = Eigen::Vector2d(0.0, -1.0);
  p.speed = 0.5;
  EXPECT_NEAR((p.position(0.0) - p.from).norm(), 0.0, 1e-12);
  EXPECT_NEAR((p.position(2.0) - Eigen::Vector2d(0.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((p.position(4.0) - p.to).norm(), 0.0, 1e-12);
  EXPECT_NEAR((p.position(6.0) - Eigen::Vector2d(0.0, 0.0)).norm(), 0.0, 1e-12);  // coming back
  EXPECT_NEAR((p.position(8.0) - p.from).norm(), 0.0, 1e-12);
}

TEST(NavigationScene, LoadsIntoMujocoWithEveryObjectAndMovesThePerson) {
  for (NavigationTask task : walkgen::all_navigation_tasks()) {
    const auto scene = walkgen::make_navigation_scene(task, 3);
    walkgen::MujocoRobotSettings settings;
    settings.objects = scene.objects();
    std::set<std::string> names;
    for (const auto& o : settings.objects) EXPECT_TRUE(names.insert(o.name).second) << o.name;
    walkgen::MujocoRobot robot(settings);
    ASSERT_EQ(robot.step(0.02), walkgen::RobotStatus::ok) << walkgen::to_string(task);
    EXPECT_NEAR(robot.output().base_height, 0.5062, 0.01);  // standing, nothing in the way
    const int target = mj_name2id(robot.model(), mjOBJ_GEOM, "target");
    ASSERT_GE(target, 0);
    EXPECT_NEAR(robot.data()->geom_xpos[3 * target], scene.target.x(), 1e-9);
    if (scene.has_person) {
      const Eigen::Vector2d p = scene.person.position(5.0);
      robot.set_object_position("person", {p.x(), p.y(), 0.0});
      ASSERT_EQ(robot.step(0.01), walkgen::RobotStatus::ok);
      const int person = mj_name2id(robot.model(), mjOBJ_GEOM, "person");
      EXPECT_NEAR(robot.data()->geom_xpos[3 * person + 1], p.y(), 1e-9);
    }
  }
}

}  // namespace
