"""walkgen.envs.NavigationEnv: the humanoid in MuJoCo walks to a target it sees (thesis §11.1)
with the Gymnasium API shape: observations from the cameras, the scripted expert reaching the
target, rewards that add up to the progress, seeding, errors."""

import numpy as np
import pytest

import walkgen
from walkgen import envs

pytestmark = pytest.mark.skipif(not walkgen.features.get("navigation"),
                                reason="built without walkgen::navigation (MuJoCo, Ceres, OpenCV)")


def test_the_expert_walks_to_the_target_it_sees():
    env = envs.NavigationEnv("straight", seed=0)
    obs, info = env.reset(options={"scene_seed": 1})
    assert set(obs) == {"rgb", "disparity", "depth"}
    assert obs["rgb"].dtype == np.uint8 and obs["rgb"].shape[2] == 3
    assert obs["disparity"].shape == obs["depth"].shape == obs["rgb"].shape[:2]
    assert env.observation_space.contains(obs)
    # the red target is in view ahead: red pixels in the middle band of the image
    rgb = obs["rgb"].astype(int)
    red = (rgb[..., 0] > 120) & (rgb[..., 1] < 80) & (rgb[..., 2] < 80)
    assert red.sum() > 20
    start = info["distance"]
    total, steps = 0.0, 0
    while True:
        action = env.expert_action()
        assert env.action_space.contains(action)  # the expert keeps to 95 % of the limits
        obs, reward, terminated, truncated, info = env.step(action)
        total += reward
        steps += 1
        if terminated or truncated:
            break
    assert info["status"] == "reached" and info["is_success"] and terminated, info["message"]
    assert info["distance"] <= 0.3
    assert total == pytest.approx(start - info["distance"] + 10.0, abs=1e-9)
    assert info["time"] == pytest.approx(0.4 * steps, abs=1e-6)
    with pytest.raises(RuntimeError, match="reset"):
        env.step([0, 0, 0])


def test_the_same_seed_gives_the_same_scene_and_images():
    a, b = envs.NavigationEnv(["straight", "obstacle"]), envs.NavigationEnv(["straight", "obstacle"])
    obs_a, info_a = a.reset(seed=4)
    obs_b, info_b = b.reset(seed=4)
    assert (info_a["task"], info_a["scene_seed"]) == (info_b["task"], info_b["scene_seed"])
    np.testing.assert_array_equal(obs_a["rgb"], obs_b["rgb"])
    np.testing.assert_array_equal(a.step([0.02, 0, 0])[0]["depth"], b.step([0.02, 0, 0])[0]["depth"])
    _, other = a.reset(seed=5)
    assert (other["task"], other["scene_seed"]) != (info_a["task"], info_a["scene_seed"])


def test_navigation_errors():
    with pytest.raises(ValueError, match="task"):
        envs.NavigationEnv("jump")
    env = envs.NavigationEnv("straight", seed=0)
    with pytest.raises(RuntimeError, match="reset"):
        env.step([0, 0, 0])
    with pytest.raises(ValueError, match="unknown options"):
        env.reset(options={"scene": 3})
    with pytest.raises(ValueError, match="scene seed"):
        env.reset(options={"scene_seed": -1})
    env.reset(options={"scene_seed": 2})
    with pytest.raises(ValueError, match=r"action.*\(3,\)"):
        env.step([0.0, 0.0])
    obs, reward, terminated, truncated, info = env.step([np.nan, 0.0, 0.0])  # NaN counts as 0
    assert not terminated and info["status"] == "running"
    assert np.isfinite(reward) and np.isfinite(info["distance"])
    with pytest.raises(ValueError, match="scene seed"):  # a failed reset ends the episode ...
        env.reset(options={"scene_seed": 2**32})
    with pytest.raises(ValueError, match="expert_command"):  # ... and its observation
        env.expert_action()
    with pytest.raises(RuntimeError, match="reset"):
        env.step([0.0, 0.0, 0.0])
