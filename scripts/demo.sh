#!/usr/bin/env bash
# Builds and runs the walking demo (release preset): the six HRP-2 walking scenarios of thesis
# §9.1 (examples/walking_scenarios), then the walking QP sequence (examples/qp_walking_sequence).
# Extra arguments go to walking_scenarios, e.g. a scenario name or --no-plot.
#   bash scripts/demo.sh [scenario|all] [--no-plot]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$(pwd)"

bash scripts/setup.sh
cmake --preset release
cmake --build --preset release --target walking_scenarios qp_walking_sequence

out="${root}/build/release/example_output"
mkdir -p "${out}"
args=("$@")
[ "${#args[@]}" -eq 0 ] && args=(all)
echo "demo: running build/release/examples/walking_scenarios ${args[*]} --out ${out}"
"${root}/build/release/examples/walking_scenarios" "${args[@]}" --out "${out}"
echo "demo: running build/release/examples/qp_walking_sequence --quiet (in ${out})"
(cd "${out}" && "${root}/build/release/examples/qp_walking_sequence" --quiet)

echo "demo: output files (CSV/PNG) are in ${out}:"
ls -l "${out}"
echo "demo: the plots (PNG) are:"
ls -1 "${out}"/*.png
