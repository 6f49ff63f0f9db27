"""walkgen.Simulation: walkgen's humanoid (and the Unitree G1) in MuJoCo under the closed loop,
from Python: it walks where it is told, its ZMP follows the plan, it stops on request, a push it cannot take ends in a
reported fall, the cameras see an obstacle at its distance, errors."""

import numpy as np
import pytest

import walkgen

pytestmark = pytest.mark.skipif(not walkgen.features.get("simulation"),
                                reason="built without walkgen::simulation (MuJoCo, Ceres)")


def walk(sim, ticks, vx=0.0, vy=0.0, wz=0.0):
    """Ticks with a command: the ticks, the ZMP errors of every valid sample and, per tick, the
    distance of MuJoCo's true CoM from the planned one (x, y)."""
    assert sim.set_command(vx, vy, wz) == "accepted"
    ticks_seen, zmp_errors, com_errors = [], [], []
    for _ in range(ticks):
        tick = sim.tick()
        ticks_seen.append(tick)
        s = sim.samples()
        valid = s["zmp_valid"]
        zmp_errors.extend(np.linalg.norm(s["zmp_measured"][valid] - s["zmp_plan"][valid], axis=1))
        com_errors.append(np.linalg.norm(sim.true_com()[:2] - s["com_plan"][-1, :2]))
    return ticks_seen, np.array(zmp_errors), np.array(com_errors)


def test_the_humanoid_walks_forward_with_its_zmp_near_the_plan():
    sim = walkgen.Simulation()
    assert sim.start().ok and sim.mode == "walking"
    start = sim.true_com()
    speed, ticks = 0.03, 30
    period = sim.state().time  # the generator's time after start
    ticks_seen, zmp_errors, com_errors = walk(sim, ticks, vx=speed)
    assert all(t.ok for t in ticks_seen), [str(t) for t in ticks_seen if not t.ok]
    assert all(0.0 < t.mpc_seconds < 1.0 for t in ticks_seen)  # the NMPC's solve, timed
    walked = sim.true_com() - start
    duration = sim.state().time - period
    assert duration == pytest.approx(ticks * 0.4)  # Heicub's period t = 0.4 s
    # the true (simulated) CoM went forward about as commanded (starting from rest) and stays on
    # the plan all the way (within 5 mm here; it sways +-7 cm from foot to foot)
    assert 0.6 * speed * duration < walked[0] < 1.2 * speed * duration
    assert com_errors.max() < 0.02
    out = sim.output()
    assert out["status"] == "ok" and out["imu"]["available"] and out["imu"]["tilt"] < 0.1
    assert out["q"].shape == (15,) and len(sim.joint_names) == 15
    assert out["base_height"] > 0.4
    # measured ZMP from the ankle sensors vs the plan (issue 24: 3.6 cm mean before balance work)
    assert len(zmp_errors) > 100 and zmp_errors.mean() < 0.05
    s = sim.samples()
    assert s["com_plan"].shape == (40, 3) and s["time"].shape == (40,)
    assert np.all(np.diff(s["time"]) > 0)


def test_request_stop_stands_the_robot_on_both_feet():
    sim = walkgen.Simulation()
    assert sim.start().ok
    walk(sim, 10, vx=0.03)
    assert sim.request_stop() == "stopping"
    modes = [str(sim.tick().mode) for _ in range(20)]
    assert modes[-1] == "stopped" and "fault" not in modes
    held = sim.true_com()
    for _ in range(3):
        assert sim.tick().ok
    np.testing.assert_allclose(sim.true_com()[:2], held[:2], atol=0.01)  # it stands still
    assert sim.output()["base_height"] > 0.4


def test_a_push_it_cannot_take_ends_in_a_reported_fall():
    sim = walkgen.Simulation()
    assert sim.start().ok
    walk(sim, 5, vx=0.03)
    sim.push([0.0, 300.0, 0.0], start=sim.output()["time"] + 0.1, duration=0.1)  # 30 N s sideways
    ticks = [sim.tick() for _ in range(10)]
    faults = [t for t in ticks if t.mode == "fault"]
    assert faults and faults[0].status in ("fallen", "fault") and faults[0].message
    assert faults[0].reason in ("fallen", "sensor_fault")


def test_the_chest_cameras_see_an_obstacle_at_its_distance():
    obstacle = walkgen.CircleObstacle(1.2, 0.1, 0.15, 0.1)
    for obstacles, expected in (([], None), ([obstacle], 1.2 - 0.15)):
        sim = walkgen.Simulation(obstacles=obstacles, view_width=320, view_height=240)
        assert sim.start().ok
        try:
            images = sim.render_cameras()
        except RuntimeError as e:  # no EGL on this machine: say so, loudly
            pytest.fail(f"rendering unavailable: {e}")
        left = images["left"]
        assert left["rgb"].dtype == np.uint8 and left["rgb"].shape[2] == 3
        assert left["depth"].dtype == np.float32 and left["depth"].shape == left["rgb"].shape[:2]
        h, w = left["depth"].shape
        centre = float(left["depth"][h // 2 - 3:h // 2 + 3, w // 2 - 3:w // 2 + 3].mean())
        camera_x = left["pose"][0, 3]
        if expected is None:
            assert centre > 3.0  # nothing ahead: the floor far away
        else:
            assert centre == pytest.approx(expected - camera_x, abs=0.03)
        view = sim.render_view(sim.true_com(), width=160, height=120)
        assert view["rgb"].shape == (120, 160, 3) and view["rgb"].std() > 5  # not a blank image


def test_the_unitree_g1_walks_forward_under_torque_control():
    sim = walkgen.Simulation("unitree_g1", view_width=64, view_height=48)
    assert sim.start().ok and sim.mode == "walking"
    assert len(sim.joint_names) == 23 and sim.output()["q"].shape == (23,)
    start = sim.true_com()
    speed, ticks = 0.1, 60  # 6 s at the G1's period t = 0.1 s
    ticks_seen, zmp_errors, _ = walk(sim, ticks, vx=speed)
    assert all(t.ok for t in ticks_seen), [str(t) for t in ticks_seen if not t.ok]
    walked = sim.true_com() - start
    # forward, from rest: 0.77 m (0.13 m/s) on 2026-12-08. Its feet land off the plan and the
    # NMPC is not restarted from the measured CoM, so the true CoM runs ahead of the plan
    # (docs/robots.md): no CoM-vs-plan bound here, a wide one on the distance.
    assert 0.4 * speed * 6.0 < walked[0] < 2.0 * speed * 6.0, walked
    out = sim.output()
    assert out["status"] == "ok" and out["base_height"] > 0.6
    # the ZMP from the feet's contact forces (no ankle sensors) near the plan (test_g1_walking)
    assert len(zmp_errors) > 300 and zmp_errors.mean() < 0.06
    with pytest.raises(RuntimeError):
        sim.render_cameras()  # the G1's model has no chest cameras


def test_simulation_errors():
    short = walkgen.WalkingSettings.heicub()
    short.n = 8
    with pytest.raises(ValueError, match="walking.n"):
        walkgen.Simulation(walking=short)  # the closed loop's horizon is 16
    with pytest.raises(ValueError, match="no_such_robot"):
        walkgen.Simulation("no_such_robot")
    sim = walkgen.Simulation(view_width=64, view_height=48)
    assert sim.tick().status == "not_started"  # before start(): a status, not an exception
    assert sim.start().ok
    with pytest.raises(ValueError, match="finite"):
        sim.set_command(float("nan"))
    assert sim.set_command(5.0) == "clamped"
    with pytest.raises(ValueError):
        sim.push([float("nan"), 0, 0], start=0.0, duration=0.1)
    with pytest.raises(ValueError, match="size"):
        sim.render_view([0, 0, 0], width=640, height=480)  # beyond view_width x view_height


def test_fk_of_the_measured_joints_matches_mujocos_sensor_poses():
    """The package's FK (KinematicTree from the URDF) against MuJoCo's own kinematics, both C++:
    the right ankle sensor seen from the left one, for the joint angles MuJoCo measures."""
    robot = walkgen.RobotDescription.find("walkgen_humanoid")
    tree = walkgen.KinematicTree.from_urdf(robot.urdf_path)
    sim = walkgen.Simulation()
    assert sim.start().ok
    walk(sim, 6, vx=0.03)  # mid-walk: bent, swinging legs
    out = sim.output()
    angles = dict(zip(sim.joint_names, out["q"]))
    k = tree.forward_kinematics([angles[name] for name in tree.joint_names])
    left, right = robot.ft_sensor_frames
    fk_relative = k.rotation(left).T @ (k.position(right) - k.position(left))
    T_left, T_right = out["ft"][0]["pose"], out["ft"][1]["pose"]
    mujoco_relative = T_left[:3, :3].T @ (T_right[:3, 3] - T_left[:3, 3])
    np.testing.assert_allclose(fk_relative, mujoco_relative, atol=1e-9)
    np.testing.assert_allclose(k.rotation(left).T @ k.rotation(right),
                               T_left[:3, :3].T @ T_right[:3, :3], atol=1e-9)
