#pragma once
/// @file
/// A RobotDescription (walkgen/robot/robot_description.hpp) against the MuJoCo model it names:
/// every name looked up, with an error that lists what the model has; and the robot's
/// kinematic tree from its MJCF plus the frames the description adds. Part of walkgen::mujoco.

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/mujoco/mujoco_kinematics.hpp"
#include "walkgen/robot/robot_description.hpp"

namespace walkgen {

namespace detail {

/// The names of the model's objects of `type` (all, or those `keep` accepts), quoted.
template <typename Keep>
std::string mj_names(const mjModel& m, mjtObj type, int count, Keep keep) {
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) {
    const char* name = mj_id2name(&m, type, i);
    if (name != nullptr && *name != '\0' && keep(i)) names.push_back(name);
  }
  return names.empty() ? std::string("none") : quoted_list(names);
}

}  // namespace detail

/// Checks that every name of `robot` is in `m`: the base and torso bodies, the joints (hinges), the
/// bodies of its added frames, the sole frames (sites or added frames), the force-torque sensor
/// sites with their "<site>_force" / "<site>_torque" sensors, the cameras and the stand keyframe.
/// @throws walkgen::invalid_argument naming the first missing one and listing the model's.
inline void check_robot_against_model(const RobotDescription& robot, const mjModel& m) {
  const std::string where = "robot '" + robot.name + "' in " + robot.mjcf_path;
  const auto all = [](int) { return true; };
  const auto require = [&](bool found, const std::string& what, const std::string& name,
                           mjtObj type, int count, auto keep) {
    check_argument(found, (where + ": " + what).c_str(),
                   "one of the model's: " + detail::mj_names(m, type, count, keep),
                   "'" + name + "'");
  };
  const auto id = [&](mjtObj type, const std::string& name) {
    return mj_name2id(&m, type, name.c_str());
  };
  require(id(mjOBJ_BODY, robot.base_body) > 0, "base_body", robot.base_body, mjOBJ_BODY, m.nbody,
          all);
  if (!robot.torso_body.empty()) {
    require(id(mjOBJ_BODY, robot.torso_body) > 0, "torso_body", robot.torso_body, mjOBJ_BODY,
            m.nbody, all);
  }
  const auto hinge = [&](int j) { return m.jnt_type[j] == mjJNT_HINGE; };
  for (const std::string& joint : robot.joint_names) {
    const int j = id(mjOBJ_JOINT, joint);
    require(j >= 0 && hinge(j), "joint", joint, mjOBJ_JOINT, m.njnt, hinge);
  }
  for (const FrameDescription& f : robot.frames) {
    require(id(mjOBJ_BODY, f.body) > 0, "body of frame '" + f.name + "'", f.body, mjOBJ_BODY,
            m.nbody, all);
    check_argument(id(mjOBJ_BODY, f.name) < 0 && id(mjOBJ_SITE, f.name) < 0,
                   (where + ": frame '" + f.name + "'").c_str(),
                   "a name no body or site of the model has", "a name the model uses");
  }
  for (const std::string& sole : robot.sole_frames) {
    bool added = false;
    for (const FrameDescription& f : robot.frames) added = added || f.name == sole;
    require(added || id(mjOBJ_SITE, sole) >= 0, "sole frame (a site or an added frame)", sole,
            mjOBJ_SITE, m.nsite, all);
  }
  if (!robot.ft_sensor_frames[0].empty()) {
    for (const std::string& site : robot.ft_sensor_frames) {
      require(id(mjOBJ_SITE, site) >= 0, "force-torque sensor site", site, mjOBJ_SITE, m.nsite,
              all);
      for (const char* suffix : {"_force", "_torque"}) {
        require(id(mjOBJ_SENSOR, site + suffix) >= 0, "sensor", site + suffix, mjOBJ_SENSOR,
                m.nsensor, all);
      }
    }
  }
  if (!robot.imu_site.empty()) {
    require(id(mjOBJ_SITE, robot.imu_site) >= 0, "IMU site", robot.imu_site, mjOBJ_SITE, m.nsite,
            all);
    for (const char* suffix : {"_quat", "_gyro", "_acc"}) {
      require(id(mjOBJ_SENSOR, robot.imu_site + suffix) >= 0, "IMU sensor", robot.imu_site + suffix,
              mjOBJ_SENSOR, m.nsensor, all);
    }
  }
  if (!robot.cameras[0].empty()) {
    for (const std::string& camera : robot.cameras) {
      require(id(mjOBJ_CAMERA, camera) >= 0, "camera", camera, mjOBJ_CAMERA, m.ncam, all);
    }
  }
  if (!robot.stand_keyframe.empty()) {
    require(id(mjOBJ_KEY, robot.stand_keyframe) >= 0, "stand_keyframe", robot.stand_keyframe,
            mjOBJ_KEY, m.nkey, all);
  }
}

/// `robot`'s kinematic description from its MJCF model `m` (the subtree of its base body,
/// kinematic_description_from_mujoco()) plus the frames it adds, welded to their bodies.
/// @throws walkgen::invalid_argument as check_robot_against_model().
inline KinematicDescription robot_kinematic_description(const RobotDescription& robot,
                                                        const mjModel& m) {
  check_robot_against_model(robot, m);
  KinematicDescription d = kinematic_description_from_mujoco(m, robot.base_body);
  for (const FrameDescription& f : robot.frames) {
    d.links.push_back({f.name, 0.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()});
    JointDescription weld;
    weld.name = f.name + "_fixed";
    weld.type = JointType::fixed;
    weld.parent = f.body;
    weld.child = f.name;
    weld.xyz = f.xyz;
    weld.rpy = f.rpy;
    d.joints.push_back(weld);
  }
  return d;
}

/// `robot`'s kinematic tree from its MJCF file (robot_kinematic_description()).
/// @throws walkgen::invalid_argument when MuJoCo cannot load the file, or as
///   check_robot_against_model().
template <typename Scalar = double>
[[nodiscard]] KinematicTree<Scalar> robot_kinematic_tree_from_mjcf(const RobotDescription& robot) {
  const detail::LoadedModel l =
      detail::load_mjcf(robot.mjcf_path, "robot_kinematic_tree_from_mjcf");
  return KinematicTree<Scalar>(robot_kinematic_description(robot, *l.m));
}

}  // namespace walkgen
