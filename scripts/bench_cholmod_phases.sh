#!/usr/bin/env bash
# CHOLMOD analysis and factorization of one feps matrix, timed apart from the rest of feps,
# with the shim of the work tree against the shim of an older commit (default: the last one
# before the node-graph ordering). feps runs once to dump its stiffness matrix (an LD_PRELOAD
# wrapper around cholmod_l_factorize); a small C driver that compiles each shim in then runs
# analyze, factorize and solve on that matrix, alternating old and new, and prints wall and
# CPU seconds, Common->lnz, Common->fl, the number of supernodes and the solution error.
#
#   bash scripts/bench_cholmod_phases.sh                        # 200k mesh, 3 pairs
#   bash scripts/bench_cholmod_phases.sh --size 50k --repeat 5 --threads 1
#   NRELAX=8,32,64 ZRELAX=0.8,0.2,0.1 bash scripts/bench_cholmod_phases.sh   # relaxation
#
# Writes into --workdir (default results/cholmod-phases, which git ignores).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
size=200k
repeat=3
threads=""
base=""
workdir="$root/results/cholmod-phases"
while (($#)); do
  case $1 in
    --size) size=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --base) base=$2; shift 2 ;;
    --workdir) workdir=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
    *) echo "bench_cholmod_phases: unknown option $1" >&2; exit 2 ;;
  esac
done
[ -n "$threads" ] && export OPENBLAS_NUM_THREADS=$threads
mkdir -p "$workdir"
cd "$workdir"
libs="-lcholmod -lsuitesparseconfig -lmetis -lm"

cat > dump.c <<'EOF'
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <suitesparse/cholmod.h>
/* Writes n, nnz, p[n+1], i[nnz] (int64) and x[nnz] (double) of the first matrix factorized. */
int cholmod_l_factorize(cholmod_sparse *a, cholmod_factor *l, cholmod_common *c)
{
    static int (*real)(cholmod_sparse *, cholmod_factor *, cholmod_common *);
    static int done;
    if (real == NULL) real = (int (*)(cholmod_sparse *, cholmod_factor *, cholmod_common *))dlsym(RTLD_NEXT, "cholmod_l_factorize");
    const char *file = getenv("FEPS_DUMP_MATRIX");
    if (file != NULL && !done) {
        FILE *out = fopen(file, "wb");
        int64_t n = (int64_t)a->ncol, nnz = ((int64_t *)a->p)[n];
        fwrite(&n, 8, 1, out); fwrite(&nnz, 8, 1, out);
        fwrite(a->p, 8, (size_t)n + 1, out); fwrite(a->i, 8, (size_t)nnz, out); fwrite(a->x, 8, (size_t)nnz, out);
        fclose(out);
        done = 1;
    }
    return real(a, l, c);
}
EOF

cat > driver.c <<'EOF'
#include SHIM
#include <math.h>
#include <stdio.h>
#include <time.h>
static double clock_s(clockid_t id) { struct timespec t; clock_gettime(id, &t); return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec; }
static void parse3(const char *text, double *v) { if (text != NULL) sscanf(text, "%lf,%lf,%lf", &v[0], &v[1], &v[2]); }
int main(int argc, char **argv)
{
    if (argc < 3) return 2;
    FILE *in = fopen(argv[1], "rb");
    int64_t n, nnz;
    if (in == NULL || fread(&n, 8, 1, in) != 1 || fread(&nnz, 8, 1, in) != 1) return 2;
    int64_t *p = malloc((size_t)(n + 1) * 8), *ii = malloc((size_t)nnz * 8), *row_ptr = malloc((size_t)(n + 1) * 8);
    double *x = malloc((size_t)nnz * 8), *xt = malloc((size_t)n * 8), *b = calloc((size_t)n, 8);
    int32_t *col = malloc((size_t)nnz * 4);
    if (fread(p, 8, (size_t)n + 1, in) != (size_t)n + 1 || fread(ii, 8, (size_t)nnz, in) != (size_t)nnz ||
        fread(x, 8, (size_t)nnz, in) != (size_t)nnz) return 2;
    fclose(in);
    for (int64_t j = 0; j <= n; j++) row_ptr[j] = p[j] + 1;   /* upper CSC = lower CSR */
    for (int64_t k = 0; k < nnz; k++) col[k] = (int32_t)ii[k] + 1;
    feps_chol_handle *h = feps_chol_create();
    cholmod_common *c = &h->common;
    double nr[3] = {(double)c->nrelax[0], (double)c->nrelax[1], (double)c->nrelax[2]};
    double zr[3] = {c->zrelax[0], c->zrelax[1], c->zrelax[2]};
    parse3(getenv("NRELAX"), nr);
    parse3(getenv("ZRELAX"), zr);
    for (int k = 0; k < 3; k++) { c->nrelax[k] = (size_t)nr[k]; c->zrelax[k] = zr[k]; }
    double w0 = clock_s(CLOCK_MONOTONIC), c0 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    if (feps_chol_analyze(h, n, row_ptr, col) != 0) return 1;
    double w1 = clock_s(CLOCK_MONOTONIC), c1 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    if (feps_chol_factorize(h, x) != 0) return 1;
    double w2 = clock_s(CLOCK_MONOTONIC), c2 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    for (int64_t k = 0; k < n; k++) xt[k] = 1.0 + sin((double)k);
    for (int64_t j = 0; j < n; j++)
        for (int64_t k = p[j]; k < p[j + 1]; k++) {
            b[ii[k]] += x[k] * xt[j];
            if (ii[k] != j) b[j] += x[k] * xt[ii[k]];
        }
    if (feps_chol_solve(h, n, 1, b) != 0) return 1;
    double err = 0.0;
    for (int64_t k = 0; k < n; k++) err = fmax(err, fabs(b[k] - xt[k]));
    printf("%s analyze %.3f s (cpu %.3f) factorize %.3f s (cpu %.3f) lnz %.0f flops %.4g nsuper %zu max_error %.1e\n",
           argv[2], w1 - w0, c1 - c0, w2 - w1, c2 - c1, c->lnz, c->fl, h->l->nsuper, err);
    feps_chol_free(h);
    return 0;
}
EOF

if [ -z "$base" ]; then   # the commit before the one that brought cholmod_l_analyze_p in
  base=$(git -C "$root" log -1 --format=%H -S cholmod_l_analyze_p -- src/solvers/feps_cholmod_shim.c)~1
fi
git -C "$root" show "$base:src/solvers/feps_cholmod_shim.c" > shim_base.c
gcc -O2 -shared -fPIC dump.c -o dump.so -ldl
gcc -O2 -DSHIM='"shim_base.c"' driver.c -o driver_base $libs
gcc -O2 -DSHIM="\"$root/src/solvers/feps_cholmod_shim.c\"" driver.c "$root/src/solvers/feps_blas_shim.c" \
  -o driver_new $libs

if [ ! -f "matrix_$size.bin" ]; then
  (cd "$root" && fpm build --profile release >/dev/null)
  feps="$root/$(cd "$root" && fpm run --profile release --runner echo 2>/dev/null | tail -1)"
  python3 "$root/scripts/make_pipe_mesh.py" --preset "$size" -o "pipe_$size.dat"
  FEPS_DUMP_MATRIX="matrix_$size.bin" LD_PRELOAD="$PWD/dump.so" "$feps" "pipe_$size.dat" --output run.h5 -q
  rm -f run.h5 run.xmf
fi
for ((r = 1; r <= repeat; r++)); do
  for v in base new; do
    echo "load $(cut -d' ' -f1 /proc/loadavg) threads ${OPENBLAS_NUM_THREADS:-default} $(./driver_$v "matrix_$size.bin" $v)"
  done
done | tee -a "phases_$size.txt"
