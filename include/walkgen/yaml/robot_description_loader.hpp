#pragma once
/// @file
/// A robot description file (`models/<robot>/robot.yaml`) into a RobotDescription
/// (walkgen/robot/robot_description.hpp): a robot becomes data, not code. Part of walkgen::yaml.
///
/// Keys (docs/robots.md has the reference and an example):
///   name (required), mjcf (required), urdf: paths relative to the file; base_body (required)
///   and torso_body (held upright by the IK);
///   joints (required): the actuated joints the walking controller commands, in order;
///   sole_frames (required), ft_sensor_frames, cameras: [left, right] frame or camera names;
///   ft_sensor_height [m] (with ft_sensor_frames); imu_site (sensors "<site>_quat", "_gyro",
///   "_acc" in the MJCF); frames: {name: {body, xyz, rpy}} added to
///   bodies of the model (e.g. soles of a model without sites); stand_keyframe;
///   stand_pose: {joint: angle [rad]}; joint_groups: {group: {joints: [..], kp, kd, held}}
///   (feedback gains of a torque-controlled robot; held: true keeps the group at its stand pose);
///   sole_polygon: [[x, y] x 4] (each sole's contact region, symmetric about x, where it is not
///   the walking settings' rectangle); balance: {com_kp, com_kd, nmpc_feedback} (a torque-driven
///   robot's contact feed-forward with CoM feedback; nmpc_feedback: false walks the plan without
///   restarting it); walking_preset: hrp2 | heicub (default heicub), the defaults of walking:
///   {walking-settings keys of docs/yaml.md, flat or in sections}.
/// Unknown keys, a missing required key and values of the wrong type are errors naming the key
/// and the file's line; validate(RobotDescription) runs on the result.

#include <yaml-cpp/yaml.h>

#include <array>
#include <string>
#include <vector>

#include "walkgen/robot/robot_description.hpp"
#include "walkgen/yaml/settings_loader.hpp"

namespace walkgen {

namespace detail {

/// `base` / `relative` unless `relative` is absolute or empty.
inline std::string path_beside(const std::string& base_dir, const std::string& relative) {
  if (relative.empty() || relative.front() == '/' || base_dir.empty()) return relative;
  return base_dir + "/" + relative;
}

inline RobotDescription robot_description_from_node_unguarded(const YAML::Node& root,
                                                              const std::string& source,
                                                              const std::string& base_dir);

/// Reads a description; a yaml-cpp error the checks did not foresee becomes an
/// invalid_argument naming the document.
inline RobotDescription robot_description_from_node(const YAML::Node& root,
                                                    const std::string& source,
                                                    const std::string& base_dir) {
  try {
    return robot_description_from_node_unguarded(root, source, base_dir);
  } catch (const YAML::Exception& e) {
    throw invalid_argument(expected_got(source.c_str(), "a readable robot description", e.what()));
  }
}

inline RobotDescription robot_description_from_node_unguarded(const YAML::Node& root,
                                                              const std::string& source,
                                                              const std::string& base_dir) {
  const YamlValue doc{source, "", root};
  check_argument(root.IsMap(), source.c_str(), "a map of robot description keys",
                 yaml_describe(root));
  static const char* const kKeys[] = {"name",
                                      "mjcf",
                                      "urdf",
                                      "base_body",
                                      "torso_body",
                                      "joints",
                                      "sole_frames",
                                      "ft_sensor_frames",
                                      "ft_sensor_height",
                                      "cameras",
                                      "imu_site",
                                      "frames",
                                      "stand_keyframe",
                                      "stand_pose",
                                      "joint_groups",
                                      "sole_polygon",
                                      "balance",
                                      "walking_preset",
                                      "walking"};
  std::string known;
  for (const char* k : kKeys) known += (known.empty() ? "" : ", ") + std::string(k);
  std::vector<std::string> seen;
  for (const auto& kv : root) {
    const std::string key = YamlValue{source, "", kv.first}.as<std::string>("a key name");
    bool ok = false;
    for (const char* k : kKeys) ok = ok || key == k;
    const std::string at = yaml_where(source, kv.first, key);
    check_argument(ok, at.c_str(), "a robot description key", "an unknown key",
                   ("known keys: " + known).c_str());
    for (const std::string& s : seen) {
      check_argument(s != key, at.c_str(), "each key once", "it repeated");
    }
    seen.push_back(key);
  }
  const auto value = [&](const char* key) { return YamlValue{source, key, root[key]}; };
  const auto required = [&](const char* key) {
    check_argument(root[key].IsDefined(), source.c_str(), std::string("the key '") + key + "'",
                   "none", ("a robot description needs " + std::string(key)).c_str());
    return value(key);
  };
  const auto text = [](const YamlValue& v) { return v.as<std::string>("a name"); };
  const auto pair = [&](const YamlValue& v) {
    v.check(v.node.IsSequence() && v.node.size() == 2, "a list [left, right] of two names");
    return std::array<std::string, 2>{
        {text(v.child(v.node[0], "[0]")), text(v.child(v.node[1], "[1]"))}};
  };

  RobotDescription d;
  d.name = text(required("name"));
  d.mjcf_path = path_beside(base_dir, text(required("mjcf")));
  if (root["urdf"]) d.urdf_path = path_beside(base_dir, text(value("urdf")));
  d.base_body = text(required("base_body"));
  if (root["torso_body"]) d.torso_body = text(value("torso_body"));
  {
    const YamlValue joints = required("joints");
    joints.check(joints.node.IsSequence() && joints.node.size() >= 1, "a list of joint names");
    for (std::size_t i = 0; i < joints.node.size(); ++i) {
      d.joint_names.push_back(text(joints.child(joints.node[i], "[" + std::to_string(i) + "]")));
    }
  }
  d.sole_frames = pair(required("sole_frames"));
  if (root["ft_sensor_frames"]) {
    d.ft_sensor_frames = pair(value("ft_sensor_frames"));
    d.ft_sensor_height = required("ft_sensor_height").number<double>();
  } else if (root["ft_sensor_height"]) {
    check_argument(false, value("ft_sensor_height").where().c_str(),
                   "ft_sensor_height only with ft_sensor_frames", "it alone");
  }
  if (root["cameras"]) d.cameras = pair(value("cameras"));
  if (root["imu_site"]) d.imu_site = text(value("imu_site"));
  if (root["frames"]) {
    const YamlValue frames = value("frames");
    frames.check(frames.node.IsMap(), "a map {name: {body: .., xyz: [..], rpy: [..]}}");
    for (const auto& kv : frames.node) {
      const std::string name = text(frames.child(kv.first, ".<name>"));
      const YamlValue f = frames.child(kv.second, "." + name);
      f.check(f.node.IsMap(), "a map {body: .., xyz: [x, y, z], rpy: [r, p, y]}");
      FrameDescription frame;
      frame.name = name;
      for (const auto& field : f.node) {
        const std::string k = field.first.Scalar();
        const YamlValue fv = f.child(field.second, "." + k);
        if (k == "body") {
          frame.body = text(fv);
        } else if (k == "xyz") {
          fv.read(frame.xyz);
        } else if (k == "rpy") {
          fv.read(frame.rpy);
        } else {
          check_argument(false, fv.where().c_str(), "body, xyz or rpy", "an unknown key");
        }
      }
      f.check(!frame.body.empty(), "a map with the key body");
      d.frames.push_back(frame);
    }
  }
  if (root["stand_keyframe"]) d.stand_keyframe = text(value("stand_keyframe"));
  if (root["stand_pose"]) {
    const YamlValue pose = value("stand_pose");
    pose.check(pose.node.IsMap(), "a map {joint: angle [rad]}");
    for (const auto& kv : pose.node) {
      const std::string joint = text(pose.child(kv.first, ".<joint>"));
      d.stand_pose.push_back({joint, pose.child(kv.second, "." + joint).number<double>()});
    }
  }
  if (root["joint_groups"]) {
    const YamlValue groups = value("joint_groups");
    groups.check(groups.node.IsMap(), "a map {group: {joints: [..], kp: .., kd: ..}}");
    for (const auto& kv : groups.node) {
      JointGroup group;
      group.name = text(groups.child(kv.first, ".<group>"));
      const YamlValue g = groups.child(kv.second, "." + group.name);
      g.check(g.node.IsMap(), "a map {joints: [..], kp: [N m/rad], kd: [N m s/rad]}");
      bool has_kp = false, has_kd = false;
      for (const auto& field : g.node) {
        const std::string k = field.first.Scalar();
        const YamlValue fv = g.child(field.second, "." + k);
        if (k == "joints") {
          fv.check(fv.node.IsSequence() && fv.node.size() >= 1, "a list of joint names");
          for (std::size_t i = 0; i < fv.node.size(); ++i) {
            group.joints.push_back(text(fv.child(fv.node[i], "[" + std::to_string(i) + "]")));
          }
        } else if (k == "kp") {
          group.kp = fv.number<double>();
          has_kp = true;
        } else if (k == "kd") {
          group.kd = fv.number<double>();
          has_kd = true;
        } else if (k == "held") {
          fv.read(group.held);
        } else {
          check_argument(false, fv.where().c_str(), "joints, kp, kd or held", "an unknown key");
        }
      }
      g.check(!group.joints.empty() && has_kp && has_kd, "a map with joints, kp and kd");
      d.joint_groups.push_back(group);
    }
  }
  if (root["sole_polygon"]) {
    const YamlValue polygon = value("sole_polygon");
    polygon.check(polygon.node.IsSequence() && polygon.node.size() == 4,
                  "a list of four corners [[x, y], ...] in the sole frame");
    for (std::size_t i = 0; i < 4; ++i) {
      const YamlValue c = polygon.child(polygon.node[i], "[" + std::to_string(i) + "]");
      c.check(c.node.IsSequence() && c.node.size() == 2, "a corner [x, y] [m]");
      d.sole_polygon.emplace_back(c.child(c.node[0], "[0]").number<double>(),
                                  c.child(c.node[1], "[1]").number<double>());
    }
  }
  if (root["balance"]) {
    const YamlValue b = value("balance");
    b.check(b.node.IsMap(), "a map {com_kp, com_kd, nmpc_feedback}");
    d.balance.contact_feedforward = true;
    for (const auto& field : b.node) {
      const std::string k = text(b.child(field.first, ".<key>"));
      const YamlValue fv = b.child(field.second, "." + k);
      if (k == "com_kp") {
        d.balance.com_kp = fv.number<double>();
      } else if (k == "com_kd") {
        d.balance.com_kd = fv.number<double>();
      } else if (k == "nmpc_feedback") {
        fv.read(d.balance.nmpc_feedback);
      } else {
        check_argument(false, fv.where().c_str(), "com_kp, com_kd or nmpc_feedback",
                       "an unknown key");
      }
    }
  }
  std::string preset = "heicub";
  if (root["walking_preset"]) {
    preset = text(value("walking_preset"));
    check_argument(preset == "heicub" || preset == "hrp2", value("walking_preset").where().c_str(),
                   "hrp2 or heicub", "'" + preset + "'");
  }
  const WalkingSettings<double> defaults =
      preset == "hrp2" ? hrp2_settings<double>() : heicub_settings<double>();
  d.walking =
      root["walking"] ? walking_settings_from_node(root["walking"], source, defaults) : defaults;
  try {
    validate(d);
  } catch (const invalid_argument& e) {
    throw invalid_argument(source + ": " + e.what());
  }
  return d;
}

}  // namespace detail

/// A robot description from a YAML file; relative model paths are taken beside the file.
/// @throws walkgen::invalid_argument for an unreadable or malformed file, an unknown or missing
///   key, a value of the wrong type (naming the key and its line) or an invalid description.
[[nodiscard]] inline RobotDescription load_robot_description(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? std::string(".") : path.substr(0, slash);
  return detail::robot_description_from_node(
      detail::load_yaml(path, [&] { return YAML::LoadFile(path); }), path, dir);
}

/// A robot description from YAML text; relative model paths are taken beside `base_dir`.
/// @throws walkgen::invalid_argument as load_robot_description().
[[nodiscard]] inline RobotDescription robot_description_from_yaml(const std::string& text,
                                                                  const std::string& base_dir) {
  const std::string source = "YAML text";
  return detail::robot_description_from_node(
      detail::load_yaml(source, [&] { return YAML::Load(text); }), source, base_dir);
}

/// The description file of a robot: NAME (models/NAME/robot.yaml under data_dir()) or a path
/// to a .yaml file.
/// @throws walkgen::invalid_argument as load_robot_description().
[[nodiscard]] inline RobotDescription find_robot_description(const std::string& name_or_path) {
  const bool is_path =
      name_or_path.find('/') != std::string::npos ||
      (name_or_path.size() > 5 && name_or_path.compare(name_or_path.size() - 5, 5, ".yaml") == 0);
  return load_robot_description(is_path ? name_or_path
                                        : data_path("models/" + name_or_path + "/robot.yaml"));
}

}  // namespace walkgen
