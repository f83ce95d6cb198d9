#!/usr/bin/env bash
# Install the Debian 12 packages xpl needs to build, test and post-process results.
# Installs only what is missing; runs `apt-get update` at most once. As non-root it only
# reports what is missing (exit 1) and leaves the system alone.
set -euo pipefail

PACKAGES=(
  build-essential cmake libeigen3-dev libhdf5-dev hdf5-tools catch2 libomp-dev
  python3-h5py python3-meshio python3-matplotlib python3-numpy
)
# XPL_WITH_PARAVIEW=1 adds ParaView's Python and a virtual X server, for the tests that look at
# results the way ParaView shows them (app_viz_paraview, app_viz_screenshot; skipped without
# them) and scripts/paraview_screenshot.py. Not by default: on the 2-core development VM (niced,
# load ~15 from other builds) the install took 12 min (paraview, xvfb, xauth: 10.7 min, 73 of
# 143 MB to download, 725 MB installed, most of the time unpacking; python3-paraview: 1.2 min),
# a third of the CI budget for tests of ~40 s; an idle machine is faster, but not seconds.
if [[ ${XPL_WITH_PARAVIEW:-0} == 1 ]]; then
  PACKAGES+=(paraview python3-paraview xvfb xauth)
fi
# XPL_WITH_MPI=1 adds OpenMPI, METIS and the OpenMPI build of HDF5, for the MPI build
# (XPL_MPI=ON, docs/dev/mpi.md; the MPI stage of scripts/run_tests.sh). Installing
# libhdf5-openmpi-dev turns Debian's hdf5.pc alternative to the MPI build; the default build
# still takes the serial HDF5, which CMakeLists.txt selects by its wrapper h5cc.
if [[ ${XPL_WITH_MPI:-0} == 1 ]]; then
  PACKAGES+=(libopenmpi-dev libmetis-dev libhdf5-openmpi-dev)
fi

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
