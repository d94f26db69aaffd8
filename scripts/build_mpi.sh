#!/usr/bin/env bash
# The MPI build of feps (issue 29): MUMPS over MPI behind `--solver mumps`, run as
# `mpirun -np N feps DECK --solver mumps`. Needs `bash scripts/setup.sh --mpi` (Debian's MUMPS
# 5.5 and OpenMPI 4.1). Builds a copy of the sources under build/mpi/ (fpm keys its C objects
# by profile, not by C flags, so building in place would mix MPI objects into the default
# build) and prints the program's path.
#
#   feps_mpi=$(bash scripts/build_mpi.sh) && mpirun -np 2 "$feps_mpi" input/modelB/SE1.dat --solver mumps
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tree=$root/build/mpi/tree
mkdir -p "$tree"
for d in src app test; do rm -rf "${tree:?}/$d"; cp -a "$root/$d" "$tree/$d"; done
cp "$root/fpm.toml" "$tree/fpm.toml"
include=$(pkg-config --variable=includedir ompi-c 2>/dev/null || echo /usr/lib/x86_64-linux-gnu/openmpi/include)
flags=(--profile release --c-flag "-DFEPS_MPI -I$include"
       --link-flag "-Wl,--no-as-needed -ldmumps -lmumps_common -lmpi")
cd "$tree"
fpm build "${flags[@]}" >&2
echo "$tree/$(fpm run "${flags[@]}" --runner echo 2>/dev/null | tail -n 1)"
