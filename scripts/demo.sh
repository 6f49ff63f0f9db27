#!/usr/bin/env bash
# Builds and runs the walking QP example (release preset). Extra arguments go to the example.
#   bash scripts/demo.sh [example args...]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$(pwd)"

bash scripts/setup.sh
cmake --preset release
cmake --build --preset release --target qp_walking_sequence

out="${root}/build/release/example_output"
mkdir -p "${out}"
echo "demo: running build/release/examples/qp_walking_sequence $* (in ${out})"
(cd "${out}" && "${root}/build/release/examples/qp_walking_sequence" "$@")

echo "demo: output files (CSV/PNG) are in ${out}:"
ls -l "${out}"
