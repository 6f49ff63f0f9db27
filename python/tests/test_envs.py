"""walkgen.envs: the learning environments with the Gymnasium API shape: spaces, seeding,
rewards that add up to the progress made, the NMPC walking to goals and around obstacles, the
vectorised variant against the single environments, errors, and Gymnasium's base classes."""

import importlib
import math
import sys
import types

import numpy as np
import pytest

import walkgen
from walkgen import envs


def heading_policy(obs):
    """Walk forward and turn towards the goal (the goal in the robot frame is obs[0:2])."""
    bearing = math.atan2(obs[1], obs[0])
    return np.array([1.0 if abs(bearing) < 0.6 else 0.2, np.clip(2.0 * bearing, -1, 1)],
                    dtype=np.float32)


def test_point_goal_spaces_and_first_observation():
    env = envs.PointGoalEnv(seed=3)
    assert env.observation_space.shape == (4,) and env.observation_space.dtype == np.float32
    assert env.action_space.shape == (2,)
    np.testing.assert_array_equal(env.action_space.low, [-1, -1])
    np.testing.assert_array_equal(env.action_space.high, [1, 1])
    obs, info = env.reset()
    assert obs.dtype == np.float32 and obs.shape == (4,)
    assert env.observation_space.contains(obs)
    np.testing.assert_array_equal(obs[:2], [0, 0])  # the agent starts at the origin
    assert np.all(np.abs(obs[2:]) <= 5.0)  # goals in [-goal_range, goal_range]^2
    np.testing.assert_allclose(info["goal"], obs[2:], atol=1e-6)


def test_seeding_is_deterministic_and_seeds_differ():
    a, b = envs.PointGoalEnv(), envs.PointGoalEnv()
    goals_a = [a.reset(seed=7)[0]] + [a.reset()[0] for _ in range(3)]
    goals_b = [b.reset(seed=7)[0]] + [b.reset()[0] for _ in range(3)]
    np.testing.assert_array_equal(goals_a, goals_b)
    assert not np.array_equal(goals_a[0], goals_a[1])  # reset() draws a new goal
    assert not np.array_equal(a.reset(seed=8)[0], goals_a[0])
    # the constructor's seed gives the same first task as reset(seed=...)
    np.testing.assert_array_equal(envs.PointGoalEnv(seed=7).reset()[0], goals_a[0])


def test_point_goal_rewards_add_up_to_the_progress_and_the_win():
    env = envs.PointGoalEnv(seed=11)
    obs, _ = env.reset(options={"goal": (2.0, -1.0)})
    start = np.linalg.norm(obs[2:] - obs[:2])
    total, steps = 0.0, 0
    while True:
        obs, reward, terminated, truncated, info = env.step(np.clip(10 * (obs[2:] - obs[:2]), -1, 1))
        total += reward
        steps += 1
        if terminated or truncated:
            break
    assert terminated and not truncated and info["end"] == "success" and info["is_success"]
    end = np.linalg.norm(obs[2:] - obs[:2])
    assert end < 0.4
    assert total == pytest.approx(start - end + 10.0, abs=1e-5)  # progress + win_reward
    # one axis moves by at most step_size per step: at least |dx|/0.1 steps
    assert steps >= math.ceil((2.0 - 0.4) / 0.1)
    with pytest.raises(RuntimeError, match="reset"):
        env.step([0, 0])


def test_point_goal_loses_when_it_walks_away_and_truncates_on_the_budget():
    env = envs.PointGoalEnv(seed=1)
    env.reset(options={"goal": (1.0, 0.0)})
    for _ in range(200):
        _, reward, terminated, truncated, info = env.step([-1, 0])
        if terminated:
            break
    assert terminated and info["end"] == "failure" and reward < -9
    short = envs.PointGoalEnv(seed=1, max_steps=5)
    short.reset(options={"goal": (4.0, 4.0)})
    ends = [short.step([0, 0])[3] for _ in range(5)]
    assert ends == [False] * 4 + [True]


def test_actions_are_clipped_and_non_finite_entries_are_zero():
    env = envs.PointGoalEnv(seed=1)
    env.reset(options={"goal": (3.0, 3.0)})
    obs, *_ = env.step([50.0, float("nan")])
    np.testing.assert_allclose(obs[:2], [0.1, 0.0], atol=1e-7)


def test_nmpc_env_walks_to_a_goal_in_front_and_the_observation_is_in_the_robot_frame():
    env = envs.NmpcGoalEnv(seed=2)
    assert env.observation_space.shape == (2,)
    obs, info = env.reset(options={"goal": (1.2, 0.4)})
    np.testing.assert_allclose(obs, np.array([1.2, 0.4]) - info["position"], atol=1e-6)
    distances = [info["distance"]]
    for _ in range(150):
        obs, reward, terminated, truncated, info = env.step(heading_policy(obs))
        distances.append(info["distance"])
        if terminated or truncated:
            break
    assert info["end"] == "success", info["message"]
    assert distances[-1] < 0.2 and distances[-1] < distances[0] - 1.0
    # the observation is the goal rotated into the robot's heading
    c, s = math.cos(info["heading"]), math.sin(info["heading"])
    d = info["goal"] - info["position"]
    np.testing.assert_allclose(obs, [c * d[0] + s * d[1], -s * d[0] + c * d[1]], atol=1e-5)
    assert env.mpc.state().time == pytest.approx(info["time"])
    np.testing.assert_allclose(env.command_of([1, 0]),
                               [0.999 * env.mpc.settings.max_command[0], 0, 0])


def run_to_goal(env, goal, obstacles):
    obs, info = env.reset(options={"goal": goal, "obstacles": obstacles})
    for _ in range(150):  # straight at the goal
        obs, _, terminated, truncated, info = env.step(heading_policy(obs))
        if terminated or truncated:
            break
    return obs, terminated, info


def test_nmpc_env_footsteps_walk_around_an_obstacle_or_fail_honestly():
    env = envs.NmpcGoalEnv(seed=4, obstacles=1)
    assert env.observation_space.shape == (5,)
    # 0.2 m beside the straight line: the footsteps go around it, at least R + m from its centre
    aside = walkgen.CircleObstacle(1.0, 0.3, 0.15, 0.15)
    obs, terminated, info = run_to_goal(env, (2.0, 0.1), [aside])
    assert terminated and info["end"] == "success", info["message"]
    assert info["min_obstacle_clearance"] >= 0.15 - 1e-6  # ||F - o|| - R >= margin
    # right on the line: the NMPC finds no plan and the episode ends as a failure, with no
    # footstep inside the obstacle
    blocking = walkgen.CircleObstacle(1.0, 0.1, 0.15, 0.15)
    obs, terminated, info = run_to_goal(env, (2.0, 0.1), [blocking])
    assert obs[4] == pytest.approx(0.3)  # radius + margin
    assert terminated and info["end"] == "failure" and "inconsistent" in info["message"]
    assert info["min_obstacle_clearance"] > 0.15


def test_nmpc_env_soft_obstacle_rows_walk_around_or_end_in_a_collision():
    # With the obstacle rows soft (WalkingSettings.soft) a QP that the linearisation made
    # infeasible is solved again; a footstep inside the circle ends the episode as a failure.
    def run(obstacle, soft):
        settings = walkgen.NmpcGoalSettings()
        settings.obstacles = 1
        settings.walking.soft.obstacles = soft
        return run_to_goal(envs.NmpcGoalEnv(settings, seed=4), (2.0, 0.1), [obstacle])

    near_line = walkgen.CircleObstacle(1.0, 0.15, 0.15, 0.15)
    obs, terminated, info = run(near_line, 0.0)
    assert terminated and info["end"] == "failure" and "inconsistent" in info["message"]
    obs, terminated, info = run(near_line, 1e4)
    assert terminated and info["end"] == "success", info["message"]
    assert info["min_obstacle_clearance"] >= 0.15 - 2e-3  # around it, the margin kept
    # Walked straight at (the policy heads for the goal whatever is in the way), the least
    # violating plan still puts a foot into the circle: a collision, not a success.
    on_line = walkgen.CircleObstacle(1.0, 0.1, 0.15, 0.15)
    obs, terminated, info = run(on_line, 1e4)
    assert terminated and info["end"] == "failure"
    assert info["message"] == "a footstep inside an obstacle"
    assert -0.05 < info["min_obstacle_clearance"] < 0.0


def test_nmpc_env_motion_in_the_state():
    """observe_motion adds 7 numbers: the CoM velocity in the robot frame, the action in
    effect, the support foot and the step's elapsed fraction."""
    env = envs.NmpcGoalEnv(seed=4, obstacles=1, observe_motion=True, max_steps=100)
    assert env.observation_space.shape == (12,)
    aside = walkgen.CircleObstacle(1.0, 0.3, 0.15, 0.15)
    obs, _ = env.reset(options={"goal": (2.0, 0.1), "obstacles": [aside]})
    assert obs[5:9].tolist() == [0.0, 0.0, 0.0, 0.0]  # standing, no command yet
    for _ in range(10):
        obs, _, terminated, truncated, info = env.step(np.array([1.0, 0.0]))
        assert not (terminated or truncated)
    assert obs[5] > 0.05 and obs[7] == pytest.approx(1.0)  # walking forward on a full command
    assert 0.0 <= obs[11] < 1.0


def test_nmpc_env_same_seed_same_episode():
    def run(seed):
        env = envs.NmpcGoalEnv(seed=seed)
        obs, _ = env.reset()
        trace = [obs]
        for _ in range(20):
            obs, reward, terminated, truncated, _ = env.step(heading_policy(obs))
            trace.append(np.append(obs, reward))
            if terminated or truncated:
                obs, _ = env.reset()
        return np.concatenate(trace)
    np.testing.assert_array_equal(run(5), run(5))
    assert not np.array_equal(run(5), run(6))


def test_vector_env_matches_the_single_environments_and_resets_ended_ones():
    n = 4
    vec = envs.PointGoalVectorEnv(n, threads=2, max_steps=6)
    assert vec.num_envs == n and vec.threads == 2
    assert vec.observation_space.shape == (n, 4) and vec.single_action_space.shape == (2,)
    singles = [envs.PointGoalEnv(max_steps=6) for _ in range(n)]
    obs, _ = vec.reset(seed=100)
    single_obs = np.array([e.reset(seed=100 + i)[0] for i, e in enumerate(singles)])
    np.testing.assert_array_equal(obs, single_obs)
    rng = np.random.default_rng(0)
    for _ in range(6):
        actions = rng.uniform(-1, 1, (n, 2)).astype(np.float32)
        obs, rewards, terminated, truncated, info = vec.step(actions)
        for i, e in enumerate(singles):
            o, r, te, tr, _ = e.step(actions[i])
            assert rewards[i] == pytest.approx(r) and te == terminated[i] and tr == truncated[i]
            if te or tr:
                np.testing.assert_array_equal(info["final_obs"][i], o)
                np.testing.assert_array_equal(info["final_observation"][i], o)
                assert info["_final_obs"][i] and info["_final_observation"][i]
                o, _ = e.reset()
            np.testing.assert_array_equal(obs[i], o)
    assert truncated.all()  # random actions from the origin: the budget of 6 steps ran out


def test_nmpc_vector_env_in_threads_equals_one_thread():
    def run(threads):
        vec = envs.NmpcGoalVectorEnv(3, seed=9, threads=threads, obstacles=1)
        obs, _ = vec.reset()
        trace = [obs]
        for _ in range(10):
            obs, rewards, *_ = vec.step(np.tile([[1.0, 0.3]], (3, 1)))
            trace += [obs, rewards[:, None]]
        return trace
    for a, b in zip(run(1), run(2)):
        np.testing.assert_array_equal(a, b)


def test_environment_errors_are_value_errors_with_walkgen_messages():
    with pytest.raises(ValueError, match="has no field 'obstacels'.*obstacles"):
        envs.NmpcGoalEnv(obstacels=1)
    with pytest.raises(ValueError, match="step_size"):
        envs.PointGoalEnv(step_size=-1.0)
    with pytest.raises(ValueError, match="seed"):
        envs.PointGoalEnv(seed=-3)
    with pytest.raises(ValueError, match="seed"):
        envs.PointGoalEnv(seed="7")
    env = envs.PointGoalEnv(seed=1)
    env.reset()
    with pytest.raises(ValueError, match=r"action.*\(2,\)"):
        env.step([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="goal"):
        env.reset(options={"goal": (float("nan"), 0.0)})
    nmpc = envs.NmpcGoalEnv(seed=1, obstacles=2)
    with pytest.raises(ValueError, match="2 obstacles"):
        nmpc.reset(options={"goal": (1.0, 0.0), "obstacles": []})
    with pytest.raises(ValueError, match="num_envs"):
        envs.PointGoalVectorEnv(0)
    vec = envs.PointGoalVectorEnv(2, seed=0)
    with pytest.raises(RuntimeError, match="reset"):
        vec.step(np.zeros((2, 2)))
    vec.reset()
    with pytest.raises(ValueError, match=r"actions.*\(2, 2\)"):
        vec.step(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="NmpcGoalSettings"):
        envs.NmpcGoalEnv(settings=walkgen.PointGoalSettings())


def test_with_gymnasium_the_environments_are_gymnasium_envs(monkeypatch):
    """Gymnasium is not packaged for Debian 12: a minimal stand-in checks the subclassing."""
    gym = types.ModuleType("gymnasium")
    spaces = types.ModuleType("gymnasium.spaces")
    vector = types.ModuleType("gymnasium.vector")

    class Env:
        def reset(self, *, seed=None, options=None):
            self.seeded_with = seed

    class VectorEnv:
        pass

    class Box(envs.Box):
        pass

    gym.Env, vector.VectorEnv, spaces.Box = Env, VectorEnv, Box
    gym.spaces, gym.vector = spaces, vector
    monkeypatch.setitem(sys.modules, "gymnasium", gym)
    monkeypatch.setitem(sys.modules, "gymnasium.spaces", spaces)
    monkeypatch.setitem(sys.modules, "gymnasium.vector", vector)
    try:
        with_gym = importlib.reload(envs)
        env = with_gym.NmpcGoalEnv(seed=1)
        assert isinstance(env, Env) and isinstance(env.observation_space, Box)
        env.reset(seed=np.int64(3))
        assert env.seeded_with == 3 and type(env.seeded_with) is int  # Gymnasium wants an int
        assert isinstance(with_gym.PointGoalVectorEnv(2, seed=0), VectorEnv)
    finally:
        monkeypatch.undo()
        importlib.reload(envs)
    assert not isinstance(envs.NmpcGoalEnv(seed=1), Env)


def test_box_samples_inside_its_bounds():
    box = envs.Box(low=[-1, 0, -np.inf], high=[1, 2, np.inf], seed=0)
    samples = np.array([box.sample() for _ in range(200)])
    assert samples.dtype == np.float32
    assert np.all(samples[:, 0] >= -1) and np.all(samples[:, 0] <= 1)
    assert np.all(samples[:, 1] >= 0) and np.all(samples[:, 1] <= 2)
    assert box.contains(samples[0]) and not box.contains(np.array([2, 0, 0], np.float32))
    with pytest.raises(ValueError):
        envs.Box(low=[1.0], high=[0.0])


def test_what_the_environments_return_are_copies_that_outlive_the_episode():
    env = envs.NmpcGoalEnv(seed=3, obstacles=1)
    env.reset()
    first = env.mpc.obstacles[0]
    first_x = first.x
    kept = env.settings
    kept.max_steps = 1  # changes the copy, not the environment
    env.reset()  # a new task reuses the environment's storage
    assert first.x == first_x and env.mpc.obstacles[0].x != first_x
    assert env.settings.max_steps == 150
    vec = envs.NmpcGoalVectorEnv(2, seed=3, obstacles=1)
    vec.reset()
    before = vec.env(0).obstacles[0].x
    vec.reset()
    assert vec.env(0).obstacles[0].x != before
