#!/usr/bin/env bash
# Drives examples/teleop through a real terminal (tmux) with keys, as a user would:
#   teleop_tmux.sh <teleop binary> <output folder>
# Walks forward (Up x4 = 0.020 m/s), turns left (Left x2 = 0.030 rad/s), stops (space) and quits
# (q); then checks the screen, the recorded commands and the summary.
set -euo pipefail
bin=$1
out=$2
mkdir -p "$out"
rm -f "$out/teleop.csv" "$out/teleop_summary.txt"
command -v tmux >/dev/null || { echo "teleop_tmux: tmux is not installed (scripts/setup.sh installs it)"; exit 1; }
socket="walkgen_teleop_$$"
session=teleop
cleanup() { tmux -L "$socket" kill-server 2>/dev/null || true; }
trap cleanup EXIT
fail() { echo "teleop_tmux: FAILED: $*"; echo "--- screen:"; tmux -L "$socket" capture-pane -p -t "$session" 2>/dev/null || true; exit 1; }

tmux -L "$socket" new-session -d -s "$session" -x 120 -y 30 \
  "'$bin' --speed 10 --record '$out/teleop.csv' --summary '$out/teleop_summary.txt' --max-time 600; sleep 30"
wait_for() {  # wait_for <pattern> <seconds>: the screen shows the pattern
  for _ in $(seq 1 $(( $2 * 10 ))); do
    if tmux -L "$socket" capture-pane -p -t "$session" | grep -q -- "$1"; then return 0; fi
    sleep 0.1
  done
  fail "the screen never showed '$1'"
}
wait_for "recorded" 60
tmux -L "$socket" send-keys -t "$session" Up Up Up Up
wait_for "v_x +0.020" 10
sleep 2   # 20 s simulated: about 0.4 m forward
tmux -L "$socket" send-keys -t "$session" Left Left
wait_for "omega +0.030" 10
sleep 2
tmux -L "$socket" send-keys -t "$session" Space
wait_for "v_x +0.000" 10
sleep 1
tmux -L "$socket" send-keys -t "$session" q
for _ in $(seq 1 100); do [ -s "$out/teleop_summary.txt" ] && break; sleep 0.1; done
[ -s "$out/teleop_summary.txt" ] || fail "teleop wrote no summary after q"
cat "$out/teleop_summary.txt"

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
