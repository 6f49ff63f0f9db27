#!/usr/bin/python3
"""Plots the CSV written by examples/qp_walking_sequence: top view of CoM, ZMP and footsteps
(foot rectangles 0.2172 x 0.1380 m at the support foot of each step), and the solve time per tick.

usage: /usr/bin/python3 python/plot_walking_qp.py qp_walking_sequence.csv out.png
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402

FOOT_LENGTH, FOOT_WIDTH = 0.2172, 0.1380


def foot_corners(x, y, yaw):
    c, s = math.cos(yaw), math.sin(yaw)
    pts = []
    for dx, dy in ((1, 1), (-1, 1), (-1, -1), (1, -1)):
        px, py = dx * FOOT_LENGTH / 2, dy * FOOT_WIDTH / 2
        pts.append((x + c * px - s * py, y + s * px + c * py))
    return pts


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    with open(argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.stderr.write(f"error: {argv[1]} has no data rows\n")
        return 1
    col = {k: [float(r[k]) for r in rows] for k in
           ("t", "com_x", "com_y", "zmp_x", "zmp_y", "support_x", "support_y", "support_yaw",
            "left_support", "solve_us", "iterations")}

    fig, (ax, at) = plt.subplots(1, 2, figsize=(13, 5.5), gridspec_kw={"width_ratios": [3, 2]})
    seen = set()
    for x, y, yaw, left in zip(col["support_x"], col["support_y"], col["support_yaw"],
                               col["left_support"]):
        key = (round(x, 6), round(y, 6))
        if key in seen:
            continue
        seen.add(key)
        color = "tab:blue" if left else "tab:red"
        ax.add_patch(Polygon(foot_corners(x, y, yaw), closed=True, fill=False, color=color, lw=1))
    ax.plot(col["com_x"], col["com_y"], "k-", lw=1.5, label="CoM")
    ax.plot(col["zmp_x"], col["zmp_y"], "g.-", lw=0.7, ms=2, label="ZMP")
    ax.plot([], [], color="tab:blue", label="left foot")
    ax.plot([], [], color="tab:red", label="right foot")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("walking-like QP sequence (68 vars, 106 rows)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(True, lw=0.3)

    at.plot(col["t"], col["solve_us"], "b.", ms=3, label="init + warm solve [us]")
    at.set_xlabel("t [s]")
    at.set_ylabel("wall time per tick [us]")
    at.set_yscale("log")
    at2 = at.twinx()
    at2.plot(col["t"], col["iterations"], "r-", lw=0.7, label="active-set changes")
    at2.set_ylabel("active-set changes", color="r")
    at.set_title("per-tick solve (one run, not a benchmark)")
    at.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
