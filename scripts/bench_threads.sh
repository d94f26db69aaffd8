#!/usr/bin/env bash
# feps over a range of thread counts (issue 28): the BLAS threads of the factorization and the
# OpenMP threads of the element loops both set to T, for each deck, alternating the order of T
# from one repeat to the next so that a drift in the machine's load falls on every T alike.
# Before the runs, the BLAS's dgemm rate at each T (C = A B, n = 4000, best of 3), the yardstick
# of the factorization's GFlop/s. Appends one CSV row per run; prints each run's summary lines.
#
#   bash scripts/bench_threads.sh --decks input/modelB/FE1.dat --threads 1,2 --repeat 5
#   bash scripts/bench_threads.sh --feps ./feps --decks pipe_200k.dat --threads 1,2,4,8,16 \
#        --label openblas-default --csv threads.csv
#   OPENBLAS_CORETYPE=Prescott bash scripts/bench_threads.sh ... --label prescott
#
# The BLAS is whatever libblas.so.3 the loader finds (LD_LIBRARY_PATH picks another one: BLIS
# reads BLIS_NUM_THREADS, which is set too). Options: --feps BIN (default: the release build),
# --decks A,B, --threads LIST, --repeat N (2), --label TEXT, --csv FILE (threads.csv),
# --no-dgemm, --workdir DIR (results/threads, which git ignores).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
feps=""
decks=""
threads="1,2"
repeat=2
label=run
csv=threads.csv
dgemm=1
workdir="$root/results/threads"
while (($#)); do
  case $1 in
    --feps) feps=$2; shift 2 ;;
    --decks) decks=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --label) label=$2; shift 2 ;;
    --csv) csv=$2; shift 2 ;;
    --no-dgemm) dgemm=0; shift ;;
    --workdir) workdir=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
    *) echo "bench_threads: unknown option $1" >&2; exit 2 ;;
  esac
done
[ -n "$decks" ] || { echo "bench_threads: --decks is required" >&2; exit 2; }
if [ -z "$feps" ]; then
  (cd "$root" && fpm build --profile release >/dev/null)
  feps=$root/$(cd "$root" && fpm run --profile release --runner echo 2>/dev/null | tail -n1)
fi
feps=$(cd "$(dirname "$feps")" && pwd)/$(basename "$feps")
case $csv in /*) ;; *) csv=$PWD/$csv ;; esac
abs_decks=()
IFS=, read -ra deck_list <<<"$decks"
for d in "${deck_list[@]}"; do
  [ -f "$d" ] || { echo "bench_threads: no deck $d" >&2; exit 2; }
  abs_decks+=("$(cd "$(dirname "$d")" && pwd)/$(basename "$d")")
done
IFS=, read -ra counts <<<"$threads"
mkdir -p "$workdir"
cd "$workdir"

echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), nproc $(nproc)"
blas=$("$feps" --version | sed -n 2p)
echo "$blas"
# dgemm on the kernels feps runs (feps chooses them at start-up when OpenBLAS's are older)
kernels=$(sed -n 's/^blas OpenBLAS [^,]*, \([A-Za-z0-9]*\) kernels.*/\1/p' <<<"$blas")
core=${OPENBLAS_CORETYPE:-$kernels}

[ -s "$csv" ] || echo "label,deck,threads,repeat,wall_s,assembly_s,factorization_s,solve_s,dgemm_gflops,load" > "$csv"
if ((dgemm)); then
  if [ ! -x dgemm_rate ]; then
    cat > dgemm_rate.c <<'EOF'
/* GFlop/s of C = A B (n x n), best of 3, through the BLAS the loader finds. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
void dgemm_(const char *, const char *, const int *, const int *, const int *, const double *,
            const double *, const int *, const double *, const int *, const double *, double *,
            const int *);
int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 4000;
    double *a = malloc(sizeof(double) * n * n), *b = malloc(sizeof(double) * n * n);
    double *c = malloc(sizeof(double) * n * n), one = 1.0, zero = 0.0, best = 0.0;
    for (long i = 0; i < (long)n * n; i++) { a[i] = (double)(i % 7) - 3.0; b[i] = (double)(i % 5) - 2.0; }
    for (int r = 0; r < 3; r++) {
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        dgemm_("N", "N", &n, &n, &n, &one, a, &n, b, &n, &zero, c, &n);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double s = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
        double rate = 2.0 * n * (double)n * n / s * 1e-9;
        if (rate > best) best = rate;
    }
    printf("%.1f\n", best);
    return 0;
}
EOF
    cc -O2 -o dgemm_rate dgemm_rate.c -lblas
  fi
  for t in "${counts[@]}"; do
    rate=$(OPENBLAS_CORETYPE=$core OPENBLAS_NUM_THREADS=$t BLIS_NUM_THREADS=$t OMP_NUM_THREADS=$t ./dgemm_rate 4000)
    echo "dgemm $label threads $t: $rate GFlop/s"
    echo "$label,dgemm,$t,0,,,,,$rate," >> "$csv"
  done
fi

for ((r = 1; r <= repeat; r++)); do
  order=("${counts[@]}")
  if ((r % 2 == 0)); then
    order=()
    for ((i = ${#counts[@]} - 1; i >= 0; i--)); do order+=("${counts[i]}"); done
  fi
  for deck in "${abs_decks[@]}"; do
    for t in "${order[@]}"; do
      load=$(cut -d' ' -f1 /proc/loadavg)
      out=$(OPENBLAS_NUM_THREADS=$t BLIS_NUM_THREADS=$t "$feps" "$deck" --threads "$t" \
              --output "$workdir/run.h5" 2>&1 | grep -E '^(blas|times|wall time|factor flops)' || true)
      times=$(grep '^times' <<<"$out" || true)
      pick() { sed -n "s/.*$1 *\([0-9.]*\) s.*/\1/p" <<<"$times"; }
      wall=$(sed -n 's/^wall time *\([0-9.]*\) s.*/\1/p' <<<"$out")
      echo "== $label $(basename "$deck") threads $t repeat $r (load $load)"
      echo "$out"
      echo "$label,$(basename "$deck"),$t,$r,$wall,$(pick assembly),$(pick factorization),$(pick solve),,$load" >> "$csv"
    done
  done
done
rm -f "$workdir/run.h5"
