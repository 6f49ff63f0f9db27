#!/usr/bin/env bash
# The README's demo (release preset): a humanoid walks in MuJoCo, by default the Unitree G1
# (torque motors; models/unitree_g1), or walkgen's own with --robot walkgen_humanoid. The closed
# loop of thesis figure 6.1 (NMPC -> interpolation -> Ceres IK -> joint controller -> MuJoCo,
# ZMP measured at the feet) runs the four test tasks of thesis §9.2 against a target object
# (straight 2 m, a curved walk to a target on the left, a chair on the way, the environmental
# scan with the target behind the robot) and films them; then the six HRP-2 pattern scenarios of
# §9.1 and the walking QP sequence of §2.2.
#
#   bash scripts/demo.sh [--quick] [--robot R] [--out DIR] [TASK...] [walking_simulation options]
#
#   --quick    a short check of the whole chain (about a minute once built): the straight task
#              shortened to 0.5 m, no video, plots on; one pattern scenario. The ctest
#              "readme_demo" runs it.
#   --robot R  unitree_g1 (default) or walkgen_humanoid (models/R/robot.yaml), or the path of a
#              robot description file (docs/robots.md)
#   --out DIR  where the results go (default build/release/example_output, or .../demo_quick)
#   --no-setup skip scripts/setup.sh (the packages are installed; readme_demo uses it)
#   TASK...    straight curved obstacle scan (default: all four); other arguments go to
#              build/release/examples/walking_simulation (see its --help), e.g. --no-plot.
set -euo pipefail
caller="$(pwd)"
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$(pwd)"

quick=0
setup=1
robot="unitree_g1"
out=""
sim_args=()
while [ "$#" -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --no-setup) setup=0 ;;
    --robot)
      if [ "$#" -lt 2 ]; then
        echo "demo: --robot needs a robot name or description file" >&2
        exit 2
      fi
      case "$2" in
        */* | *.yaml | *.yml) robot="$(cd "${caller}" && realpath -m -- "$2")" ;;  # a file
        *) robot="$2" ;;
      esac
      shift
      ;;
    --out)
      if [ "$#" -lt 2 ]; then
        echo "demo: --out needs a folder" >&2
        exit 2
      fi
      case "$2" in
        /*) out="$2" ;;
        *) out="${caller}/$2" ;;
      esac
      shift
      ;;
    -h | --help)
      sed -n '2,21p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *) sim_args+=("$1") ;;
  esac
  shift
done

if [ "${setup}" -eq 1 ]; then
  bash scripts/setup.sh
fi
cmake --preset release
cmake --build --preset release --target walking_simulation walking_scenarios qp_walking_sequence

bin="${root}/build/release/examples"
if [ -z "${out}" ]; then
  out="${root}/build/release/example_output"
  [ "${quick}" -eq 1 ] && out="${out}/demo_quick"
fi
mkdir -p "${out}"
out="$(cd "${out}" && pwd)"
sim="${out}/simulation"
mkdir -p "${sim}"
export EGL_PLATFORM="${EGL_PLATFORM:-surfaceless}"

start=${SECONDS}
if [ "${quick}" -eq 1 ]; then
  echo "demo (quick): walking_simulation straight --scale 0.25 --robot ${robot} --out ${sim} ${sim_args[*]}"
  "${bin}/walking_simulation" straight --scale 0.25 --robot "${robot}" --out "${sim}" "${sim_args[@]}"
  echo "demo (quick): walking_scenarios straight --out ${out}"
  "${bin}/walking_scenarios" straight --out "${out}"
else
  echo "demo: walking_simulation --video --robot ${robot} --out ${sim} ${sim_args[*]}"
  "${bin}/walking_simulation" --video --robot "${robot}" --out "${sim}" "${sim_args[@]}"
  echo "demo: walking_scenarios all --out ${out}"
  "${bin}/walking_scenarios" all --out "${out}"
  echo "demo: qp_walking_sequence --quiet (in ${out})"
  (cd "${out}" && "${bin}/qp_walking_sequence" --quiet)
fi

echo "demo: done in $((SECONDS - start)) s. The walk in MuJoCo is in ${sim}:"
find "${sim}" -maxdepth 1 -type f -printf '  %f\n' | sort
echo "demo: per task: ${sim}/<task>.png (path, desired vs measured ZMP, velocity histograms),"
echo "      ${sim}/<task>.csv (one row per 10 ms), ${sim}/simulation_summary.csv (per task),"
if [ "${quick}" -eq 0 ]; then
  echo "      ${sim}/<task>_frames.png (frame strip), ${sim}/<task>.mp4 (video)"
fi
echo "demo: the pattern generator's plots are ${out}/*.png"
