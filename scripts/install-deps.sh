#!/usr/bin/env bash
# Installs what rigidity needs from Debian's packages, if anything is missing.
# Needs root (or sudo) only when something has to be installed.
set -euo pipefail

# Extra package names may be given as arguments (the sanitizer and fuzzing job adds clang).
# Sphinx and its MyST parser build the documentation (scripts/docs.sh); python3-venv makes the
# virtual environment of the pip install test; nbclient and ipykernel run the notebooks
# (scripts/notebooks.sh). muparser parses the expressions of `model: formula` materials; HDF5
# writes run.h5 (outputs.hdf5), which the tests read back with h5py too.
packages=(build-essential cmake libeigen3-dev libyaml-cpp-dev libgsl-dev libmuparser-dev pkg-config libbenchmark-dev libgtest-dev gnuplot-nox
          python3-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib libopenmpi-dev openmpi-bin
          python3-sphinx python3-myst-parser python3-venv python3-nbclient python3-ipykernel libhdf5-dev python3-h5py "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "rigidity: installing ${missing[*]}" >&2
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
