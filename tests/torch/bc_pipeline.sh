#!/usr/bin/env bash
# Behavioural cloning end to end, tiny (issue 8): records two expert episodes in random rooms,
# trains the U-Net-LSTM on them for a few steps on the CPU, and drives the robot with it.
#   bc_pipeline.sh <record_demonstrations> <bc_evaluate> <bc_train.py> <output folder>
set -euo pipefail
record=$1
evaluate=$2
train=$3
out=$4
rm -rf "$out"
mkdir -p "$out"
python=/usr/bin/python3
"$python" -c "import torch, PIL, matplotlib" || { echo "bc_pipeline: $python lacks torch, PIL or matplotlib (scripts/setup.sh installs python3-torch, python3-matplotlib)"; exit 1; }

"$record" --out "$out/data" --episodes 2 --tasks straight --seed 77
# (with the brightness normalisation and the hue-blind colours inside the exported model, which
# the C++ side must reproduce: test_velocity_network compares it with the reference below)
"$python" "$train" "$out/data" "$out/model" --epochs 3 --width 4 --threads 2 --normalize-brightness \
  --hue-blind
# The reference for test_velocity_network: the Python model's commands on the first 12 frames of
# the first episode, with bc_train.py's own pre-processing and 5-frame windows.
"$python" - "$train" "$out" <<'PY'
import importlib.util, os, sys
import numpy as np, torch
spec = importlib.util.spec_from_file_location("bc_train", sys.argv[1])
bc = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bc)
out = sys.argv[2]
episodes = bc.read_index(os.path.join(out, "data"))
rows = episodes[sorted(episodes)[0]][:12]
model = torch.jit.load(os.path.join(out, "model", "model.pt"))
t = model.sequence
frames = torch.from_numpy(np.stack([bc.load_frame(r[1], r[2], r[3]) for r in rows]))
with torch.no_grad():
    features = model.encode(frames)
    padded = torch.cat([features[:1].expand(t - 1, -1), features])
    with open(os.path.join(out, "reference.csv"), "w") as f:
        f.write("rgb,disparity,v_x,omega_z\n")
        for i, r in enumerate(rows):
            y = model.head(padded[i:i + t].unsqueeze(0))[0]
            f.write("%s,%s,%.8f,%.8f\n" % (r[2], r[3], float(y[0]), float(y[1])))
PY
"$evaluate" --model "$out/model/model.pt" --tasks straight --layouts 1 --time-limit 16 --out "$out" \
  --dagger "$out/data"

"$python" - "$out" <<'PY'
import csv, os, sys
out = sys.argv[1]
def fail(msg):
    sys.exit("bc_pipeline: FAILED: " + msg)
for f in ("model/model.pt", "model/training.png", "model/histograms.png"):
    if not os.path.getsize(os.path.join(out, f)) > 0:
        fail("missing " + f)
log = list(csv.DictReader(open(os.path.join(out, "model/training_log.csv"))))
if len(log) != 3:
    fail("expected 3 epochs in training_log.csv, got %d" % len(log))
command = open(os.path.join(out, "model/command.txt")).read()
if "--epochs 3 --width 4" not in command:
    fail("model/command.txt does not hold the training command: %r" % command)
first, last = float(log[0]["train_mse"]), float(log[-1]["train_mse"])
if not last < first:
    fail("the training loss did not fall: %g -> %g" % (first, last))
kl = {r["velocity"]: float(r["kl_divergence"]) for r in csv.DictReader(open(os.path.join(out, "model/histograms.csv")))}
if set(kl) != {"v_x", "omega_z"} or not all(v >= 0 for v in kl.values()):
    fail("histograms.csv: %s" % kl)
rows = list(csv.DictReader(open(os.path.join(out, "bc_evaluation.csv"))))
if len(rows) != 1 or float(rows[0]["inference_ms"]) <= 0 or float(rows[0]["time"]) < 15:
    fail("bc_evaluation.csv: %s" % rows)
if rows[0]["fell"] != "0":
    fail("the robot fell under the network's commands")
dagger = [l.split() for l in open(os.path.join(out, "data/index.txt")) if l.startswith("rgb/dagger_")]
if len(dagger) < 35:  # 40 ticks in 16 s
    fail("DAgger recorded %d frames, expected one per tick of 16 s" % len(dagger))
if not any(abs(float(d[6])) > 0.01 or float(d[4]) > 0.01 for d in dagger):
    fail("the DAgger labels are not the expert's commands: %s" % dagger[:3])
paths = list(csv.DictReader(open(os.path.join(out, "bc_paths.csv"))))
if len(paths) != len(dagger) or abs(float(paths[0]["x"])) > 0.05:
    fail("bc_paths.csv: %d ticks for %d frames, starting at x = %s"
         % (len(paths), len(dagger), paths[0]["x"] if paths else "?"))
if not float(paths[-1]["x"]) > float(paths[0]["x"]) + 0.1:
    fail("the network did not walk toward the target ahead: x %s -> %s"
         % (paths[0]["x"], paths[-1]["x"]))
print("bc_pipeline: training MSE %.4f -> %.4f, KL v_x %.3f omega %.3f, %.1f s in the loop at %.2f ms per frame"
      % (first, last, kl["v_x"], kl["omega_z"], float(rows[0]["time"]), float(rows[0]["inference_ms"])))
PY
"$python" "$(dirname "$train")/plot_bc_evaluation.py" "$out/bc_evaluation.csv" --out "$out/bc_evaluation.png" \
  --paths "$out/bc_paths.png"
test -s "$out/bc_evaluation.png" && test -s "$out/bc_paths.png"
