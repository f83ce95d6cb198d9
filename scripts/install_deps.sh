#!/usr/bin/env bash
# Install the Debian 12 packages xpl needs to build, test and post-process results.
# Installs only what is missing; runs `apt-get update` at most once. As non-root it only
# reports what is missing (exit 1) and leaves the system alone.
set -euo pipefail

PACKAGES=(
  build-essential cmake libeigen3-dev libhdf5-dev hdf5-tools catch2 libomp-dev
  python3-h5py python3-meshio python3-matplotlib python3-numpy
)

is_installed() {
  # `dpkg -s` also succeeds for removed-but-not-purged packages: check the status line.
  dpkg -s "$1" 2>/dev/null | grep -q '^Status: install ok installed'
}

missing=()
for package in "${PACKAGES[@]}"; do
  is_installed "$package" || missing+=("$package")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install_deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
  echo "install_deps: missing packages: ${missing[*]}" >&2
  echo "install_deps: as root, run: apt-get update && apt-get install -y ${missing[*]}" >&2
  exit 1
fi

echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt_options=(-qq -y -o Dpkg::Use-Pty=0 -o APT::Install-Recommends=false)
apt-get "${apt_options[@]}" update >/dev/null
apt-get "${apt_options[@]}" install "${missing[@]}" >/dev/null </dev/null
echo "install_deps: done"
