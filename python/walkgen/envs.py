"""Reinforcement-learning environments with the Gymnasium API shape (docs/python.md).

- ``PointGoalEnv``: the benchmarking environment of thesis §11.2.1 (a point walks to a goal).
- ``NmpcGoalEnv``: a policy steers the NMPC walking generator to a goal, around obstacles
  (thesis §11.2.2; ``obstacles=k`` puts k in the way).
- ``PointGoalVectorEnv`` and ``NmpcGoalVectorEnv``: N of them stepped at once in C++ threads.

``reset(seed=None) -> (obs, info)`` and ``step(action) -> (obs, reward, terminated, truncated,
info)``; ``observation_space`` and ``action_space`` are Box spaces (shape, dtype, low, high).
When the ``gymnasium`` package is importable the environments subclass ``gymnasium.Env`` (and
``gymnasium.vector.VectorEnv``) and the spaces are ``gymnasium.spaces.Box``; without it they
behave the same with walkgen's own ``Box``.

Seeding follows Gymnasium: ``reset(seed=s)`` restarts the task generator, ``reset()`` draws the
next task; an environment made without a seed starts from a random one.
"""

import secrets

import numpy as np

from . import _core

try:  # Gymnasium is optional: Debian 12 does not package it.
    import gymnasium as _gymnasium
    from gymnasium import spaces as _spaces
except ImportError:  # pragma: no cover - depends on the machine
    _gymnasium = None
    _spaces = None


class Box:
    """A box in R^shape (what ``gymnasium.spaces.Box`` is, for machines without Gymnasium)."""

    def __init__(self, low, high, shape=None, dtype=np.float32, seed=None):
        self.dtype = np.dtype(dtype)
        if shape is None:
            shape = np.shape(low)
        self.shape = tuple(int(k) for k in shape)
        self.low = np.broadcast_to(np.asarray(low, dtype=self.dtype), self.shape).copy()
        self.high = np.broadcast_to(np.asarray(high, dtype=self.dtype), self.shape).copy()
        if np.any(self.low > self.high):
            raise ValueError("Box: every low must be <= its high")
        self._rng = np.random.default_rng(seed)

    def seed(self, seed=None):
        self._rng = np.random.default_rng(seed)
        return [seed]

    def sample(self):
        """A uniform sample where both bounds are finite, normal where one is not."""
        low = np.where(np.isfinite(self.low), self.low, -np.inf)
        high = np.where(np.isfinite(self.high), self.high, np.inf)
        bounded = np.isfinite(low) & np.isfinite(high)
        x = self._rng.standard_normal(self.shape)
        x = np.where(bounded, self._rng.uniform(np.where(bounded, low, 0),
                                                np.where(bounded, high, 1)), x)
        return np.clip(x, low, high).astype(self.dtype)

    def contains(self, x):
        x = np.asarray(x)
        return (x.shape == self.shape and np.can_cast(x.dtype, self.dtype, "same_kind")
                and bool(np.all(x >= self.low)) and bool(np.all(x <= self.high)))

    __contains__ = contains

    def __repr__(self):
        return f"Box({self.low.min()}, {self.high.max()}, {self.shape}, {self.dtype})"


class Dict:
    """A dictionary of spaces (what ``gymnasium.spaces.Dict`` is, without Gymnasium)."""

    def __init__(self, spaces):
        self.spaces = dict(spaces)

    def __getitem__(self, key):
        return self.spaces[key]

    def sample(self):
        return {k: s.sample() for k, s in self.spaces.items()}

    def contains(self, x):
        return (isinstance(x, dict) and x.keys() == self.spaces.keys()
                and all(s.contains(x[k]) for k, s in self.spaces.items()))

    __contains__ = contains

    def __repr__(self):
        return f"Dict({self.spaces!r})"


def _box(low, high):
    low = np.asarray(low, dtype=np.float32)
    high = np.asarray(high, dtype=np.float32)
    if _spaces is not None:
        return _spaces.Box(low=low, high=high, dtype=np.float32)
    return Box(low, high, dtype=np.float32)


def _image_space(shape, low, high, dtype):
    if _spaces is not None:
        return _spaces.Box(low=low, high=high, shape=shape, dtype=dtype)
    return Box(low, high, shape=shape, dtype=dtype)


def _dict_space(spaces):
    return _spaces.Dict(spaces) if _spaces is not None else Dict(spaces)


def _seed_or_random(seed):
    if seed is None:
        return secrets.randbits(63)
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"seed: expected an int >= 0 or None, got {type(seed).__name__}")
    if not 0 <= int(seed) < 2**64:
        raise ValueError(f"seed: expected an int in [0, 2**64), got {seed}")
    return int(seed)


def _gymnasium_reset(env, seed):
    """gymnasium.Env.reset(seed) (its np_random), with the seed as a plain int, when present."""
    if _gymnasium is not None:
        _gymnasium.Env.reset(env, seed=None if seed is None else _seed_or_random(seed))


_EnvBase = _gymnasium.Env if _gymnasium is not None else object
_VectorBase = _gymnasium.vector.VectorEnv if _gymnasium is not None else object


class _Env(_EnvBase):
    """What both single environments share; subclasses make ``self._core`` and the spaces."""

    metadata = {"render_modes": []}
    render_mode = None
    spec = None

    def reset(self, *, seed=None, options=None):
        """A new task (reseeded when `seed` is given): ``(observation, info)``."""
        _gymnasium_reset(self, seed)
        if seed is not None:
            self._core.seed(_seed_or_random(seed))
        if options and "goal" in options:
            self._reset_to(options)
        else:
            self._core.reset()
        self._ended = False
        return self._core.observe(), self._info()

    def step(self, action):
        """One step: ``(observation, reward, terminated, truncated, info)``. Actions are
        clipped to [-1, 1]; non-finite entries count as 0."""
        if self._ended:
            raise RuntimeError(f"{type(self).__name__}.step: the episode has ended; "
                               "call reset() first")
        reward, end, message = self._core.step(action)
        self._ended = end != "none"
        info = self._info()
        info.update(end=str(end), message=message, is_success=end == "success")
        return (self._core.observe(), float(reward), end in ("success", "failure"),
                end == "truncated", info)

    def close(self):
        pass

    @property
    def settings(self):
        """A copy of the environment's settings."""
        return self._core.settings

    def _info(self):
        return {}


class PointGoalEnv(_Env):
    """Thesis §11.2.1: the agent starts at the origin and moves by ``action * step_size`` towards
    a random goal. Observation (agent x, y, goal x, y), float32; action (dx, dy) in [-1, 1]^2.
    Reward: progress towards the goal, +win_reward within win_radius (terminated), lose_reward
    beyond lose_radius (terminated); max_steps truncates when > 0.

    ``reset(options={"goal": (x, y)})`` starts an episode with that goal."""

    def __init__(self, settings=None, seed=None, **fields):
        self._settings = _settings(_core.PointGoalSettings, settings, fields)
        self._core = _core._PointGoalCore(self._settings, 0)
        self._core.seed(_seed_or_random(seed))  # the first reset() draws the seed's first task
        s = self._settings
        reach = s.goal_range + s.lose_radius + 2 * s.step_size  # the last step may overshoot
        self.observation_space = _box([-reach] * 2 + [-s.goal_range] * 2,
                                      [reach] * 2 + [s.goal_range] * 2)
        self.action_space = _box([-1.0, -1.0], [1.0, 1.0])
        self._ended = True

    def _reset_to(self, options):
        self._core.reset_to(options["goal"])

    def _info(self):
        return {"agent": self._core.agent, "goal": self._core.goal}


class NmpcGoalEnv(_Env):
    """Thesis §11.2.2: a policy steers ``WalkingMpc`` to a goal by (v_x, w_z) commands.
    Observation: the goal in the robot frame (x, y), then per obstacle its centre in the robot
    frame and radius + margin; float32. Action (v_x, w_z) in [-1, 1]^2, scaled to the preset's
    limits. Terminated on success (the CoM within success_radius) or failure (the NMPC found no
    plan); truncated after max_steps.

    ``NmpcGoalEnv(obstacles=2)`` sets fields of ``NmpcGoalSettings`` by keyword;
    ``reset(options={"goal": (x, y), "obstacles": [CircleObstacle, ...]})`` sets the task."""

    def __init__(self, settings=None, seed=None, **fields):
        self._settings = _settings(_core.NmpcGoalSettings, settings, fields)
        self._core = _core._NmpcGoalCore(self._settings, 0)
        self._core.seed(_seed_or_random(seed))  # the first reset() draws the seed's first task
        self.observation_space, self.action_space = _nmpc_spaces(self._settings)
        self._ended = True

    @property
    def mpc(self):
        """The environment's WalkingMpc (to read its plan; stepping it is the environment's)."""
        return self._core.mpc

    def command_of(self, action):
        """The velocity command (vx, vy, wz) an action maps to."""
        return self._core.command_of(action)

    def _reset_to(self, options):
        self._core.reset_to(options["goal"], list(options.get("obstacles", [])))

    def _info(self):
        c = self._core
        return {"position": c.position, "heading": c.heading, "distance": c.distance,
                "goal": c.goal, "time": c.time,
                "min_obstacle_clearance": c.min_obstacle_clearance}


def _settings(kind, settings, fields):
    """A copy of `settings` (default: kind()) with `fields` set, checked."""
    if settings is None:
        s = kind()
    elif isinstance(settings, kind):
        s = settings.copy()
    else:
        raise ValueError(f"settings: expected {kind.__name__} or None, "
                         f"got {type(settings).__name__}")
    for name, value in fields.items():
        if name.startswith("_") or not hasattr(s, name) or callable(getattr(s, name)):
            known = sorted(k for k in dir(kind) if not k.startswith("_")
                           and not callable(getattr(kind, k)))
            raise ValueError(f"{kind.__name__} has no field '{name}'; fields: {', '.join(known)}")
        setattr(s, name, value)
    s.validate()
    return s


def _nmpc_spaces(s):
    inf = np.inf
    # the goal, per obstacle its centre and R + m, then (observe_motion) the CoM velocity, the
    # action in effect, the support foot and the step's elapsed fraction
    motion_low = [-inf, -inf, -1.0, -1.0, -inf, -inf, 0.0] if s.observe_motion else []
    motion_high = [inf, inf, 1.0, 1.0, inf, inf, 1.0] if s.observe_motion else []
    low = [-inf, -inf] + [-inf, -inf, 0.0] * s.obstacles + motion_low
    high = [inf] * (2 + 3 * s.obstacles) + motion_high
    return _box(low, high), _box([-1.0, -1.0], [1.0, 1.0])


NAVIGATION_TASKS = ("straight", "curved", "obstacle", "scan", "dynamic", "distractor")


class NavigationEnv(_EnvBase):
    """Thesis §11.1: walkgen's humanoid in MuJoCo walks to a red target in a room, seeing through
    its chest cameras (the closed loop of figure 6.1 under it). One step is one NMPC tick (0.4 s).

    Observation (a dict): ``rgb`` (h, w, 3) uint8 of the left camera, ``disparity`` (h, w)
    float32 [px] of the stereo pair (WLS, <= 0 where unknown), ``depth`` (h, w) float32 [m], the
    renderer's exact depth. Action: the velocity command (v_x, v_y, w_z) [m/s, rad/s], clipped
    to 95 % of Heicub's limits (the action space's bounds). Reward: the progress of the true
    CoM towards the target [m], +10 on reaching it (terminated), -10 on a collision, a fall or a
    fault (terminated); the time limit truncates. ``expert_action()`` is the scripted expert's
    command for the current observation (for behavioural cloning).

    ``task`` is one of NAVIGATION_TASKS or a list to draw from; each reset draws a scene seed
    from the environment's generator (``reset(seed=s)`` restarts it); ``reset(options={"task":
    "obstacle", "scene_seed": 3})`` picks a scene. Needs walkgen.features["navigation"] and EGL
    rendering (RuntimeError when unavailable)."""

    metadata = {"render_modes": []}
    render_mode = None
    spec = None

    def __init__(self, task="straight", seed=None, time_limit=0.0, reach_distance=0.3):
        if not hasattr(_core, "_NavigationCore"):
            raise RuntimeError("NavigationEnv: walkgen was built without walkgen::navigation "
                               "(MuJoCo, Ceres, OpenCV); see walkgen.features")
        tasks = [task] if isinstance(task, str) else list(task)
        for t in tasks:
            if t not in NAVIGATION_TASKS:
                raise ValueError(f"NavigationEnv: task: expected one of {', '.join(NAVIGATION_TASKS)}, "
                                 f"got '{t}'")
        self._tasks = tasks
        self._core = _core._NavigationCore(float(time_limit), float(reach_distance))
        self._rng = np.random.default_rng(_seed_or_random(seed))
        limit = self._core.max_command.astype(np.float32)
        self.action_space = _box(-limit, limit)
        h, w = 240, 320  # the chest cameras (models/walkgen_humanoid.xml); checked on reset
        self._set_observation_space(h, w)
        self._ended = True

    def _set_observation_space(self, h, w):
        self.observation_space = _dict_space({
            "rgb": _image_space((h, w, 3), 0, 255, np.uint8),
            "disparity": _image_space((h, w), -np.inf, np.inf, np.float32),
            "depth": _image_space((h, w), 0.0, np.inf, np.float32)})

    def reset(self, *, seed=None, options=None):
        _gymnasium_reset(self, seed)
        if seed is not None:
            self._rng = np.random.default_rng(_seed_or_random(seed))
        self._ended = True  # until the new episode has started
        options = dict(options or {})
        task = options.pop("task", None) or self._tasks[int(self._rng.integers(len(self._tasks)))]
        scene_seed = options.pop("scene_seed", None)
        if scene_seed is None:
            scene_seed = int(self._rng.integers(2**32))
        if options:
            raise ValueError(f"NavigationEnv.reset: unknown options {sorted(options)}; "
                             "known: task, scene_seed")
        if task not in NAVIGATION_TASKS:
            raise ValueError(f"NavigationEnv.reset: task: expected one of "
                             f"{', '.join(NAVIGATION_TASKS)}, got '{task}'")
        if self._core.reset(task, scene_seed):  # did not start: a fall or no rendering
            status, message = self._core.status, self._core.message
            raise RuntimeError(f"NavigationEnv.reset: the episode could not start: {status} "
                               f"({message})")
        h, w = self._core.image_size
        if self.observation_space["rgb"].shape[:2] != (h, w):
            self._set_observation_space(h, w)
        self._ended = False
        obs = self._core.observe()
        self._distance = float(np.linalg.norm(self._core.true_com() - self._core.scene["target"]))
        return obs, self._info()

    def expert_action(self):
        """The scripted expert's command (v_x, v_y, w_z) for the current observation. The expert
        remembers whether it has seen the target: call it on every step of an episode for its
        behaviour (as run_navigation_episode does)."""
        return self._core.expert_command().astype(np.float32)

    def step(self, action):
        if self._ended:
            raise RuntimeError("NavigationEnv.step: the episode has ended; call reset() first")
        done = self._core.step(action)
        distance = self._core.distance
        reward = self._distance - distance
        self._distance = distance
        status = self._core.status if done else "running"
        terminated = done and status != "timed_out"
        truncated = done and status == "timed_out"
        if status == "reached":
            reward += 10.0
        elif terminated:
            reward -= 10.0
        self._ended = done
        obs = self._core.observe()  # after the end too: the robot where the episode left it
        info = self._info()
        info.update(status=status, message=self._core.message if done else "",
                    is_success=status == "reached")
        return obs, float(reward), terminated, truncated, info

    def _info(self):
        scene = self._core.scene
        return {"task": scene["task"], "scene_seed": scene["seed"], "target": scene["target"],
                "distance": self._distance, "time": self._core.time,
                "time_limit": self._core.time_limit}

    def close(self):
        pass


class _VectorEnv(_VectorBase):
    """N environments stepped in C++ threads (the GIL released). Same-step auto-reset: when an
    environment's episode ends its returned observation is the first of the next episode, and
    ``info["final_obs"][i]`` (with ``info["_final_obs"][i]`` True; also under Gymnasium 0.29's
    names ``final_observation``, ``_final_observation``) holds the last one of the episode that
    ended."""

    metadata = {"render_modes": [],
                # Gymnasium >= 1.0 names the mode with an enum; 0.29 had none (same-step only)
                "autoreset_mode": getattr(getattr(getattr(_gymnasium, "vector", None),
                                                  "AutoresetMode", None), "SAME_STEP", "SameStep")}
    render_mode = None
    spec = None

    def _init_spaces(self, single_obs, single_act):
        n = self.num_envs
        self.single_observation_space = single_obs
        self.single_action_space = single_act
        self.observation_space = _box(np.tile(single_obs.low, (n, 1)),
                                      np.tile(single_obs.high, (n, 1)))
        self.action_space = _box(np.tile(single_act.low, (n, 1)), np.tile(single_act.high, (n, 1)))

    @property
    def num_envs(self):
        return self._core.num_envs

    @property
    def threads(self):
        """Threads that step the environments."""
        return self._core.threads

    def env(self, index):
        """Environment `index` (its position, goal, obstacles, mpc, ...), to read; stepping it
        is the vector's."""
        return self._core.env(index)

    def reset(self, *, seed=None, options=None):
        """Resets every environment (environment i reseeded with seed + i): ``(obs, info)``."""
        if options:
            raise ValueError("VectorEnv.reset: options are not supported")
        obs = self._core.reset(None if seed is None else _seed_or_random(seed))
        self._reset_done = True
        return obs, {}

    def step(self, actions):
        """Steps all: ``(obs (N, o), rewards (N,), terminated (N,), truncated (N,), info)``."""
        if not getattr(self, "_reset_done", False):
            raise RuntimeError(f"{type(self).__name__}.step: call reset() first")
        obs, rewards, ends, messages, final_obs = self._core.step(actions)
        names = np.array([str(e) for e in ends])
        terminated = (names == "success") | (names == "failure")
        truncated = names == "truncated"
        done = terminated | truncated
        info = {"end": names, "message": np.array(messages, dtype=object),
                "is_success": names == "success",
                # Gymnasium >= 1.0's same-step keys, and 0.29's (and Stable-Baselines3's)
                "final_obs": final_obs, "_final_obs": done,
                "final_observation": final_obs, "_final_observation": done}
        return obs, rewards, terminated, truncated, info

    def close(self, **kwargs):
        pass


class PointGoalVectorEnv(_VectorEnv):
    """``num_envs`` PointGoalEnv stepped in C++ threads (``threads=0``: one per core)."""

    def __init__(self, num_envs, settings=None, seed=None, threads=0, **fields):
        s = _settings(_core.PointGoalSettings, settings, fields)
        self._core = _core._PointGoalVectorCore(s, num_envs, _seed_or_random(seed), threads)
        single = PointGoalEnv(s, seed=0)
        self._init_spaces(single.observation_space, single.action_space)


class NmpcGoalVectorEnv(_VectorEnv):
    """``num_envs`` NmpcGoalEnv stepped in C++ threads (``threads=0``: one per core)."""

    def __init__(self, num_envs, settings=None, seed=None, threads=0, **fields):
        s = _settings(_core.NmpcGoalSettings, settings, fields)
        self._core = _core._NmpcGoalVectorCore(s, num_envs, _seed_or_random(seed), threads)
        self._init_spaces(*_nmpc_spaces(s))
