#!/usr/bin/env bash
# Benchmark of the feps linear run on pipe-in-soil hex8 meshes (scripts/make_pipe_mesh.py):
# assembly, factorization and solve times (from the feps summary), total wall time and peak
# RSS (/usr/bin/time -v), matrix and factor nonzeros and flops, for CHOLMOD and skyline.
# Writes runs.csv (one row per run), summary.md (medians) and machine.txt into the results
# folder (default results/bench-<date>, which git ignores).
#
#   bash scripts/bench_solvers.sh                          # 10k..1m, both solvers, release build
#   bash scripts/bench_solvers.sh --sizes 10k,50k --repeat 5
#   bash scripts/bench_solvers.sh --sizes 1.1m,1.2m --solvers cholmod --repeat 1
#
# Runs are repeated (--repeat, default 3) only while a case's first run took less than
# --repeat-below seconds (default 60); the solvers alternate within each repetition so that
# their ratio is measured side by side. skyline runs only up to --skyline-max-dofs free DOFs
# (default 250000): its profile grows too fast beyond. A watchdog kills a run whose resident
# memory passes --mem-limit-gib (default 16) and records it as "oom-killed".
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cmdline="bash scripts/bench_solvers.sh $*"

sizes=10k,50k,200k,1m
solvers=cholmod,skyline
repeat=3
repeat_below=60
skyline_max=250000
mem_limit_gib=16
profile=release
feps=""
outdir=""
keep_h5=0

usage() { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; cat <<EOF
options: --sizes LIST (presets of make_pipe_mesh.py: $(python3 "$root/scripts/make_pipe_mesh.py" --help | grep -o '{[^}]*}' | head -1 | tr -d '{}'))
         --solvers LIST   --repeat N   --repeat-below SECONDS   --skyline-max-dofs N
         --mem-limit-gib G   --profile release|debug   --feps EXECUTABLE (skip the build)
         --outdir DIR   --keep-h5
EOF
}

while (($#)); do
  case $1 in
    --sizes) sizes=$2; shift 2 ;;
    --solvers) solvers=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --repeat-below) repeat_below=$2; shift 2 ;;
    --skyline-max-dofs) skyline_max=$2; shift 2 ;;
    --mem-limit-gib) mem_limit_gib=$2; shift 2 ;;
    --profile) profile=$2; shift 2 ;;
    --feps) feps=$2; shift 2 ;;
    --outdir) outdir=$2; shift 2 ;;
    --keep-h5) keep_h5=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "bench_solvers: unknown option $1" >&2; usage >&2; exit 2 ;;
  esac
done

# GNU time for the peak RSS (the shell keyword `time` does not give it).
if [ ! -x /usr/bin/time ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq time
fi

feps_origin="fpm --profile $profile"
[ -z "$feps" ] || feps_origin="given with --feps"
if [ -z "$feps" ]; then
  # The default fpm profile (debug: -O0 and bounds checks) is not what one benchmarks.
  (cd "$root" && fpm build --profile "$profile" >/dev/null) || { echo "bench_solvers: build failed" >&2; exit 1; }
  feps=$root/$(cd "$root" && fpm run --profile "$profile" --runner echo 2>/dev/null | tail -n 1)
fi
feps=$(readlink -f "$feps")      # absolute, as bench_calculix.sh
[ -x "$feps" ] || { echo "bench_solvers: no feps executable at $feps" >&2; exit 1; }

outdir=${outdir:-$root/results/bench-$(date +%Y%m%d-%H%M%S)}
mkdir -p "$outdir/meshes" "$outdir/runs"
outdir=$(cd "$outdir" && pwd)
csv=$outdir/runs.csv

{
  echo "date: $(date -Iseconds)"
  echo "command: $cmdline"
  echo "feps: $feps ($feps_origin)"
  echo "host: $(hostname)"
  echo "nproc: $(nproc)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)"
  echo "kernel: $(uname -r)"
  echo "gfortran: $(gfortran -dumpversion 2>/dev/null || echo '?')"
  echo "openblas: $(dpkg-query -W -f='${Version}' libopenblas0-pthread 2>/dev/null || echo '?')"
  echo "cholmod: $(dpkg-query -W -f='${Version}' libcholmod3 2>/dev/null || echo '?')"
  echo "OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-unset} OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}"
} >"$outdir/machine.txt"

[ -s "$csv" ] || echo "size,dofs,solver,run,status,load1,assembly_s,factorization_s,solve_s,feps_wall_s,elapsed_s,peak_rss_mib,matrix_nnz,factor_nnz,flops,elements" >"$csv"

field() {  # field FILE REGEX AWK-FIELD: a value from the feps summary
  grep -E "$2" "$1" 2>/dev/null | head -n 1 | awk "{print \$$3}" | tr -d ','
}

# Run once under /usr/bin/time -v with a resident-memory watchdog; append a CSV row.
run_case() {  # size deck dofs elements solver run
  local size=$1 deck=$2 dofs=$3 elements=$4 solver=$5 run=$6
  local tag=$outdir/runs/${size}_${solver}_$run
  local limit_kib=$((mem_limit_gib * 1048576)) status=ok load1
  load1=$(cut -d' ' -f1 /proc/loadavg)
  echo "bench: $size ($dofs DOFs) $solver run $run (load $load1) ..." >&2
  /usr/bin/time -v -o "$tag.time" "$feps" "$deck" --solver "$solver" --output "$tag.h5" >"$tag.out" 2>"$tag.err" &
  local tpid=$! child="" rss killed=0
  while kill -0 "$tpid" 2>/dev/null; do
    [ -n "$child" ] || child=$(pgrep -P "$tpid" | head -n 1 || true)
    if [ -n "$child" ]; then
      rss=$(awk '/VmRSS/ {print $2}' "/proc/$child/status" 2>/dev/null || echo 0)
      if [ "${rss:-0}" -gt "$limit_kib" ]; then kill -KILL "$child" 2>/dev/null || true; killed=1; fi
    fi
    sleep 0.5
  done
  local rc=0
  wait "$tpid" || rc=$?
  if ((killed)); then status=oom-killed
  elif ((rc != 0)); then status="failed-rc$rc"; fi
  [ "$keep_h5" -eq 1 ] || rm -f "$tag.h5" "$tag.h5.part" "$tag.xmf"
  local elapsed rss_kib
  elapsed=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s}' "$tag.time")
  rss_kib=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$tag.time")
  local times
  times=$(grep -E '^times' "$tag.out" 2>/dev/null | sed -E 's/.*assembly ([0-9.]+) s, factorization ([0-9.]+) s, solve ([0-9.]+) s.*/\1,\2,\3/')
  [[ $times == *,*,* ]] || times=",,"
  echo "$size,$dofs,$solver,$run,$status,$load1,$times,$(field "$tag.out" '^wall time' 3),${elapsed:-},$(awk -v k="${rss_kib:-0}" 'BEGIN {printf "%.0f", k / 1024}'),$(field "$tag.out" '^matrix nonzeros' 3),$(field "$tag.out" '^factor nonzeros' 3),$(field "$tag.out" '^factor flops' 3),$elements" >>"$csv"
  if [ "$status" = oom-killed ]; then
    echo "bench: $size $solver run $run: killed by the watchdog (resident memory passed $mem_limit_gib GiB)" >&2
  elif [ "$status" != ok ]; then
    echo "bench: $size $solver run $run: $status ($(tail -n 1 "$tag.err" 2>/dev/null))" >&2
  fi
  echo "$elapsed"
}

IFS=, read -ra size_list <<<"$sizes"
IFS=, read -ra solver_list <<<"$solvers"
for size in "${size_list[@]}"; do
  deck=$outdir/meshes/pipe_$size.dat
  counts=$(python3 "$root/scripts/make_pipe_mesh.py" --preset "$size" -o "$deck")
  dofs=$(awk '{print $8}' <<<"$counts")
  elements=$(awk '{print $4}' <<<"$counts")
  active=()
  for solver in "${solver_list[@]}"; do
    if [ "$solver" = skyline ] && [ "$dofs" -gt "$skyline_max" ]; then
      echo "bench: $size: skyline skipped ($dofs DOFs > --skyline-max-dofs $skyline_max)" >&2
      continue
    fi
    active+=("$solver")
  done
  for ((run = 1; run <= repeat; run++)); do
    next=()
    for solver in "${active[@]}"; do
      t=$(run_case "$size" "$deck" "$dofs" "$elements" "$solver" "$run")
      # Repeat only the cases whose first run was short.
      if [ -n "$t" ] && awk -v t="$t" -v m="$repeat_below" 'BEGIN {exit !(t < m)}'; then next+=("$solver"); fi
    done
    ((${#next[@]})) || break
    active=("${next[@]}")
  done
done

python3 - "$csv" "$outdir/summary.md" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
order = {}
for r in rows:
    order.setdefault((r["size"], r["solver"]), []).append(r)

def med(rs, key):
    v = [float(r[key]) for r in rs if r[key] not in ("", None)]
    return statistics.median(v) if v else None

def fmt(x, spec):
    return "-" if x is None else format(x, spec)

out = ["| size | DOFs | elements | solver | runs | assembly s | factorization s | solve s | total wall s |"
       " peak RSS MiB | matrix nnz | factor nnz | GFlop | GFlop/s | status |",
       "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
fact = {}
wall = {}
for (size, solver), rs in order.items():
    ok = [r for r in rs if r["status"] == "ok"]
    st = ", ".join(sorted({r["status"] for r in rs}))
    use = ok or rs
    tf = med(ok, "factorization_s")
    flops = med(ok, "flops")
    gf = flops / 1e9 if flops else None
    rate = gf / tf if gf and tf else None
    fnnz = med(ok, "factor_nnz")
    fact[(size, solver)] = tf
    wall[(size, solver)] = med(ok, "elapsed_s")
    out.append(f"| {size} | {rs[0]['dofs']} | {rs[0]['elements']} | {solver} | {len(ok)}/{len(rs)} | "
               f"{fmt(med(ok, 'assembly_s'), '.2f')} | {fmt(tf, '.2f')} | {fmt(med(ok, 'solve_s'), '.3f')} | "
               f"{fmt(med(ok, 'elapsed_s'), '.2f')} | {fmt(med(use, 'peak_rss_mib'), '.0f')} | "
               f"{fmt(med(ok, 'matrix_nnz'), '.3e')} | {fmt(fnnz, '.3e')} | {fmt(gf, '.1f')} | {fmt(rate, '.2f')} | {st} |")
out += ["", "| size | skyline / CHOLMOD factorization | skyline / CHOLMOD total wall |", "|---|---:|---:|"]
for size in dict.fromkeys(s for s, _ in order):
    a, b = fact.get((size, "skyline")), fact.get((size, "cholmod"))
    c, d = wall.get((size, "skyline")), wall.get((size, "cholmod"))
    if a and b and c and d:
        out.append(f"| {size} | {a / b:.1f} | {c / d:.1f} |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
echo "bench: results in $outdir (runs.csv, summary.md, machine.txt)" >&2
