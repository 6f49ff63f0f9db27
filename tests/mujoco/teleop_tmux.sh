#!/usr/bin/env bash
# Drives examples/teleop through a real terminal (tmux) with keys, as a user would:
#   teleop_tmux.sh <teleop binary> <output folder> [demonstrations]
# Walks forward (Up x4 = 0.020 m/s), turns left (Left x2 = 0.030 rad/s), stops (space) and quits
# (q); then checks the screen, the recorded commands and the summary.
# With "demonstrations": in the room "straight" (seed 5), records demonstrations into
# <output folder>/demonstrations while walking forward (Up x4) for at least 10 NMPC ticks, quits,
# and checks index.txt: at least 10 frames, their rgb/ and disparity/ images exist, v_x > 0.
set -euo pipefail
bin=$1
out=$2
mode=${3:-keys}
[ "$mode" = keys ] || [ "$mode" = demonstrations ] || { echo "teleop_tmux: unknown mode '$mode'"; exit 2; }
demos="$out/demonstrations"
mkdir -p "$out"
rm -rf "$out/teleop.csv" "$out/teleop_summary.txt" "$demos"  # the recorder would append
room_args=()
[ "$mode" = demonstrations ] && room_args=(--room straight --seed 5 --demonstrations "'$demos'")
command -v tmux >/dev/null || { echo "teleop_tmux: tmux is not installed (scripts/setup.sh installs it)"; exit 1; }
socket="walkgen_teleop_$$"
session=teleop
cleanup() { tmux -L "$socket" kill-server 2>/dev/null || true; }
trap cleanup EXIT
fail() { echo "teleop_tmux: FAILED: $*"; echo "--- screen:"; tmux -L "$socket" capture-pane -p -t "$session" 2>/dev/null || true; exit 1; }

tmux -L "$socket" new-session -d -s "$session" -x 120 -y 30 \
  "'$bin' --speed 10 ${room_args[*]:-} --record '$out/teleop.csv' --summary '$out/teleop_summary.txt' --max-time 600; sleep 30"
wait_for() {  # wait_for <pattern> <seconds>: the screen shows the pattern
  for _ in $(seq 1 $(( $2 * 10 ))); do
    if tmux -L "$socket" capture-pane -p -t "$session" | grep -q -- "$1"; then return 0; fi
    sleep 0.1
  done
  fail "the screen never showed '$1'"
}
quit_and_summary() {
  tmux -L "$socket" send-keys -t "$session" q
  for _ in $(seq 1 100); do [ -s "$out/teleop_summary.txt" ] && break; sleep 0.1; done
  [ -s "$out/teleop_summary.txt" ] || fail "teleop wrote no summary after q"
  cat "$out/teleop_summary.txt"
}
wait_for "recorded" 60
tmux -L "$socket" send-keys -t "$session" Up Up Up Up

if [ "$mode" = demonstrations ]; then
  frames() { local n; n=$(grep -vc '^#' "$demos/index.txt" 2>/dev/null) || true; echo "${n:-0}"; }
  wait_for "v_x +0.020" 10
  start=$(frames)
  for _ in $(seq 1 600); do  # at least 10 frames after the keys (4 s simulated)
    [ "$(frames)" -ge $(( start + 10 )) ] && break
    sleep 0.1
  done
  quit_and_summary
  /usr/bin/env python3 - "$demos" "$out/teleop_summary.txt" <<'PY'
import os, sys
folder = sys.argv[1]
summary = dict(line.strip().split("=", 1) for line in open(sys.argv[2]) if "=" in line)
def fail(msg):
    sys.exit("teleop_tmux demonstrations: FAILED: " + msg)
if summary["status"] != "ok":
    fail("status " + summary["status"])
rows = [l.split() for l in open(os.path.join(folder, "index.txt")) if l.strip() and l[0] != "#"]
if len(rows) < 10:
    fail("%d frames in index.txt, expected at least 10" % len(rows))
for r in rows:
    if len(r) != 7 or not r[0].startswith("rgb/") or not r[1].startswith("disparity/"):
        fail("malformed line: %s" % " ".join(r))
    if r[2] != "straight_5_teleop":
        fail("episode %s, expected straight_5_teleop" % r[2])
    for f in r[:2]:
        path = os.path.join(folder, f)
        if not os.path.isfile(path) or os.path.getsize(path) == 0:
            fail("missing or empty %s" % f)
vx = [float(r[4]) for r in rows]
if not max(vx) > 0.0:
    fail("no recorded command with v_x > 0")
if int(summary["frames"]) != len(rows):
    fail("the summary says %s frames, index.txt has %d" % (summary["frames"], len(rows)))
print("teleop_tmux demonstrations: %d frames recorded, max v_x %.3f m/s, target %.2f m away"
      % (len(rows), max(vx), float(summary["target_distance"])))
PY
  exit 0
fi

wait_for "v_x +0.020" 10
sleep 2   # 20 s simulated: about 0.4 m forward
tmux -L "$socket" send-keys -t "$session" Left Left
wait_for "omega +0.030" 10
sleep 2
tmux -L "$socket" send-keys -t "$session" Space
wait_for "v_x +0.000" 10
sleep 1
quit_and_summary

/usr/bin/env python3 - "$out/teleop.csv" "$out/teleop_summary.txt" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
summary = dict(line.strip().split("=", 1) for line in open(sys.argv[2]) if "=" in line)
def fail(msg):
    sys.exit("teleop_tmux: FAILED: " + msg)
if summary["status"] != "ok":
    fail("status " + summary["status"])
vx = [float(r["v_x"]) for r in rows]
om = [float(r["omega"]) for r in rows]
keys = [r["key"] for r in rows if r["key"]]
times = [float(r["sim_time"]) for r in rows]
if any(b <= a for a, b in zip(times, times[1:])):
    fail("timestamps do not increase")
if abs(max(vx) - 0.020) > 1e-9:
    fail("v_x never reached 4 steps of 0.005: max %g" % max(vx))
if abs(max(om) - 0.030) > 1e-9:
    fail("omega never reached 2 steps of 0.015: max %g" % max(om))
if vx[-1] != 0.0 or om[-1] != 0.0:
    fail("space did not stop the robot: last command %g %g" % (vx[-1], om[-1]))
if "up" not in " ".join(keys) or "left" not in " ".join(keys) or "stop" not in keys:
    fail("keys not recorded: %s" % keys)
x, y, heading = (float(summary[k]) for k in ("x", "y", "heading"))
if not x > 0.15:
    fail("the robot did not walk forward: x = %g" % x)
if not heading > 0.05:
    fail("the robot did not turn left: heading = %g" % heading)
print("teleop_tmux: %d ticks recorded, keys %s; walked to (%.2f, %.2f), heading %.2f rad"
      % (len(rows), keys, x, y, heading))
PY
