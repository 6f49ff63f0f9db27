#!/usr/bin/python3
"""Generates walkgen's humanoid model, modelled on Heicub (thesis section 5), in two formats:

    models/walkgen_humanoid.urdf   kinematics and inertias (walkgen's KinematicTree reads it)
    models/walkgen_humanoid.xml    the same robot for MuJoCo (MJCF): floor, position actuators,
                                   ankle force-torque and joint-position sensors, a base IMU,
                                   chest cameras

Both files are written from the one description below, so they cannot drift apart; both are
committed, and a ctest (model_generator_reproduces) checks that running this script reproduces
them byte for byte. Edit this script, never the generated files, then run

    /usr/bin/python3 models/generate.py            # rewrites the two files beside this script
    /usr/bin/python3 models/generate.py --output-dir DIR

Conventions (models/README.md): x forward, y left, z up, SI units, angles in radians. In the
zero configuration the legs are straight, the feet flat and every link frame is parallel to the
root frame. Every joint axis is +x (roll), +y (pitch) or +z (yaw) of its link frame, so a
positive angle turns the child by the right-hand rule: positive hip pitch swings the leg
backwards, positive knee bends it, positive torso pitch leans forwards.

Standard library only; no timestamps and a fixed order, so the output is reproducible.
"""

import argparse
import math
import os
import sys

MODEL_NAME = "walkgen_humanoid"

# --- Numbers ---------------------------------------------------------------------------------
FOOT_SIZE = (0.2, 0.1, 0.03)     # sole length x width [m] and sole-plate thickness
FOOT_DISTANCE = 0.14             # lateral distance of the sole frames [m]
ANKLE_HEIGHT = 0.06              # ankle joints above the sole [m]
# Position servos: stiffness [N m/rad] of every joint and the joints' viscous damping [N m s/rad].
# Stiff enough that the loaded stance leg tracks the IK to about 5 mrad (walking in MuJoCo:
# 200 let the robot sag 0.1 rad at the ankle and fall sideways), damped near critically.
KP = 2000.0
JOINT_DAMPING = 10.0
FT_SENSOR_HEIGHT = 0.03          # ankle force-torque sensor frame above the sole, d in eq. 2.11
HIP_BELOW_ROOT = 0.06            # hip pitch/roll joints below the root frame [m]
HIP_YAW_BELOW_HIP = 0.04         # hip yaw joint below the hip pitch/roll joints [m]
THIGH = 0.22                     # hip pitch/roll joints to knee [m]
SHANK = 0.22                     # knee to ankle [m]
TORSO_PITCH_ABOVE_ROOT = 0.08    # torso pitch/roll joints above the root frame [m]
TORSO_YAW_ABOVE_ROLL = 0.04      # torso yaw joint (chest frame) above the torso roll joint [m]
CAMERA_BASELINE = 0.068          # distance of the two chest cameras [m]
CAMERA_POSITION = (0.07, 0.19)   # cameras' x and z in the chest frame [m]
CAMERA_PITCH = 0.1               # cameras look down by this angle [rad]
CAMERA_IMAGE = (320, 240)        # width x height [px], 60 fps
CAMERA_FOVY_DEG = 45             # vertical field of view [deg]
CAMERA_HFOV = "1.00880"          # horizontal field of view [rad] = 2 atan(4/3 tan(22.5 deg))
STAND_ANGLES = {"hip_pitch": -0.5, "knee": 1.0, "ankle_pitch": -0.5}  # MJCF keyframe "stand"


def box(size, xyz=(0.0, 0.0, 0.0)):
    return {"type": "box", "size": size, "xyz": xyz}


def cylinder(radius, length, xyz=(0.0, 0.0, 0.0)):
    """A cylinder along the link's z axis."""
    return {"type": "cylinder", "radius": radius, "length": length, "xyz": xyz}


def inertia(mass, shape):
    """Principal moments [kg m^2] of a solid box or z-cylinder about its centre."""
    if shape["type"] == "box":
        a, b, c = shape["size"]
        return (mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12,
                mass * (a * a + b * b) / 12)
    r, h = shape["radius"], shape["length"]
    side = mass * (3 * r * r + h * h) / 12
    return (side, side, mass * r * r / 2)


def link(name, mass, shape, rgba):
    """A body whose mass is spread as a solid `shape` (its centre is the centre of mass)."""
    return {"name": name, "mass": mass, "shape": shape, "rgba": rgba}


def joint(name, parent, child, xyz, axis, limits, effort, kp, rpy=(0.0, 0.0, 0.0)):
    return {"name": name, "type": "revolute", "parent": parent, "child": child, "xyz": xyz,
            "rpy": rpy, "axis": axis, "limits": limits, "effort": effort, "kp": kp}


def fixed(name, parent, child, xyz, rpy=(0.0, 0.0, 0.0)):
    return {"name": name, "type": "fixed", "parent": parent, "child": child, "xyz": xyz,
            "rpy": rpy}


GREY = (0.6, 0.6, 0.65, 1.0)
DARK = (0.25, 0.25, 0.3, 1.0)
ORANGE = (0.9, 0.5, 0.1, 1.0)
AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


def leg(side):
    """Links and joints of one leg; side 'l' (y > 0) or 'r'. Roll and yaw limits are mirrored."""
    s = 1.0 if side == "l" else -1.0

    def mirrored(lower, upper):  # limits of the left leg -> this leg's
        return (lower, upper) if s > 0 else (-upper, -lower)

    p = side + "_"
    links = [
        link(p + "hip_1", 0.5, cylinder(0.035, 0.07), DARK),
        link(p + "hip_2", 0.6, box((0.07, 0.06, 0.07), (0.0, 0.0, -0.02)), DARK),
        link(p + "upper_leg", 2.3,
             cylinder(0.045, THIGH - HIP_YAW_BELOW_HIP,
                      (0.0, 0.0, -(THIGH - HIP_YAW_BELOW_HIP) / 2)), GREY),
        link(p + "lower_leg", 1.6, cylinder(0.04, SHANK, (0.0, 0.0, -SHANK / 2)), GREY),
        link(p + "ankle_1", 0.3, box((0.06, 0.05, 0.05)), DARK),
        link(p + "foot", 0.8,
             box(FOOT_SIZE, (0.0, 0.0, FOOT_SIZE[2] / 2 - ANKLE_HEIGHT)), ORANGE),
    ]
    # (joint, parent, child, origin xyz, axis, limits of the left leg [rad], effort [N m], kp)
    joints = [
        joint(p + "hip_pitch", "root_link", p + "hip_1",
              (0.0, s * FOOT_DISTANCE / 2, -HIP_BELOW_ROOT), "y", (-1.9, 0.6), 150.0, KP),
        joint(p + "hip_roll", p + "hip_1", p + "hip_2", (0.0, 0.0, 0.0), "x",
              mirrored(-0.35, 1.2), 150.0, KP),
        joint(p + "hip_yaw", p + "hip_2", p + "upper_leg", (0.0, 0.0, -HIP_YAW_BELOW_HIP), "z",
              mirrored(-1.0, 1.0), 100.0, KP),
        joint(p + "knee", p + "upper_leg", p + "lower_leg",
              (0.0, 0.0, -(THIGH - HIP_YAW_BELOW_HIP)), "y", (0.0, 2.0), 150.0, KP),
        joint(p + "ankle_pitch", p + "lower_leg", p + "ankle_1", (0.0, 0.0, -SHANK), "y",
              (-0.8, 0.8), 150.0, KP),
        joint(p + "ankle_roll", p + "ankle_1", p + "foot", (0.0, 0.0, 0.0), "x",
              mirrored(-0.4, 0.4), 100.0, KP),
    ]
    frames = [
        fixed(p + "sole_fixed", p + "foot", p + "sole", (0.0, 0.0, -ANKLE_HEIGHT)),
        fixed(p + "foot_ft_sensor_fixed", p + "foot", p + "foot_ft_sensor",
              (0.0, 0.0, FT_SENSOR_HEIGHT - ANKLE_HEIGHT)),
    ]
    return links, joints, frames


def robot():
    """The whole robot: links (with mass), joints (revolute, in q order) and fixed frames."""
    links = [link("root_link", 4.2, box((0.12, 0.22, 0.1), (0.0, 0.0, -0.01)), GREY)]
    joints, frames = [], []
    for side in ("l", "r"):
        leg_links, leg_joints, leg_frames = leg(side)
        links += leg_links
        joints += leg_joints
        frames += leg_frames
    links += [
        link("torso_1", 0.4, cylinder(0.03, 0.06), DARK),
        link("torso_2", 0.4, box((0.05, 0.05, 0.04), (0.0, 0.0, 0.02)), DARK),
        link("chest", 7.8, box((0.14, 0.22, 0.2), (0.0, 0.0, 0.1)), GREY),
    ]
    joints += [
        joint("torso_pitch", "root_link", "torso_1", (0.0, 0.0, TORSO_PITCH_ABOVE_ROOT), "y",
              (-0.4, 1.0), 150.0, KP),
        joint("torso_roll", "torso_1", "torso_2", (0.0, 0.0, 0.0), "x", (-0.5, 0.5), 150.0, KP),
        joint("torso_yaw", "torso_2", "chest", (0.0, 0.0, TORSO_YAW_ABOVE_ROLL), "z",
              (-0.9, 0.9), 100.0, KP),
    ]
    x, z = CAMERA_POSITION
    for name, y in (("left_camera", CAMERA_BASELINE / 2), ("right_camera", -CAMERA_BASELINE / 2)):
        frames.append(fixed(name + "_fixed", "chest", name, (x, y, z), (0.0, CAMERA_PITCH, 0.0)))
    return links, joints, frames


# --- Text ------------------------------------------------------------------------------------
def num(value):
    """Shortest text that reads back as the same double (10 significant digits at most)."""
    text = "%.10g" % value
    return "0" if text in ("0", "-0") else text


def nums(values):
    return " ".join(num(v) for v in values)


def check(links, joints, frames):
    """Sanity of the description: names, tree shape, inertias (the loaders check again)."""
    names = [l["name"] for l in links] + [f["child"] for f in frames]
    assert len(set(names)) == len(names), "duplicate link names"
    for l in links:
        moments = inertia(l["mass"], l["shape"])
        a, b, c = (float(num(m)) for m in moments)
        assert l["mass"] > 0 and min(a, b, c) > 0, l["name"]
        assert a + b >= c and b + c >= a and a + c >= b, "triangle inequality: " + l["name"]
    for j in joints + frames:
        assert j["parent"] in names and j["child"] in names, j["name"]


def header_comment(links):
    total = sum(l["mass"] for l in links)
    return ("Generated by models/generate.py from one description; do not edit, run the script. "
            "walkgen's humanoid modelled on Heicub: 15 revolute joints and a floating base, "
            "%s kg, x forward, y left, z up, zero configuration = straight legs, feet flat. "
            "See models/README.md." % num(total))


def urdf(links, joints, frames):
    out = ['<?xml version="1.0"?>', "<!-- %s -->" % header_comment(links),
           '<robot name="%s">' % MODEL_NAME]
    colours = {GREY: "grey", DARK: "dark", ORANGE: "orange"}
    for rgba, name in colours.items():
        out.append('  <material name="%s"><color rgba="%s"/></material>' % (name, nums(rgba)))
    for l in links:
        shape = l["shape"]
        ixx, iyy, izz = inertia(l["mass"], shape)
        if shape["type"] == "box":
            geometry = '<box size="%s"/>' % nums(shape["size"])
        else:
            geometry = '<cylinder radius="%s" length="%s"/>' % (num(shape["radius"]),
                                                                num(shape["length"]))
        origin = '<origin xyz="%s" rpy="0 0 0"/>' % nums(shape["xyz"])
        out += [
            '  <link name="%s">' % l["name"],
            "    <inertial>",
            "      " + origin,
            '      <mass value="%s"/>' % num(l["mass"]),
            '      <inertia ixx="%s" ixy="0" ixz="0" iyy="%s" iyz="0" izz="%s"/>'
            % (num(ixx), num(iyy), num(izz)),
            "    </inertial>",
            "    <visual>%s<geometry>%s</geometry><material name=\"%s\"/></visual>"
            % (origin, geometry, colours[l["rgba"]]),
            "    <collision>%s<geometry>%s</geometry></collision>" % (origin, geometry),
            "  </link>",
        ]
    for f in frames:
        out.append('  <link name="%s"/>' % f["child"])
    for j in joints:
        lower, upper = j["limits"]
        out += [
            '  <joint name="%s" type="revolute">' % j["name"],
            '    <origin xyz="%s" rpy="%s"/>' % (nums(j["xyz"]), nums(j["rpy"])),
            '    <parent link="%s"/>' % j["parent"],
            '    <child link="%s"/>' % j["child"],
            '    <axis xyz="%s"/>' % nums(AXES[j["axis"]]),
            '    <limit lower="%s" upper="%s" effort="%s" velocity="6"/>'
            % (num(lower), num(upper), num(j["effort"])),
            "  </joint>",
        ]
    for f in frames:
        out += [
            '  <joint name="%s" type="fixed">' % f["name"],
            '    <origin xyz="%s" rpy="%s"/>' % (nums(f["xyz"]), nums(f["rpy"])),
            '    <parent link="%s"/>' % f["parent"],
            '    <child link="%s"/>' % f["child"],
            "  </joint>",
        ]
    width, height = CAMERA_IMAGE
    for f in frames:
        if not f["child"].endswith("_camera"):
            continue
        out += [
            '  <sensor name="%s_sensor" update_rate="60">' % f["child"],
            '    <parent link="%s"/>' % f["child"],
            '    <origin xyz="0 0 0" rpy="0 0 0"/>',
            '    <camera><image width="%d" height="%d" hfov="%s" format="RGB8" near="0.01"'
            ' far="20"/></camera>' % (width, height, CAMERA_HFOV),
            "  </sensor>",
        ]
    out.append("</robot>")
    return "\n".join(out) + "\n"


def mjcf(links, joints, frames):
    by_name = {l["name"]: l for l in links}
    children = {}
    for j in joints + frames:
        children.setdefault(j["parent"], []).append(j)
    width, height = CAMERA_IMAGE
    out = [
        "<!-- %s -->" % header_comment(links),
        '<mujoco model="%s">' % MODEL_NAME,
        '  <compiler angle="radian" eulerseq="XYZ" inertiafromgeom="false"/>',
        '  <option timestep="0.002"/>',
        "  <!-- The cameras render %dx%d images (60 fps on the robot). -->" % (width, height),
        "  <custom>",
        '    <numeric name="camera_resolution" data="%d %d"/>' % (width, height),
        '    <numeric name="ft_sensor_height" data="%s"/>' % num(FT_SENSOR_HEIGHT),
        "  </custom>",
        "  <default>",
        '    <joint limited="true" damping="%s" armature="0.01"/>' % num(JOINT_DAMPING),
        '    <geom contype="2" conaffinity="1" condim="3" friction="1 0.005 0.0001"/>',
        '    <position ctrllimited="true" forcelimited="true"/>',
        '    <site size="0.01" rgba="1 0 0 1"/>',
        "  </default>",
        "  <asset>",
        '    <texture name="grid" type="2d" builtin="checker" rgb1="0.2 0.3 0.4"'
        ' rgb2="0.3 0.4 0.5" width="512" height="512"/>',
        '    <material name="floor" texture="grid" texrepeat="8 8" reflectance="0.1"/>',
        "  </asset>",
        "  <worldbody>",
        '    <light name="sun" pos="0 0 4" dir="0 0 -1" directional="true"/>',
        '    <geom name="floor" type="plane" size="0 0 0.05" contype="1" conaffinity="1"'
        ' material="floor"/>',
    ]

    def body(name, indent):
        pad = "  " * indent
        l = by_name[name]
        shape = l["shape"]
        ixx, iyy, izz = inertia(l["mass"], shape)
        out.append('%s<inertial pos="%s" mass="%s" diaginertia="%s"/>'
                   % (pad, nums(shape["xyz"]), num(l["mass"]), nums((ixx, iyy, izz))))
        if shape["type"] == "box":
            size = nums(s / 2 for s in shape["size"])
            geom = 'type="box" size="%s"' % size
        else:
            geom = 'type="cylinder" size="%s %s"' % (num(shape["radius"]),
                                                     num(shape["length"] / 2))
        out.append('%s<geom name="%s" %s pos="%s" rgba="%s"/>'
                   % (pad, name, geom, nums(shape["xyz"]), nums(l["rgba"])))
        for j in children.get(name, []):
            if j["type"] == "fixed" and j["child"].endswith("_camera"):
                # A massless welded body, so that its frame carries the URDF rpy exactly; the
                # MuJoCo camera looks along its -z with y up, i.e. along the link's +x.
                out.append('%s<body name="%s" pos="%s" euler="%s">'
                           % (pad, j["child"], nums(j["xyz"]), nums(j["rpy"])))
                out.append('%s  <site name="%s"/>' % (pad, j["child"]))
                out.append('%s  <camera name="%s" xyaxes="0 -1 0 0 0 1" fovy="%d"/>'
                           % (pad, j["child"], CAMERA_FOVY_DEG))
                out.append("%s</body>" % pad)
            elif j["type"] == "fixed":
                out.append('%s<site name="%s" pos="%s" euler="%s"/>'
                           % (pad, j["child"], nums(j["xyz"]), nums(j["rpy"])))
            else:
                lower, upper = j["limits"]
                out.append('%s<body name="%s" pos="%s" euler="%s">'
                           % (pad, j["child"], nums(j["xyz"]), nums(j["rpy"])))
                out.append('%s  <joint name="%s" axis="%s" range="%s %s"/>'
                           % (pad, j["name"], nums(AXES[j["axis"]]), num(lower), num(upper)))
                body(j["child"], indent + 1)
                out.append("%s</body>" % pad)

    root_height = stand_root_height()
    out.append('    <body name="root_link" pos="0 0 %s">' % root_height)
    out.append('      <freejoint name="root"/>')
    out.append('      <site name="imu"/>')  # the base IMU: its frame is the root link's
    body("root_link", 3)
    out += ["    </body>", "  </worldbody>", "  <actuator>"]
    for j in joints:
        lower, upper = j["limits"]
        out.append('    <position name="%s" joint="%s" kp="%s" ctrlrange="%s %s" forcerange="%s %s"/>'
                   % (j["name"], j["name"], num(j["kp"]), num(lower), num(upper),
                      num(-j["effort"]), num(j["effort"])))
    out += ["  </actuator>", "  <sensor>"]
    for side in ("l", "r"):
        site = side + "_foot_ft_sensor"
        out.append('    <force name="%s_force" site="%s"/>' % (site, site))
        out.append('    <torque name="%s_torque" site="%s"/>' % (site, site))
    out.append('    <framequat name="imu_quat" objtype="site" objname="imu"/>')
    out.append('    <gyro name="imu_gyro" site="imu"/>')
    out.append('    <accelerometer name="imu_acc" site="imu"/>')
    for j in joints:
        out.append('    <jointpos name="%s_pos" joint="%s"/>' % (j["name"], j["name"]))
    out += ["  </sensor>", "  <keyframe>"]
    # "stand": knees bent, soles flat on the floor; qpos in MuJoCo's order (depth first).
    angles = []
    for j in joints:
        key = j["name"].split("_", 1)[1] if j["name"][:2] in ("l_", "r_") else j["name"]
        angles.append(STAND_ANGLES.get(key, 0.0))
    out.append('    <key name="stand" qpos="0 0 %s 1 0 0 0 %s" ctrl="%s"/>'
               % (root_height, nums(angles), nums(angles)))
    out += ["  </keyframe>", "</mujoco>"]
    return "\n".join(out) + "\n"


def stand_root_height():
    """Root height [m] of the keyframe "stand" with the soles on the floor, 4 decimals."""
    thigh_angle = STAND_ANGLES["hip_pitch"]
    shank_angle = thigh_angle + STAND_ANGLES["knee"]
    height = (HIP_BELOW_ROOT + THIGH * math.cos(thigh_angle) + SHANK * math.cos(shank_angle) +
              ANKLE_HEIGHT)
    return "%.4f" % (math.ceil(height * 1e4) / 1e4)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--output-dir", default=os.path.dirname(os.path.abspath(__file__)),
                        help="where to write the two files (default: beside this script)")
    args = parser.parse_args(argv)
    links, joints, frames = robot()
    check(links, joints, frames)
    files = {MODEL_NAME + ".urdf": urdf(links, joints, frames),
             MODEL_NAME + ".xml": mjcf(links, joints, frames)}
    os.makedirs(args.output_dir, exist_ok=True)
    for name, text in files.items():
        with open(os.path.join(args.output_dir, name), "w", encoding="ascii", newline="\n") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
