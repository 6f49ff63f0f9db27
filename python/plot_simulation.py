#!/usr/bin/python3
"""Plots of the simulated §9.2 tasks (examples/walking_simulation), like thesis figures 9.4-9.7.

    /usr/bin/python3 python/plot_simulation.py DIR

For every DIR/<task>.csv: DIR/<task>.png with (a), the main panel, the path from above (true
CoM, planned CoM, measured ZMP, start, target, obstacle with its margin; legend below the data),
(b) desired (NMPC) vs measured ZMP over time, (c) histograms of the velocity commands v_x and
omega_z. When DIR/<task>_frames/ holds frames frame_<time>s.ppm (walking_simulation --video
built without OpenCV): DIR/<task>_frames.png, those frames side by side.
"""
import csv
import glob
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]} if rows else {}


def read_ppm(path):
    with open(path, "rb") as f:
        data = f.read()
    # P6, width, height, maxval, then exactly one whitespace byte before the pixels (which may
    # themselves start with bytes that look like whitespace)
    header = re.match(rb"P6\s+(\d+)\s+(\d+)\s+\d+\s", data)
    if header is None:
        raise ValueError(f"{path}: not a binary PPM (P6) file")
    width, height = int(header.group(1)), int(header.group(2))
    pixels = data[header.end() : header.end() + width * height * 3]
    return np.frombuffer(pixels, dtype=np.uint8).reshape(height, width, 3)


def path_panel(ax, d, valid, scene, task):
    """The walk from above: the main panel, its legend below the data."""
    ax.plot(d["zmp_true_x"][valid], d["zmp_true_y"][valid], ".", ms=1.5, color="0.72",
            label="measured ZMP (true sensor poses)")
    ax.plot(d["com_plan_x"], d["com_plan_y"], "-", lw=1.4, color="tab:blue", label="planned CoM")
    ax.plot(d["com_true_x"], d["com_true_y"], "--", lw=1.4, color="tab:green", label="true CoM")
    ax.plot(d["com_true_x"][:1], d["com_true_y"][:1], "o", ms=7, color="black", label="start")
    for item in scene:
        x, y, r, m = (float(item[k]) for k in ("x", "y", "radius", "margin"))
        if item["kind"] == "target":
            ax.add_patch(plt.Circle((x, y), r, color="tab:red", zorder=5, label="target"))
            ax.add_patch(plt.Circle((x, y), 0.25, fill=False, ls=":", lw=1.5, color="tab:red",
                                    zorder=5, label="reached within 0.25 m"))
        else:
            ax.add_patch(plt.Circle((x, y), r, color="tab:brown", alpha=0.6, zorder=4,
                                    label="obstacle"))
            ax.add_patch(plt.Circle((x, y), r + m, fill=False, ls="--", color="tab:brown",
                                    zorder=4, label="obstacle + margin"))
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.08)
    ax.grid(True, lw=0.4, alpha=0.5)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("(a) path of %s, from above" % task)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.09), ncol=3, fontsize=9,
              frameon=False)


def plot_task(directory, task):
    d = read_csv(os.path.join(directory, task + ".csv"))
    if not d:
        return
    scene_path = os.path.join(directory, task + "_scene.csv")
    scene = list(csv.DictReader(open(scene_path))) if os.path.exists(scene_path) else []
    valid = d["zmp_valid"] > 0.5
    fig = plt.figure(figsize=(16, 8.5), layout="constrained")
    grid = fig.add_gridspec(3, 5, width_ratios=(1, 1, 1, 0.8, 0.8))
    path_panel(fig.add_subplot(grid[:, :3]), d, valid, scene, task)

    for row, axis in enumerate(("x", "y")):
        ax = fig.add_subplot(grid[row, 3:])
        ax.plot(d["time"], d["zmp_plan_" + axis], lw=1.0, label="NMPC ZMP")
        measured = np.where(valid, d["zmp_measured_" + axis], np.nan)
        ax.plot(d["time"], measured, lw=0.7, alpha=0.8, label="measured ZMP (foot forces)")
        ax.set_ylabel("ZMP %s [m]" % axis)
        if row == 0:
            distance = np.hypot(d["zmp_measured_x"] - d["zmp_plan_x"],
                                d["zmp_measured_y"] - d["zmp_plan_y"])[valid]
            ax.set_title("(b) desired vs measured ZMP: %.2f ± %.2f cm apart"
                         % (100 * distance.mean(), 100 * distance.std()))
            ax.legend(fontsize=9, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2,
                      frameon=False)
        else:
            ax.set_xlabel("time [s]")

    for col, (key, label, width) in enumerate((("v_x", "v_x [m/s]", 0.002),
                                               ("omega", "omega_z [rad/s]", 0.005))):
        ax = fig.add_subplot(grid[2, 3 + col])
        values = d[key]
        lo, hi = min(values.min(), -width), max(values.max(), width)
        bins = np.arange(np.floor(lo / width) * width, hi + 2 * width, width)
        ax.hist(values, bins=bins, color="tab:purple")
        ax.set_xlabel(label)
        ax.set_ylabel("samples" if col == 0 else "")
        ax.set_title("(c) velocity commands" if col == 0 else "")
    fig.savefig(os.path.join(directory, task + ".png"), dpi=110)
    plt.close(fig)

    # Without OpenCV, walking_simulation --video leaves six frames as
    # <task>_frames/frame_<time>s.ppm; with it, it writes <task>_frames.png itself.
    frames = sorted(glob.glob(os.path.join(directory, task + "_frames", "frame_*s.ppm")))
    if frames:
        fig, axes = plt.subplots(1, len(frames), figsize=(3.2 * len(frames), 2.2),
                                 layout="constrained", squeeze=False)
        for ax, path in zip(axes[0], frames):
            ax.imshow(read_ppm(path))
            ax.set_title("t = %.1f s" % float(os.path.basename(path)[6:-5]), fontsize=10)
            ax.axis("off")
        fig.savefig(os.path.join(directory, task + "_frames.png"), dpi=150)
        plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_simulation.py DIR")
    directory = sys.argv[1]
    tasks = [os.path.basename(p)[:-4] for p in sorted(glob.glob(os.path.join(directory, "*.csv")))]
    tasks = [t for t in tasks if not t.endswith("_scene") and t != "simulation_summary"
             and os.path.exists(os.path.join(directory, t + "_scene.csv"))]
    for task in tasks:
        plot_task(directory, task)
        print("plot_simulation: wrote %s.png" % os.path.join(directory, task))


if __name__ == "__main__":
    main()
