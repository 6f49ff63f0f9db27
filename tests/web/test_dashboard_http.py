"""The dashboard's HTTP API (label web): the state, commands that move the robot, the stop, and
bad requests refused with 400/413 leaving the command unchanged; 200 concurrent state requests
all answered; the server survives all of it."""

import concurrent.futures
import json


def test_state_has_what_the_page_draws(dashboard):
    s = dashboard.state()
    for key in ("time", "com", "zmp", "footsteps", "status", "mode", "command", "max_command",
                "feet", "obstacles"):
        assert key in s, key
    assert s["status"] == "ok" and s["mode"] == "walking"
    assert 0.0 < s["mpc_ms"] < s["compute_ms"]  # the NMPC's solve is timed, within the tick
    assert len(s["footsteps"]) >= 1 and len(s["footsteps"][0]) == 3
    status, page = dashboard.request("/")
    assert status == 200 and b"<canvas id=\"topview\"" in page
    for asset in ("/dashboard.js", "/dashboard.css"):
        assert dashboard.request(asset)[0] == 200


def test_a_command_walks_the_robot_forward_and_stop_stops_it(dashboard):
    start = dashboard.state()
    status, body = dashboard.request("/api/command", json.dumps({"vx": 0.03}))
    assert status == 200, body
    walked = dashboard.wait(lambda s: s["com"][0] > start["com"][0] + 0.05, timeout=60)
    assert walked["command"] == [0.03, 0.0, 0.0]
    assert dashboard.request("/api/stop", "", method="POST")[0] == 200
    stopped = dashboard.wait(lambda s: s["mode"] == "stopped", timeout=60)
    assert stopped["command"] == [0.0, 0.0, 0.0] and stopped["status"] == "ok"


def test_bad_requests_are_refused_and_change_nothing(dashboard):
    assert dashboard.request("/api/command", json.dumps({"vx": 0.01, "wz": 0.02}))[0] == 200
    dashboard.wait(lambda s: s["command"] == [0.01, 0.0, 0.02])
    bad = [
        ("{\"vx\": 0.01", 400, "malformed"),                    # malformed JSON
        ("[0.01, 0, 0]", 400, "object"),                        # not an object
        ("{\"vx\": NaN}", 400, "malformed"),                    # NaN is not JSON
        ("{\"vx\": \"fast\"}", 400, "number"),                  # non-numeric
        ("{\"vx\": 1e400}", 400, ""),                           # overflows to inf
        ("{\"vx\": 1e300}", 400, "limit"),                      # huge
        ("{\"vx\": 0.5}", 400, "limit"),                        # out of range
        ("{\"speed\": 0.01}", 400, "unknown key"),              # unknown key
        ("{\"vx\": " + "1" * 200_000 + "}", 413, ""),           # 200 kB body
    ]
    for body, code, message in bad:
        status, reply = dashboard.request("/api/command", body)
        assert status == code, (body[:40], status, reply[:200])
        if message:
            assert message in json.loads(reply)["message"], reply
    assert dashboard.request("/api/nothing")[0] == 404
    s = dashboard.wait(lambda s: s["ticks"] >= 3)
    assert s["command"] == [0.01, 0.0, 0.02]  # unchanged by all of the above
    assert dashboard.process.poll() is None  # the server survived


def test_200_concurrent_state_requests_are_all_answered(dashboard):
    def get(_):
        status, body = dashboard.request("/api/state", timeout=30)
        return status, json.loads(body)["time"]
    with concurrent.futures.ThreadPoolExecutor(max_workers=200) as pool:
        results = list(pool.map(get, range(200)))
    assert all(status == 200 for status, _ in results)
    assert dashboard.process.poll() is None


def test_events_stream_states(dashboard):
    import urllib.request
    with urllib.request.urlopen(dashboard.url + "/api/events", timeout=10) as stream:
        assert stream.headers["Content-Type"].startswith("text/event-stream")
        times = []
        while len(times) < 3:
            line = stream.readline().decode()
            if line.startswith("data: "):
                times.append(json.loads(line[6:])["time"])
    assert times == sorted(times) and times[-1] > times[0]


def test_camera_images_are_jpegs(dashboard):
    status, rgb = dashboard.request("/api/camera/rgb.jpg")
    assert status == 200 and rgb[:2] == b"\xff\xd8"  # JPEG's start of image
    status, depth = dashboard.request("/api/camera/depth.jpg")
    assert status == 200 and depth[:2] == b"\xff\xd8"


def test_training_logs_are_served_live(training_dashboard, training_run):
    from conftest import ppo_row
    status, body = training_dashboard.request("/api/training")
    reply = json.loads(body)
    assert status == 200 and reply["enabled"]
    files = {f["name"]: f for f in reply["files"]}
    log = files["learning_nmpc.csv"]
    assert log["columns"][:3] == ["epoch", "steps", "mean_reward"] and len(log["rows"]) == 5
    assert log["rows"][-1][2] == -0.5  # mean_reward of epoch 5
    assert files["notes.csv"]["rows"] == []  # text rows are left out
    with open(training_run / "learning_nmpc.csv", "a") as f:  # the run goes on
        f.write(ppo_row(6))
    rows = json.loads(training_dashboard.request("/api/training")[1])["files"]
    assert [len(f["rows"]) for f in rows if f["name"] == "learning_nmpc.csv"] == [6]


def test_without_a_training_folder_the_view_is_off(dashboard):
    status, body = dashboard.request("/api/training")
    assert status == 200 and json.loads(body)["enabled"] is False


def test_the_camera_finds_the_chair_of_the_obstacle_room():
    from conftest import Dashboard
    d = Dashboard(["--speed", "4", "--scene", "obstacle", "--seed", "3"])
    try:
        s = d.wait(lambda s: s.get("ticks", 0) >= 1)
        chair = s["obstacles"][0]  # the room's chair, an NMPC obstacle (x, y, radius, margin)
        seen = s["seen_obstacles"]
        assert seen, "nothing found in the depth image"
        nearest = min(seen, key=lambda o: (o[0] - chair[0]) ** 2 + (o[1] - chair[1]) ** 2)
        assert abs(nearest[0] - chair[0]) < 0.1 and abs(nearest[1] - chair[1]) < 0.1, (nearest, chair)
        assert abs(nearest[2] - chair[2]) < 0.1
    finally:
        assert d.stop() == 0


def test_the_unitree_g1_walks_forward_from_the_page():
    """--robot unitree_g1: the torque-driven G1 (23 joints, no chest cameras) stands, walks
    forward on a command, and the camera endpoint says why it has no image."""
    from conftest import Dashboard
    d = Dashboard(["--robot", "unitree_g1", "--speed", "4"])
    try:
        start = d.wait(lambda s: s.get("ticks", 0) >= 1, timeout=60)
        assert start["status"] == "ok" and start["max_command"][0] > 0.1
        assert d.request("/api/command", json.dumps({"vx": 0.1}))[0] == 200
        walked = d.wait(lambda s: s["com"][0] > start["com"][0] + 0.1, timeout=90)
        assert walked["status"] == "ok" and walked["command"] == [0.1, 0.0, 0.0]
        assert abs(walked["heading"]) < 0.2  # forward, not turning away
        status, body = d.request("/api/camera/rgb.jpg")
        assert status == 503 and json.loads(body)["message"], body  # no cameras, and why
    finally:
        assert d.stop() == 0, d.process.stdout.read()
