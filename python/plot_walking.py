#!/usr/bin/python3
"""Plots one walk written by examples/walking_scenarios (thesis §9.1, figures 9.1-9.3).

Reads BASE.csv (trajectory, thesis column order), BASE_footsteps.csv (time,foot,x,y,q) and
BASE_meta.csv (key,value) and writes BASE.png: a top view of the CoM and ZMP paths, every landed
footstep (sole rectangle, left blue / right red, with its shrunk ZMP area dashed) and the
obstacles (filled circle, dashed margin circle); beside it the CoM velocity over time.

usage: /usr/bin/python3 python/plot_walking.py DIR/NAME
"""
import csv
import math
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Polygon
except ImportError as e:
    sys.stderr.write(f"error: plot_walking.py needs matplotlib ({e}); "
                     "install it with: apt-get install python3-matplotlib\n")
    sys.exit(3)

COLORS = {"left": "tab:blue", "right": "tab:red"}


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError(f"{path} has no data rows")
    return rows


def rectangle(x, y, yaw, length, width):
    c, s = math.cos(yaw), math.sin(yaw)
    return [(x + c * dx - s * dy, y + s * dx + c * dy)
            for dx, dy in ((length / 2, width / 2), (-length / 2, width / 2),
                           (-length / 2, -width / 2), (length / 2, -width / 2))]


def read_meta(path):
    meta = {}
    for r in read_rows(path):
        meta.setdefault(r["key"], []).append(float(r["value"]))
    return meta


def main(argv):
    if len(argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    base = argv[1]
    name = os.path.basename(base)
    try:
        traj = read_rows(base + ".csv")
        steps = read_rows(base + "_footsteps.csv")
        meta = read_meta(base + "_meta.csv")
    except (OSError, ValueError, KeyError) as e:
        sys.stderr.write(f"error: {e}\n")
        return 1
    col = {k: [float(r[k]) for r in traj] for k in
           ("com_x", "com_y", "com_dx", "com_dy", "zmp_x", "zmp_y")}
    length, width = meta["foot_length"][0], meta["foot_width"][0]
    margin_x, margin_y = meta["security_margin_x"][0], meta["security_margin_y"][0]
    period = meta["command_period"][0]

    fig, (ax, av) = plt.subplots(1, 2, figsize=(14, 6), gridspec_kw={"width_ratios": [3, 2]})
    for ox, oy, r, m in zip(meta.get("obstacle_x", []), meta.get("obstacle_y", []),
                            meta.get("obstacle_radius", []), meta.get("obstacle_margin", [])):
        ax.add_patch(Circle((ox, oy), r, color="0.85", lw=0, label="obstacle"))
        ax.add_patch(Circle((ox, oy), r + m, fill=False, ls="--", color="0.4", lw=0.8,
                            label="obstacle + margin"))
    for s in steps:
        x, y, q, color = float(s["x"]), float(s["y"]), float(s["q"]), COLORS[s["foot"]]
        ax.add_patch(Polygon(rectangle(x, y, q, length, width), closed=True, fill=False,
                             color=color, lw=0.8))
        ax.add_patch(Polygon(rectangle(x, y, q, length - 2 * margin_x, width - 2 * margin_y),
                             closed=True, fill=False, color=color, lw=0.5, ls="--"))
    ax.plot(col["com_x"], col["com_y"], "k-", lw=1.5, label="CoM")
    ax.plot(col["zmp_x"], col["zmp_y"], "g-", lw=0.8, label="ZMP")
    ax.plot([], [], color=COLORS["left"], lw=0.8, label="left foot")
    ax.plot([], [], color=COLORS["right"], lw=0.8, label="right foot")
    ax.plot([], [], color="0.3", lw=0.5, ls="--", label="ZMP area (shrunk sole)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{name}: {len(steps) - 2} steps, HRP-2 preset (top view)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(True, lw=0.3)

    t = [i * period for i in range(len(traj))]
    av.plot(t, col["com_dx"], "b-", lw=1, label="CoM dx/dt")
    av.plot(t, col["com_dy"], "r-", lw=1, label="CoM dy/dt")
    av.set_xlabel("t [s]")
    av.set_ylabel("velocity [m/s] (world frame)")
    av.set_title(f"{name}: CoM velocity")
    av.legend(loc="best", fontsize=8)
    av.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(base + ".png", dpi=110)
    plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
