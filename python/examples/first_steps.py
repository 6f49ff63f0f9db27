#!/usr/bin/python3
"""walkgen from Python in a minute: a small QP from NumPy, then the HRP-2 NMPC walking 0.2 m/s
forward for 60 ticks (6 s), with its plan plotted (docs/python.md walks through it).

    PYTHONPATH=build/release/python /usr/bin/python3 python/examples/first_steps.py --out plan.png
"""

import argparse
import sys

import numpy as np

import walkgen


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ticks", type=int, default=60, help="NMPC ticks of 0.1 s (default 60)")
    parser.add_argument("--speed", type=float, default=0.2, help="forward command [m/s]")
    parser.add_argument("--out", default="", help="PNG of the CoM, ZMP and footsteps (optional)")
    args = parser.parse_args()
    if args.ticks < 1:
        parser.error("--ticks must be >= 1")

    # 1. A QP: min ½|x|² - x0  s.t.  x0 + x1 <= 0.5.
    qp = walkgen.DenseQp(2, 1)
    r = qp.solve(np.eye(2), [-1.0, 0.0], [[1.0, 1.0]], [-np.inf], [0.5])
    print(f"QP: {r.status}, x = {r.x}, multiplier {r.y[0]:.3f}")

    # 2. The walking pattern generator.
    mpc = walkgen.WalkingMpc(walkgen.WalkingSettings.hrp2())
    print(f"command: {mpc.set_command(args.speed)}")
    com, zmp, feet = [], [], []
    for tick in range(args.ticks):
        result = mpc.solve()
        if not result.ok:
            print(f"tick {tick}: {result.status} ({result.message})", file=sys.stderr)
            return 1
        zmp.append(mpc.zmp_trajectory()[0])
        mpc.advance()
        state = mpc.state()
        com.append((state.com_x[0], state.com_y[0]))
        feet.append((state.support.x, state.support.y))
    print(f"after {state.time:.1f} s: CoM at x = {state.com_x[0]:.3f} m, "
          f"{state.step_count} steps")

    if args.out:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from walkgen.plots import save_figure
        com, zmp, feet = np.array(com), np.array(zmp), np.unique(np.array(feet), axis=0)
        fig, ax = plt.subplots(figsize=(8, 3.5))
        ax.plot(com[:, 0], com[:, 1], label="CoM")
        ax.plot(zmp[:, 0], zmp[:, 1], ".-", label="ZMP (planned)")
        ax.plot(feet[:, 0], feet[:, 1], "ks", label="footsteps")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_aspect("equal")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0))
        fig.tight_layout()
        save_figure(fig, args.out)  # atomically: a temporary file, then renamed
        print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
