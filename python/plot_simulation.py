#!/usr/bin/python3
"""Plots of the simulated §9.2 tasks (examples/walking_simulation), like thesis figures 9.4-9.7.

    /usr/bin/python3 python/plot_simulation.py DIR

For every DIR/<task>.csv: DIR/<task>.png with (a) the path from above (true CoM, planned CoM,
measured ZMP, target, obstacle with its margin), (b) desired (NMPC) vs measured ZMP over time,
(c) histograms of the velocity commands v_x and omega_z. When DIR/<task>_frames/ holds PPM
frames: DIR/<task>_frames.png, a strip of six of them.
"""
import csv
import glob
import os
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
    parts = data.split(maxsplit=4)  # P6, width, height, maxval, pixels
    width, height = int(parts[1]), int(parts[2])
    pixels = parts[4][: width * height * 3]
    return np.frombuffer(pixels, dtype=np.uint8).reshape(height, width, 3)


def plot_task(directory, task):
    d = read_csv(os.path.join(directory, task + ".csv"))
    if not d:
        return
    scene_path = os.path.join(directory, task + "_scene.csv")
    scene = list(csv.DictReader(open(scene_path))) if os.path.exists(scene_path) else []
    valid = d["zmp_valid"] > 0.5
    fig = plt.figure(figsize=(15, 4.6))
    grid = fig.add_gridspec(2, 4)

    ax = fig.add_subplot(grid[:, 0])
    ax.plot(d["zmp_true_x"][valid], d["zmp_true_y"][valid], ".", ms=0.6, color="0.7",
            label="measured ZMP")
    ax.plot(d["com_plan_x"], d["com_plan_y"], "-", lw=1.0, color="tab:blue", label="planned CoM")
    ax.plot(d["com_true_x"], d["com_true_y"], "--", lw=1.0, color="tab:green", label="true CoM")
    for item in scene:
        x, y, r, m = (float(item[k]) for k in ("x", "y", "radius", "margin"))
        if item["kind"] == "target":
            ax.add_patch(plt.Circle((x, y), r, color="tab:red", label="target"))
            ax.add_patch(plt.Circle((x, y), 0.25, fill=False, ls=":", color="tab:red",
                                    label="0.25 m"))
        else:
            ax.add_patch(plt.Circle((x, y), r, color="tab:brown", alpha=0.6, label="obstacle"))
            ax.add_patch(plt.Circle((x, y), r + m, fill=False, ls="--", color="tab:brown",
                                    label="+ margin"))
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("(a) path of " + task)
    ax.legend(fontsize=7, loc="best")

    for row, axis in enumerate(("x", "y")):
        ax = fig.add_subplot(grid[row, 1:3])
        ax.plot(d["time"], d["zmp_plan_" + axis], lw=1.0, label="NMPC ZMP")
        measured = np.where(valid, d["zmp_measured_" + axis], np.nan)
        ax.plot(d["time"], measured, lw=0.7, alpha=0.8, label="measured ZMP (FT sensors)")
        ax.set_ylabel("ZMP %s [m]" % axis)
        if row == 0:
            distance = np.hypot(d["zmp_measured_x"] - d["zmp_plan_x"],
                                d["zmp_measured_y"] - d["zmp_plan_y"])[valid]
            ax.set_title("(b) desired vs measured ZMP: distance %.2f ± %.2f cm"
                         % (100 * distance.mean(), 100 * distance.std()))
            ax.legend(fontsize=7, loc="upper right")
        else:
            ax.set_xlabel("time [s]")

    for row, (key, label, width) in enumerate((("v_x", "v_x [m/s]", 0.002),
                                               ("omega", "omega_z [rad/s]", 0.005))):
        ax = fig.add_subplot(grid[row, 3])
        values = d[key]
        lo, hi = min(values.min(), -width), max(values.max(), width)
        bins = np.arange(np.floor(lo / width) * width, hi + 2 * width, width)
        ax.hist(values, bins=bins, color="tab:purple")
        ax.set_xlabel(label)
        ax.set_ylabel("samples")
        if row == 0:
            ax.set_title("(c) velocity commands")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, task + ".png"), dpi=110)
    plt.close(fig)

    frames = sorted(glob.glob(os.path.join(directory, task + "_frames", "frame_*.ppm")))
    if frames:
        picks = [frames[int(round(i * (len(frames) - 1) / 5))] for i in range(6)]
        images = [read_ppm(p) for p in picks]
        fig, axes = plt.subplots(1, 6, figsize=(18, 2.6))
        for ax, image, path in zip(axes, images, picks):
            ax.imshow(image)
            index = int(os.path.basename(path)[6:11])
            ax.set_title("t = %.1f s" % (0.4 * (index + 1)), fontsize=9)
            ax.axis("off")
        fig.tight_layout()
        fig.savefig(os.path.join(directory, task + "_frames.png"), dpi=100)
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
