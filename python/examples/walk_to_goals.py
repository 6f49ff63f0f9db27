#!/usr/bin/python3
"""The NMPC goal environment from Python (walkgen.envs, Gymnasium API shape): a hand-written
policy (walk forward, turn towards the goal) steers the HRP-2 NMPC to random goals with an
obstacle in the way, in N environments stepped at once in C++ threads; prints the success rate
and plots the walked paths (docs/python.md, "Learning environments").

    PYTHONPATH=build/release/python /usr/bin/python3 python/examples/walk_to_goals.py --out goals.png
"""

import argparse
import sys

import numpy as np

from walkgen import envs


def heading_policy(obs):
    """(N, obs) -> (N, 2): full speed when the goal is ahead, slow while turning towards it."""
    bearing = np.arctan2(obs[:, 1], obs[:, 0])
    forward = np.where(np.abs(bearing) < 0.6, 1.0, 0.2)
    return np.stack([forward, np.clip(2.0 * bearing, -1.0, 1.0)], axis=1).astype(np.float32)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--episodes", type=int, default=16, help="episodes in all (default 16)")
    parser.add_argument("--envs", type=int, default=4, help="environments stepped at once")
    parser.add_argument("--threads", type=int, default=0, help="C++ threads (0: one per core)")
    parser.add_argument("--obstacles", type=int, default=1, help="obstacles per episode")
    parser.add_argument("--seed", type=int, default=0, help="seed of the tasks")
    parser.add_argument("--out", default="", help="PNG of the walked paths (optional)")
    args = parser.parse_args()
    if args.episodes < 1 or args.envs < 1 or args.threads < 0 or args.obstacles < 0:
        parser.error("--episodes and --envs must be >= 1, --threads and --obstacles >= 0")

    vec = envs.NmpcGoalVectorEnv(args.envs, seed=args.seed, threads=args.threads,
                                 obstacles=args.obstacles)
    print(f"{vec.num_envs} environments on {vec.threads} threads; observation "
          f"{vec.single_observation_space.shape}, action {vec.single_action_space.shape}")
    obs, _ = vec.reset(seed=args.seed)
    # Each environment's current path (every episode starts at the preset's initial CoM,
    # facing +x), with the goal and the obstacles of its episode.
    def task(i):
        env = vec.env(i)
        return {"path": [env.position], "goal": env.goal, "obstacles": list(env.obstacles)}
    current = [task(i) for i in range(vec.num_envs)]
    finished, ends, reported = [], {}, 0
    while len(finished) < args.episodes:
        obs, _, terminated, truncated, info = vec.step(heading_policy(obs))
        for i in range(vec.num_envs):
            if terminated[i] or truncated[i]:
                if len(finished) < args.episodes:
                    current[i]["end"] = info["end"][i]
                    finished.append(current[i])
                    ends[info["end"][i]] = ends.get(info["end"][i], 0) + 1
                current[i] = task(i)
            else:
                current[i]["path"].append(vec.env(i).position)
        if len(finished) != reported:  # progress, on the terminal's line
            reported = len(finished)
            print(f"\repisodes {reported}/{args.episodes}", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    summary = ", ".join(f"{k} {v}" for k, v in sorted(ends.items()))
    print(f"{args.episodes} episodes: {summary}; success rate "
          f"{ends.get('success', 0) / args.episodes:.2f}")

    if args.out:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from walkgen.plots import save_figure
        fig, ax = plt.subplots(figsize=(6, 6))
        colours = {"success": "tab:green", "failure": "tab:red", "truncated": "tab:orange"}
        for episode in finished:
            path = np.array(episode["path"])
            colour = colours.get(episode["end"], "k")
            ax.plot(path[:, 0], path[:, 1], color=colour, lw=1)
            ax.plot(*episode["goal"], "*", color=colour, ms=10)
            for o in episode["obstacles"]:
                ax.add_patch(plt.Circle((o.x, o.y), o.radius, color="grey", alpha=0.4))
        for end, colour in colours.items():
            ax.plot([], [], color=colour, label=end)
        ax.plot(*finished[0]["path"][0], "ko", label="start")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_aspect("equal")
        ax.legend(loc="best")
        ax.set_title("NMPC goal environment, heading policy")
        fig.tight_layout()
        save_figure(fig, args.out)  # atomically: a temporary file, then renamed
        print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
