#!/usr/bin/env bash
# Bounded libFuzzer runs of every fuzz harness (tests/fuzz/README.md): configures and builds the
# fuzz preset (clang, ASan + UBSan), then runs each harness for a fixed time on a copy of its
# corpus. Exit 0 when no harness found a crash, 1 otherwise (the crashing inputs are listed).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds=60
usage() {
  cat <<'USAGE'
Usage: bash scripts/fuzz.sh [--seconds N] [--no-build] [HARNESS...]
  --seconds N   run each harness for N seconds (default 60)
  --no-build    use the harnesses already built in build/fuzz
  HARNESS       only these harnesses (e.g. fuzz_dense_qp); default: all
Crashes and their inputs go to build/fuzz/artifacts/<harness>/; add a fixed one to the corpus
(tests/fuzz/corpus/<name>/) so that ctest replays it from then on.
USAGE
}
build=1
only=()
while [ "$#" -gt 0 ]; do
  case "$1" in
    --seconds)
      if [ "$#" -lt 2 ] || ! [[ "$2" =~ ^[1-9][0-9]{0,4}$ ]]; then
        echo "fuzz: --seconds needs a whole number of seconds in [1, 99999]" >&2
        exit 2
      fi
      seconds="$2"
      shift 2
      ;;
    --no-build) build=0; shift ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "fuzz: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) only+=("$1"); shift ;;
  esac
done

if [ "${build}" -eq 1 ]; then
  cmake --preset fuzz
  cmake --build --preset fuzz
fi
list=build/fuzz/fuzz_harnesses.txt
if [ ! -s "${list}" ]; then
  echo "fuzz: ${list} is missing; build the fuzz preset first (drop --no-build)" >&2
  exit 2
fi

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
failed=()
ran=0
while read -r name folders; do
  [ -n "${name}" ] || continue
  if [ "${#only[@]}" -gt 0 ] && ! printf '%s\n' "${only[@]}" | grep -qx "${name}"; then
    continue
  fi
  work="build/fuzz/corpus_work/${name}"
  artifacts="build/fuzz/artifacts/${name}"
  mkdir -p "${work}" "${artifacts}"
  read -r -a seeds <<< "${folders}"
  echo "fuzz: ${name} for ${seconds} s (corpus ${folders})"
  log="build/fuzz/artifacts/${name}.log"
  if "build/fuzz/tests/fuzz/${name}" -max_total_time="${seconds}" -timeout=20 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="${artifacts}/" "${work}" "${seeds[@]}" \
      > "${log}" 2>&1; then
    runs=$(grep -m1 'stat::number_of_executed_units' "${log}" | awk '{print $2}')
    echo "fuzz: ${name}: no crash in ${runs:-?} runs"
  else
    echo "fuzz: ${name}: CRASH; the log's end (full log ${log}):" >&2
    tail -n 30 "${log}" >&2
    failed+=("${name}")
  fi
  ran=$((ran + 1))
done < "${list}"

if [ "${ran}" -eq 0 ]; then
  echo "fuzz: no harness ran (names: $(cut -d' ' -f1 "${list}" | tr '\n' ' '))" >&2
  exit 2
fi
if [ "${#failed[@]}" -gt 0 ]; then
  echo "fuzz: crashes in ${failed[*]}; inputs in build/fuzz/artifacts/" >&2
  exit 1
fi
echo "fuzz: ${ran} harnesses ran ${seconds} s each without a crash"
