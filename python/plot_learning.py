#!/usr/bin/python3
"""Plots of examples/ppo_train (thesis figures 11.17-11.19).

usage: plot_learning.py OUT_DIR ENV      ENV: benchmark, nmpc or nmpc_obstacles

Reads OUT_DIR/learning_ENV.csv (one row per epoch) and OUT_DIR/trajectories_ENV.csv, writes
OUT_DIR/learning_ENV.png (mean reward per step and the policy's sigma over the epochs, figure
11.17) and OUT_DIR/learning_ENV_trajectories.png (test-mode paths: figure 11.18 for the
benchmark, the CoM paths and footsteps of four goals for the NMPC, figure 11.19).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    out, env = sys.argv[1], sys.argv[2]
    rows = read(os.path.join(out, "learning_%s.csv" % env))
    if rows:
        epoch = [int(r["epoch"]) for r in rows]
        fig, ax = plt.subplots(1, 2, figsize=(10, 3.6))
        ax[0].plot(epoch, [float(r["mean_reward"]) for r in rows], "b-")
        ax[0].set_xlabel("epoch")
        ax[0].set_ylabel("mean reward per step")
        ax[0].set_title("(a) reward")
        ax2 = ax[0].twinx()
        ax2.plot(epoch, [int(r["wins"]) for r in rows], "g:", label="wins")
        ax2.plot(epoch, [int(r["losses"]) for r in rows], "r:", label="losses")
        ax2.set_ylabel("episodes per epoch")
        ax2.legend(loc="lower right")
        ax[1].plot(epoch, [float(r["std"]) for r in rows], "k-")
        ax[1].set_xlabel("epoch")
        ax[1].set_ylabel("policy standard deviation σ")
        ax[1].set_title("(b) exploration")
        fig.suptitle("PPO on the %s environment" % env)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "learning_%s.png" % env), dpi=110)
        plt.close(fig)

    traj_path = os.path.join(out, "trajectories_%s.csv" % env)
    if not os.path.exists(traj_path):
        return
    traj = read(traj_path)
    if env == "benchmark":
        fig, ax = plt.subplots(figsize=(5, 5))
        episodes = sorted({int(r["episode"]) for r in traj})
        for e in episodes:
            pts = [r for r in traj if int(r["episode"]) == e]
            ax.plot([0] + [float(r["agent_x"]) for r in pts],
                    [0] + [float(r["agent_y"]) for r in pts], "-", lw=1)
            ax.plot(float(pts[0]["goal_x"]), float(pts[0]["goal_y"]), "ro", ms=5)
        ax.plot(0, 0, "ks")
        ax.set_xlim(-6, 6)
        ax.set_ylim(-6, 6)
        ax.set_aspect("equal")
        ax.set_title("test mode (policy mean), %d episodes" % len(episodes))
    else:
        obstacles = []
        obst_path = os.path.join(out, "obstacles_%s.csv" % env)
        if os.path.exists(obst_path):
            obstacles = read(obst_path)
        fig, axes = plt.subplots(1, 4, figsize=(14, 3.8))
        for c, ax in enumerate(axes):
            pts = [r for r in traj if int(r["case"]) == c]
            if not pts:
                continue
            for o in obstacles:
                if int(o["case"]) != c:
                    continue
                x, y, rad, m = (float(o[k]) for k in ("x", "y", "radius", "margin"))
                ax.add_patch(plt.Circle((x, y), rad, color="0.4"))
                ax.add_patch(plt.Circle((x, y), rad + m, color="0.4", fill=False, ls="--"))
            ax.plot([float(r["com_x"]) for r in pts], [float(r["com_y"]) for r in pts], "b-",
                    label="CoM")
            feet = []
            for r in pts:
                f = (round(float(r["foot_x"]), 4), round(float(r["foot_y"]), 4))
                if not feet or feet[-1] != f:
                    feet.append(f)
            ax.plot([f[0] for f in feet], [f[1] for f in feet], "k.", ms=4, label="footsteps")
            gx, gy = float(pts[0]["goal_x"]), float(pts[0]["goal_y"])
            ax.add_patch(plt.Circle((gx, gy), 0.2, color="r", alpha=0.3))
            ax.plot(gx, gy, "r*", ms=10, label="goal")
            ax.set_aspect("equal")
            ax.set_xlim(-2.0, 2.0)
            ax.set_ylim(-1.8, 1.8)
            ax.set_title("(%s) goal (%.1f, %.1f), %.1f s" % ("abcd"[c], gx, gy,
                                                             float(pts[-1]["tick"])))
            ax.set_xlabel("x [m]")
        axes[0].set_ylabel("y [m]")
        axes[0].legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "learning_%s_trajectories.png" % env), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
