#!/usr/bin/env bash
# Installs every system package the simulator needs (Debian 12, as root).
# Idempotent: packages already present are not fetched again.
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  libdeal.ii-dev            # FE library, brings MPI, p4est, PETSc (MUMPS), Trilinos, UMFPACK
  libopenblas0              # BLAS/LAPACK for the sparse direct solvers (4-5x over reference BLAS)
  openmpi-bin               # mpirun for parallel runs and the MPI tests
  libgtest-dev libbenchmark-dev
  python3-numpy python3-matplotlib python3-vtk9   # plots, pictures, VTU read-back test
  xvfb libgl1-mesa-dri      # off-screen X server and software OpenGL for VTK's renderer (no display needed)
  ffmpeg                    # movies (python3 -m membrane_flow movie)
  python3-dev pybind11-dev  # the Python module membrane_flow (docs/python.md)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "[deps] all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "[deps] missing packages: ${missing[*]}; run this script as root" >&2
  exit 1
fi
echo "[deps] installing: ${missing[*]}"
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
