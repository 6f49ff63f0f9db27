#!/usr/bin/env bash
# ctest "layers": the floors of include/walkgen/ include only the floors below them, so the data
# path runs one way (docs/design.md, "The house"); examples/ and benchmarks/ include nothing
# from tests/, and tests/support/ holds test helpers only (at most 500 lines; the application
# layer lives in the library). Prints every offence and fails on any.
#   bash tests/layers.sh [REPO_ROOT]
set -euo pipefail
root="$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/..}" && pwd)"
cd "${root}/include/walkgen"

# floor -> the floors its headers may include (itself included). Adapters and the application
# layer above these floors may include any of them.
declare -A allowed=(
  [core]="core"
  [model]="core model"
  [qp]="core qp"
  [interpolation]="core interpolation"
  [kinematics]="core kinematics"
  [mpc]="core model qp interpolation mpc"
)

failures=0
for floor in "${!allowed[@]}"; do
  [ -d "${floor}" ] || continue
  while IFS= read -r line; do
    file="${line%%:*}"
    included="${line#*\"walkgen/}"
    target="${included%%/*}"
    case " ${allowed[${floor}]} " in
      *" ${target} "*) ;;
      *)
        echo "layers: ${floor}/ may include only {${allowed[${floor}]}}: ${file} includes" \
          "walkgen/${included%\"*}" >&2
        failures=$((failures + 1))
        ;;
    esac
  done < <(grep -rHo '#include "walkgen/[^"]*"' "${floor}" || true)
done

cd "${root}"
while IFS= read -r line; do
  echo "layers: examples/ and benchmarks/ must not include test code: ${line}" >&2
  failures=$((failures + 1))
done < <(grep -rnE '#include "(support/|\.\./tests/|tests/)' examples benchmarks || true)

support_lines=$(cat tests/support/* | wc -l)
if [ "${support_lines}" -gt 500 ]; then
  echo "layers: tests/support/ has ${support_lines} lines (at most 500: test helpers only)" >&2
  failures=$((failures + 1))
fi

if [ "${failures}" -gt 0 ]; then
  echo "layers: ${failures} include(s) against the layering" >&2
  exit 1
fi
echo "layers: every floor includes only the floors below it; examples and benchmarks include" \
  "no test code; tests/support/ has ${support_lines} lines"
