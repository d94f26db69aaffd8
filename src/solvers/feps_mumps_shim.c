/* MUMPS over MPI for feps (issue 29).
 *
 * Every rank runs feps, the same analysis on the same replicated vectors, and makes each of
 * these calls together with the others. On more than one rank each rank assembles only its own
 * elements' share of the matrix and gives MUMPS those entries (distributed assembled input,
 * ICNTL(18) = 3, which MUMPS sums); on one rank the matrix is whole (centralised input). The
 * right-hand sides are rank 0's, and every rank gets the solution back. Only rank 0 prints and
 * writes (feps_parallel).
 *
 * Built with MPI and MUMPS only when FEPS_MPI is defined (the MPI build, docs); otherwise every
 * function says that MPI is not there, and feps runs as one process. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { MUMPS_OK = 0, MUMPS_NO_MPI = 1, MUMPS_BAD_INPUT = 2, MUMPS_FAILED = 3, MUMPS_NO_MEMORY = 4,
       MUMPS_SINGULAR = 5 };

#ifdef FEPS_MPI
#include <mpi.h>
#include "dmumps_c.h"

#define MAX_INSTANCES 16
#define USE_COMM_WORLD -987654

typedef struct {
    DMUMPS_STRUC_C id;
    int in_use;
    MUMPS_INT *irn, *jcn;        /* the pattern given, 1-based: whole on rank 0, or this rank's entries */
    int64_t *pick;               /* distributed: the positions in the values of this rank's entries */
    double *a_loc;               /* distributed: this rank's values, in the order of pick */
    int distributed;
    double *rank_stats;          /* rank 0: per rank, the last factorization's memory (MB) and seconds */
} instance;

static instance instances[MAX_INSTANCES];
static int started = 0, rank = 0, size = 1;

static void release(instance *in)
{
    free(in->irn);
    free(in->jcn);
    free(in->pick);
    free(in->a_loc);
    in->irn = in->jcn = NULL;
    in->pick = NULL;
    in->a_loc = NULL;
}

/* The controls every rank gives MUMPS: quiet, centralised assembled input (distributed where
 * the analysis is given each rank's entries), dense centralised right-hand side and solution,
 * automatic ordering, null-pivot detection. */
static void set_controls(DMUMPS_STRUC_C *id)
{
    id->icntl[0] = -1;           /* ICNTL(1) error messages: none (feps reports the errors) */
    id->icntl[1] = -1;           /* ICNTL(2) diagnostics */
    id->icntl[2] = -1;           /* ICNTL(3) global information */
    id->icntl[3] = 0;            /* ICNTL(4) print level */
    id->icntl[4] = 0;            /* ICNTL(5) assembled matrix */
    id->icntl[6] = 7;            /* ICNTL(7) ordering: automatic (METIS where built in) */
    id->icntl[17] = 0;           /* ICNTL(18) matrix centralised on the host */
    id->icntl[19] = 0;           /* ICNTL(20) dense right-hand side */
    id->icntl[20] = 0;           /* ICNTL(21) centralised solution */
    id->icntl[23] = 1;           /* ICNTL(24) detect null pivots: names the equation */
    id->icntl[32] = 1;           /* ICNTL(33) the determinant, for its sign (the stability
                                  * check); the factors' arithmetic is unchanged */
    id->cntl[2] = 1e-11;         /* CNTL(3): a pivot row below 1e-11 of the matrix's norm is null
                                  * (CHOLMOD's rule is 1e-11 of the equation's own diagonal) */
}

/* The folder of the out-of-core factor files: MUMPS_OOC_TMPDIR, else TMPDIR, else /tmp. MUMPS
 * makes its files there (names starting "feps_") and removes them when the instance ends. */
static void set_out_of_core(DMUMPS_STRUC_C *id)
{
    const char *dir = getenv("MUMPS_OOC_TMPDIR");
    if (dir == NULL || dir[0] == '\0') dir = getenv("TMPDIR");
    if (dir == NULL || dir[0] == '\0') dir = "/tmp";
    id->icntl[21] = 1;           /* ICNTL(22) the factors go to disk */
    strncpy(id->ooc_tmpdir, dir, sizeof id->ooc_tmpdir - 1);
    id->ooc_tmpdir[sizeof id->ooc_tmpdir - 1] = '\0';
    strncpy(id->ooc_prefix, "feps_", sizeof id->ooc_prefix - 1);
    id->ooc_prefix[sizeof id->ooc_prefix - 1] = '\0';
}

/* `mode`: MUMPS's SYM (0 unsymmetric, 2 general symmetric) plus 16 for out-of-core factors. */
static int create_on_all(int which, int mode)
{
    int sym = mode & 15, out_of_core = (mode & 16) != 0;
    instance *in = &instances[which];
    memset(&in->id, 0, sizeof in->id);
    in->id.job = -1;
    in->id.par = 1;              /* the host works too */
    in->id.sym = sym;
    in->id.comm_fortran = USE_COMM_WORLD;
    dmumps_c(&in->id);
    if (in->id.infog[0] < 0) return MUMPS_FAILED;
    set_controls(&in->id);
    if (out_of_core) set_out_of_core(&in->id);
    in->in_use = 1;
    return MUMPS_OK;
}

/* One MUMPS job on this rank. After a factorization every rank sends rank 0 the memory it used
 * (INFO(22), MB) and its wall time, for the run summary. */
static void run_job(int which, int job)
{
    instance *in = &instances[which];
    double start = MPI_Wtime();
    in->id.job = job;
    dmumps_c(&in->id);
    if (job != 2) return;
    double mine[2] = {(double)in->id.info[21], MPI_Wtime() - start};
    if (rank == 0) {
        free(in->rank_stats);
        in->rank_stats = malloc(sizeof(double) * 2 * (size_t)size);
    }
    MPI_Gather(mine, 2, MPI_DOUBLE, rank == 0 ? in->rank_stats : NULL, 2, MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

static void free_on_all(int which)
{
    instance *in = &instances[which];
    if (!in->in_use) return;
    in->id.job = -2;
    dmumps_c(&in->id);
    in->in_use = 0;
    free(in->rank_stats);
    in->rank_stats = NULL;
}

int feps_mpi_start(int *my_rank, int *ranks)
{
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
        int provided;
        if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) return MUMPS_NO_MPI;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    started = 1;
    *my_rank = rank;
    *ranks = size;
    return MUMPS_OK;
}

/* Every rank ends together (every rank reaches the end with the same status). */
void feps_mpi_stop(int status)
{
    (void)status;
    if (!started) return;
    for (int i = 0; i < MAX_INSTANCES; i++)
        if (instances[i].in_use) {
            free_on_all(i);
            release(&instances[i]);
        }
    MPI_Finalize();
    started = 0;
}

/* A MUMPS instance, sym 2 (general symmetric, LDL') or 0 (unsymmetric, LU), its factors on disk
 * when out_of_core is not 0; -1 when none is free or MUMPS cannot start. */
int feps_mumps_create(int sym, int out_of_core)
{
    if (!started) return -1;
    int mode = (sym & 15) | (out_of_core ? 16 : 0);
    for (int i = 0; i < MAX_INSTANCES; i++)
        if (!instances[i].in_use) {
            if (create_on_all(i, mode) != MUMPS_OK) return -1;
            return i;
        }
    return -1;
}

/* The number of ranks, and rank r's (0-based) memory in MB and seconds in the last
 * factorization; 0 when there was none. */
int feps_mumps_ranks(void) { return started ? size : 0; }

double feps_mumps_rank_stat(int which, int r, int k)
{
    if (!started || which < 0 || which >= MAX_INSTANCES || r < 0 || r >= size || k < 0 || k > 1) return 0.0;
    const double *stats = instances[which].rank_stats;
    return stats == NULL ? 0.0 : stats[2 * r + k];
}

/* MUMPS's estimate after the analysis of the memory, in MB summed over the ranks, that the
 * factorization needs: in core (INFOG(17)) or with the factors on disk (INFOG(27)). */
double feps_mumps_memory_estimate(int which)
{
    if (!started || which < 0 || which >= MAX_INSTANCES) return 0.0;
    const DMUMPS_STRUC_C *id = &instances[which].id;
    return (double)(id->icntl[21] == 1 ? id->infog[26] : id->infog[16]);
}

void feps_mumps_free(int which)
{
    if (!started || which < 0 || which >= MAX_INSTANCES || !instances[which].in_use) return;
    free_on_all(which);
    release(&instances[which]);
}

static int result_of(const DMUMPS_STRUC_C *id)
{
    if (id->infog[0] >= 0) return MUMPS_OK;
    if (id->infog[0] == -13 || id->infog[0] == -9 || id->infog[0] == -19) return MUMPS_NO_MEMORY;
    if (id->infog[0] == -10) return MUMPS_SINGULAR;
    return MUMPS_FAILED;
}

/* The pattern (lower triangle, or both for LU) in compressed rows (1-based row_ptr and col):
 * ordering and symbolic analysis, on every rank together. `distributed`: each rank gives the
 * entries where local[k] is not 0 (its own elements'), and its values of them at each
 * factorization; otherwise rank 0 gives the whole matrix. */
int feps_mumps_analyze(int which, int64_t n, const int64_t *row_ptr, const int32_t *col, int distributed,
                       const int32_t *local)
{
    if (!started || which < 0 || which >= MAX_INSTANCES || !instances[which].in_use) return MUMPS_BAD_INPUT;
    instance *in = &instances[which];
    int64_t nnz = row_ptr[n] - 1, m = 0;
    release(in);
    in->distributed = distributed != 0;
    if (in->distributed)
        for (int64_t k = 0; k < nnz; k++) m += local[k] != 0;
    else
        m = rank == 0 ? nnz : 0;
    in->irn = malloc(sizeof(MUMPS_INT) * (size_t)(m > 0 ? m : 1));
    in->jcn = malloc(sizeof(MUMPS_INT) * (size_t)(m > 0 ? m : 1));
    if (in->distributed) {
        in->pick = malloc(sizeof(int64_t) * (size_t)(m > 0 ? m : 1));
        in->a_loc = malloc(sizeof(double) * (size_t)(m > 0 ? m : 1));
    }
    int no_memory = in->irn == NULL || in->jcn == NULL ||
                    (in->distributed && (in->pick == NULL || in->a_loc == NULL));
    MPI_Allreduce(MPI_IN_PLACE, &no_memory, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (no_memory) return MUMPS_NO_MEMORY;
    int64_t j = 0;
    for (int64_t i = 0; i < n && m > 0; i++)
        for (int64_t k = row_ptr[i] - 1; k < row_ptr[i + 1] - 1; k++) {
            if (in->distributed && local[k] == 0) continue;
            in->irn[j] = (MUMPS_INT)(i + 1);
            in->jcn[j] = (MUMPS_INT)col[k];
            if (in->distributed) in->pick[j] = k;
            j++;
        }
    in->id.n = (MUMPS_INT)n;
    if (in->distributed) {
        in->id.icntl[17] = 3;    /* ICNTL(18): each rank gives its own entries, which MUMPS sums */
        in->id.nnz_loc = m;
        in->id.irn_loc = in->irn;
        in->id.jcn_loc = in->jcn;
    } else {
        in->id.icntl[17] = 0;
        in->id.nnz = m;
        in->id.irn = in->irn;
        in->id.jcn = in->jcn;
    }
    run_job(which, 1);
    return result_of(&in->id);
}

/* Numerical factorization of the values `val` in the analysed pattern's order (rank 0's whole
 * matrix, or each rank's share of the matrix in a distributed analysis). */
int feps_mumps_factorize(int which, double *val)
{
    if (!started || which < 0 || which >= MAX_INSTANCES || !instances[which].in_use) return MUMPS_BAD_INPUT;
    instance *in = &instances[which];
    if (in->distributed) {
        for (int64_t j = 0; j < in->id.nnz_loc; j++) in->a_loc[j] = val[in->pick[j]];
        in->id.a_loc = in->a_loc;
    } else {
        in->id.a = val;
    }
    run_job(which, 2);
    in->id.a = NULL;
    if (in->id.infog[0] >= 0 && in->id.infog[27] > 0) return MUMPS_SINGULAR;   /* INFOG(28) null pivots */
    return result_of(&in->id);
}

/* The first null pivot's equation (1-based), 0 when MUMPS named none: rank 0 holds the list,
 * every rank gets its first entry. */
int64_t feps_mumps_null_pivot(int which)
{
    if (!started || which < 0 || which >= MAX_INSTANCES) return 0;
    instance *in = &instances[which];
    int64_t first = 0;
    if (rank == 0 && in->id.infog[27] > 0 && in->id.pivnul_list != NULL) first = in->id.pivnul_list[0];
    MPI_Bcast(&first, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
    return first;
}

/* The sign of the last factorized matrix's determinant (RINFOG(12) times 2^INFOG(34), ICNTL(33)),
 * root node included, which INFOG(12)'s count of negative pivots leaves out on several ranks
 * unless ScaLAPACK is given up for it: 1 or -1, 0 when unknown. Rank 0's, sent to every rank. */
int feps_mumps_determinant_sign(int which)
{
    if (!started || which < 0 || which >= MAX_INSTANCES || !instances[which].in_use) return 0;
    double mantissa = instances[which].id.rinfog[11];
    int sign = mantissa > 0.0 ? 1 : (mantissa < 0.0 ? -1 : 0);
    MPI_Bcast(&sign, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return sign;
}

/* Factor entries (INFOG(29), or -INFOG(29) millions when negative) and flops (RINFOG(3)). */
int64_t feps_mumps_factor_entries(int which)
{
    if (!started || which < 0 || which >= MAX_INSTANCES) return 0;
    int v = instances[which].id.infog[28];                 /* INFOG(29): after factorization */
    if (v == 0) v = instances[which].id.infog[19];          /* INFOG(20): the analysis's estimate */
    return v >= 0 ? (int64_t)v : -(int64_t)v * 1000000;
}

double feps_mumps_flops(int which)
{
    if (!started || which < 0 || which >= MAX_INSTANCES) return 0.0;
    double done = instances[which].id.rinfog[2];           /* RINFOG(3): after factorization */
    return done > 0.0 ? done : instances[which].id.rinfog[0];   /* RINFOG(1): the estimate */
}

/* Solve in place: b holds nrhs right-hand sides of n each, one after another (rank 0's are
 * solved; every rank gets the solutions). */
int feps_mumps_solve(int which, int64_t n, int64_t nrhs, double *b)
{
    if (!started || which < 0 || which >= MAX_INSTANCES || !instances[which].in_use) return MUMPS_BAD_INPUT;
    instance *in = &instances[which];
    in->id.rhs = b;
    in->id.nrhs = (MUMPS_INT)nrhs;
    in->id.lrhs = (MUMPS_INT)n;
    run_job(which, 3);
    in->id.rhs = NULL;
    int code = result_of(&in->id);
    if (code == MUMPS_OK && size > 1)
        for (int64_t i = 0; i < n * nrhs; i += 1 << 30) {
            int m = (int)(n * nrhs - i < (1 << 30) ? n * nrhs - i : (1 << 30));
            MPI_Bcast(b + i, m, MPI_DOUBLE, 0, MPI_COMM_WORLD);
        }
    return code;
}

/* MUMPS's own error code (INFOG(1)) and detail (INFOG(2)), for messages. */
int feps_mumps_infog(int which, int k)
{
    if (!started || which < 0 || which >= MAX_INSTANCES || k < 1 || k > 80) return 0;
    return instances[which].id.infog[k - 1];
}

#else   /* no MPI: one process, no MUMPS */

int feps_mpi_start(int *my_rank, int *ranks) { *my_rank = 0; *ranks = 1; return MUMPS_NO_MPI; }
void feps_mpi_stop(int status) { (void)status; }
int feps_mumps_create(int sym, int out_of_core) { (void)sym; (void)out_of_core; return -1; }
int feps_mumps_ranks(void) { return 0; }
double feps_mumps_rank_stat(int which, int r, int k) { (void)which; (void)r; (void)k; return 0.0; }
double feps_mumps_memory_estimate(int which) { (void)which; return 0.0; }
void feps_mumps_free(int which) { (void)which; }
int feps_mumps_analyze(int which, int64_t n, const int64_t *row_ptr, const int32_t *col, int distributed,
                       const int32_t *local)
{ (void)which; (void)n; (void)row_ptr; (void)col; (void)distributed; (void)local; return MUMPS_NO_MPI; }
int feps_mumps_factorize(int which, double *val) { (void)which; (void)val; return MUMPS_NO_MPI; }
int64_t feps_mumps_null_pivot(int which) { (void)which; return 0; }
int feps_mumps_determinant_sign(int which) { (void)which; return 0; }
int64_t feps_mumps_factor_entries(int which) { (void)which; return 0; }
double feps_mumps_flops(int which) { (void)which; return 0.0; }
int feps_mumps_solve(int which, int64_t n, int64_t nrhs, double *b)
{ (void)which; (void)n; (void)nrhs; (void)b; return MUMPS_NO_MPI; }
int feps_mumps_infog(int which, int k) { (void)which; (void)k; return 0; }

#endif

/* Whether this build has MPI and MUMPS. */
int feps_mpi_built(void)
{
#ifdef FEPS_MPI
    return 1;
#else
    return 0;
#endif
}
