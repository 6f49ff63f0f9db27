"""walkgen.RobotDescription and walkgen.KinematicTree: descriptions of both robots, FK and CoM
against an independent NumPy reading of the URDF, the URDF and MJCF trees of the same robot
against each other, Jacobians against finite differences, errors."""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import walkgen

needs_urdf = pytest.mark.skipif(not walkgen.features["urdf"], reason="built without walkgen::urdf")
needs_mujoco = pytest.mark.skipif(not walkgen.features["mujoco"],
                                  reason="built without walkgen::mujoco")


def rpy_matrix(rpy):
    r, p, y = rpy
    Rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    Ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    Rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def axis_angle(axis, q):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + math.sin(q) * K + (1 - math.cos(q)) * K @ K


def numbers(element, key, default):
    if element is None or element.get(key) is None:
        return np.array(default, float)
    return np.array([float(v) for v in element.get(key).split()])


class UrdfReference:
    """Forward kinematics and CoM read straight from the URDF with NumPy (no walkgen code)."""

    def __init__(self, path):
        root = ET.parse(path).getroot()
        self.links = {}
        for link in root.findall("link"):
            inertial = link.find("inertial")
            mass, com = 0.0, np.zeros(3)
            if inertial is not None:
                mass = float(inertial.find("mass").get("value"))
                com = numbers(inertial.find("origin"), "xyz", [0, 0, 0])
            self.links[link.get("name")] = (mass, com)
        self.joints = []
        for j in root.findall("joint"):
            origin = j.find("origin")
            self.joints.append(dict(
                name=j.get("name"), type=j.get("type"), parent=j.find("parent").get("link"),
                child=j.find("child").get("link"), xyz=numbers(origin, "xyz", [0, 0, 0]),
                rpy=numbers(origin, "rpy", [0, 0, 0]), axis=numbers(j.find("axis"), "xyz", [1, 0, 0])))
        children = {j["child"] for j in self.joints}
        (self.root,) = [name for name in self.links if name not in children]

    def fk(self, angles, p0=np.zeros(3), R0=np.eye(3)):
        poses = {self.root: (np.asarray(p0, float), np.asarray(R0, float))}
        pending = list(self.joints)
        while pending:
            for j in list(pending):
                if j["parent"] in poses:
                    p, R = poses[j["parent"]]
                    Rj = R @ rpy_matrix(j["rpy"])
                    if j["type"] in ("revolute", "continuous"):
                        Rj = Rj @ axis_angle(j["axis"], angles[j["name"]])
                    poses[j["child"]] = (p + R @ j["xyz"], Rj)
                    pending.remove(j)
        return poses

    def com(self, poses):
        total = sum(m for m, _ in self.links.values())
        return sum(m * (poses[n][0] + poses[n][1] @ c) for n, (m, c) in self.links.items()) / total


@pytest.fixture
def humanoid(source_dir):
    return walkgen.RobotDescription.load(str(source_dir / "models/walkgen_humanoid/robot.yaml"))


def test_descriptions_load_by_name_and_path_and_agree_with_the_code(humanoid):
    by_name = walkgen.RobotDescription.find("walkgen_humanoid")
    code = walkgen.RobotDescription.walkgen_humanoid()
    assert humanoid.joint_names == by_name.joint_names == code.joint_names
    assert len(humanoid.joint_names) == 15 and humanoid.sole_frames == ["l_sole", "r_sole"]
    assert humanoid.stand_pose["l_knee"] == pytest.approx(1.0)
    assert humanoid.walking.t_step == pytest.approx(walkgen.WalkingSettings.heicub().t_step)
    np.testing.assert_allclose(humanoid.stand_angles[humanoid.joint_names.index("r_knee")], 1.0)
    g1 = walkgen.RobotDescription.find("unitree_g1")
    assert g1.name == "unitree_g1" and len(g1.joint_names) == 23 and g1.urdf_path == ""


@needs_urdf
def test_fk_and_com_equal_an_independent_reading_of_the_urdf(humanoid):
    tree = walkgen.KinematicTree.from_urdf(humanoid.urdf_path)
    ref = UrdfReference(humanoid.urdf_path)
    assert sorted(tree.joint_names) == sorted(humanoid.joint_names)
    assert tree.mass == pytest.approx(sum(m for m, _ in ref.links.values()), rel=1e-12)
    rng = np.random.default_rng(3)
    for _ in range(5):
        q = rng.uniform(-1, 1, tree.num_joints)
        p0 = rng.uniform(-1, 1, 3)
        R0 = rpy_matrix(rng.uniform(-math.pi, math.pi, 3))
        k = tree.forward_kinematics(q, p0, R0)
        poses = ref.fk(dict(zip(tree.joint_names, q)), p0, R0)
        for name in tree.link_names:
            np.testing.assert_allclose(k.position(name), poses[name][0], atol=1e-12)
            np.testing.assert_allclose(k.rotation(name), poses[name][1], atol=1e-12)
            T = k.pose(name)
            np.testing.assert_allclose(T[:3, 3], poses[name][0], atol=1e-12)
        np.testing.assert_allclose(k.center_of_mass(), ref.com(poses), atol=1e-12)
        assert k.positions().shape == (tree.num_links, 3)


@needs_urdf
@needs_mujoco
def test_the_urdf_and_mjcf_trees_of_the_humanoid_agree(humanoid):
    """models/generate.py writes both files of one robot: the soles and the CoM must agree."""
    from_urdf = walkgen.KinematicTree.from_urdf(humanoid.urdf_path)
    from_mjcf = walkgen.KinematicTree.from_description(humanoid)
    assert from_mjcf.mass == pytest.approx(from_urdf.mass, rel=1e-9)
    rng = np.random.default_rng(5)
    for _ in range(5):
        angles = dict(zip(humanoid.joint_names, rng.uniform(-0.8, 0.8, 15)))
        ku = from_urdf.forward_kinematics([angles[n] for n in from_urdf.joint_names])
        km = from_mjcf.forward_kinematics([angles[n] for n in from_mjcf.joint_names])
        for sole in humanoid.sole_frames:
            np.testing.assert_allclose(km.position(sole), ku.position(sole), atol=1e-9)
            np.testing.assert_allclose(km.rotation(sole), ku.rotation(sole), atol=1e-9)
        np.testing.assert_allclose(km.center_of_mass(), ku.center_of_mass(), atol=1e-9)


@needs_mujoco
def test_the_g1_stands_with_level_soles_and_its_com_between_them():
    g1 = walkgen.RobotDescription.find("unitree_g1")
    tree = walkgen.KinematicTree.from_description(g1)
    assert tree.num_joints == 23 and 30 < tree.mass < 40  # 34 kg (models/unitree_g1/SOURCE.txt)
    k = tree.forward_kinematics(tree.stand_configuration(g1))
    left, right = (k.position(s) for s in g1.sole_frames)
    assert left[2] == pytest.approx(right[2], abs=1e-9) and left[1] == pytest.approx(-right[1])
    np.testing.assert_allclose(k.rotation(g1.sole_frames[0]), np.eye(3), atol=1e-6)
    com = k.center_of_mass()
    assert abs(com[1]) < 0.01 and abs(com[0] - left[0]) < 0.05  # over the middle of the soles
    assert 0.5 < com[2] - left[2] < 0.8


@needs_urdf
def test_jacobians_equal_finite_differences(humanoid):
    tree = walkgen.KinematicTree.from_urdf(humanoid.urdf_path)
    rng = np.random.default_rng(8)
    q = rng.uniform(-0.7, 0.7, tree.num_joints)
    k = tree.forward_kinematics(q)
    Jc, Jf = k.com_jacobian(), k.frame_jacobian("l_sole", point=[0.05, 0.0, 0.0])
    assert Jc.shape == (3, 21) and Jf.shape == (6, 21)
    np.testing.assert_allclose(Jc[:, :3], np.eye(3), atol=1e-12)  # the base moves the CoM 1:1
    h = 1e-6
    point = lambda kin: kin.position("l_sole") + kin.rotation("l_sole") @ [0.05, 0.0, 0.0]
    for i in range(tree.num_joints):
        dq = np.zeros_like(q)
        dq[i] = h
        kp, km = tree.forward_kinematics(q + dq), tree.forward_kinematics(q - dq)
        np.testing.assert_allclose(Jc[:, 6 + i], (kp.center_of_mass() - km.center_of_mass()) / (2 * h),
                                   atol=1e-8)
        np.testing.assert_allclose(Jf[:3, 6 + i], (point(kp) - point(km)) / (2 * h), atol=1e-8)


def test_kinematics_errors_are_value_errors_naming_what_is_wrong(humanoid, tmp_path):
    with pytest.raises(ValueError, match="unitree_g2"):
        walkgen.RobotDescription.find("unitree_g2")
    with pytest.raises(ValueError, match="jionts"):
        walkgen.RobotDescription.from_yaml("name: x\njionts: [a]\n")
    if not walkgen.features["urdf"]:
        return
    with pytest.raises(ValueError, match="missing.urdf"):
        walkgen.KinematicTree.from_urdf(str(tmp_path / "missing.urdf"))
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='r'><link name='a'/><joint name='j' type='revolute'>")
    with pytest.raises(ValueError, match="broken.urdf"):
        walkgen.KinematicTree.from_urdf(str(broken))
    tree = walkgen.KinematicTree.from_urdf(humanoid.urdf_path)
    with pytest.raises(ValueError, match=r"q.*\(15,\)"):
        tree.forward_kinematics(np.zeros(14))
    with pytest.raises(ValueError, match="NaN"):
        tree.forward_kinematics(np.full(15, np.nan))
    with pytest.raises(ValueError, match="rotation"):
        tree.forward_kinematics(np.zeros(15), [0, 0, 0], 2 * np.eye(3))
    k = tree.forward_kinematics(np.zeros(15))
    with pytest.raises(ValueError, match="l_sole"):  # the message lists the links
        k.position("left_sole")
    with pytest.raises(ValueError, match="link index"):
        k.position(99)
    with pytest.raises(ValueError, match="l_knee"):
        tree.joint_index("knee")


needs_ik = pytest.mark.skipif(not walkgen.features.get("ik"), reason="built without Ceres IK")


def check_solution(tree, robot, ik, com, left, right, yaws=(0.0, 0.0), tol=1e-6):
    k = tree.forward_kinematics(ik.q, ik.base_position, ik.base_rotation)
    np.testing.assert_allclose(k.center_of_mass(), com, atol=tol)
    for sole, target, yaw in zip(robot.sole_frames, (left, right), yaws):
        np.testing.assert_allclose(k.position(sole), target, atol=tol)
        R = k.rotation(sole)
        np.testing.assert_allclose(R[:, 2], [0, 0, 1], atol=tol)  # flat
        assert math.atan2(R[1, 0], R[0, 0]) == pytest.approx(yaw, abs=tol)
    assert np.all(ik.q >= tree.lower_limits - 1e-12) and np.all(ik.q <= tree.upper_limits + 1e-12)


@needs_ik
@pytest.mark.parametrize("name", ["walkgen_humanoid", "unitree_g1"])
def test_ik_reaches_a_shifted_com_with_the_feet_kept(name):
    robot = walkgen.RobotDescription.find(name)
    tree = walkgen.KinematicTree.from_description(robot)
    ik = walkgen.InverseKinematics(tree, robot)  # starts standing, left sole at the origin
    k = tree.forward_kinematics(ik.q, ik.base_position, ik.base_rotation)
    left, right = (k.position(s) for s in robot.sole_frames)
    np.testing.assert_allclose(left, 0.0, atol=1e-12)
    com = k.center_of_mass() + [0.02, 0.01, -0.01]
    result = ik.solve(com, left, right)
    assert result.ok and result.status == "converged" and result.applied, result.message
    assert result.com_error < 1e-6 and result.foot_position_error < 1e-6
    check_solution(tree, robot, ik, com, left, right)


@needs_ik
def test_ik_follows_the_generators_interpolated_walk():
    robot = walkgen.RobotDescription.find("walkgen_humanoid")
    tree = walkgen.KinematicTree.from_description(robot)
    settings = robot.walking
    mpc = walkgen.WalkingMpc(settings)
    mpc.set_command(settings.max_command[0] * 0.9)
    col = {n: i for i, n in enumerate(walkgen.trajectory_columns)}
    ik = None
    for tick in range(40):  # 40 ticks of t: the first steps (Heicub's preset: 3.2 s steps)
        assert mpc.solve().ok
        for sample in mpc.interpolate(command_period=settings.t / 4)["samples"]:
            com = sample[[col["com_x"], col["com_y"], col["com_z"]]]
            left = sample[[col["lf_x"], col["lf_y"], col["lf_z"]]]
            right = sample[[col["rf_x"], col["rf_y"], col["rf_z"]]]
            if ik is None:
                ik = walkgen.InverseKinematics(tree, robot)
                ik.stand(left_sole=left, yaw=sample[col["lf_q"]])
            yaw = 0.5 * (sample[col["lf_q"]] + sample[col["rf_q"]])
            r = ik.solve(com, left, right, sample[col["lf_q"]], sample[col["rf_q"]], yaw=yaw)
            assert r.ok, (tick, r.message)
            check_solution(tree, robot, ik, com, left, right,
                           yaws=(sample[col["lf_q"]], sample[col["rf_q"]]))
        mpc.advance()
    assert mpc.state().step_count >= 3  # 16 s: the swing feet left the ground and landed


@needs_ik
def test_ik_reports_unreachable_targets_and_keeps_its_solution():
    robot = walkgen.RobotDescription.find("walkgen_humanoid")
    tree = walkgen.KinematicTree.from_description(robot)
    ik = walkgen.InverseKinematics(tree, robot)
    k = tree.forward_kinematics(ik.q, ik.base_position, ik.base_rotation)
    left, right = (k.position(s) for s in robot.sole_frames)
    q_before = ik.q.copy()
    result = ik.solve(k.center_of_mass() + [0, 0, 1.0], left, right)  # CoM 1 m higher
    assert result.status == "not_converged" and not result.ok and not result.applied
    assert result.com_error > 0.1 and "kept" in result.message
    np.testing.assert_array_equal(ik.q, q_before)
    with pytest.raises(ValueError, match="finite"):
        ik.solve([np.nan, 0, 0.4], left, right)
    with pytest.raises(ValueError, match=r"left_foot.*\(3,\)"):
        ik.solve(k.center_of_mass(), left[:2], right)
    with pytest.raises(ValueError, match="robot"):
        walkgen.InverseKinematics(tree).stand()
    with pytest.raises(ValueError, match="q"):
        ik.set_initial_guess([0, 0, 0.5], np.eye(3), np.zeros(3))
