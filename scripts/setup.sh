#!/usr/bin/env bash
# Idempotent set-up of everything feps needs on a fresh Debian bookworm machine (run as root).
# Debian: compiler, BLAS/LAPACK, SuiteSparse (CHOLMOD), METIS, HDF5 with Fortran bindings.
# PyPI: fpm (the Fortran package manager), numpy, h5py, matplotlib, vtk (only for
# test/reference/check_xdmf_vtk.py: the XDMF files read as ParaView reads them), meshio (5.3.5
# checked; test/reference/check_meshio.py reads the meshio file with it, and
# scripts/import_mesh.py reads gmsh meshes through it) and gmsh (test/cli/check_import.py
# meshes a pipe with it; its library needs the X and GLU libraries below).
# Debian's calculix-ccx-test: CalculiX's published test examples, which check_import.py imports.
# --mpi: also MUMPS 5.5 and OpenMPI 4.1 from Debian, for the MPI build (scripts/build_mpi.sh).
set -euo pipefail
mpi=0
for a in "$@"; do
  case $a in
    --mpi) mpi=1 ;;
    *) echo "setup: unknown option $a (--mpi)" >&2; exit 2 ;;
  esac
done

debs=(gfortran libopenblas-dev liblapack-dev libsuitesparse-dev libmetis-dev
      libhdf5-dev hdf5-tools pkg-config hyperfine calculix-ccx-test
      libglu1-mesa libxrender1 libxcursor1 libxft2 libxinerama1)
((mpi)) && debs+=(libmumps-dev libopenmpi-dev openmpi-bin)

missing=()
for p in "${debs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

py=(fpm numpy h5py matplotlib vtk meshio gmsh)
need_py=()
for p in "${py[@]}"; do
  python3 -m pip show -q "$p" >/dev/null 2>&1 || need_py+=("$p")
done
if ((${#need_py[@]})); then
  python3 -m pip install -q "${need_py[@]}"
fi
# pyenv shims: make sure a newly installed fpm is on PATH.
command -v pyenv >/dev/null 2>&1 && pyenv rehash || true
command -v fpm >/dev/null || { echo "setup: fpm not on PATH after install" >&2; exit 1; }
echo "setup: toolchain ready ($(gfortran -dumpversion | head -1), fpm $(fpm --version 2>/dev/null | head -1 | awk '{print $2}'))"
