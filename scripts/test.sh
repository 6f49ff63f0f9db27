#!/usr/bin/env bash
# Configures, builds and runs the whole test suite with the release preset (what CI runs).
# Extra arguments go to ctest, e.g. `bash scripts/test.sh -L unit`. Exit code = ctest's.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
cmake --preset release
cmake --build --preset release

set +e
ctest --preset release "$@"
rc=$?
set -e
echo "test: ctest exited with ${rc}"
exit "${rc}"
