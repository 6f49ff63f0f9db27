#!/usr/bin/env bash
# The whole test suite (what CI runs): installs missing Debian packages, then three stages:
#   release   configure, build and ctest the release preset (every test, examples included);
#   sanitize  the same tests under ASan + UBSan (sanitize preset: tests and fuzz replays, no
#             examples, benchmarks or libtorch);
#   fuzz      a bounded libFuzzer run of every fuzz harness (scripts/fuzz.sh, 60 s each; 30 s
#             with CI=true; WALKGEN_FUZZ_SECONDS sets it).
# Options: --only STAGE[,STAGE...] runs those stages; arguments after them go to the release
# stage's ctest, e.g. `bash scripts/test.sh --only release -L unit`. Exit code: 0 when every
# stage passed, else the first failing stage's.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

stages="release,sanitize,fuzz"
if [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ]; then
  sed -n '2,10p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
  exit 0
fi
if [ "${1:-}" = "--only" ]; then
  if [ "$#" -lt 2 ] || ! [[ "$2" =~ ^(release|sanitize|fuzz)(,(release|sanitize|fuzz))*$ ]]; then
    echo "test: --only needs stages from release, sanitize, fuzz (comma-separated)" >&2
    exit 2
  fi
  stages="$2"
  shift 2
fi
has_stage() { [[ ",${stages}," == *",$1,"* ]]; }

bash scripts/setup.sh
rc=0
finish_stage() {  # name, exit status, start time: reports it, remembers the first failure
  echo "test: stage $1 exited with $2 after $((SECONDS - $3)) s"
  if [ "$2" -ne 0 ] && [ "${rc}" -eq 0 ]; then rc=$2; fi
}
set +e
if has_stage release; then
  start=${SECONDS}
  cmake --preset release && cmake --build --preset release && ctest --preset release "$@"
  finish_stage release $? "${start}"
fi
if has_stage sanitize; then
  start=${SECONDS}
  cmake --preset sanitize && cmake --build --preset sanitize && ctest --preset sanitize
  finish_stage sanitize $? "${start}"
fi
if has_stage fuzz; then
  start=${SECONDS}
  fuzz_seconds=60
  if [ "${CI:-}" = "true" ]; then fuzz_seconds=30; fi
  bash scripts/fuzz.sh --seconds "${WALKGEN_FUZZ_SECONDS:-${fuzz_seconds}}"
  finish_stage fuzz $? "${start}"
fi
echo "test: exited with ${rc} (stages ${stages})"
exit "${rc}"
