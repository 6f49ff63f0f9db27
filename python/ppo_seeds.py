#!/usr/bin/env python3
"""PPO's reliability over seeds (issue 27): trains examples/ppo_train once per environment and
seed, tests each policy on held-out goals, and writes one row per run to a CSV file with the
columns env, seed, success_rate (plus reached, goals, qp_failures, collisions: episodes ended
by a footstep inside an obstacle, timeouts, and seconds: the wall time of training and test).

    /usr/bin/python3 python/ppo_seeds.py --ppo-train build/release/examples/ppo_train \\
        --out docs/results/ppo_seeds.csv --work ppo_seeds_runs --seeds 1 2 3 4 5 --require 0.95

--jobs J trains J seeds at once (one thread each; a seed's result is the same either way).
Each run is `ppo_train nmpc --seed S` (and `--obstacles 1`, with its defaults: the robot's
motion in the state, success reward 10 000, soft obstacle rows, an annealed step size, 200
epochs, for nmpc_obstacles);
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
    "nmpc_obstacles": (["nmpc", "--obstacles", "1"], 200),
}
COLUMNS = ["env", "seed", "success_rate", "reached", "goals", "qp_failures", "collisions", "timeouts",
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
            "qp_failures": ends.count("failure"), "collisions": ends.count("inside_obstacle"),
            "timeouts": ends.count("truncated")}


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
    p.add_argument("--jobs", type=int, default=1,
                   help="runs at once, each on one thread (the results do not change)")
    p.add_argument("--require", type=float,
                   help="exit 1 unless every run's success rate is at least this")
    a = p.parse_args()
    if not os.access(a.ppo_train, os.X_OK):
        sys.exit("ppo_seeds: %s is not an executable (build ppo_train first)" % a.ppo_train)
    if a.test_goals < 1 or a.jobs < 1 or (a.epochs is not None and a.epochs < 1):
        sys.exit("ppo_seeds: --test-goals, --jobs and --epochs must be >= 1")
    runs = []  # (env, seed, command line, output folder) in the CSV's order
    for env in a.envs:
        for seed in a.seeds:
            out = os.path.join(a.work, "%s_seed%d" % (env, seed))
            env_args, epochs = ENVS[env]
            args = [a.ppo_train] + env_args + ["--seed", str(seed), "--out", out, "--quiet",
                                               "--test-goals", str(a.test_goals),
                                               "--epochs", str(a.epochs or epochs)]
            if a.steps is not None:
                args += ["--steps", str(a.steps)]
            if a.jobs > 1:  # one thread per run (a seed's result does not depend on it)
                args += ["--threads", "1"]
            runs.append((env, seed, args, out))
    done = {}  # run index -> CSV row

    def finish(i, proc, start):
        env, seed, args, out = runs[i]
        if proc.returncode != 0:
            with open(os.path.join(out, "stderr.txt")) as f:
                sys.exit("ppo_seeds: %s failed (%d):\n%s" % (" ".join(args), proc.returncode,
                                                              f.read()))
        r = result(os.path.join(out, "test_%s.csv" % env))
        r.update(env=env, seed=seed, success_rate="%.2f" % (r["reached"] / r["goals"]),
                 seconds="%.0f" % (time.monotonic() - start))
        done[i] = r
        print("[%d/%d] %s seed %d: success %s (%d of %d; %d QP failures, %d collisions, %d out "
              "of time), %s s" % (len(done), len(runs), env, seed, r["success_rate"], r["reached"],
                                  r["goals"], r["qp_failures"], r["collisions"], r["timeouts"],
                                  r["seconds"]), flush=True)
        write_atomically(a.out, [done[k] for k in sorted(done)])

    running = {}  # run index -> (process, start)
    for i, (env, seed, args, out) in enumerate(runs):
        while len(running) >= a.jobs:  # wait for a free slot
            time.sleep(0.5)
            for k in [k for k, (proc, _) in running.items() if proc.poll() is not None]:
                finish(k, *running.pop(k))
        print("started %s" % " ".join(args[1:]), flush=True)
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, "stderr.txt"), "w") as err:  # the child keeps its own copy
            proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=err)
        running[i] = (proc, time.monotonic())
    for k in sorted(running):
        running[k][0].wait()
        finish(k, *running[k])
    rows = [done[k] for k in sorted(done)]
    worst = min(float(r["success_rate"]) for r in rows)
    print("ppo_seeds: %d runs, lowest success rate %.2f, written to %s" % (len(rows), worst, a.out))
    if a.require is not None and worst < a.require:
        sys.exit("ppo_seeds: a success rate below the required %.2f" % a.require)


if __name__ == "__main__":
    main()
