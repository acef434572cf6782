#!/usr/bin/env bash
# Installs msislab's Debian 12 build and test dependencies when any is missing (apt-get; root or sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libeigen3-dev libembree-dev libsleef-dev libtbb-dev libopencv-dev libvtk9-dev libyaml-cpp-dev
  libcli11-dev libproj-dev
  libboost-dev libceres-dev nlohmann-json3-dev proj-data zlib1g-dev libgtest-dev libgmock-dev
  libbenchmark-dev xvfb xauth fonts-dejavu-core
  universal-ctags  # tools/check_sizes.sh: the length of every function
  clang libclang-rt-14-dev llvm  # tools/fuzz.sh (libFuzzer) and symbolized sanitizer reports
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
