#!/usr/bin/python3
"""Plots examples/bc_evaluate's closed-loop results (thesis §11.1.2): the success rate per task
and, per episode, the mean distance between the NMPC's and the measured ZMP against the entropy
of the network's commands (figure 11.12: does noisier steering cost balance?).

    /usr/bin/python3 python/plot_bc_evaluation.py EVAL.csv [EVAL.csv ...] --out bc_evaluation.png
                                                  [--label NAME ...] [--paths PATHS.png]

Each CSV is one bc_evaluate run (e.g. the network and the scripted expert); --label names them
(default: the folder of the file). Prints the success rate per task and the correlation of ZMP
distance and entropy. --paths draws the walked paths of the first run (bc_paths.csv next to its
bc_evaluation.csv), one panel per task, in the robot's start frame: green reached, red failed,
the targets as circles and the chairs as grey discs.
"""
import argparse
import csv
import os
import sys

import numpy as np


def read(path):
    try:
        rows = list(csv.DictReader(open(path)))
    except OSError as e:
        sys.exit("plot_bc_evaluation: %s" % e)
    need = {"task", "reached", "zmp_distance_mean", "command_entropy"}
    if not rows or not need <= set(rows[0]):
        sys.exit("plot_bc_evaluation: %s: expected bc_evaluate's columns %s" % (path, sorted(need)))
    return rows


def plot_paths(evaluation_csv, rows, out):
    """The paths of one bc_evaluate run, one panel per task (see the module's docstring)."""
    path = os.path.join(os.path.dirname(os.path.abspath(evaluation_csv)), "bc_paths.csv")
    try:
        ticks = list(csv.DictReader(open(path)))
    except OSError as e:
        sys.exit("plot_bc_evaluation: --paths: %s" % e)
    if not ticks or not {"task", "seed", "x", "y"} <= set(ticks[0]):
        sys.exit("plot_bc_evaluation: %s: expected bc_evaluate's path columns" % path)
    if "target_x" not in rows[0]:
        sys.exit("plot_bc_evaluation: %s lacks the target's place (rerun bc_evaluate)"
                 % evaluation_csv)
    walked = {}
    for t in ticks:
        walked.setdefault((t["task"], t["seed"]), []).append((float(t["x"]), float(t["y"])))
    tasks = []
    for r in rows:
        if r["task"] not in tasks:
            tasks.append(r["task"])
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(tasks), figsize=(3.6 * len(tasks), 3.8), squeeze=False)
    for ax, task in zip(axes[0], tasks):
        mine = [r for r in rows if r["task"] == task]
        for r in mine:
            xy = np.array(walked.get((task, r["seed"]), [(0.0, 0.0)]))
            ax.plot(xy[:, 0], xy[:, 1], color="tab:green" if r["reached"] == "1" else "tab:red",
                    lw=0.8, alpha=0.8)
            ax.add_patch(plt.Circle((float(r["target_x"]), float(r["target_y"])), 0.05,
                                    color="tab:orange"))
            if r.get("chair_radius"):
                ax.add_patch(plt.Circle((float(r["chair_x"]), float(r["chair_y"])),
                                        float(r["chair_radius"]), color="grey", alpha=0.4))
        reached = sum(r["reached"] == "1" for r in mine)
        ax.set_title("%s: %d / %d reached" % (task, reached, len(mine)))
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x [m]")
        ax.plot(0.0, 0.0, "k^")
    axes[0][0].set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print("plot_bc_evaluation: wrote %s" % out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", nargs="+")
    parser.add_argument("--out", default="bc_evaluation.png")
    parser.add_argument("--label", action="append", default=[])
    parser.add_argument("--paths", help="also draw the first run's paths into this PNG")
    args = parser.parse_args()
    labels = args.label + [os.path.basename(os.path.dirname(os.path.abspath(p)))
                           for p in args.csv[len(args.label):]]
    runs = [read(p) for p in args.csv]

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (bars, scatter) = plt.subplots(1, 2, figsize=(12, 4.2))
    tasks = []
    for rows in runs:
        for r in rows:
            if r["task"] not in tasks:
                tasks.append(r["task"])
    width = 0.8 / len(runs)
    for k, (label, rows) in enumerate(zip(labels, runs)):
        rates = []
        for t in tasks:
            mine = [r for r in rows if r["task"] == t]
            reached = sum(int(r["reached"]) for r in mine)
            rates.append(100.0 * reached / len(mine) if mine else 0.0)
            if mine:
                print("%-12s %-10s %2d / %2d reached (%.0f %%)" % (label, t, reached, len(mine),
                                                                    rates[-1]))
        x = np.arange(len(tasks)) + (k - (len(runs) - 1) / 2.0) * width
        bars.bar(x, rates, width=width, label=label)
        entropy = np.array([float(r["command_entropy"]) for r in rows])
        zmp = 1e3 * np.array([float(r["zmp_distance_mean"]) for r in rows])
        scatter.scatter(entropy, zmp, s=14, label=label)
        if len(rows) > 2 and entropy.std() > 0 and zmp.std() > 0:
            print("%-12s correlation of ZMP distance and command entropy: %.2f (%d episodes)"
                  % (label, np.corrcoef(entropy, zmp)[0, 1], len(rows)))
    bars.axhline(90.0, color="grey", lw=0.8, ls="--")
    bars.set_xticks(np.arange(len(tasks)))
    bars.set_xticklabels(tasks)
    bars.set_ylabel("reached without collision or fall [%]")
    bars.set_ylim(0, 105)
    bars.legend(fontsize=8)
    scatter.set_xlabel("command entropy [nats] (eq. 9.1)")
    scatter.set_ylabel("mean |ZMP_NMPC - ZMP_measured| [mm]")
    scatter.set_title("figure 11.12: balance against the noise of the commands")
    scatter.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print("plot_bc_evaluation: wrote %s" % args.out)
    if args.paths:
        plot_paths(args.csv[0], runs[0], args.paths)


if __name__ == "__main__":
    main()
