#!/usr/bin/env python3
"""PPO's reliability over seeds (issue 27): trains examples/ppo_train once per environment and
seed, tests each policy on held-out goals, and writes one row per run to a CSV file with the
columns env, seed, success_rate (plus reached, goals, qp_failures, timeouts, and seconds: the
wall time of training and test).

    /usr/bin/python3 python/ppo_seeds.py --ppo-train build/release/examples/ppo_train \\
        --out docs/results/ppo_seeds.csv --work ppo_seeds_runs --seeds 1 2 3 4 5 --require 0.95

Each run is `ppo_train nmpc --seed S` (and `--obstacles 1 --epochs 80` for nmpc_obstacles);
success is measured on the 100 held-out goals of `run.evaluation_seed`, which training never
draws. --epochs and --test-goals shorten the runs (the ctest ppo_seeds_short does). The CSV is
written atomically (a temporary file renamed over it) after every run, so an interrupted study
keeps the rows it finished.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

ENVS = {  # env name -> ppo_train arguments and training epochs (docs/learning.md)
    "nmpc": (["nmpc"], 30),
    "nmpc_obstacles": (["nmpc", "--obstacles", "1"], 80),
}
COLUMNS = ["env", "seed", "success_rate", "reached", "goals", "qp_failures", "timeouts",
           "seconds"]


def write_atomically(path, rows):
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fd, temp = tempfile.mkstemp(dir=folder, prefix=".ppo_seeds.", suffix=".csv")
    with os.fdopen(fd, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    os.replace(temp, path)


def result(test_csv):
    with open(test_csv, newline="") as f:
        # as ppo_train counts: reached, and (with obstacles) no footstep inside one
        ends = [r["end"] if float(r["min_clearance"]) >= 0.0 else "inside_obstacle"
                for r in csv.DictReader(f)]
    return {"reached": ends.count("success"), "goals": len(ends),
            "qp_failures": ends.count("failure"), "timeouts": ends.count("truncated")}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--ppo-train", required=True, help="the ppo_train program")
    p.add_argument("--out", required=True, help="the CSV file to write")
    p.add_argument("--work", required=True, help="folder of the runs' outputs")
    p.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5])
    p.add_argument("--envs", nargs="+", choices=sorted(ENVS), default=sorted(ENVS))
    p.add_argument("--epochs", type=int, help="override the epochs (short runs)")
    p.add_argument("--steps", type=int, help="override the steps per epoch (short runs)")
    p.add_argument("--test-goals", type=int, default=100)
    p.add_argument("--require", type=float,
                   help="exit 1 unless every run's success rate is at least this")
    a = p.parse_args()
    if not os.access(a.ppo_train, os.X_OK):
        sys.exit("ppo_seeds: %s is not an executable (build ppo_train first)" % a.ppo_train)
    if a.test_goals < 1 or (a.epochs is not None and a.epochs < 1):
        sys.exit("ppo_seeds: --test-goals and --epochs must be >= 1")
    rows = []
    total = len(a.envs) * len(a.seeds)
    for env in a.envs:
        for seed in a.seeds:
            out = os.path.join(a.work, "%s_seed%d" % (env, seed))
            env_args, epochs = ENVS[env]
            args = [a.ppo_train] + env_args + ["--seed", str(seed), "--out", out, "--quiet",
                                               "--test-goals", str(a.test_goals),
                                               "--epochs", str(a.epochs or epochs)]
            if a.steps is not None:
                args += ["--steps", str(a.steps)]
            print("[%d/%d] %s" % (len(rows) + 1, total, " ".join(args[1:])), flush=True)
            start = time.monotonic()
            run = subprocess.run(args, capture_output=True, text=True, check=False)
            if run.returncode != 0:
                sys.exit("ppo_seeds: %s failed (%d):\n%s" % (" ".join(args), run.returncode,
                                                             run.stderr))
            r = result(os.path.join(out, "test_%s.csv" % env))
            r.update(env=env, seed=seed, success_rate="%.2f" % (r["reached"] / r["goals"]),
                     seconds="%.0f" % (time.monotonic() - start))
            rows.append(r)
            print("        success %s (%d of %d; %d QP failures, %d out of time), %s s"
                  % (r["success_rate"], r["reached"], r["goals"], r["qp_failures"],
                     r["timeouts"], r["seconds"]), flush=True)
            write_atomically(a.out, rows)
    worst = min(float(r["success_rate"]) for r in rows)
    print("ppo_seeds: %d runs, lowest success rate %.2f, written to %s" % (len(rows), worst, a.out))
    if a.require is not None and worst < a.require:
        sys.exit("ppo_seeds: a success rate below the required %.2f" % a.require)


if __name__ == "__main__":
    main()
