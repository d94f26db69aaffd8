#!/usr/bin/env bash
# Open feps results with ParaView's three XDMF readers ("XDMF Reader", Xdmf3ReaderS, Xdmf3ReaderT)
# under pvbatch and compare every array at every step with the HDF5 file
# (test/reference/check_paraview.py), on four small decks: several stages and steps with
# interface and bar groups, 2D tri6 with a line interface, solids with interfaces, and model B's
# pipe SE1, whose deformed pipe, coloured by the most tensile principal stress, is rendered.
# Installs Debian's paraview and xvfb when pvbatch or xvfb-run is missing (root: apt-get).
# Usage: bash scripts/check_paraview.sh [OUTDIR]   (default: a temporary folder; the PNG is
# OUTDIR/SE1_principal.png). Exit status 0 when every reader shows every array right.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v pvbatch >/dev/null 2>&1 || ! command -v xvfb-run >/dev/null 2>&1; then
  echo "== installing Debian's paraview and xvfb"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq paraview xvfb >/dev/null
fi

# the build `fpm test` made (FEPS=path for another binary)
feps=${FEPS:-}
if [ -z "$feps" ]; then
  fpm build >/dev/null
  feps=$(fpm run --runner echo 2>/dev/null | tail -1)
fi
out=${1:-$(mktemp -d)}
mkdir -p "$out"
for deck in test/data/slide_1dof_support_change.dat test/data/contact_2d.dat \
            test/data/friction_pull.dat input/modelB/SE1.dat; do
  name=$(basename "$deck" .dat)
  "$feps" "$deck" --output "$out/$name.h5" >"$out/$name.log" 2>&1 || { echo "feps $deck failed"; cat "$out/$name.log"; exit 1; }
done
python3 test/reference/check_paraview.py --png "$out/SE1_principal.png" "$out/SE1.xmf" \
  "$out/slide_1dof_support_change.xmf" "$out/contact_2d.xmf" "$out/friction_pull.xmf"
echo "rendered $out/SE1_principal.png"
