"""walkgen.WalkingSettings and walkgen.WalkingMpc: presets, YAML, walking forward and turning,
the plan's physics (ZMP inside the support, CoM dynamics), errors."""

import math

import numpy as np
import pytest

import walkgen


def walk(mpc, ticks, vx=0.0, vy=0.0, wz=0.0):
    mpc.set_command(vx, vy, wz)
    results = []
    for _ in range(ticks):
        results.append(mpc.solve())
        mpc.advance()
    return results


def test_presets_differ_where_the_robots_do():
    hrp2, heicub = walkgen.WalkingSettings.hrp2(), walkgen.WalkingSettings.heicub()
    assert hrp2.t_step == pytest.approx(0.8) and heicub.t_step == pytest.approx(3.2)
    assert hrp2.n == 16 and hrp2.samples_per_step == 8
    assert hrp2.left_foot_convex_hull.shape == (5, 2)
    hrp2.validate()
    heicub.validate()


def test_yaml_text_and_files_load(source_dir):
    s = walkgen.WalkingSettings.from_yaml("t_step: 1.6\nstep_height: 0.04\n")
    assert s.t_step == pytest.approx(1.6) and s.step_height == pytest.approx(0.04)
    from_file = walkgen.WalkingSettings.load(str(source_dir / "configs" / "heicub.yaml"))
    assert from_file.t_step == pytest.approx(walkgen.WalkingSettings.heicub().t_step)


def test_bad_yaml_and_missing_files_raise_value_error_naming_the_key():
    with pytest.raises(ValueError, match="t_stpe"):
        walkgen.WalkingSettings.from_yaml("t_stpe: 0.8\n")
    with pytest.raises(ValueError, match="well-formed YAML"):
        walkgen.WalkingSettings.from_yaml("t_step: [0.8\n")
    with pytest.raises(ValueError, match="no_such_file.yaml"):
        walkgen.WalkingSettings.load("no_such_file.yaml")


def test_settings_fields_are_checked_with_a_clear_message():
    s = walkgen.WalkingSettings.hrp2()
    s.t = -0.1
    with pytest.raises(ValueError, match="t"):
        s.validate()
    with pytest.raises(ValueError, match="t"):
        walkgen.WalkingMpc(s)
    with pytest.raises(ValueError, match="security_margin: expected a vector of shape \\(2,\\)"):
        s.security_margin = [0.1, 0.2, 0.3]
    with pytest.raises(ValueError, match="vertices of shape \\(k, 2\\)"):
        s.left_foot_convex_hull = np.zeros((4, 3))


def test_newcomer_script_walks_forward_at_the_commanded_speed():
    mpc = walkgen.WalkingMpc(walkgen.WalkingSettings.hrp2())
    x0 = mpc.state().com_x[0]
    results = walk(mpc, 60, vx=0.2)
    assert all(r.status == "solved" for r in results)
    state = mpc.state()
    assert state.time == pytest.approx(6.0)
    # 6 s at 0.2 m/s, less the start-up of the first steps.
    assert 0.8 < state.com_x[0] - x0 < 1.3
    assert abs(state.com_y[0] - 0.0) < 0.15
    assert state.step_count >= 6


def test_turning_command_turns_the_feet():
    mpc = walkgen.WalkingMpc()
    walk(mpc, 80, vx=0.1, wz=0.2)
    # 8 s at 0.2 rad/s: the heading follows the reference within a step's lag.
    assert mpc.reference_heading == pytest.approx(1.6, abs=1e-9)
    assert 1.0 < mpc.state().heading < 1.8


def test_plan_zmp_stays_inside_the_sole_and_matches_the_cart_table_model():
    s = walkgen.WalkingSettings.hrp2()
    mpc = walkgen.WalkingMpc(s)
    walk(mpc, 20, vx=0.2)
    assert mpc.solve().ok
    com = mpc.com_trajectory()
    acc = mpc.com_acceleration_trajectory()
    zmp = mpc.zmp_trajectory()
    assert com.shape == zmp.shape == (16, 2)
    # Z = C - c_z / g C̈ (thesis eq. 2.40), sample by sample.
    np.testing.assert_allclose(zmp, com - s.com_z / s.gravity * acc, atol=1e-9)
    # The first planned ZMP lies within the feet's reach: at most half a sole plus a step away.
    st = mpc.state()
    feet = np.array([[st.support.x, st.support.y], [st.swing.x, st.swing.y]])
    nearest = np.min(np.linalg.norm(zmp[:1, None, :] - feet[None, :, :], axis=2))
    assert nearest < 0.5 * math.hypot(s.foot_length, s.foot_width) + 1e-6


def test_footsteps_alternate_sides_and_advance():
    mpc = walkgen.WalkingMpc()
    walk(mpc, 10, vx=0.2)
    steps = mpc.footsteps()
    assert steps.shape == (mpc.planned_steps, 3)
    st = mpc.state()
    side = 1.0 if str(st.support_foot) == "right" else -1.0  # the next step lands on the other side
    assert side * (steps[0, 1] - st.support.y) > 0.1
    assert steps[-1, 0] >= steps[0, 0]


def test_command_beyond_the_limit_is_clamped_and_nan_raises():
    mpc = walkgen.WalkingMpc()
    assert mpc.set_command(5.0) == "clamped"
    np.testing.assert_allclose(mpc.command, [0.35, 0.0, 0.0])
    assert mpc.set_command(0.1, 0.0, 0.1) == walkgen.CommandStatus.accepted
    with pytest.raises(ValueError, match="finite"):
        mpc.set_command(math.nan)
    np.testing.assert_allclose(mpc.command, [0.1, 0.0, 0.1])


def test_set_state_feeds_back_and_rejects_implausible_states():
    mpc = walkgen.WalkingMpc()
    st = mpc.state()
    st.com_x = [0.01, 0.0, 0.0]
    mpc.set_state(st)
    assert mpc.state().com_x[0] == pytest.approx(0.01)
    st.com_x = [50.0, 0.0, 0.0]
    with pytest.raises(ValueError, match="max_state_distance"):
        mpc.set_state(st)
    assert mpc.state().com_x[0] == pytest.approx(0.01)
    with pytest.raises(ValueError, match="com_x: expected a vector of shape \\(3,\\)"):
        st.com_x = [1.0, 2.0]


def test_obstacles_keep_the_footsteps_out():
    # Beside the path of the left foot: the footsteps must step around it (radius + margin 0.2 m).
    mpc = walkgen.WalkingMpc(walkgen.WalkingSettings.hrp2(), obstacle_capacity=1)
    mpc.set_obstacles([walkgen.CircleObstacle(1.0, 0.15, 0.1, margin=0.1)])
    mpc.set_command(0.25)
    closest = math.inf
    for _ in range(80):
        assert mpc.solve().status == "solved"
        for x, y, _ in mpc.footsteps():
            assert math.hypot(x - 1.0, y - 0.15) >= 0.2 - 2e-3
        mpc.advance()
        support = mpc.state().support
        closest = min(closest, math.hypot(support.x - 1.0, support.y - 0.15))
    assert 0.2 - 2e-3 <= closest < 0.3  # it passed close by, outside
    assert mpc.state().com_x[0] > 1.5
    with pytest.raises(ValueError, match="capacity"):
        mpc.set_obstacles([(0, 0, 0.1), (1, 1, 0.1)])


def test_soft_obstacle_rows_relax_an_infeasible_tick_and_say_so():
    # An obstacle appears 0.25 m ahead of the robot walking at 0.3 m/s: the margin cannot be kept.
    soft_settings = walkgen.WalkingSettings.hrp2()
    assert soft_settings.soft.obstacles == 0.0  # hard by default
    soft_settings.soft.obstacles = 1e4
    soft = walkgen.WalkingMpc(soft_settings, obstacle_capacity=1)
    hard = walkgen.WalkingMpc(walkgen.WalkingSettings.hrp2(), obstacle_capacity=1)
    for mpc in (soft, hard):
        assert all(r.status == "solved" for r in walk(mpc, 40, vx=0.3))
        x, y = mpc.state().com_x[0], mpc.state().com_y[0]
        mpc.set_obstacles([walkgen.CircleObstacle(x + 0.4, y, 0.15, margin=0.15)])
    assert hard.solve().status == "qp_failed"
    assert "obstacles" in hard.block_names(hard.conflicting_blocks())
    r = soft.solve()
    assert r.status == "relaxed" and r.soft_fallback, r.message
    assert soft.block_names(r.relaxed_blocks) == "obstacles (eq. 2.79-2.82)"
    assert 1e-3 < r.constraint_violation < 0.15  # into the margin, not into the circle
    bad = walkgen.WalkingSettings.hrp2()
    bad.soft.obstacles = -1.0
    with pytest.raises(ValueError, match="soft.obstacles"):
        walkgen.WalkingMpc(bad)


def test_horizon_argument_sizes_the_problem():
    short = walkgen.WalkingMpc(horizon=8)
    long_ = walkgen.WalkingMpc(horizon=32)
    assert short.horizon == 8 and long_.horizon == 32
    assert long_.num_vars > short.num_vars
    with pytest.raises(ValueError, match="horizon"):
        walkgen.WalkingMpc(horizon=0)


def test_identical_runs_are_deterministic():
    a, b = walkgen.WalkingMpc(), walkgen.WalkingMpc()
    walk(a, 25, vx=0.2, wz=0.1)
    walk(b, 25, vx=0.2, wz=0.1)
    np.testing.assert_array_equal(a.decision_vector(), b.decision_vector())


def test_interpolated_samples_join_the_ticks_and_obey_the_pendulum():
    s = walkgen.WalkingSettings.hrp2()
    mpc = walkgen.WalkingMpc(s)
    walk(mpc, 12, vx=0.2)
    mpc.solve()
    out = mpc.interpolate()
    k = round(s.t / s.command_period)
    assert out["samples"].shape == (k, 21) and len(walkgen.trajectory_columns) == 21
    col = {name: i for i, name in enumerate(walkgen.trajectory_columns)}
    samples, state = out["samples"], mpc.state()
    np.testing.assert_allclose(out["time"], state.time + s.command_period * np.arange(k))
    np.testing.assert_allclose(samples[0, [col["com_x"], col["com_dx"], col["com_ddx"]]],
                               state.com_x, atol=1e-12)
    # z = c - c_z / g * c'' in every sample (eq. 2.6)
    h = s.com_z / s.gravity
    np.testing.assert_allclose(samples[:, col["zmp_x"]],
                               samples[:, col["com_x"]] - h * samples[:, col["com_ddx"]],
                               atol=1e-12)
    # the last sample continues into the next tick: one command period on, the state advanced
    mpc.advance()
    c, dc, ddc = samples[-1, [col["com_x"], col["com_dx"], col["com_ddx"]]]
    assert mpc.state().com_x[0] == pytest.approx(c + dc * s.command_period, abs=2e-4)
    # the support foot stands still in every sample
    foot = "lf" if out["support_foot"][0] == 0 else "rf"
    assert np.ptp(samples[:, col[foot + "_x"]]) == 0.0 and np.all(samples[:, col[foot + "_z"]] == 0)
    assert out["double_support"].dtype == bool
    with pytest.raises(ValueError, match="command_period"):
        mpc.interpolate(command_period=0.03)
    assert mpc.interpolate(command_period=0.01)["samples"].shape == (round(s.t / 0.01), 21)
