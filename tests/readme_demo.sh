#!/usr/bin/env bash
# ctest "readme_demo": the README's first command in its quick mode, `bash scripts/demo.sh
# --quick` (with --no-setup: a test installs no packages), which configures and builds the
# release tree (up to date when ctest runs) and runs the programs. Passes when the demo exits 0,
# walked the Unitree G1 (its default robot), every file it
# promises exists and is not empty (the task's CSV, PNG, scene and summary; the scenario's PNG),
# and the robot walked toward the target (its true CoM ended at least 0.1 m closer to the target
# than it started, and the summary says "reached").
#   bash tests/readme_demo.sh [OUT_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-${root}/build/release/example_output/readme_demo}"
rm -rf "${out}"

mkdir -p "${out}"
bash "${root}/scripts/demo.sh" --quick --no-setup --out "${out}" 2>&1 | tee "${out}/demo.log"
# The README promises the Unitree G1 by default.
if ! grep -q "^straight (unitree_g1):" "${out}/demo.log"; then
  echo "readme_demo: the demo did not walk the Unitree G1 (no 'straight (unitree_g1):' line)" >&2
  exit 1
fi

sim="${out}/simulation"
missing=0
for f in "${sim}/straight.csv" "${sim}/straight.png" "${sim}/straight_scene.csv" \
  "${sim}/simulation_summary.csv" "${out}/straight.png"; do
  if [ ! -s "${f}" ]; then
    echo "readme_demo: the demo promised ${f}, which is missing or empty" >&2
    missing=$((missing + 1))
  fi
done
[ "${missing}" -eq 0 ] || exit 1

/usr/bin/python3 - "${sim}" <<'PY'
import csv, math, sys
sim = sys.argv[1]
with open(f"{sim}/straight_scene.csv") as f:
    target = next((float(r["x"]), float(r["y"])) for r in csv.DictReader(f) if r["kind"] == "target")
with open(f"{sim}/straight.csv") as f:
    rows = list(csv.DictReader(f))
if len(rows) < 100:
    sys.exit(f"readme_demo: straight.csv has {len(rows)} rows, expected at least 100 (1 s)")
def distance(r):
    return math.hypot(float(r["com_true_x"]) - target[0], float(r["com_true_y"]) - target[1])
start, end = distance(rows[0]), distance(rows[-1])
with open(f"{sim}/simulation_summary.csv") as f:
    summary = {r["task"]: r for r in csv.DictReader(f)}
straight = summary.get("straight", {})
reached = straight.get("reached") == "1"
print(f"readme_demo: true CoM {start:.3f} m from the target at the start, {end:.3f} m at the end "
      f"after {rows[-1]['time']} s; reached: {reached}")
if not start - end >= 0.1:
    sys.exit("readme_demo: the robot did not walk toward the target (expected at least 0.1 m closer)")
if not reached:
    sys.exit("readme_demo: simulation_summary.csv does not say the straight task was reached")
if straight.get("fallen") != "0" or not float(straight.get("mean_speed", "0")) > 0.0:
    sys.exit(f"readme_demo: simulation_summary.csv says fallen={straight.get('fallen')}, "
             f"mean_speed={straight.get('mean_speed')} for the straight task")
PY
echo "readme_demo: passed"
