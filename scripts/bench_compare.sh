#!/usr/bin/env bash
# Two feps builds side by side: each deck run by OLD and NEW alternately, REPEAT times each, and
# the median wall time of each with their ratio (docs/performance.md: a refactoring may not slow
# FE1 or the 200k mesh by more than 3%). The machine is shared: alternating runs see the same load.
#
#   bash scripts/bench_compare.sh OLD_FEPS NEW_FEPS [--repeat N] [--args "FEPS OPTIONS"]
#        [--new-args "FEPS OPTIONS"] DECK [DECK ...]
#
# --args gives both builds the same options (e.g. "--threads 2"); --new-args gives NEW more, so
# that one build can be compared with itself under an option (e.g. "--mixed-precision").
# Prints one line per deck: deck, median old (s), median new (s), new / old, and the load average.
set -euo pipefail
usage() { echo "usage: bash scripts/bench_compare.sh OLD_FEPS NEW_FEPS [--repeat N] [--args \"FEPS OPTIONS\"] [--new-args \"FEPS OPTIONS\"] DECK [DECK ...]" >&2; exit 2; }
[ $# -ge 3 ] || usage
old=$1 new=$2; shift 2
repeat=5
args=()
new_args=()
while [ "${1:-}" = --repeat ] || [ "${1:-}" = --args ] || [ "${1:-}" = --new-args ]; do
  [ $# -ge 2 ] || usage
  case $1 in
    --repeat) repeat=$2 ;;
    --args) read -ra args <<<"$2" ;;
    *) read -ra new_args <<<"$2" ;;
  esac
  shift 2
done
[[ "$repeat" =~ ^[1-9][0-9]*$ ]] || usage
for f in "$old" "$new"; do [ -x "$f" ] || { echo "bench_compare.sh: $f is not an executable" >&2; exit 2; }; done
[ $# -ge 1 ] || usage
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
for deck in "$@"; do [ -f "$deck" ] || { echo "bench_compare.sh: no deck $deck" >&2; exit 2; }; done
printf '%-40s %10s %10s %8s %s\n' deck old_s new_s new/old load
for deck in "$@"; do
  : >"$tmp/old"; : >"$tmp/new"
  for ((i = 1; i <= repeat; i++)); do
    for which in old new; do
      exe=$old; more=()
      [ $which = new ] && { exe=$new; more=(${new_args[@]+"${new_args[@]}"}); }
      s=$(date +%s.%N)
      "$exe" "$deck" ${args[@]+"${args[@]}"} ${more[@]+"${more[@]}"} --quiet --output "$tmp/r.h5" >/dev/null 2>&1 || { echo "bench_compare.sh: $exe $deck failed" >&2; exit 1; }
      e=$(date +%s.%N)
      awk -v s="$s" -v e="$e" 'BEGIN {print e - s}' >>"$tmp/$which"
    done
  done
  mo=$(median <"$tmp/old"); mn=$(median <"$tmp/new")
  printf '%-40s %10.2f %10.2f %8.4f %s\n' "$deck" "$mo" "$mn" "$(awk -v a="$mn" -v b="$mo" 'BEGIN {print a / b}')" "$(cut -d' ' -f1-3 /proc/loadavg)"
done
