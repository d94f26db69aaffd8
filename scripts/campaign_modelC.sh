#!/usr/bin/env bash
# Run the 12 cases of thesis model C (chapter 6) and gather Tables 7.3 / 7.4 into one CSV.
#
#   scripts/campaign_modelC.sh [-j JOBS] [-o RESULTS_DIR] [--feps PATH] [--regenerate]
#                              [--cases "C_G300_nu0.1_b0.09 ..."] [--grid "MAKE_MODEL_C OPTIONS"]
#                              [-- extra feps options]
#
# A parametric campaign beyond the thesis's cases: --grid passes its options to
# scripts/make_model_c.py, which writes one deck per combination into RESULTS_DIR/decks, and the
# campaign runs those, e.g.
#   scripts/campaign_modelC.sh -o results/packing_nu --grid "--Gp 600 --nup 0,0.1,0.2,0.3,0.4 --beta 0.18"
# feps is fpm's release build unless --feps names one.
# Each case runs in RESULTS_DIR/<case>/ (default results/modelC) with its HDF5 file and log.txt.
# Resumable: a case whose HDF5 exists and whose log ends with feps's "results" line is not rerun
# (feps writes the HDF5 under a temporary name and renames it only when the run ends well).
# JOBS (default `nproc`) cases run at once; each gets OPENBLAS_NUM_THREADS = nproc / JOBS.
# Extra options after `--` go to every feps run (e.g. -- --method modified-newton-raphson).
# Then scripts/postprocess_model_c.py writes RESULTS_DIR/table.csv (beta*, beta_bar, Z, sigma_max
# per case, with the thesis values beside) and the campaign's wall time is printed.
# Exit status: 0 when every case finished and the table was written; 1 when any case failed or
# is missing (named at the end) or the post-processing failed; 2 for bad arguments or a deck
# that fails feps --check (nothing is run).
set -u
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
JOBS="$(nproc)"
OUT="$ROOT/results/modelC"
FEPS=""
REGEN=0
CASES=""
GRID=""
EXTRA=()
usage() { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; }
while [ $# -gt 0 ]; do
  case "$1" in
    -j|-o|--feps|--cases|--grid)
      [ $# -ge 2 ] || { echo "campaign_modelC: $1 needs a value" >&2; exit 2; } ;;
  esac
  case "$1" in
    -j) JOBS="$2"; shift 2 ;;
    -o) OUT="$2"; shift 2 ;;
    --feps) FEPS="$2"; shift 2 ;;
    --regenerate) REGEN=1; shift ;;
    --cases) CASES="$2"; shift 2 ;;
    --grid) GRID="$2"; shift 2 ;;
    --) shift; EXTRA=("$@"); break ;;
    -h|--help) usage; exit 0 ;;
    *) echo "campaign_modelC: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
case "$JOBS" in
  ''|*[!0-9]*|0) echo "campaign_modelC: -j $JOBS: give a number of cases at once, at least 1" >&2; exit 2 ;;
esac
if [ -n "$FEPS" ]; then
  # a command name (no slash) is looked up on PATH; a relative path is made absolute, since every
  # case runs in its own folder
  case "$FEPS" in */*) ;; *) FEPS="$(command -v -- "$FEPS" || echo "$FEPS")" ;; esac
  { [ -f "$FEPS" ] && [ -x "$FEPS" ]; } || { echo "campaign_modelC: --feps $FEPS is not an executable file" >&2; exit 2; }
  FEPS="$(cd "$(dirname "$FEPS")" && pwd)/$(basename "$FEPS")"
fi
mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"

DECKS="$ROOT/input/modelC"
if [ -n "$GRID" ]; then
  # the grid's decks live with its results; rewriting them leaves finished cases finished
  # (same parameters, same deck) and adds the new combinations
  DECKS="$OUT/decks"
  # shellcheck disable=SC2086  # GRID is a list of options
  python3 "$ROOT/scripts/make_model_c.py" --outdir "$DECKS" $GRID || exit 2
elif [ "$REGEN" = 1 ] || [ ! -d "$DECKS" ]; then
  python3 "$ROOT/scripts/make_model_c.py" --outdir "$DECKS" || exit 1
fi
if [ -z "$FEPS" ]; then
  # the release build (-O3): 2-3x faster than fpm's default debug build (bounds checks, -O0)
  (cd "$ROOT" && fpm build --profile release > /dev/null 2>&1) || { echo "campaign_modelC: fpm build failed" >&2; exit 1; }
  FEPS="$ROOT/$(cd "$ROOT" && fpm run --profile release --runner echo 2>/dev/null | tail -n1)"
fi
[ -x "$FEPS" ] || { echo "campaign_modelC: no feps executable at $FEPS" >&2; exit 1; }

if [ -z "$CASES" ]; then
  CASES="$(cd "$DECKS" && ls C_*.dat | sed 's/\.dat$//')"
fi

# Check every deck first (feps --check: input, model, one factorization per stage, about a
# second each): a bad deck stops the campaign before any case runs.
nbad=0
for case in $CASES; do
  if ! msg=$("$FEPS" "$DECKS/$case.dat" --check --quiet "${EXTRA[@]}" 2>&1); then
    echo "campaign_modelC: $msg" >&2
    nbad=$((nbad + 1))
  fi
done
[ "$nbad" -eq 0 ] || { echo "campaign_modelC: $nbad deck(s) failed feps --check; nothing was run" >&2; exit 2; }

THREADS=$(( $(nproc) / JOBS ))
[ "$THREADS" -ge 1 ] || THREADS=1

done_ok() {   # the case's HDF5 exists and its log ends well
  local dir="$OUT/$1"
  [ -f "$dir/$1.h5" ] && [ -f "$dir/log.txt" ] && tail -n 1 "$dir/log.txt" | grep -q '^results '
}

run_case() {
  local case="$1" dir="$OUT/$1" t0 t1 rc
  mkdir -p "$dir"
  t0=$(date +%s.%N)
  ( cd "$dir" && OPENBLAS_NUM_THREADS=$THREADS OMP_NUM_THREADS=$THREADS \
      "$FEPS" "$DECKS/$case.dat" --output "$case.h5" "${EXTRA[@]}" > log.txt 2>&1 )
  rc=$?
  t1=$(date +%s.%N)
  printf '%s %.1f s exit %d\n' "$case" "$(echo "$t1 - $t0" | bc)" "$rc" | tee "$dir/time.txt"
  if [ "$rc" -ne 0 ]; then
    echo "  $case failed: $(tail -n 2 "$dir/log.txt" | tr '\n' ' ')"
  fi
}

START=$(date +%s.%N)
echo "model C campaign: $(echo $CASES | wc -w) cases, $JOBS at once ($THREADS BLAS threads each), feps $FEPS"
for case in $CASES; do
  if done_ok "$case"; then
    echo "$case: done already (skipped)"
    continue
  fi
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do
    wait -n
  done
  run_case "$case" &
done
wait
END=$(date +%s.%N)
printf 'campaign wall time %.1f s\n' "$(echo "$END - $START" | bc)"

prc=0
python3 "$ROOT/scripts/postprocess_model_c.py" --table "$OUT" --csv "$OUT/table.csv" || prc=$?
[ "$prc" -eq 0 ] || echo "campaign_modelC: postprocess_model_c.py failed (exit $prc)" >&2
nfail=0
for case in $CASES; do done_ok "$case" || { echo "campaign_modelC: missing or failed: $case" >&2; nfail=$((nfail + 1)); }; done
[ "$nfail" -eq 0 ] && [ "$prc" -eq 0 ]
