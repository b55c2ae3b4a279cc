#!/usr/bin/env bash
# Installs the Debian packages radquad needs, only those that are missing.
# Safe to run repeatedly: with everything present it does nothing.
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev libembree-dev libtbb-dev
  libgtest-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libstb-dev
  libpolyclipping-dev libcubature-dev libzip-dev
  clang libclang-rt-14-dev
  python3-matplotlib python3-numpy
  pybind11-dev python3-dev python3-pytest
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
