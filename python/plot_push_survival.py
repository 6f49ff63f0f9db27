#!/usr/bin/python3
"""Survival map of a push sweep (examples/push_recovery): one panel per kick direction, gait
phases as rows, velocity changes as columns, green where the robot stayed up and red where it
fell. Writes push_survival.png beside the CSV (through a temporary file, then a rename).

    /usr/bin/python3 python/plot_push_survival.py OUT/push_summary.csv
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

DIRECTIONS = ["forward", "backward", "left", "right"]
PHASES = ["ss_start", "ss_middle", "ss_end", "ds"]
COLUMNS = ["robot", "direction", "phase", "delta_v", "survived"]


def read(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames != COLUMNS:
            raise SystemExit("plot_push_survival: %s: expected the columns %s, got %s"
                             % (path, ",".join(COLUMNS), reader.fieldnames))
        rows = []
        for n, r in enumerate(reader, start=2):
            try:
                rows.append((r["robot"], r["direction"], r["phase"], float(r["delta_v"]),
                             int(r["survived"])))
            except ValueError as e:
                raise SystemExit("plot_push_survival: %s:%d: %s" % (path, n, e))
    if not rows:
        raise SystemExit("plot_push_survival: %s has no kicks" % path)
    return rows


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) == 2 else 2
    path = sys.argv[1]
    rows = read(path)
    robot = rows[0][0]
    dvs = sorted({r[3] for r in rows})
    directions = [d for d in DIRECTIONS if any(r[1] == d for r in rows)]
    phases = [p for p in PHASES if any(r[2] == p for r in rows)]
    fig, axes = plt.subplots(1, len(directions), figsize=(3.2 * len(directions) + 1, 3.2),
                             sharey=True, squeeze=False)
    cmap = ListedColormap(["#d62728", "#2ca02c", "#dddddd"])  # fell, survived, not run
    for ax, d in zip(axes[0], directions):
        grid = [[2] * len(dvs) for _ in phases]
        for _, rd, rp, dv, ok in rows:
            if rd == d and rp in phases:
                grid[phases.index(rp)][dvs.index(dv)] = ok
        ax.imshow(grid, cmap=cmap, vmin=0, vmax=2, aspect="auto")
        ax.set_title(d)
        ax.set_xticks(range(len(dvs)))
        ax.set_xticklabels(["%.2f" % v for v in dvs], rotation=90, fontsize=7)
        ax.set_xlabel("velocity change [m/s]")
        ax.set_yticks(range(len(phases)))
        ax.set_yticklabels(phases)
    fig.suptitle("%s: kicks of 0.1 s while walking (green: stays up, red: falls)" % robot)
    fig.tight_layout()
    out = os.path.join(os.path.dirname(os.path.abspath(path)), "push_survival.png")
    temp = out + ".tmp.png"
    fig.savefig(temp, dpi=110)
    os.replace(temp, out)
    print("plot_push_survival: wrote %s" % out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
