#!/usr/bin/env bash
# ctest "layers": the floors of include/walkgen/ include only the floors below them, so the data
# path runs one way (docs/design.md, "The house"); an adapter (one backend each) includes the
# floors and itself, never another adapter nor the application layer; every folder of
# include/walkgen/ is a floor, an adapter or an application folder, and every adapter and
# application folder has its umbrella header include/walkgen/<name>.hpp, which includes only
# that folder (the core umbrella walkgen.hpp only the floors); examples/ and benchmarks/ include
# nothing from tests/, and tests/support/ holds test helpers only (at most 500 lines; the
# application layer lives in the library). Prints every offence and fails on any.
#   bash tests/layers.sh [REPO_ROOT]
set -euo pipefail
root="$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/..}" && pwd)"
cd "${root}/include/walkgen"

# floor -> the floors its headers may include (itself included). Together the core
# (walkgen::walkgen, Eigen only); scenarios/, the application layer's Eigen-only folder, is
# checked as a floor.
declare -A allowed=(
  [core]="core"
  [model]="core model"
  [qp]="core qp"
  [interpolation]="core interpolation"
  [kinematics]="core kinematics"
  [robot]="core model qp interpolation mpc robot"
  [mpc]="core model qp interpolation mpc"
  [estimation]="core model qp interpolation kinematics robot mpc estimation"
  [control]="core model qp interpolation kinematics robot mpc estimation control"
  [learning]="core model qp interpolation mpc learning"
  [scenarios]="core model qp interpolation mpc scenarios"
)
# Adapters: one backend each (walkgen::<name>); the application layer: built on adapters.
adapters="ceres mujoco opencv torch urdf yaml"
applications="humanoid simulation navigation"
floors="core model qp interpolation kinematics robot mpc estimation control learning scenarios"
for adapter in ${adapters}; do
  allowed[${adapter}]="${floors} ${adapter}"
done

failures=0
# offence MESSAGE: prints one offence against the layering and counts it.
offence() {
  echo "layers: $*" >&2
  failures=$((failures + 1))
}
# in_list WORD LIST: whether WORD is one of the space-separated words of LIST.
in_list() {
  case " $2 " in
    *" $1 "*) return 0 ;;
  esac
  return 1
}

# check_includes WHO PERMITTED PATH: every "walkgen/<x>/..." (or "walkgen/<x>") that the headers at
# PATH include has <x> in the space-separated PERMITTED.
check_includes() {
  local line file included
  while IFS= read -r line; do
    file="${line%%:*}"
    included="${line#*\"walkgen/}"
    included="${included%\"}"
    in_list "${included%%/*}" "$2" ||
      offence "$1 may include only {$2}: ${file} includes walkgen/${included}"
  done < <(grep -rHo '#include "walkgen/[^"]*"' "$3" || true)
}

for floor in "${!allowed[@]}"; do
  [ -d "${floor}" ] || continue
  check_includes "${floor}/" "${allowed[${floor}]}" "${floor}"
done

for folder in */; do
  folder="${folder%/}"
  in_list "${folder}" "${floors} ${adapters} ${applications}" ||
    offence "include/walkgen/${folder}/ is not a known floor, adapter or application folder" \
      "(tests/layers.sh lists them)"
done

# Umbrella headers: walkgen.hpp includes floors only; <name>.hpp only its own folder.
for header in *.hpp; do
  in_list "${header%.hpp}" "walkgen version ${adapters} ${applications}" ||
    offence "include/walkgen/${header} is neither the core umbrella nor an adapter's or" \
      "application folder's umbrella"
done
for umbrella in walkgen ${adapters} ${applications}; do
  if [ ! -f "${umbrella}.hpp" ]; then
    offence "include/walkgen/${umbrella}.hpp (the umbrella header of ${umbrella}/) is missing"
    continue
  fi
  permitted="${umbrella}"
  [ "${umbrella}" = walkgen ] && permitted="${floors} version.hpp"
  check_includes "the umbrella ${umbrella}.hpp" "${permitted}" "${umbrella}.hpp"
done

cd "${root}"
while IFS= read -r line; do
  offence "examples/ and benchmarks/ must not include test code: ${line}"
done < <(grep -rnE '#include "(support/|\.\./tests/|tests/)' examples benchmarks || true)

support_lines=$(cat tests/support/* | wc -l)
if [ "${support_lines}" -gt 500 ]; then
  offence "tests/support/ has ${support_lines} lines (at most 500: test helpers only)"
fi

if [ "${failures}" -gt 0 ]; then
  echo "layers: ${failures} offence(s) against the layering" >&2
  exit 1
fi
echo "layers: every floor includes only the floors below it, every adapter only the floors and" \
  "itself, every umbrella only its folder; examples and benchmarks include no test code;" \
  "tests/support/ has ${support_lines} lines"
