/* Thin handle-based shim over UMFPACK (64-bit umfpack_dl_* API) for feps's non-symmetric
 * tangents (interfaces and Matsuoka-Nakai soil with psi /= phi, under full Newton).
 *
 * Fortran passes the full matrix (both triangles) in 1-based compressed rows: row_ptr as int64,
 * columns as int32.  Read as compressed columns that is A^T, which UMFPACK factorizes; the solve
 * asks for the transposed system (UMFPACK_At), i.e. A x = b.  The symbolic analysis is kept while
 * the pattern stays the same.
 *
 * Return codes: FEPS_UMF_* below (0 = success).
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/umfpack.h>

_Static_assert(sizeof(SuiteSparse_long) == sizeof(int64_t), "SuiteSparse_long must be 64-bit");

enum {
    FEPS_UMF_OK = 0,
    FEPS_UMF_BAD_INPUT = 1,   /* sizes or pattern invalid */
    FEPS_UMF_SINGULAR = 2,    /* the matrix is singular (a zero pivot) */
    FEPS_UMF_ERROR = 3,       /* UMFPACK failed (out of memory, ...): see feps_umf_status */
    FEPS_UMF_NOT_READY = 4    /* solve before a successful factorization */
};

typedef struct {
    double control[UMFPACK_CONTROL];
    double info[UMFPACK_INFO];
    void *symbolic;
    void *numeric;
    int64_t n, nnz;
    int64_t *ap, *ai;         /* 0-based compressed columns of A^T */
    double *ax;
    double *x;                /* solution workspace */
    int status;               /* last UMFPACK status */
    double flops;             /* flops of the last numeric factorization */
    double rcond;             /* UMFPACK's reciprocal condition estimate of the last one */
    int det_sign;             /* the sign of its determinant: +1, -1, 0 where not known */
} feps_umf_handle;

void *feps_umf_create(void)
{
    feps_umf_handle *h = calloc(1, sizeof(*h));
    if (h == NULL) return NULL;
    umfpack_dl_defaults(h->control);
    h->control[UMFPACK_PRL] = 0;   /* silent */
    return h;
}

static void release(feps_umf_handle *h)
{
    if (h->numeric != NULL) umfpack_dl_free_numeric(&h->numeric);
    if (h->symbolic != NULL) umfpack_dl_free_symbolic(&h->symbolic);
    free(h->ap);
    free(h->ai);
    free(h->ax);
    free(h->x);
    h->ap = h->ai = NULL;
    h->ax = h->x = NULL;
    h->n = h->nnz = 0;
}

void feps_umf_free(void *handle)
{
    if (handle == NULL) return;
    release(handle);
    free(handle);
}

/* Factorize the n x n matrix given in 1-based compressed rows (row_ptr[n] - 1 entries). */
int feps_umf_factorize(void *handle, int64_t n, const int64_t *row_ptr, const int32_t *col, const double *val)
{
    feps_umf_handle *h = handle;
    if (h == NULL || n < 1) return FEPS_UMF_BAD_INPUT;
    int64_t nnz = row_ptr[n] - 1;
    if (nnz < 1 || row_ptr[0] != 1) return FEPS_UMF_BAD_INPUT;
    if (h->numeric != NULL) umfpack_dl_free_numeric(&h->numeric);
    if (n != h->n || nnz != h->nnz) {
        release(h);
        h->ap = calloc((size_t)(n + 1), sizeof(int64_t));
        h->ai = calloc((size_t)nnz, sizeof(int64_t));
        h->ax = malloc((size_t)nnz * sizeof(double));
        h->x = malloc((size_t)n * sizeof(double));
        if (!h->ap || !h->ai || !h->ax || !h->x) {
            release(h);
            return FEPS_UMF_ERROR;
        }
        h->n = n;
        h->nnz = nnz;
    }
    /* The symbolic analysis is kept only for the very pattern it was made for: equations
     * renumbered between stages may keep n and the number of entries. */
    int same = 1;
    for (int64_t i = 0; i <= n; i++) {
        if (h->ap[i] != row_ptr[i] - 1) same = 0;
        h->ap[i] = row_ptr[i] - 1;
    }
    for (int64_t k = 0; k < nnz; k++) {
        if (col[k] < 1 || col[k] > n) return FEPS_UMF_BAD_INPUT;
        if (h->ai[k] != col[k] - 1) same = 0;
        h->ai[k] = col[k] - 1;
    }
    if (!same && h->symbolic != NULL) umfpack_dl_free_symbolic(&h->symbolic);
    memcpy(h->ax, val, (size_t)nnz * sizeof(double));
    if (h->symbolic == NULL) {
        h->status = umfpack_dl_symbolic(n, n, h->ap, h->ai, h->ax, &h->symbolic, h->control, h->info);
        if (h->status != UMFPACK_OK) return FEPS_UMF_ERROR;
    }
    h->status = umfpack_dl_numeric(h->ap, h->ai, h->ax, h->symbolic, &h->numeric, h->control, h->info);
    h->flops = h->info[UMFPACK_FLOPS];
    h->rcond = h->info[UMFPACK_RCOND];
    if (h->status == UMFPACK_WARNING_singular_matrix) {
        umfpack_dl_free_numeric(&h->numeric);
        return FEPS_UMF_SINGULAR;
    }
    if (h->status != UMFPACK_OK) {
        if (h->numeric != NULL) umfpack_dl_free_numeric(&h->numeric);
        return FEPS_UMF_ERROR;
    }
    /* det(A^T) = det(A): mantissa and exponent apart, so that it cannot overflow */
    double mantissa = 0.0, exponent = 0.0;
    h->det_sign = 0;
    if (umfpack_dl_get_determinant(&mantissa, &exponent, h->numeric, h->info) == UMFPACK_OK)
        h->det_sign = (mantissa > 0.0) - (mantissa < 0.0);
    return FEPS_UMF_OK;
}

/* The sign of the last numeric factorization's determinant (+1, -1; 0 where not known). */
int feps_umf_determinant_sign(const void *handle)
{
    return handle == NULL ? 0 : ((const feps_umf_handle *)handle)->det_sign;
}

/* UMFPACK's reciprocal condition estimate of the last numeric factorization: min / max of
 * |diag(U)| after its row scaling.  A matrix singular but for rounding passes UMFPACK's own test
 * (an exactly zero pivot) with an estimate near machine precision. */
double feps_umf_rcond(void *handle)
{
    feps_umf_handle *h = handle;
    return h == NULL ? 0.0 : h->rcond;
}

/* Solve A x = b in place (b becomes x). */
int feps_umf_solve(void *handle, double *b)
{
    feps_umf_handle *h = handle;
    if (h == NULL || h->numeric == NULL) return FEPS_UMF_NOT_READY;
    h->status = umfpack_dl_solve(UMFPACK_At, h->ap, h->ai, h->ax, h->x, b, h->numeric, h->control, h->info);
    if (h->status != UMFPACK_OK) return FEPS_UMF_ERROR;
    memcpy(b, h->x, (size_t)h->n * sizeof(double));
    return FEPS_UMF_OK;
}

int feps_umf_status(const void *handle) { return handle == NULL ? 0 : ((const feps_umf_handle *)handle)->status; }

double feps_umf_flops(const void *handle) { return handle == NULL ? 0.0 : ((const feps_umf_handle *)handle)->flops; }
