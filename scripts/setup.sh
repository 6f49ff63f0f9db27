#!/usr/bin/env bash
# Installs the Debian packages walkgen needs to build, test and plot. Idempotent: apt-get runs
# only when a package is missing. Uses sudo only when not root and sudo exists.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev libyaml-cpp-dev
  libtinyxml2-dev libmujoco-dev libceres-dev liborocos-kdl-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libopencv-dev libopencv-contrib-dev
  libtorch-dev python3-torch libgloo-dev
  libcli11-dev shellcheck
  clang libclang-rt-14-dev
  ffmpeg tmux clang-format python3-numpy python3-matplotlib
  pybind11-dev python3-dev python3-pytest
  libcpp-httplib-dev nlohmann-json3-dev chromium chromium-driver python3-selenium
)

missing=()
for pkg in "${packages[@]}"; do
  if dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    :
  else
    missing+=("$pkg")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "setup: all ${#packages[@]} required Debian packages are installed"
  exit 0
fi

echo "setup: installing missing packages: ${missing[*]}"
if ! command -v apt-get >/dev/null 2>&1; then
  echo "setup: apt-get not found; install these packages by hand: ${missing[*]}" >&2
  exit 1
fi
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "setup: not root and sudo is not available; as root run:" >&2
    echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
echo "setup: ${sudo_cmd[*]:+${sudo_cmd[*]} }apt-get update"
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
echo "setup: ${sudo_cmd[*]:+${sudo_cmd[*]} }apt-get install -y --no-install-recommends ${missing[*]}"
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y --no-install-recommends "${missing[@]}"
echo "setup: done"
