"""Starts walkgen_dashboard for the web tests (ctests dashboard_http, label web, and
dashboard_browser, label browser; examples/CMakeLists.txt passes the program's path in
WALKGEN_DASHBOARD). Loopback only; every request has a timeout."""

import json
import os
import re
import signal
import subprocess
import time
import urllib.error
import urllib.request

import pytest


class Dashboard:
    def __init__(self, args):
        program = os.environ.get("WALKGEN_DASHBOARD")
        if not program:
            pytest.fail("WALKGEN_DASHBOARD is not set: run these tests through ctest")
        self.process = subprocess.Popen([program, "--port", "0", *args], stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, text=True)
        line = self.process.stdout.readline()
        match = re.search(r"http://(127\.0\.0\.1):(\d+)/", line)
        if not match:
            self.process.kill()
            pytest.fail(f"walkgen_dashboard did not start: {line}{self.process.stdout.read()}")
        self.url = f"http://{match.group(1)}:{match.group(2)}"

    def request(self, path, body=None, method=None, timeout=10):
        """(HTTP status, body bytes) of a request to the dashboard."""
        data = body.encode() if isinstance(body, str) else body
        req = urllib.request.Request(self.url + path, data=data, method=method)
        if data is not None:
            req.add_header("Content-Type", "application/json")
        try:
            with urllib.request.urlopen(req, timeout=timeout) as res:
                return res.status, res.read()
        except urllib.error.HTTPError as e:
            return e.code, e.read()

    def state(self):
        status, body = self.request("/api/state")
        assert status == 200
        return json.loads(body)

    def wait(self, predicate, timeout=30.0):
        """The first state for which predicate holds, within timeout seconds."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            s = self.state()
            if predicate(s):
                return s
            time.sleep(0.1)
        raise AssertionError(f"state never satisfied the condition; last: {self.state()}")

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                pytest.fail("walkgen_dashboard did not stop on SIGTERM within 20 s")
        return self.process.returncode


@pytest.fixture
def dashboard():
    """A dashboard on the empty floor at 4x real time."""
    d = Dashboard(["--speed", "4"])
    d.wait(lambda s: s.get("ticks", 0) >= 1)
    yield d
    assert d.stop() == 0, d.process.stdout.read()


HEADER = ("epoch,steps,mean_reward,mean_return,episodes,wins,losses,truncations,std,seconds,"
          "policy_loss,value_loss,entropy,approx_kl,clip_fraction\n")


def ppo_row(epoch):
    """A row of examples/ppo_train's learning_<env>.csv, improving with the epoch."""
    return (f"{epoch},{2048 * epoch},{-1 + 0.1 * epoch},{10 * epoch},20,{min(20, 2 * epoch)},"
            f"{max(0, 10 - epoch)},0,0.5,1.2,{1 / epoch},{5 / epoch},1.3,0.01,0.1\n")


@pytest.fixture
def training_run(tmp_path):
    """A training run's folder with a PPO log of 5 epochs (more can be appended)."""
    log = tmp_path / "learning_nmpc.csv"
    log.write_text(HEADER + "".join(ppo_row(e) for e in range(1, 6)))
    (tmp_path / "notes.csv").write_text("not,numbers\nsome,text\n")
    return tmp_path


@pytest.fixture
def training_dashboard(training_run):
    d = Dashboard(["--speed", "4", "--training", str(training_run)])
    d.wait(lambda s: s.get("ticks", 0) >= 1)
    yield d
    assert d.stop() == 0, d.process.stdout.read()


@pytest.fixture
def screenshots():
    directory = os.environ.get("WALKGEN_SCREENSHOTS", "dashboard_screenshots")
    os.makedirs(directory, exist_ok=True)
    return directory
