/* The MPI collectives of feps's element-partitioned runs (issue 29), behind feps_parallel.f90.
 *
 * Under `mpirun -np N feps DECK --solver mumps` every rank runs the same analysis on the same
 * replicated vectors; each rank updates and assembles only its own block of elements, and these
 * calls put the pieces together: a sum of the ranks' internal forces (reduced on rank 0 and sent
 * back, so every rank holds the same bits), the exchange of the point-state blocks (copies, no
 * arithmetic), and rank 0's word on the errors only it can meet (writing the results).
 *
 * MPI is started by feps_mumps_shim.c (feps_mpi_start). Built with MPI only when FEPS_MPI is
 * defined (the MPI build); otherwise, and before MPI starts, there is one rank and every call
 * leaves its data as they are. */
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <fcntl.h>
#include <unistd.h>
#include <sys/resource.h>

#ifdef FEPS_MPI
#include <mpi.h>

static int running(void)
{
    int initialized = 0, finalized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) return 0;
    MPI_Finalized(&finalized);
    return !finalized;
}

int feps_par_rank(void)
{
    int r = 0;
    if (running()) MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int feps_par_size(void)
{
    int s = 1;
    if (running()) MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
}

/* MPI counts are int: long arrays go in pieces. */
#define PIECE (1 << 30)

void feps_par_sum(double *x, int64_t n)
{
    if (feps_par_size() < 2) return;
    int rank = feps_par_rank();
    for (int64_t i = 0; i < n; i += PIECE) {
        int m = (int)(n - i < PIECE ? n - i : PIECE);
        if (rank == 0) MPI_Reduce(MPI_IN_PLACE, x + i, m, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
        else MPI_Reduce(x + i, NULL, m, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
        MPI_Bcast(x + i, m, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    }
}

void feps_par_min_int(int32_t *x, int64_t n)
{
    if (feps_par_size() < 2) return;
    for (int64_t i = 0; i < n; i += PIECE) {
        int m = (int)(n - i < PIECE ? n - i : PIECE);
        MPI_Allreduce(MPI_IN_PLACE, x + i, m, MPI_INT32_T, MPI_MIN, MPI_COMM_WORLD);
    }
}

/* Rank r's block is x[displs[r] .. displs[r] + counts[r]): every rank gets every block. A count
 * or offset beyond an int is a broken invariant (feps checks each group's size when it
 * partitions the elements): every rank stops, with one line from the rank that found it. */
static int gather(void *x, const int64_t *counts, const int64_t *displs, MPI_Datatype type)
{
    int size = feps_par_size();
    if (size < 2) return 0;
    int *c = malloc(sizeof(int) * (size_t)size), *d = malloc(sizeof(int) * (size_t)size);
    if (c == NULL || d == NULL) {
        fprintf(stderr, "feps: error: out of memory exchanging the point states\n");
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    for (int r = 0; r < size; r++) {
        if (counts[r] > INT_MAX || displs[r] > INT_MAX) {
            fprintf(stderr, "feps: error: internal: a block of point states beyond 2**31 values\n");
            MPI_Abort(MPI_COMM_WORLD, 1);
        }
        c[r] = (int)counts[r];
        d[r] = (int)displs[r];
    }
    MPI_Allgatherv(MPI_IN_PLACE, 0, type, x, c, d, type, MPI_COMM_WORLD);
    free(c);
    free(d);
    return 0;
}

int feps_par_gather_real(double *x, const int64_t *counts, const int64_t *displs)
{ return gather(x, counts, displs, MPI_DOUBLE); }

int feps_par_any(int flag)
{
    int any = flag != 0;
    if (feps_par_size() > 1) MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return any;
}

void feps_par_from_root(int32_t *v, int n)
{
    if (feps_par_size() > 1) MPI_Bcast(v, n, MPI_INT32_T, 0, MPI_COMM_WORLD);
}

#else   /* no MPI: one rank */

int feps_par_rank(void) { return 0; }
int feps_par_size(void) { return 1; }
void feps_par_sum(double *x, int64_t n) { (void)x; (void)n; }
void feps_par_min_int(int32_t *x, int64_t n) { (void)x; (void)n; }
int feps_par_gather_real(double *x, const int64_t *counts, const int64_t *displs)
{ (void)x; (void)counts; (void)displs; return 0; }
int feps_par_any(int flag) { return flag != 0; }
void feps_par_from_root(int32_t *v, int n) { (void)v; (void)n; }

#endif

/* This process's largest resident memory so far, in MB (getrusage: kB on Linux). */
double feps_par_peak_memory_mb(void)
{
    struct rusage usage;
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
    return (double)usage.ru_maxrss / 1024.0;
}

/* The ranks above 0 print nothing: their standard output and error go to /dev/null, so that
 * rank 0's lines are the run's only ones (every rank meets the same errors). */
void feps_par_silence(void)
{
    int null = open("/dev/null", O_WRONLY);
    if (null < 0) return;
    dup2(null, 1);
    dup2(null, 2);
    if (null > 2) close(null);
}
