#!/usr/bin/env bash
# feps against CalculiX (ccx 2.20 from Debian, SPOOLES) on the same linear model: the same mesh
# (exported from feps's own HDF5 mesh by scripts/export_inp.py), materials, supports and nodal
# loads. For each size it alternates feps and ccx runs (feps, ccx, feps, ...) so that both see
# about the same machine load, compares the displacements node by node, and measures this
# machine's dgemm rate (the system BLAS that CHOLMOD links, 2 threads) to say what fraction
# of it feps's CHOLMOD factorization reaches (factor flops / factorization time).
#
#   bash scripts/bench_calculix.sh                              # SE1 (13k DOFs) and the 200k mesh
#   bash scripts/bench_calculix.sh --sizes se1 --repeat 5
#   bash scripts/bench_calculix.sh --sizes 200k --feps-only 1m  # + feps alone on the 1M mesh
#
# Sizes: `se1` is input/modelB/SE1.dat (model B, elastic soil, graded hex8 mesh); `se1-hex20`,
# `se1-wedge6`, `se1-wedge15`, `se1-tet4` and `se1-tet10` the same mesh in those elements
# (scripts/make_model_b.py --element; C3D20, C3D6, C3D15, C3D4, C3D10 in ccx); other names are
# presets of scripts/make_pipe_mesh.py
# (uniform model-B-like meshes; 200k is the issue's).
# A case is run --repeat times (default 3) if its first ccx run took less than --long seconds
# (default 20), otherwise --repeat-long times (default 2). Threads (--threads, default 2): feps
# gets --threads N (its element loops and solves; its factorization at most N BLAS threads),
# ccx OMP_NUM_THREADS=N (SPOOLES and its assembly). Writes runs.csv, compare_<size>.txt, dgemm.txt, summary.md and machine.txt into
# the results folder (default results/calculix-<date>, which git ignores).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cmdline="bash scripts/bench_calculix.sh $*"

sizes=se1,200k
feps_only=""
repeat=3
repeat_long=2
long=20
threads=2
dgemm_n=4000
dgemm_reps=5
profile=release
feps=""
outdir=""
keep=0

usage() { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; cat <<EOF
options: --sizes LIST   --feps-only LIST (sizes run with feps alone, for the dgemm fraction)
         --repeat N   --repeat-long N   --long SECONDS   --threads N (default 2)
         --dgemm-n N (matrix order, default 4000)   --dgemm-reps N (default 5)
         --profile release|debug   --feps EXECUTABLE (skip the build)   --outdir DIR   --keep
EOF
}

while (($#)); do
  case $1 in
    --sizes) sizes=$2; shift 2 ;;
    --feps-only) feps_only=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --repeat-long) repeat_long=$2; shift 2 ;;
    --long) long=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --dgemm-n) dgemm_n=$2; shift 2 ;;
    --dgemm-reps) dgemm_reps=$2; shift 2 ;;
    --profile) profile=$2; shift 2 ;;
    --feps) feps=$2; shift 2 ;;
    --outdir) outdir=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "bench_calculix: unknown option $1" >&2; usage >&2; exit 2 ;;
  esac
done

# CalculiX and GNU time (for the peak RSS) from Debian when missing.
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
missing=()
command -v ccx >/dev/null || missing+=(calculix-ccx)
[ -x /usr/bin/time ] || missing+=(time)
if ((${#missing[@]})); then
  echo "bench_calculix: installing ${missing[*]}" >&2
  $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}"
fi

if [ -z "$feps" ]; then
  # The default fpm profile (debug: -O0 and bounds checks) is not what one benchmarks.
  (cd "$root" && fpm build --profile "$profile" >/dev/null) || { echo "bench_calculix: build failed" >&2; exit 1; }
  feps=$root/$(cd "$root" && fpm run --profile "$profile" --runner echo 2>/dev/null | tail -n 1)
fi
feps=$(readlink -f "$feps")
[ -x "$feps" ] || { echo "bench_calculix: no feps executable at $feps" >&2; exit 1; }

outdir=${outdir:-$root/results/calculix-$(date +%Y%m%d-%H%M%S)}
mkdir -p "$outdir/runs"
outdir=$(cd "$outdir" && pwd)
csv=$outdir/runs.csv

export OPENBLAS_NUM_THREADS=$threads OMP_NUM_THREADS=$threads
{
  echo "date: $(date -Iseconds)"
  echo "command: $cmdline"
  echo "feps: $feps (profile $profile)"
  echo "ccx: $(command -v ccx) $(dpkg-query -W -f='${Version}' calculix-ccx 2>/dev/null || echo '?')," \
       "SPOOLES $(dpkg-query -W -f='${Version}' libspooles2.2 2>/dev/null || echo '?')"
  echo "host: $(hostname)"
  echo "nproc: $(nproc)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)"
  echo "kernel: $(uname -r)"
  echo "openblas: $(dpkg-query -W -f='${Version}' libopenblas0-pthread 2>/dev/null || echo '?')" \
       "(core: $(OPENBLAS_VERBOSE=2 "$feps" --help 2>&1 | sed -n 's/^Core: //p' | head -n 1))"
  echo "cholmod: $(dpkg-query -W -f='${Version}' libcholmod3 2>/dev/null || echo '?')"
  echo "OPENBLAS_NUM_THREADS=$OPENBLAS_NUM_THREADS OMP_NUM_THREADS=$OMP_NUM_THREADS"
} >"$outdir/machine.txt"

[ -s "$csv" ] || echo "size,dofs,program,run,status,load1,elapsed_s,user_s,sys_s,peak_rss_mib,assembly_s,factorization_s,solve_s,factor_flops" >"$csv"

# Seconds from /usr/bin/time -v's fields.
time_field() {  # file label
  awk -F': ' -v k="$2" 'index($0, k) {v = $2; n = split(v, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s; exit}' "$1"
}
rss_mib() { awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$1"; }

run_feps() {  # size deck run -> prints the elapsed seconds; keeps the HDF5 of run 1
  local size=$1 deck=$2 run=$3 tag=$outdir/runs/${1}_feps_$3 load1 rc=0 status=ok
  load1=$(cut -d' ' -f1 /proc/loadavg)
  echo "bench: $size feps run $run (load $load1) ..." >&2
  /usr/bin/time -v -o "$tag.time" "$feps" "$deck" --solver cholmod --threads "$threads" --output "$tag.h5" \
    >"$tag.out" 2>"$tag.err" || rc=$?
  ((rc == 0)) || status="failed-rc$rc"
  local times dofs flops
  times=$(grep -E '^times' "$tag.out" | sed -E 's/.*assembly ([0-9.]+) s, factorization ([0-9.]+) s, solve ([0-9.]+) s.*/\1,\2,\3/' || true)
  [[ $times == *,*,* ]] || times=",,"
  dofs=$(awk '/^dofs/ {print $2}' "$tag.out")
  flops=$(awk '/^factor flops/ {print $3}' "$tag.out")
  echo "$size,$dofs,feps,$run,$status,$load1,$(time_field "$tag.time" 'Elapsed (wall clock)'),$(time_field "$tag.time" 'User time'),$(time_field "$tag.time" 'System time'),$(rss_mib "$tag.time"),$times,$flops" >>"$csv"
  [ "$status" = ok ] || { echo "bench: feps failed: $(tail -n 1 "$tag.err")" >&2; exit 1; }
  ((run == 1 || keep)) || rm -f "$tag.h5" "$tag.xmf"
  time_field "$tag.time" 'Elapsed (wall clock)'
}

run_ccx() {  # size inp run dofs -> prints the elapsed seconds
  local size=$1 inp=$2 run=$3 dofs=$4 dir=$outdir/runs/${1}_ccx_$3 load1 rc=0 status=ok
  mkdir -p "$dir"
  cp "$inp" "$dir/model.inp"
  load1=$(cut -d' ' -f1 /proc/loadavg)
  echo "bench: $size ccx run $run (load $load1) ..." >&2
  (cd "$dir" && /usr/bin/time -v -o ccx.time ccx -i model >ccx.out 2>ccx.err) || rc=$?
  ((rc == 0)) && grep -q 'Job finished' "$dir/ccx.out" || status="failed-rc$rc"
  echo "$size,$dofs,ccx,$run,$status,$load1,$(time_field "$dir/ccx.time" 'Elapsed (wall clock)'),$(time_field "$dir/ccx.time" 'User time'),$(time_field "$dir/ccx.time" 'System time'),$(rss_mib "$dir/ccx.time"),,,," >>"$csv"
  [ "$status" = ok ] || { echo "bench: ccx failed: $(grep -m1 ERROR "$dir/ccx.out")" >&2; exit 1; }
  rm -f "$dir/model.inp" "$dir/model.frd"
  ((run == 1 || keep)) || rm -f "$dir/model.dat"
  time_field "$dir/ccx.time" 'Elapsed (wall clock)'
}

# Node-by-node comparison of feps's HDF5 displacements and ccx's printed ones.
compare() {  # h5 ccx.dat out
  python3 - "$@" <<'PY'
import sys
import h5py
import numpy as np

h5, dat, out = sys.argv[1:4]
u = h5py.File(h5, "r")["steps/0001/displacement"][...]
rows, on = [], False
for line in open(dat):
    if line.lstrip().startswith("displacements"):
        on = True
        continue
    if on:
        p = line.split()
        if len(p) == 4:
            rows.append(p)
nodes = np.array([int(r[0]) for r in rows])
text = np.array([r[1:] for r in rows])
uc = np.zeros_like(u)
uc[nodes - 1] = text.astype(float)
if len(nodes) != len(u):
    sys.exit(f"compare: ccx printed {len(nodes)} nodes, feps has {len(u)}")
d = np.abs(u - uc)
umax = np.abs(u).max()
i, k = np.unravel_index(d.argmax(), d.shape)
# ccx prints 7 significant digits (E13.6): print feps's values the same way.
same = text == np.array([[f"{v:.6E}" for v in row] for row in u[nodes - 1]])
uf = u[nodes - 1]
unit = 10.0 ** (np.floor(np.log10(np.maximum(np.abs(uf), 1e-300))) - 6)
last_digit = (~same) & (np.abs(uf - text.astype(float)) <= 1.0000001 * unit)
rest = (~same) & (~last_digit)
rest_max = (np.abs(uf - text.astype(float))[rest].max() / umax) if rest.any() else 0.0
lines = [
    f"nodes {len(u)}, values {u.size}",
    f"max |u| feps {umax:.9e}, ccx {np.abs(uc).max():.9e} (largest component)",
    f"max |u_feps - u_ccx| {d.max():.3e} at node {i + 1} component {'xyz'[k]}",
    f"relative max |u_feps - u_ccx| / max |u| {d.max() / umax:.3e}",
    f"printed as ccx prints (7 digits): identical {same.sum()}, one unit apart in the 7th digit"
    f" {last_digit.sum()}, further apart {rest.sum()} (all within {rest_max:.1e} max|u|: values near zero)",
    f"equal to 1e-6 relative: {'yes' if d.max() / umax <= 1e-6 else 'NO'}",
]
open(out, "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
}

# CalculiX's equations applied to feps's solution: every DOF prescribed to feps's displacement,
# ccx prints K u as nodal forces (RF), and at the free DOFs these must equal the exported loads.
# RF of small magnitude is printed to 7 digits of itself, so the residual is seen far below the
# 7-digit limit of the displacement comparison.
residual_check() {  # h5 inp dir out
  local h5=$1 inp=$2 dir=$3 out=$4
  mkdir -p "$dir"
  python3 - write "$h5" "$inp" "$dir/residual.inp" <<'PY'
import sys
import h5py
_, mode, h5, inp, res = sys.argv
u = h5py.File(h5, "r")["steps/0001/displacement"][...]
text = open(inp).read()
with open(res, "w") as out:
    out.write(text[:text.index("*BOUNDARY")] + "*BOUNDARY\n")
    for n, row in enumerate(u, start=1):
        for d in range(3):
            out.write(f"{n}, {d + 1}, {d + 1}, {row[d]:.13e}\n")
    out.write("*STEP\n*STATIC, SOLVER=SPOOLES\n*NODE PRINT, NSET=NALL\nRF\n*END STEP\n")
PY
  (cd "$dir" && ccx -i residual >residual.out 2>&1) || { echo "bench: ccx residual run failed" >&2; exit 1; }
  python3 - "$h5" "$inp" "$dir/residual.dat" "$out" <<'PY'
import sys
import h5py
import numpy as np
h5, inp, dat, out = sys.argv[1:5]
h = h5py.File(h5, "r")
u = h["steps/0001/displacement"][...]
reaction = h["steps/0001/reaction"][...]
rf = np.zeros_like(u)
on = False
for line in open(dat):
    if line.lstrip().startswith("forces"):
        on = True
        continue
    p = line.split()
    if on and len(p) == 4:
        rf[int(p[0]) - 1] = [float(x) for x in p[1:]]
f = np.zeros_like(u)
fixed = np.zeros(u.shape, dtype=bool)
section = None
for line in open(inp):
    if line.startswith("*"):
        section = line.split(",")[0].strip().upper()
        continue
    p = [x.strip() for x in line.split(",")]
    if section == "*CLOAD":
        f[int(p[0]) - 1, int(p[1]) - 1] += float(p[2])
    elif section == "*BOUNDARY":
        fixed[int(p[0]) - 1, int(p[1]) - 1] = True
# Nodes of no element (DATAIN lattice points a hex20 mesh skips) have no equations in ccx.
used = np.zeros(len(u), dtype=bool)
for g in h["mesh/groups"].values():
    used[g["connectivity"][...].ravel() - 1] = True
free, loaded = ~fixed & used[:, None], f != 0
fmax = np.abs(f).max()
r = np.abs(rf - f)
lines = [
    f"residual of feps's u in CalculiX's equations, max |K_ccx u_feps - f| / max |f| (max |f| = {fmax:.6g} N):",
    f"  free DOFs without load: {r[free & ~loaded].max() / fmax:.2e} ({(free & ~loaded).sum()} DOFs)",
    f"  loaded free DOFs: {r[free & loaded].max() / fmax:.2e} ({(free & loaded).sum()} DOFs; 7-digit print of RF)",
    f"  reactions, max |RF_ccx - f - reaction_feps| / max |reaction|: "
    f"{np.abs(rf - f - reaction)[fixed].max() / np.abs(reaction).max():.2e} (7-digit print of RF)",
]
open(out, "a").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
  rm -f "$dir/residual.inp" "$dir/residual.dat" "$dir/residual.frd"
}

# This machine's dgemm rate with the BLAS that CHOLMOD uses (libblas.so.3 -> OpenBLAS).
dgemm_rate() {
  cat >"$outdir/dgemm_rate.c" <<'EOF'
/* dgemm rate of the system BLAS: C = A B with n x n doubles, wall and process CPU time. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <sys/resource.h>
void dgemm_(const char *, const char *, const int *, const int *, const int *, const double *,
            const double *, const int *, const double *, const int *, const double *, double *, const int *);
static double wall(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
static double cpu(void) {
  struct rusage r; getrusage(RUSAGE_SELF, &r);
  return r.ru_utime.tv_sec + 1e-6 * r.ru_utime.tv_usec + r.ru_stime.tv_sec + 1e-6 * r.ru_stime.tv_usec;
}
int main(int argc, char **argv) {
  int n = argc > 1 ? atoi(argv[1]) : 4000, reps = argc > 2 ? atoi(argv[2]) : 5;
  double *a = malloc(sizeof(double) * n * n), *b = malloc(sizeof(double) * n * n), *c = malloc(sizeof(double) * n * n);
  double one = 1.0, zero = 0.0, flops = 2.0 * n * (double)n * n;
  if (!a || !b || !c) return 1;
  for (long i = 0; i < (long)n * n; i++) { a[i] = (double)(i % 17) / 17.0 - 0.5; b[i] = (double)(i % 13) / 13.0 - 0.5; }
  dgemm_("N", "N", &n, &n, &n, &one, a, &n, b, &n, &zero, c, &n);  /* warm-up: threads, pages */
  for (int r = 0; r < reps; r++) {
    double w0 = wall(), c0 = cpu();
    dgemm_("N", "N", &n, &n, &n, &one, a, &n, b, &n, &zero, c, &n);
    double w = wall() - w0, t = cpu() - c0;
    printf("dgemm n %d run %d wall %.3f s cpu %.3f s rate %.2f GFlop/s per-cpu-second %.2f GFlop/s\n",
           n, r + 1, w, t, flops / w / 1e9, flops / t / 1e9);
  }
  free(a); free(b); free(c);
  return 0;
}
EOF
  cc -O2 -o "$outdir/dgemm_rate" "$outdir/dgemm_rate.c" -lblas
  echo "bench: dgemm n $dgemm_n with $threads threads (load $(cut -d' ' -f1 /proc/loadavg)) ..." >&2
  {
    echo "load1 before: $(cut -d' ' -f1 /proc/loadavg)"
    OPENBLAS_NUM_THREADS=$threads "$outdir/dgemm_rate" "$dgemm_n" "$dgemm_reps"
    echo "load1 after: $(cut -d' ' -f1 /proc/loadavg)"
  } >"$outdir/dgemm.txt"
}

deck_of() {  # size -> deck path (writes the pipe meshes)
  if [ "$1" = se1 ]; then
    echo "$root/input/modelB/SE1.dat"
  elif [[ "$1" =~ ^se1-(hex20|wedge6|wedge15|tet4|tet10)$ ]]; then
    mkdir -p "$outdir/meshes"
    python3 "$root/scripts/make_model_b.py" --outdir "$outdir/meshes" --cases SE1 --element "${BASH_REMATCH[1]}" >/dev/null
    echo "$outdir/meshes/SE1_${BASH_REMATCH[1]}_r1.dat"
  else
    [ -f "$root/scripts/make_pipe_mesh.py" ] || { echo "bench_calculix: scripts/make_pipe_mesh.py is missing" >&2; exit 1; }
    mkdir -p "$outdir/meshes"
    python3 "$root/scripts/make_pipe_mesh.py" --preset "$1" -o "$outdir/meshes/pipe_$1.dat" >/dev/null
    echo "$outdir/meshes/pipe_$1.dat"
  fi
}

dgemm_rate

IFS=, read -ra size_list <<<"$sizes"
for size in "${size_list[@]}"; do
  deck=$(deck_of "$size")
  run_feps "$size" "$deck" 1 >/dev/null
  dofs=$(awk '/^dofs/ {print $2}' "$outdir/runs/${size}_feps_1.out")
  inp=$outdir/runs/${size}.inp
  python3 "$root/scripts/export_inp.py" "$outdir/runs/${size}_feps_1.h5" -o "$inp" >&2
  t=$(run_ccx "$size" "$inp" 1 "$dofs")
  compare "$outdir/runs/${size}_feps_1.h5" "$outdir/runs/${size}_ccx_1/model.dat" "$outdir/compare_$size.txt" >&2
  residual_check "$outdir/runs/${size}_feps_1.h5" "$inp" "$outdir/runs/${size}_residual" "$outdir/compare_$size.txt" >&2
  n=$repeat
  awk -v t="$t" -v l="$long" 'BEGIN {exit !(t >= l)}' && n=$repeat_long
  for ((run = 2; run <= n; run++)); do
    run_feps "$size" "$deck" "$run" >/dev/null
    run_ccx "$size" "$inp" "$run" "$dofs" >/dev/null
  done
  ((keep)) || rm -f "$inp"
done

if [ -n "$feps_only" ]; then
  IFS=, read -ra only_list <<<"$feps_only"
  for size in "${only_list[@]}"; do
    run_feps "$size" "$(deck_of "$size")" 1 >/dev/null
    ((keep)) || rm -f "$outdir/runs/${size}_feps_1.h5" "$outdir/runs/${size}_feps_1.xmf"
  done
fi

python3 - "$csv" "$outdir" <<'PY'
import csv, os, re, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
outdir = sys.argv[2]

def med(rs, key):
    v = [float(r[key]) for r in rs if r[key] not in ("", None)]
    return statistics.median(v) if v else None

def fmt(x, spec):
    return "-" if x is None else format(x, spec)

dg = [float(m.group(1)) for m in re.finditer(r" rate ([0-9.]+) GFlop/s", open(os.path.join(outdir, "dgemm.txt")).read())]
dg_cpu = [float(m.group(1)) for m in re.finditer(r"per-cpu-second ([0-9.]+)", open(os.path.join(outdir, "dgemm.txt")).read())]
best = max(dg)
out = [f"dgemm (system OpenBLAS, {os.environ.get('OPENBLAS_NUM_THREADS')} threads): best {best:.1f} GFlop/s, "
       f"median {statistics.median(dg):.1f}; per CPU-second best {max(dg_cpu):.1f}", ""]
out += ["| size | DOFs | program | runs | load1 | wall s | user+sys s | peak RSS MiB | factorization s | GFlop | GFlop/s | of dgemm best |",
        "|---|---:|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
groups = {}
for r in rows:
    groups.setdefault((r["size"], r["program"]), []).append(r)
walls = {}
for (size, prog), rs in groups.items():
    ok = [r for r in rs if r["status"] == "ok"]
    loads = [float(r["load1"]) for r in rs]
    w = med(ok, "elapsed_s")
    walls[(size, prog)] = w
    cpu = statistics.median([float(r["user_s"]) + float(r["sys_s"]) for r in ok]) if ok else None
    tf = med(ok, "factorization_s")
    fl = med(ok, "factor_flops")
    rate = fl / 1e9 / tf if fl and tf else None
    out.append(f"| {size} | {rs[0]['dofs']} | {prog} | {len(ok)} | {min(loads):.1f}-{max(loads):.1f} | {fmt(w, '.2f')} | "
               f"{fmt(cpu, '.2f')} | {fmt(med(ok, 'peak_rss_mib'), '.0f')} | {fmt(tf, '.2f')} | "
               f"{fmt(fl / 1e9 if fl else None, '.1f')} | {fmt(rate, '.1f')} | {fmt(rate / best if rate else None, '.0%')} |")
out += ["", "| size | ccx / feps wall (medians) | per pair |", "|---|---:|---|"]
for size in dict.fromkeys(s for s, _ in groups):
    f, c = walls.get((size, "feps")), walls.get((size, "ccx"))
    if f and c:
        fe = {r["run"]: float(r["elapsed_s"]) for r in groups[(size, "feps")] if r["status"] == "ok"}
        cc = {r["run"]: float(r["elapsed_s"]) for r in groups[(size, "ccx")] if r["status"] == "ok"}
        pairs = ", ".join(f"{cc[k] / fe[k]:.1f}" for k in cc if k in fe)
        out.append(f"| {size} | {c / f:.1f} | {pairs} |")
for size in dict.fromkeys(s for s, _ in groups):
    p = os.path.join(outdir, f"compare_{size}.txt")
    if os.path.exists(p):
        out += ["", f"{size}: displacements feps vs ccx", "", "```", open(p).read().rstrip(), "```"]
open(os.path.join(outdir, "summary.md"), "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
echo "bench: results in $outdir (runs.csv, summary.md, compare_*.txt, dgemm.txt, machine.txt)" >&2
