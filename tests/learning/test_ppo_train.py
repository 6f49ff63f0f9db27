"""examples/ppo_train as a user runs it: data-parallel training over two processes on loopback
(c10d Gloo), resuming an interrupted run, the YAML configuration and the progress bar.

Run by ctest (label learning) with PPO_TRAIN=<path of the ppo_train program>; each run is a few
short epochs, bounded by a timeout.
"""
import csv
import os
import pty
import socket
import subprocess
import sys
import time

import pytest

PPO_TRAIN = os.environ.get("PPO_TRAIN", "")
TIMEOUT = 240  # seconds, for any one run

if not os.path.exists(PPO_TRAIN):
    raise RuntimeError("set PPO_TRAIN to the ppo_train program (ctest does)")


def run(args, **kw):
    """Runs ppo_train; returns the completed process (stdout and stderr as text)."""
    return subprocess.run([PPO_TRAIN] + args, capture_output=True, text=True, timeout=TIMEOUT,
                          check=False, **kw)


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def parameters(path):
    """The named tensors of a policy saved by TorchPpo::save, as float64 numpy arrays."""
    import torch  # Debian's python3-torch (scripts/setup.sh)
    module = torch.jit.load(path)
    return {n: p.detach().double().numpy() for n, p in module.named_parameters()}


def max_difference(a, b):
    assert a.keys() == b.keys()
    return max(float(abs(a[k] - b[k]).max()) for k in a)


# Short NMPC runs: 8 environments, 2 epochs of 2 updates (4 x 256 x 8 samples).
SHORT = ["nmpc", "--epochs", "2", "--steps", "4096", "--envs", "8", "--test-goals", "2",
         "--quiet"]


def test_distributed_two_ranks_match_one_process(tmp_path):
    """Two ranks with 4 environments each keep identical weights, equal to one process with 8."""
    one = run(SHORT + ["--out", str(tmp_path / "one"), "--threads", "2"])
    assert one.returncode == 0, one.stderr
    port = str(free_port())
    common = SHORT + ["--out", str(tmp_path / "two"), "--world-size", "2", "--master-addr",
                      "127.0.0.1", "--master-port", port, "--threads", "1"]
    rank1 = subprocess.Popen([PPO_TRAIN] + common + ["--rank", "1"], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        rank0 = run(common + ["--rank", "0"])
        out1, err1 = rank1.communicate(timeout=TIMEOUT)
    finally:
        rank1.kill()
    assert rank0.returncode == 0, rank0.stderr
    assert rank1.returncode == 0, err1
    assert "2 processes" in rank0.stdout
    # the ranks' weights after training are the same
    two = tmp_path / "two"
    p0 = parameters(str(two / "ppo_nmpc_last.pt"))
    p1 = parameters(str(two / "ppo_nmpc_last.rank1.pt"))
    assert max_difference(p0, p1) == 0.0
    # ... and those of the single process with the same total batch, to float rounding
    p = parameters(str(tmp_path / "one" / "ppo_nmpc_last.pt"))
    difference = max_difference(p, p0)
    print("largest weight difference, 1 vs 2 processes: %.3g" % difference)
    assert difference < 1e-4
    assert max_difference(p, parameters(str(tmp_path / "one" / "ppo_nmpc.pt"))) == 0.0
    # the logs agree: same episodes, rewards and losses
    a, b = rows(str(tmp_path / "one" / "learning_nmpc.csv")), rows(str(two / "learning_nmpc.csv"))
    assert len(a) == len(b) == 2
    for x, y in zip(a, b):
        for key in ("steps", "episodes", "wins", "losses", "truncations"):
            assert x[key] == y[key], key
        for key in ("mean_reward", "policy_loss", "value_loss", "approx_kl", "std"):
            assert float(x[key]) == pytest.approx(float(y[key]), rel=1e-3, abs=1e-6), key
    assert int(a[-1]["steps"]) == 4096


def test_resume_equals_the_uninterrupted_run(tmp_path):
    """Stopped after 1 of 3 epochs and resumed, a run ends with the same policy and log."""
    args = ["benchmark", "--epochs", "3", "--test-runs", "1", "--quiet"]
    whole = run(args + ["--out", str(tmp_path / "whole")])
    assert whole.returncode == 0, whole.stderr
    cut = run(args + ["--out", str(tmp_path / "cut"), "--stop-after", "1"])
    assert cut.returncode == 0, cut.stderr
    assert "stopped after epoch 1" in cut.stdout
    assert len(rows(str(tmp_path / "cut" / "learning_benchmark.csv"))) == 1
    resumed = run(args + ["--out", str(tmp_path / "cut"), "--resume"])
    assert resumed.returncode == 0, resumed.stderr
    assert "resumed benchmark" in resumed.stdout and "after epoch 1" in resumed.stdout
    a = rows(str(tmp_path / "whole" / "learning_benchmark.csv"))
    b = rows(str(tmp_path / "cut" / "learning_benchmark.csv"))
    assert [r["epoch"] for r in b] == ["1", "2", "3"]
    for x, y in zip(a, b):  # everything but the wall times
        for key in x:
            if key not in ("seconds", "elapsed"):
                assert x[key] == y[key], key
    with open(tmp_path / "whole" / "ppo_benchmark.pt", "rb") as f1, \
            open(tmp_path / "cut" / "ppo_benchmark.pt", "rb") as f2:
        assert f1.read() == f2.read()
    # resuming with other settings is refused, naming the difference
    other = run(args + ["--out", str(tmp_path / "cut"), "--resume", "--envs", "4"])
    assert other.returncode == 1
    assert "envs" in other.stderr
    missing = run(args + ["--out", str(tmp_path / "nothing"), "--resume"])
    assert missing.returncode == 1 and "checkpoint" in missing.stderr


def test_config_file_and_options(tmp_path):
    """--config sets PPO's and the run's settings; options override it; bad files are named."""
    config = tmp_path / "ppo.yaml"
    config.write_text("ppo:\n  learning_rate: 0.002\n  actor_hidden: [8, 8]\n"
                      "run:\n  epochs: 1\n  seed: 3\n")
    r = run(["benchmark", "--config", str(config), "--seed", "4", "--test-runs", "1", "--quiet",
             "--out", str(tmp_path / "out")])
    assert r.returncode == 0, r.stderr
    written = (tmp_path / "out" / "config_benchmark.yaml").read_text()
    assert "learning_rate: 0.002" in written and "actor_hidden: [8, 8]" in written
    assert "seed: 4" in written and "epochs: 1" in written
    assert len(rows(str(tmp_path / "out" / "learning_benchmark.csv"))) == 1
    # the written file reads back to the same settings
    again = run(["benchmark", "--config", str(tmp_path / "out" / "config_benchmark.yaml"),
                 "--test-runs", "1", "--quiet", "--out", str(tmp_path / "again")])
    assert again.returncode == 0, again.stderr
    assert (tmp_path / "again" / "config_benchmark.yaml").read_text() == written
    config.write_text("ppo:\n  learning_rat: 0.002\n")
    bad = run(["benchmark", "--config", str(config), "--out", str(tmp_path / "bad")])
    assert bad.returncode == 1
    assert "learning_rat" in bad.stderr and "learning_rate" in bad.stderr
    assert str(config) + ":2" in bad.stderr


def test_obstacle_defaults_and_environment_options(tmp_path):
    """With obstacles the state adds the robot's motion (12 inputs), the success reward is
    10 000, the NMPC's obstacle rows are soft and the step size is annealed over 200 epochs;
    --no-observe-motion gives the thesis's state plus the obstacle (5 inputs); the written config
    names the environment's options and a resumed run must share them."""
    import torch  # Debian's python3-torch (scripts/setup.sh)
    base = ["nmpc", "--obstacles", "1", "--steps", "2048", "--test-goals", "2", "--quiet"]
    short = base + ["--epochs", "1"]
    for extra, inputs in (([], 12), (["--no-observe-motion"], 5)):
        out = tmp_path / ("motion" if not extra else "plain")
        r = run(short + extra + ["--out", str(out)])
        assert r.returncode == 0, r.stderr
        policy = torch.jit.load(str(out / "ppo_nmpc_obstacles.pt"))
        first = next(p for p in policy.parameters() if p.dim() == 2)  # the first layer's weights
        assert first.shape[1] == inputs, (extra, first.shape)
        config = (out / "config_nmpc_obstacles.yaml").read_text()
        assert config.splitlines()[0] == (
            "# environment: ppo_train nmpc --obstacles 1 "
            + ("--no-observe-motion" if extra else "--observe-motion")
            + " --success-reward 10000 --obstacle-weight 0 --soft-obstacles 10000"), config
        assert "epochs: 1" in config
    # the run's defaults with obstacles: 200 epochs, the step size annealed
    r = run(base + ["--stop-after", "1", "--out", str(tmp_path / "defaults")])
    assert r.returncode == 0, r.stderr
    written = (tmp_path / "defaults" / "config_nmpc_obstacles.yaml").read_text()
    assert "epochs: 200" in written and "anneal_learning_rate: true" in written
    # a checkpoint made with one success reward is not resumed with another
    r = run(base + ["--stop-after", "1", "--epochs", "2", "--out", str(tmp_path / "resume")])
    assert r.returncode == 0, r.stderr
    r = run(base + ["--epochs", "2", "--resume", "--success-reward", "50",
                     "--out", str(tmp_path / "resume")])
    assert r.returncode == 1 and "settings" in r.stderr, r.stderr


def test_bad_command_lines():
    """Each is refused at once, naming what is wrong, before any rank waits for another."""
    cases = ((["nmpc", "--world-size", "2", "--rank", "2"], "--rank"),
             (["nmpc", "--envs", "3", "--world-size", "2"], "--envs"),
             (["nmpc", "--steps", "1000000000001"], "steps"),
             (["nmpc", "--master-port", "70000", "--world-size", "2"], "--master-port"),
             (["nmpc", "--epochs", "0"], "--epochs"))
    for args, named in cases:
        start = time.monotonic()
        r = run(args + ([] if "--master-port" in args else ["--master-port", str(free_port())]))
        assert r.returncode in (1, 2), (args, r.stdout, r.stderr)
        assert named in r.stderr, (args, r.stderr)
        assert time.monotonic() - start < 30, args  # no waiting for a rank that never comes
    env = dict(os.environ, RANK="x")
    r = run(["nmpc"], env=env)
    assert r.returncode == 2 and "RANK" in r.stderr


def test_progress_bar_on_a_terminal(tmp_path):
    """On a terminal, training draws one bar line rewritten with \\r, with an ETA."""
    pid, fd = pty.fork()
    if pid == 0:  # the child: ppo_train on the pseudo-terminal
        os.execv(PPO_TRAIN, [PPO_TRAIN, "benchmark", "--epochs", "3", "--test-runs", "1",
                             "--out", str(tmp_path)])
    output = b""
    while True:
        try:
            chunk = os.read(fd, 4096)
        except OSError:
            break
        if not chunk:
            break
        output += chunk
    _, status = os.waitpid(pid, 0)
    assert os.WEXITSTATUS(status) == 0
    text = output.decode(errors="replace")
    sys.stdout.write(text)
    assert "\r" in text and "ETA" in text
    assert "3/3" in text and "[########################]" in text
    assert "epoch   1/3" not in text  # no per-epoch lines on a terminal
