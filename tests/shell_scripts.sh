#!/usr/bin/env bash
# ctest "shell_scripts": every shell script the repository tracks parses (bash -n) and passes
# ShellCheck; every tracked file that starts with "#!" has its run bit, in the working tree
# and in git's index (what a fresh clone gets).
#   bash tests/shell_scripts.sh [REPO_ROOT]
set -euo pipefail
root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
cd "${root}"

if ! command -v shellcheck >/dev/null 2>&1; then
  echo "shell_scripts: shellcheck not found; install the Debian package shellcheck" \
    "(bash scripts/setup.sh does)" >&2
  exit 1
fi

files=()
if git -C "${root}" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  while IFS= read -r f; do
    [ -f "${f}" ] && files+=("${f}")
  done < <(git ls-files --cached --others --exclude-standard)
  in_git=1
else
  while IFS= read -r f; do
    files+=("${f#./}")
  done < <(find . -path ./build -prune -o -path ./.git -prune -o -type f -print)
  in_git=0
fi

shells=()
scripts=()
for f in "${files[@]}"; do
  first="$(head -c 64 "${f}" | head -n 1 | tr -d '\0')"
  case "${first}" in
    '#!'*) scripts+=("${f}") ;;
  esac
  case "${f}" in
    *.sh) shells+=("${f}") ;;
    *)
      case "${first}" in
        '#!'*bash* | '#!'*/sh) shells+=("${f}") ;;
      esac
      ;;
  esac
done

failures=0
for f in "${shells[@]}"; do
  if ! bash -n "${f}"; then
    echo "shell_scripts: ${f}: bash -n failed" >&2
    failures=$((failures + 1))
  fi
done
if ! shellcheck --external-sources "${shells[@]}"; then
  echo "shell_scripts: shellcheck found problems (above)" >&2
  failures=$((failures + 1))
fi
for f in "${scripts[@]}"; do
  if [ ! -x "${f}" ]; then
    echo "shell_scripts: ${f} starts with #! but is not executable (chmod +x ${f})" >&2
    failures=$((failures + 1))
  fi
  if [ "${in_git}" -eq 1 ]; then
    mode="$(git ls-files -s -- "${f}" | cut -d' ' -f1)"
    if [ -n "${mode}" ] && [ "${mode}" != 100755 ]; then
      echo "shell_scripts: ${f} has mode ${mode} in git's index, expected 100755" \
        "(git update-index --chmod=+x ${f})" >&2
      failures=$((failures + 1))
    fi
  fi
done

echo "shell_scripts: ${#shells[@]} shell scripts (bash -n, shellcheck)," \
  "${#scripts[@]} files with #! (run bit); ${failures} problem(s)"
[ "${failures}" -eq 0 ]
