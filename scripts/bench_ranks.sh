#!/usr/bin/env bash
# The MPI build over a range of ranks (issue 29): `mpirun -np N feps DECK --solver mumps` for each
# N and deck, the order of N alternating from one repeat to the next so that a drift in the
# machine's load falls on every N alike. Prints and appends to a CSV each run's wall time and
# what feps's summary says of each rank: its elements, its time assembling and updating them,
# its MUMPS factorization memory and time, its peak resident memory. One BLAS thread a rank.
#
#   bash scripts/bench_ranks.sh --decks input/modelB/FE1.dat --ranks 1,2,4 --repeat 3
#
# Options: --feps BIN (default: scripts/build_mpi.sh's build), --decks A,B, --ranks LIST (1,2),
# --repeat N (1), --csv FILE (ranks.csv), --workdir DIR (results/ranks, which git ignores).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
feps=""
decks=""
ranks="1,2"
repeat=1
csv=ranks.csv
workdir="$root/results/ranks"
while (($#)); do
  case $1 in
    --feps) feps=$2; shift 2 ;;
    --decks) decks=$2; shift 2 ;;
    --ranks) ranks=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --csv) csv=$2; shift 2 ;;
    --workdir) workdir=$2; shift 2 ;;
    *) echo "bench_ranks: unknown option $1" >&2; exit 2 ;;
  esac
done
[ -n "$decks" ] || { echo "bench_ranks: --decks is needed" >&2; exit 2; }
[ -n "$feps" ] || feps=$(bash "$root/scripts/build_mpi.sh")
mkdir -p "$workdir"
mpi=(mpirun --oversubscribe -np)
[ "$(id -u)" -eq 0 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np)
[ -e "$csv" ] || echo "date,deck,ranks,wall_s,rank_elements,rank_element_s,rank_factor_mb,rank_factor_s,rank_peak_mb,load1" >"$csv"
IFS=, read -r -a deck_list <<<"$decks"
IFS=, read -r -a rank_list <<<"$ranks"
for ((k = 1; k <= repeat; k++)); do
  order=("${rank_list[@]}")
  if ((k % 2 == 0)); then order=(); for ((i = ${#rank_list[@]} - 1; i >= 0; i--)); do order+=("${rank_list[i]}"); done; fi
  for deck in "${deck_list[@]}"; do
    for np in "${order[@]}"; do
      out="$workdir/$(basename "$deck" .dat).$np.h5"
      load=$(cut -d' ' -f1 /proc/loadavg)
      start=$(date +%s.%N)
      OPENBLAS_NUM_THREADS=1 "${mpi[@]}" "$np" "$feps" "$deck" --quiet --solver mumps --output "$out"
      wall=$(echo "$(date +%s.%N) - $start" | bc)
      row=$(python3 - "$out" <<'PY'
import sys, h5py
s = h5py.File(sys.argv[1], 'r')['summary'].attrs
def join(key, fmt):
    return ' '.join(fmt % v for v in s[key]) if key in s else ''
print(','.join([join('rank_elements', '%d'), join('rank_element_time', '%.2f'), join('rank_memory_mb', '%.0f'),
                join('rank_factorization_time', '%.2f'), join('rank_peak_memory_mb', '%.0f')]))
PY
)
      line="$(date -u +%FT%TZ),$(basename "$deck"),$np,$(printf %.2f "$wall"),$row,$load"
      echo "$line" | tee -a "$csv"
    done
  done
done
