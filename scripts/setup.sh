#!/usr/bin/env bash
# Install what visco2d needs, only what is missing: gfortran, LAPACK/BLAS
# (reference and OpenBLAS serial),
# HDF5 (Fortran), CHOLMOD, pkg-config, numdiff, h5dump (Debian packages), fpm,
# h5py, matplotlib, meshio, scipy and vtk (PyPI). Safe to run again; quiet when everything is present.
#   bash scripts/setup.sh mpi       also OpenMPI (openmpi-bin libopenmpi-dev: mpif90, mpirun) for the
#                                   MPI task farm (make mpi, the MPI stage of make test; ~25 s to install)
#   bash scripts/setup.sh paraview  also ParaView (Debian's python3-paraview, 5.11 on Debian 12: pvpython),
#                                   whose XDMF readers scripts/test_xdmf.sh then tries too (about 210
#                                   packages, 207 MB to download, 2-3 min to install)
set -euo pipefail

packages=()
# mpif90 and mpirun alone are not enough: openmpi-bin can be present (pulled in
# by another package) without libopenmpi-dev, whose mpi_f08 module the farm
# needs; so the check compiles a two-line program that uses it.
mpi_usable() {
  command -v mpif90 >/dev/null 2>&1 && command -v mpirun >/dev/null 2>&1 || return 1
  local dir
  dir=$(mktemp -d)
  printf 'program probe\n  use mpi_f08\nend program probe\n' > "$dir/probe.f90"
  (cd "$dir" && mpif90 -c probe.f90 -o probe.o) >/dev/null 2>&1
  local status=$?
  rm -rf "$dir"
  return $status
}
if [ "${1:-}" = "mpi" ]; then
  mpi_usable || packages+=(openmpi-bin libopenmpi-dev)
fi
command -v gfortran >/dev/null 2>&1 || packages+=(gfortran)
command -v pkg-config >/dev/null 2>&1 || packages+=(pkg-config)
command -v numdiff >/dev/null 2>&1 || packages+=(numdiff)
command -v h5dump >/dev/null 2>&1 || packages+=(hdf5-tools)
ls /usr/lib/*/liblapack.so >/dev/null 2>&1 || packages+=(liblapack-dev)
ls /usr/lib/*/libblas.so >/dev/null 2>&1 || packages+=(libblas-dev)
# An optimized single-threaded BLAS/LAPACK behind the same libblas.so.3 /
# liblapack.so.3 (Debian alternatives): dpbtrf 4-5x faster than the reference BLAS.
ls /usr/lib/*/openblas-serial/libblas.so.3 >/dev/null 2>&1 || packages+=(libopenblas0-serial)
pkg-config --exists hdf5 2>/dev/null && ls /usr/include/hdf5/serial/hdf5.mod >/dev/null 2>&1 || packages+=(libhdf5-dev)
# CHOLMOD (SuiteSparse): the sparse Cholesky factor of S~ (src/base/visco2d_cholmod.f90, linked
# always: fpm.toml); about 5 s to install (19 small Debian packages).
ls /usr/include/suitesparse/cholmod.h >/dev/null 2>&1 || packages+=(libsuitesparse-dev)

if [ ${#packages[@]} -gt 0 ]; then
  echo "setup: installing ${packages[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${packages[@]}" >/dev/null
fi
if [ "${1:-}" = "paraview" ] && ! command -v pvpython >/dev/null 2>&1; then
  echo "setup: installing python3-paraview (ParaView and pvpython; 2-3 min)"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends python3-paraview >/dev/null
fi

python=$(command -v python3 || true)
if [ -z "$python" ]; then
  echo "setup: python3 is needed (for fpm and the output checks)" >&2
  exit 1
fi
pip_missing=()
command -v fpm >/dev/null 2>&1 || pip_missing+=(fpm)
"$python" -c "import h5py" 2>/dev/null || pip_missing+=(h5py)
"$python" -c "import matplotlib" 2>/dev/null || pip_missing+=(matplotlib)   # make study, make figures
"$python" -c "import pytest" 2>/dev/null || pip_missing+=(pytest)           # python/tests (make test)
"$python" -c "import meshio" 2>/dev/null || pip_missing+=(meshio)           # the results.xmf test (make test)
"$python" -c "import scipy" 2>/dev/null || pip_missing+=(scipy)             # visco2d-fit: least_squares (doc/calibration.md)
# VTK's legacy XDMF reader, the one ParaView's "Xdmf Reader" is (scripts/test_xdmf.sh; ~20 s, one wheel)
"$python" -c "import vtkmodules.vtkIOXdmf2" 2>/dev/null || pip_missing+=(vtk)
if [ ${#pip_missing[@]} -gt 0 ]; then
  echo "setup: pip installing ${pip_missing[*]}"
  if ! "$python" -m pip --version >/dev/null 2>&1; then
    sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq python3-pip >/dev/null
  fi
  # Debian's own Python refuses system-wide pip installs (PEP 668) unless told.
  "$python" -m pip install -q "${pip_missing[@]}" 2>/dev/null \
    || "$python" -m pip install -q --break-system-packages "${pip_missing[@]}"
  command -v pyenv >/dev/null 2>&1 && pyenv rehash || true
  hash -r
fi
command -v fpm >/dev/null 2>&1 || { echo "setup: fpm not on PATH after installing it" >&2; exit 1; }
