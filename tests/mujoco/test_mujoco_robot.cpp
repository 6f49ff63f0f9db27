// walkgen::MujocoRobot on walkgen's humanoid (models/walkgen_humanoid.xml): loading and name
// mapping, standing with the measured ZMP (thesis eq. 2.11-2.17) against MuJoCo's own centre of
// pressure, falls, bad commands and bad models, and the chest cameras.
#include "walkgen/mujoco/mujoco_robot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/enum_strings.hpp"
#include "support/expect_error.hpp"
#include "walkgen/core/math.hpp"

namespace {

using walkgen::MujocoRobot;
using walkgen::MujocoRobotSettings;
using walkgen::RobotStatus;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string thrown_message(const MujocoRobotSettings& settings) {
  try {
    MujocoRobot robot(settings);
  } catch (const walkgen::invalid_argument& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

/// MuJoCo's centre of pressure: contact positions weighted by their normal forces.
Eigen::Vector2d contact_cop(const mjModel* m, const mjData* d) {
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero();
  double total = 0.0;
  for (int i = 0; i < d->ncon; ++i) {
    mjtNum force[6];
    mj_contactForce(m, d, i, force);
    const double fz = force[0] * d->contact[i].frame[2];  // normal force, world z component
    weighted += fz * Eigen::Vector2d(d->contact[i].pos[0], d->contact[i].pos[1]);
    total += fz;
  }
  return weighted / total;
}

/// Signed distance of p inside the convex hull of points (> 0 inside); Andrew's monotone chain.
double depth_in_hull(std::vector<Eigen::Vector2d> pts, const Eigen::Vector2d& p) {
  std::sort(pts.begin(), pts.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {  // upper hull
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  double depth = 1e9;  // counter-clockwise: the interior is left of every edge
  for (std::size_t i = 0; i + 1 < k; ++i) {
    const Eigen::Vector2d edge = hull[i + 1] - hull[i];
    depth = std::min(depth, cross(hull[i], hull[i + 1], p) / edge.norm());
  }
  return depth;
}

TEST(MujocoRobot, LoadsTheHumanoidAndMapsEveryName) {
  MujocoRobot robot;
  const walkgen::RobotInfo& info = robot.info();
  ASSERT_EQ(info.joint_names.size(), 15u);
  EXPECT_EQ(info.joint_names.front(), "l_hip_pitch");
  EXPECT_EQ(info.joint_names.back(), "torso_yaw");
  EXPECT_DOUBLE_EQ(info.ft_sensor_height, 0.03);
  EXPECT_DOUBLE_EQ(info.timestep, 0.002);
  EXPECT_EQ(info.image_width, 320);
  EXPECT_EQ(info.image_height, 240);
  EXPECT_NEAR(info.nominal_base_height, 0.5062, 1e-9);
  EXPECT_NEAR(info.fall_height, 0.8 * 0.5062, 1e-9);
  const walkgen::RobotOutput& out = robot.output();
  EXPECT_EQ(out.status, RobotStatus::ok);
  EXPECT_EQ(out.q.size(), 15);
  EXPECT_NEAR(out.q[0], -0.5, 1e-12);  // stand: hip pitch -0.5, knee 1.0, ankle pitch -0.5
  EXPECT_NEAR(out.q[3], 1.0, 1e-12);
  EXPECT_NEAR(out.q[4], -0.5, 1e-12);
  // The sensor sites 0.03 m above the soles, 0.14 m apart; both feet carry weight.
  EXPECT_NEAR(out.sensor(walkgen::Foot::left).pose_W_S.translation().y(), 0.07, 1e-6);
  EXPECT_NEAR(out.sensor(walkgen::Foot::right).pose_W_S.translation().y(), -0.07, 1e-6);
  EXPECT_NEAR(out.sensor(walkgen::Foot::left).pose_W_S.translation().z(), 0.03, 1e-3);
}

TEST(MujocoRobot, StandsInTheKeyframeWithTheMeasuredZmpUnderTheCom) {
  MujocoRobot robot;
  ASSERT_EQ(robot.step(2.0), RobotStatus::ok) << robot.output().message;
  const walkgen::RobotOutput& out = robot.output();
  EXPECT_NEAR(out.time, 2.0, 1e-9);
  const double nominal = robot.info().nominal_base_height;
  EXPECT_NEAR(out.base_height, nominal, 0.05 * nominal);

  const walkgen::MeasuredZmp zmp = walkgen::measured_zmp(out.ft, robot.info().ft_sensor_height);
  ASSERT_TRUE(zmp.valid);
  EXPECT_TRUE(zmp.in_contact[0] && zmp.in_contact[1]);
  // The feet (2 x 0.8 kg) are below the sensors: the sensors carry the rest of the 25 kg.
  EXPECT_NEAR(zmp.normal_force, (25.0 - 1.6) * 9.81, 2.0);

  // Inside the support polygon: the convex hull of both soles (0.2 x 0.1 m).
  std::vector<Eigen::Vector2d> corners;
  for (const char* sole : {"l_sole", "r_sole"}) {
    const int id = mj_name2id(robot.model(), mjOBJ_SITE, sole);
    ASSERT_GE(id, 0);
    const mjData* d = robot.data();
    for (double sx : {-0.1, 0.1}) {
      for (double sy : {-0.05, 0.05}) {
        corners.emplace_back(
            d->site_xpos[3 * id] + d->site_xmat[9 * id] * sx + d->site_xmat[9 * id + 1] * sy,
            d->site_xpos[3 * id + 1] + d->site_xmat[9 * id + 3] * sx +
                d->site_xmat[9 * id + 4] * sy);
      }
    }
  }
  const Eigen::Vector2d zmp_xy = zmp.zmp_W.head<2>();
  EXPECT_GT(depth_in_hull(corners, zmp_xy), 0.04);  // well inside: 5 cm is the hull's half width

  // Against MuJoCo's centre of pressure and the ground projection of the centre of mass.
  const Eigen::Vector2d cop = contact_cop(robot.model(), robot.data());
  const Eigen::Vector2d com(robot.data()->subtree_com[3], robot.data()->subtree_com[4]);
  std::printf("measured ZMP (%.5f, %.5f) m, MuJoCo CoP (%.5f, %.5f) m, CoM (%.5f, %.5f) m\n",
              zmp_xy.x(), zmp_xy.y(), cop.x(), cop.y(), com.x(), com.y());
  EXPECT_LT((zmp_xy - cop).norm(), 0.003);
  EXPECT_LT((zmp_xy - com).norm(), 0.003);
}

// The base IMU (site "imu" at the root link's origin): at rest the accelerometer reads +g along
// the vertical; after one physics step from a tilted, spinning base the orientation is the root
// body's and the gyroscope reads the free joint's angular velocity (MuJoCo's: in the body frame).
TEST(MujocoRobot, ReadsTheBaseImu) {
  MujocoRobot robot;
  ASSERT_EQ(robot.step(1.0), RobotStatus::ok) << robot.output().message;
  const walkgen::ImuReading& rest = robot.output().imu;
  ASSERT_TRUE(rest.available);
  EXPECT_LT(rest.tilt(), 0.01);
  EXPECT_LT(rest.angular_velocity_I.norm(), 0.01);
  EXPECT_NEAR(rest.acceleration_I.z(), 9.81, 0.05);
  EXPECT_LT(rest.acceleration_I.head<2>().norm(), 0.1);

  mjData* d = robot.data();
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  d->qpos[3] = tilted.w();
  d->qpos[4] = tilted.x();
  d->qpos[5] = tilted.y();
  d->qpos[6] = tilted.z();
  d->qvel[3] = 0.5;
  d->qvel[4] = -0.2;
  d->qvel[5] = 0.1;
  ASSERT_EQ(robot.step(0.002), RobotStatus::ok) << robot.output().message;
  const walkgen::ImuReading& imu = robot.output().imu;
  const int base = mj_name2id(robot.model(), mjOBJ_BODY, "root_link");
  const Eigen::Quaterniond body(d->xquat[4 * base], d->xquat[4 * base + 1], d->xquat[4 * base + 2],
                                d->xquat[4 * base + 3]);
  EXPECT_LT(imu.orientation_W_I.angularDistance(body), 1e-9);
  EXPECT_LT((imu.angular_velocity_I - Eigen::Map<const Eigen::Vector3d>(d->qvel + 3)).norm(), 1e-9);
  EXPECT_NEAR(imu.tilt(), std::acos((body * Eigen::Vector3d::UnitZ()).z()), 1e-9);
  EXPECT_NEAR(imu.tilt(), 0.3, 0.01);  // one step of 0.5 rad/s about x moves it 1 mrad

  walkgen::MujocoRobotSettings none;
  none.imu_site.clear();
  EXPECT_FALSE(MujocoRobot(none).output().imu.available);
}

TEST(MujocoRobot, ReportsAPushedRobotAsFallenAndStopsUntilReset) {
  MujocoRobot robot;
  ASSERT_EQ(robot.set_joint_targets(Eigen::VectorXd::Zero(15)),
            walkgen::JointCommandStatus::accepted);
  robot.data()->qvel[1] = 2.0;  // 2 m/s sideways
  EXPECT_EQ(robot.step(3.0), RobotStatus::fallen);
  const walkgen::RobotOutput& out = robot.output();
  EXPECT_LT(out.base_height, robot.info().fall_height);
  EXPECT_NE(out.message.find("fallen"), std::string::npos) << out.message;
  std::printf("%s\n", out.message.c_str());
  const double t_fall = out.time;
  EXPECT_LT(t_fall, 3.0);
  EXPECT_EQ(robot.step(0.1), RobotStatus::fallen);  // never continues silently
  EXPECT_EQ(robot.output().time, t_fall);
  robot.reset();
  EXPECT_EQ(robot.output().status, RobotStatus::ok);
  EXPECT_EQ(robot.output().time, 0.0);
  EXPECT_EQ(robot.step(0.1), RobotStatus::ok);
}

TEST(MujocoRobot, ReportsARobotWithoutAFloorAsFallen) {
  std::string xml = read_text(walkgen::humanoid_mjcf_path());
  const std::size_t floor = xml.find("<geom name=\"floor\"");
  ASSERT_NE(floor, std::string::npos);
  xml.erase(floor, xml.find('\n', floor) - floor);
  MujocoRobotSettings settings;
  settings.model_path = write_temp("walkgen_humanoid_no_floor.xml", xml);
  // The model directory is not needed: the humanoid has no mesh or texture files.
  MujocoRobot robot(settings);
  EXPECT_EQ(robot.step(1.0), RobotStatus::fallen);
  std::printf("%s\n", robot.output().message.c_str());
  EXPECT_LT(robot.output().time, 0.5);
}

TEST(MujocoRobot, RejectsNonFiniteCommandsAndThrowsOnWrongSizes) {
  MujocoRobot robot;
  Eigen::VectorXd q = robot.output().q;
  q[3] = std::nan("");
  EXPECT_EQ(robot.set_joint_targets(q), walkgen::JointCommandStatus::rejected);
  q[3] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(robot.set_joint_targets(q), walkgen::JointCommandStatus::rejected);
  ASSERT_EQ(robot.step(0.5), RobotStatus::ok);
  MujocoRobot reference;  // never commanded: keeps the stand targets
  ASSERT_EQ(reference.step(0.5), RobotStatus::ok);
  EXPECT_TRUE(robot.output().q.allFinite());
  EXPECT_EQ(robot.output().q, reference.output().q);  // the bad commands changed nothing
  EXPECT_THROW((void)robot.set_joint_targets(Eigen::VectorXd::Zero(14)), walkgen::invalid_argument);
  EXPECT_THROW((void)robot.step(0.0), walkgen::invalid_argument);
  EXPECT_THROW((void)robot.step(std::nan("")), walkgen::invalid_argument);
}

TEST(MujocoRobot, WrongNamesThrowNamingEveryMissingOne) {
  MujocoRobotSettings settings;
  settings.joint_names[3] = "l_kneee";
  settings.joint_names.push_back("neck_yaw");
  settings.ft_sensor_sites[1] = "r_ankle_sensor";
  const std::string message = thrown_message(settings);
  std::printf("%s\n", message.c_str());
  for (const char* expected : {"joint 'l_kneee'", "joint 'neck_yaw'", "site 'r_ankle_sensor'",
                               "sensor 'r_ankle_sensor_force'", "walkgen_humanoid.xml",
                               "the model has joints [", "l_hip_pitch, "}) {
    EXPECT_NE(message.find(expected), std::string::npos) << expected << " in: " << message;
  }
  EXPECT_EQ(message.find("'l_knee'"), std::string::npos) << message;

  MujocoRobotSettings fewer;  // a model actuator without a joint name
  fewer.joint_names.pop_back();
  EXPECT_NE(thrown_message(fewer).find("expected 14 (one per joint name), got 15"),
            std::string::npos)
      << thrown_message(fewer);
}

TEST(MujocoRobot, UnknownOrBrokenModelFilesThrowNamingTheFile) {
  MujocoRobotSettings missing;
  missing.model_path = "/nonexistent/robot.xml";
  const std::string m1 = thrown_message(missing);
  EXPECT_NE(m1.find("'/nonexistent/robot.xml' (cannot be opened)"), std::string::npos) << m1;

  MujocoRobotSettings broken;
  broken.model_path = write_temp("walkgen_broken.xml", "<mujoco><worldbody><body>\n");
  const std::string m2 = thrown_message(broken);
  std::printf("%s\n", m2.c_str());
  EXPECT_NE(m2.find("walkgen_broken.xml"), std::string::npos) << m2;
  EXPECT_NE(m2.find("MuJoCo: "), std::string::npos) << m2;
}

TEST(MujocoRobot, RendersBothChestCamerasWithDepth) {
  MujocoRobot robot;
  ASSERT_EQ(robot.step(0.1), RobotStatus::ok);
  const walkgen::StereoImages& images = robot.render_cameras();
  // scripts/setup.sh installs EGL and Mesa's software renderer: rendering must work here. (Where
  // it cannot, render_cameras() says so with this prefix instead of crashing.)
  if (images.status != walkgen::RenderStatus::ok) {
    EXPECT_EQ(images.message.rfind("rendering unavailable: ", 0), 0u) << images.message;
    FAIL() << images.message;
  }
  for (const walkgen::CameraImage* image : {&images.left, &images.right}) {
    ASSERT_EQ(image->width, 320);
    ASSERT_EQ(image->height, 240);
    ASSERT_EQ(image->rgb.size(), 320u * 240u * 3u);
    ASSERT_EQ(image->depth.size(), 320u * 240u);
    const auto rgb = std::minmax_element(image->rgb.begin(), image->rgb.end());
    EXPECT_GT(*rgb.second - *rgb.first, 30) << "a uniform image";
    for (float z : image->depth) {
      ASSERT_TRUE(std::isfinite(z));
      ASSERT_GE(z, image->near_clip * 0.999);
      ASSERT_LE(z, image->far_clip * 1.001);
    }
    EXPECT_NEAR(image->fovy, 45.0 * walkgen::kPi / 180.0, 1e-12);
    // A pinhole camera: the ray through a pixel's centre meets the floor at that pixel's depth
    // (along the optical axis, x of the camera frame). Checks the depth scale and the pose.
    const double focal = 0.5 * image->height / std::tan(0.5 * image->fovy);  // [px]
    for (int row : {119, 160, 239}) {
      const int col = 100;
      const Eigen::Vector3d ray_C(1.0, -((col + 0.5) - 0.5 * image->width) / focal,
                                  (0.5 * image->height - (row + 0.5)) / focal);
      const Eigen::Vector3d ray_W = image->pose_W_C.linear() * ray_C;
      ASSERT_LT(ray_W.z(), 0.0);  // looks down at the floor
      const double expected = -image->pose_W_C.translation().z() / ray_W.z();
      const double measured = image->depth[static_cast<std::size_t>(row) * image->width + col];
      std::printf("row %d: depth %.4f m, floor along the pixel's ray %.4f m\n", row, measured,
                  expected);
      EXPECT_NEAR(measured, expected, 0.001 * expected);
    }
  }
  EXPECT_NEAR(images.left.pose_W_C.translation().y() - images.right.pose_W_C.translation().y(),
              0.068, 1e-6);
  EXPECT_NE(images.left.rgb, images.right.rgb);
}

TEST(MujocoRobot, AddsSceneObjectsToTheWorldAndRendersAFreeView) {
  MujocoRobotSettings settings;
  walkgen::SceneObject box;
  box.name = "chair";
  box.position = Eigen::Vector3d(1.0, 0.5, 0.0);
  box.size = Eigen::Vector3d(0.2, 0.3, 0.4);
  box.rgb = Eigen::Vector3d(0.9, 0.1, 0.1);
  walkgen::SceneObject ghost;
  ghost.name = "target";
  ghost.shape = walkgen::SceneShape::cylinder;
  ghost.position = Eigen::Vector3d(-1.0, 0.0, 0.0);
  ghost.size = Eigen::Vector3d(0.05, 0.05, 0.35);
  ghost.collides = false;
  settings.objects = {box, ghost};
  MujocoRobot robot(settings);
  const mjModel* m = robot.model();
  const int chair = mj_name2id(m, mjOBJ_GEOM, "chair");
  const int target = mj_name2id(m, mjOBJ_GEOM, "target");
  ASSERT_GE(chair, 0);
  ASSERT_GE(target, 0);
  EXPECT_EQ(m->geom_type[chair], mjGEOM_BOX);
  EXPECT_NEAR(m->geom_size[3 * chair + 0], 0.1, 1e-12);  // half sizes
  EXPECT_NEAR(m->geom_size[3 * chair + 2], 0.2, 1e-12);
  EXPECT_EQ(m->geom_type[target], mjGEOM_CYLINDER);
  EXPECT_EQ(m->geom_contype[target], 0);
  EXPECT_EQ(m->geom_conaffinity[target], 0);
  ASSERT_EQ(robot.step(0.05), RobotStatus::ok);
  const double* p = robot.data()->geom_xpos + 3 * chair;
  EXPECT_NEAR(p[0], 1.0, 1e-12);
  EXPECT_NEAR(p[1], 0.5, 1e-12);
  EXPECT_NEAR(p[2], 0.2, 1e-12);                          // standing on the floor
  EXPECT_NEAR(robot.output().base_height, 0.5062, 0.01);  // the keyframe still fits

  walkgen::CameraImage view;
  ASSERT_TRUE(robot.render_view({1.0, 0.5, 0.2}, 1.5, 180.0, -20.0, 160, 120, view))
      << robot.render_cameras().message;
  ASSERT_EQ(view.rgb.size(), 160u * 120u * 3u);
  const std::size_t centre = (60u * 160u + 80u) * 3u;  // looking at the red box
  EXPECT_GT(int(view.rgb[centre]), 2 * int(view.rgb[centre + 1]));
  EXPECT_NEAR(view.depth[60u * 160u + 80u], 1.5 - 0.1, 0.05);  // its face, 0.1 m before the centre
  EXPECT_THROW((void)robot.render_view({0, 0, 0}, 1.0, 0.0, 0.0, 4000, 10, view),
               walkgen::invalid_argument);

  settings.objects = {box};
  settings.objects[0].name = "bad name";
  EXPECT_NE(thrown_message(settings).find("'bad name'"), std::string::npos);
  settings.objects[0].name = "ok";
  settings.objects[0].size.x() = -1.0;
  EXPECT_NE(thrown_message(settings).find("'ok'"), std::string::npos);
}

// A model split over files (the G1's scene includes its robot file, whose meshes lie in a
// folder beside it): with objects added, the includes are still read from the model's folder.
TEST(MujocoRobot, AddsObjectsToAModelThatIncludesFilesFromItsFolder) {
  const std::string folder = ::testing::TempDir() + "walkgen_split_model/";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::ofstream(folder + "robot_part.xml") << read_text(walkgen::humanoid_mjcf_path());
  std::ofstream(folder + "scene.xml")
      << "<mujoco model=\"scene\">\n  <include file=\"robot_part.xml\"/>\n"
         "  <worldbody>\n    <light name=\"lamp\" pos=\"1 0 3\"/>\n  </worldbody>\n</mujoco>\n";
  MujocoRobotSettings settings;
  settings.model_path = folder + "scene.xml";
  walkgen::SceneObject box;
  box.name = "chair";
  box.position = Eigen::Vector3d(1.0, 0.5, 0.0);
  box.size = Eigen::Vector3d(0.2, 0.3, 0.4);
  settings.objects = {box};
  MujocoRobot robot(settings);  // threw "Include error ... robot_part.xml" before
  EXPECT_GE(mj_name2id(robot.model(), mjOBJ_GEOM, "chair"), 0);
  EXPECT_GE(mj_name2id(robot.model(), mjOBJ_LIGHT, "lamp"), 0);
  ASSERT_EQ(robot.step(0.05), RobotStatus::ok);
  EXPECT_NEAR(robot.output().base_height, 0.5062, 0.01);  // the robot of the included file
}

TEST(MujocoRobot, MovesMovableObjectsAndTexturesTexturedOnes) {
  MujocoRobotSettings settings;
  walkgen::SceneObject person;
  person.name = "person";
  person.shape = walkgen::SceneShape::cylinder;
  person.position = Eigen::Vector3d(2.0, 1.0, 0.0);
  person.size = Eigen::Vector3d(0.2, 0.2, 1.7);
  person.movable = true;
  walkgen::SceneObject wall;
  wall.name = "wall";
  wall.position = Eigen::Vector3d(1.5, 0.0, 0.0);
  wall.size = Eigen::Vector3d(0.1, 2.0, 1.0);
  wall.rgb = Eigen::Vector3d(0.2, 0.6, 0.3);
  wall.textured = true;
  settings.objects = {person, wall};
  MujocoRobot robot(settings);
  const int geom = mj_name2id(robot.model(), mjOBJ_GEOM, "person");
  ASSERT_GE(geom, 0);
  ASSERT_EQ(robot.step(0.01), RobotStatus::ok);
  const double* p = robot.data()->geom_xpos + 3 * geom;
  EXPECT_NEAR(p[0], 2.0, 1e-9);  // the keyframe reset kept the object where it was placed
  EXPECT_NEAR(p[1], 1.0, 1e-9);
  EXPECT_NEAR(p[2], 0.85, 1e-9);
  robot.set_object_position("person", {2.5, -0.5, 0.0});
  ASSERT_EQ(robot.step(0.01), RobotStatus::ok);
  EXPECT_NEAR(p[0], 2.5, 1e-9);
  EXPECT_NEAR(p[1], -0.5, 1e-9);
  EXPECT_NEAR(p[2], 0.85, 1e-9);
  EXPECT_THROW(robot.set_object_position("wall", {0, 0, 0}), walkgen::invalid_argument);
  EXPECT_THROW(robot.set_object_position("nobody", {0, 0, 0}), walkgen::invalid_argument);
  EXPECT_THROW(robot.set_object_position("person", {std::nan(""), 0, 0}),
               walkgen::invalid_argument);
  // The textured wall fills the chest cameras' view: speckle, not one flat colour.
  const walkgen::StereoImages& images = robot.render_cameras();
  ASSERT_EQ(images.status, walkgen::RenderStatus::ok) << images.message;
  const walkgen::CameraImage& left = images.left;
  int lo = 255, hi = 0;
  for (int col = 140; col < 180; ++col) {  // the middle of the image: the wall
    const int g = left.rgb[(std::size_t(100) * left.width + col) * 3 + 1];
    lo = std::min(lo, g);
    hi = std::max(hi, g);
  }
  EXPECT_GT(hi - lo, 40);
  EXPECT_NEAR(left.depth[std::size_t(100) * left.width + 160],
              1.45 - left.pose_W_C.translation().x(), 0.05);
}

// The settings that need no model are checked first (validate()), naming the field.
TEST(MujocoRobot, SettingsAreValidatedNamingTheField) {
  using S = MujocoRobotSettings;
  walkgen::SceneObject box;
  box.name = "box";
  walkgen_test::expect_rejected<S>(
      S(), {{[](S& s) { s.joint_names.clear(); }, {"MujocoRobotSettings.joint_names", "none"}},
            {[](S& s) { s.fall_height_ratio = 1.5; },
             {"MujocoRobotSettings.fall_height_ratio", "(0, 1)", "1.5"}},
            {[](S& s) { s.fall_height_ratio = std::nan(""); },
             {"MujocoRobotSettings.fall_height_ratio", "nan"}},
            {[](S& s) { s.view_width = 0; }, {"MujocoRobotSettings.view_width", "[1, 16384]", "0"}},
            {[](S& s) { s.view_height = 100000; }, {"MujocoRobotSettings.view_height", "100000"}},
            {[box](S& s) {
               s.objects = {box, box};
               s.objects[1].name = "a b";
             },
             {"MujocoRobotSettings.objects: name", "'a b'"}},
            {[box](S& s) {
               s.objects = {box};
               s.objects[0].rgb.x() = 2.0;
             },
             {"MujocoRobotSettings.objects: 'box' rgb", "[0, 1]"}}});
}

TEST(MujocoRobot, SceneShapeStrings) {
  walkgen_test::expect_enum_strings(std::array<walkgen::SceneShape, 3>{
      walkgen::SceneShape::box, walkgen::SceneShape::cylinder, walkgen::SceneShape::sphere});
  static_assert(to_string(walkgen::SceneShape::sphere)[0] == 's');
}

}  // namespace
