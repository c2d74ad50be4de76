#!/usr/bin/env bash
# Installs CovContact's build, test and post-processing dependencies from Debian's packages.
# Safe to run twice: apt-get skips what is already installed. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libsuitesparse-dev libgmsh-dev gmsh
  # PETSc with MUMPS, hypre, SuperLU_dist (issue 13); it links the Open MPI HDF5, which the
  # results writer therefore uses as well (one HDF5 library per process); mpirun for runs on
  # several processes (issue 17)
  libpetsc-real3.18-dev libhdf5-openmpi-dev openmpi-bin
  # Scotch partitions the mesh of such runs (PETSc's PT-Scotch brings it too)
  libscotch-dev
  libmuparser-dev libcli11-dev libfmt-dev libgtest-dev libgmock-dev
  libopenblas0-serial
  python3-h5py python3-matplotlib python3-numpy python3-scipy
  paraview python3-paraview xvfb hdf5-tools
  # scripts/bench.py compares with CalculiX; tests count instructions with valgrind
  calculix-ccx valgrind
  # tests/structure checks the formatting of the sources
  clang-format-14
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
